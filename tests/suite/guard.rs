//! The runtime guard on the GPU (validation and synchronization validation on): a non-finite
//! or runaway particle is reported after the frame with its object and index; a stable scene
//! never trips it. Each test runs drawn and headless (`set_drawn(false)`: the surface stage
//! runs the guard alone).

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::gpu_types::Particle;
use msdsim::sim::model::Integrator;
use msdsim::sim::stability::GuardTrip;

#[test]
fn a_non_finite_particle_trips_the_guard() {
    for drawn in [true, false] {
        non_finite(drawn);
    }
}

fn non_finite(drawn: bool) {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    c.stiffness = [60.0, 20.0, 5.0];
    let mut model = scene(vec![rope(40, 0.025), c]);
    model.gravity = DVec3::new(0.0, -9.81, 0.0);
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    sim.set_drawn(drawn);
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
    for drawn in [true, false] {
        runaway(drawn);
    }
}

fn runaway(drawn: bool) {
    let ctx = gpu();
    let mut model = scene(vec![rope(40, 0.025)]);
    model.max_speed = 50.0;
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    sim.set_drawn(drawn);
    sim.set_particle(0, 7, Particle { pos: [0.0, 1.0, 0.0, 0.0], vel: [80.0, 0.0, 0.0, 0.0] });
    let err = sim.step_frame(&ctx).expect_err("80 m/s is past the 50 m/s bound");
    let trip = err.downcast_ref::<GuardTrip>().expect("a GuardTrip");
    assert!(trip.what.contains("ran away") && trip.particle == 7, "{trip}");
    sim.destroy(&ctx);
    assert_clean(&ctx);
}

/// Headless frames leave the surface as the last drawn frame wrote it while the particles move
/// on; drawing again brings it up to date.
#[test]
fn headless_frames_skip_the_surface() {
    let ctx = gpu();
    let mut model = scene(vec![rope(40, 0.025), cloth(13, 9, 0.05)]);
    model.gravity = DVec3::new(0.0, -9.81, 0.0);
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    sim.step_frame(&ctx).unwrap();
    let drawn = sim.read_states(&ctx).unwrap();
    sim.set_drawn(false);
    sim.step_frame(&ctx).unwrap();
    let headless = sim.read_states(&ctx).unwrap();
    sim.set_drawn(true);
    sim.step_frame(&ctx).unwrap();
    let again = sim.read_states(&ctx).unwrap();
    for o in 0..2 {
        let pos =
            |s: &[msdsim::sim::gpu::ObjectState]| s[o].particles.iter().map(|p| p.pos).collect::<Vec<_>>();
        let surf =
            |s: &[msdsim::sim::gpu::ObjectState]| s[o].surface.iter().map(|v| v.pos).collect::<Vec<_>>();
        assert_ne!(pos(&drawn), pos(&headless), "object {o}: the particles fall");
        assert_eq!(surf(&drawn), surf(&headless), "object {o}: a headless frame wrote the surface");
        assert_ne!(surf(&headless), surf(&again), "object {o}: drawing again updates the surface");
    }
    sim.destroy(&ctx);
    assert_clean(&ctx);
}

/// An implausible state is an error too, not only a blow-up: a cloth whose pinned corner is
/// dragged 40 cm away within a frame (its structural springs at several times their rest
/// length) trips the guard as over-stretched (past sim.max_strain = 1: twice the rest length),
/// drawn and headless; with `sim.max_strain = 0` the check is off. The same cloth hanging from
/// its corners for 30 frames does not trip it.
#[test]
fn an_overstretched_cloth_trips_the_guard() {
    let mut c = cloth(13, 9, 0.05);
    c.stiffness = [2000.0, 500.0, 5.0];
    c.pinned[0] = true;
    c.pinned[12] = true;
    let mut model = scene(vec![c]);
    model.gravity = DVec3::new(0.0, -9.81, 0.0);
    for (drawn, max_strain) in [(true, 1.0), (false, 1.0), (true, 0.0)] {
        model.max_strain = max_strain;
        let ctx = gpu();
        let mut sim = GpuSim::new(&ctx, &model).unwrap();
        sim.set_drawn(drawn);
        for _ in 0..30 {
            sim.step_frame(&ctx).expect("a cloth hanging from its corners is plausible");
        }
        sim.set_particle(0, 0, Particle { pos: [-0.4, 1.0, 0.0, 1.0], vel: [0.0; 4] });
        let result = sim.step_frame(&ctx);
        if max_strain == 0.0 {
            result.expect("sim.max_strain = 0 turns the check off");
        } else {
            let err = result.expect_err("a spring at several times its rest length must trip the guard");
            let trip = err.downcast_ref::<GuardTrip>().expect("a GuardTrip");
            assert_eq!(trip.cause, msdsim::sim::stability::GuardCause::Overstretched, "{trip}");
            assert!(
                trip.what.contains("over-stretched") && trip.what.contains("sim.max_strain = 1"),
                "{trip}"
            );
            assert_eq!(trip.particle, 0, "{trip}");
        }
        sim.destroy(&ctx);
        assert_clean(&ctx);
    }
}

