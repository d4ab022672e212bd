//! The runtime guard on the GPU (validation and synchronization validation on): a non-finite
//! or runaway particle is reported after the frame with its object and index; a stable scene
//! never trips it.

mod common;

use common::*;
use glam::DVec3;
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::gpu_types::Particle;
use msdsim::sim::stability::GuardTrip;

#[test]
fn a_non_finite_particle_trips_the_guard() {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    c.stiffness = [60.0, 20.0, 5.0];
    let mut model = scene(vec![rope(40, 0.025), c]);
    model.gravity = DVec3::new(0.0, -9.81, 0.0);
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    for _ in 0..3 {
        sim.step_frame(&ctx).expect("a stable scene does not trip the guard");
    }
    sim.set_particle(1, 40, Particle { pos: [f32::NAN, 1.0, 0.0, 0.0], vel: [0.0; 4] });
    let err = sim.step_frame(&ctx).expect_err("NaN must trip the guard");
    let trip = err.downcast_ref::<GuardTrip>().expect("a GuardTrip");
    assert_eq!(trip.name, "cloth13x9");
    assert!(trip.what.contains("blew up"), "{trip}");
    // NaN spreads through the springs within the frame: the lowest flagged index is at most 40.
    assert!(trip.particle <= 40, "{trip}");
    sim.destroy(&ctx);
    assert_clean(&ctx);
}

#[test]
fn a_runaway_particle_trips_the_guard() {
    let ctx = gpu();
    let mut model = scene(vec![rope(40, 0.025)]);
    model.max_speed = 50.0;
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    sim.set_particle(0, 7, Particle { pos: [0.0, 1.0, 0.0, 0.0], vel: [80.0, 0.0, 0.0, 0.0] });
    let err = sim.step_frame(&ctx).expect_err("80 m/s is past the 50 m/s bound");
    let trip = err.downcast_ref::<GuardTrip>().expect("a GuardTrip");
    assert!(trip.what.contains("ran away") && trip.particle == 7, "{trip}");
    sim.destroy(&ctx);
    assert_clean(&ctx);
}