/// A scene that only trades energy between its springs and its motion is not stopped: an
/// undamped 20-node rope released stretched (structural rest at 0.8 of its spacing: 0.19 J in
/// its springs, 200 N/m, 10 g nodes), no gravity, symplectic Euler at 16 substeps, for 2 s.
/// The method conserves a modified energy, so the true one rises and falls by a share of what
/// sloshes (omega_max dt = 0.29 here); it was stopped at 1.5 s by a scale that left the
/// springs' energy out ("3.00 times the scale of 1.0e-3 J"). Independently of the guard, the
/// energy stays within 10% of its start (that bounded oscillation, no drift).
#[test]
fn a_stretched_undamped_rope_is_not_stopped() {
    let mut rope = rope(20, 0.05);
    rope.stiffness = [200.0, 0.0, 0.0];
    rope.rest_scale = [0.8, 1.0, 1.0];
    let mut model = scene(vec![rope]);
    model.max_energy_gain = 0.5;
    let ctx = gpu();
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    let energy = |sim: &mut GpuSim| {
        let s = &sim.read_states(&ctx).unwrap()[0];
        msdsim::sim::cpu::energy(&model, &model.objects[0], &s.positions(), &s.velocities())
    };
    let start = energy(&mut sim);
    assert!((start - 0.19).abs() < 1e-6, "the springs' energy at the start: {start}");
    for frame in 0..120 {
        sim.step_frame(&ctx).unwrap_or_else(|e| panic!("frame {frame}: {e:#}"));
        if frame % 10 == 9 {
            let e = energy(&mut sim);
            assert!((e - start).abs() < 0.1 * start, "frame {frame}: {e} J against {start} J at the start");
        }
    }
    sim.destroy(&ctx);
    assert_clean(&ctx);
}

/// Energy made without a source is an error too (sim.max_energy_gain, default 0.5 of the
/// scene's scale): two free 8 x 8 cloths started 5 mm apart, inside each other's contact reach
/// (2 cm), nothing else acting, fly apart (contact gives the overlap it resolves as speed) and
/// trip the guard; with the check off they run on. The same cloths 10 cm apart, falling under
/// gravity (energy conserved but for rounding), do not trip it. Each runs 32 frames: the check
/// comes every 30 (`CHECK_FRAMES`).
#[test]
fn energy_made_without_a_source_trips_the_guard() {
    let pair = |gap: f64| {
        let mut back = cloth(8, 8, 0.04);
        back.margin = 0.01;
        back.stiffness = [50.0, 10.0, 1.0];
        let mut front = back.clone();
        front.name = "front".into();
        front.positions.iter_mut().for_each(|p| p.z += gap);
        let mut model = scene(vec![back, front]);
        model.inter_object = true;
        model.max_energy_gain = 0.5;
        model
    };
    let ctx = gpu();
    let mut falling = pair(0.1);
    falling.gravity = DVec3::new(0.0, -9.81, 0.0);
    for (model, trips) in [(pair(0.005), true), (falling, false)] {
        let mut sim = GpuSim::new(&ctx, &model).unwrap();
        let result = (0..32).try_for_each(|_| sim.step_frame(&ctx).map(|_| ()));
        if trips {
            let err = result.expect_err("cloths pushed apart from rest gain energy");
            let trip = err.downcast_ref::<GuardTrip>().expect("a GuardTrip");
            assert_eq!(trip.cause, msdsim::sim::stability::GuardCause::EnergyGain, "{trip}");
            assert!(
                trip.what.contains("without a source") && trip.advice.contains("max_energy_gain = 0"),
                "{trip}"
            );
        } else {
            result.expect("a falling pair keeps its energy");
        }
        sim.destroy(&ctx);
    }
    let mut off = pair(0.005);
    off.max_energy_gain = 0.0;
    let mut sim = GpuSim::new(&ctx, &off).unwrap();
    for _ in 0..32 {
        sim.step_frame(&ctx).expect("sim.max_energy_gain = 0 turns the check off");
    }
    sim.destroy(&ctx);
    assert_clean(&ctx);
}

/// Undamped cloths released stretched are not stopped over 10,000 substeps of either explicit
/// method: a 6 x 6 cloth (5 cm spacing, 10 g particles, springs 200, 50 and 10 N/m, every rest
/// length 0.8 of its spacing: 0.95 J in its springs), no gravity, no dashpots, no drag, 16
/// substeps a frame for 625 frames. Independently of the guard, its energy stays within 10% of
/// its start at every check (symplectic Euler and Verlet keep a modified energy: the true one
/// rises and falls by a share of what sloshes, without drift; measured within 5.2% and 0.23%).
#[test]
fn cloths_released_stretched_run_10000_explicit_substeps() {
    let ctx = gpu();
    for method in [Integrator::SymplecticEuler, Integrator::Verlet] {
        let mut c = cloth(6, 6, 0.05);
        c.stiffness = [200.0, 50.0, 10.0];
        c.rest_scale = [0.8, 0.8, 0.8];
        c.damping = 0.0;
        c.drag = 0.0;
        let mut model = scene(vec![c]);
        model.integrator = method;
        model.max_energy_gain = 0.5;
        let mut sim = GpuSim::new(&ctx, &model).unwrap();
        let energy = |sim: &mut GpuSim| {
            let s = &sim.read_states(&ctx).unwrap()[0];
            msdsim::sim::cpu::energy(&model, &model.objects[0], &s.positions(), &s.velocities())
        };
        let start = energy(&mut sim);
        let mut worst = 0.0f64;
        for frame in 0..625 {
            sim.step_frame(&ctx).unwrap_or_else(|e| panic!("{method:?}, frame {frame}: {e:#}"));
            if frame % 25 == 24 {
                worst = worst.max((energy(&mut sim) / start - 1.0).abs());
            }
        }
        println!(
            "{method:?}: energy {start:.4} J at the start, within {:.2}% over 10,000 substeps",
            100.0 * worst
        );
        assert!(worst < 0.1, "{method:?}: the energy strayed {:.1}% from its start", 100.0 * worst);
        sim.destroy(&ctx);
    }
    assert_clean(&ctx);
}

/// A compliant method is judged by the energy it integrates: XPBD and XPBD by Jacobi at one
/// 1/60 s substep and 4 iterations leave a stiff cloth's springs far longer than their
/// stiffness says (`stiff_cloth` at 1e4 N/m with the presets' light dashpots: on the f64
/// reference they hang about 5 and 15 times the equilibrium's sag), so the springs' energy at
/// their stiffness grows as it settles, which the energy check took for a gain and stopped at
/// frame 31 (7.0 and 186 times the scale). It now runs 90 frames. Independently, nothing
/// supplies energy, so the motion's and gravity's energy must stay below its start, and the
/// settling cloth slows (its fastest particle at the end below a tenth of the fastest at frame
/// 30; measured 0.4% and 0.4%).
#[test]
fn a_compliant_method_that_hangs_long_is_not_stopped() {
    let ctx = gpu();
    for method in [Integrator::Xpbd, Integrator::XpbdJacobi] {
        let mut model = stiff_cloth(1e4);
        model.objects[0].damping = 0.01;
        model.integrator = method;
        model.iterations = 4;
        model.max_energy_gain = 0.5;
        let o = &model.objects[0];
        let motion = |x: &[DVec3], v: &[DVec3]| -> f64 {
            x.iter()
                .zip(v)
                .map(|(x, v)| 0.5 * o.mass * v.length_squared() - o.mass * model.gravity.dot(*x))
                .sum()
        };
        let fastest = |v: &[DVec3]| v.iter().map(|v| v.length()).fold(0.0, f64::max);
        let start = motion(&o.positions, &o.velocities);
        let mut sim = GpuSim::new(&ctx, &model).unwrap();
        let mut at_30 = 0.0;
        for frame in 1..=90 {
            sim.step_frame(&ctx).unwrap_or_else(|e| panic!("{method:?}, frame {frame}: {e:#}"));
            if frame % 30 == 0 {
                let s = &sim.read_states(&ctx).unwrap()[0];
                let (x, v) = (s.positions(), s.velocities());
                let e = motion(&x, &v);
                println!("{method:?}, frame {frame}: motion and gravity {e:.4} J (start {start:.4}), fastest {:.3e} m/s", fastest(&v));
                assert!(
                    e < start,
                    "{method:?}, frame {frame}: {e} J of motion and gravity, {start} J at the start"
                );
                if frame == 30 {
                    at_30 = fastest(&v);
                } else if frame == 90 {
                    assert!(
                        fastest(&v) < 0.1 * at_30,
                        "{method:?}: not settling ({:.3e} m/s, {at_30:.3e} at frame 30)",
                        fastest(&v)
                    );
                }
            }
        }
        sim.destroy(&ctx);
    }
    assert_clean(&ctx);
}
