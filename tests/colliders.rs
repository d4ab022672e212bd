//! Colliders that move (kinematic bodies): their contacts follow their velocity, so friction
//! drags what they touch. On lavapipe with validation and synchronization validation, both GPU
//! paths (fused and per stage).

mod common;

use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::gpu::GpuSim;

/// Mean particle position of object 0.
fn centre(states: &[msdsim::sim::gpu::ObjectState]) -> DVec3 {
    let p = states[0].positions();
    p.iter().sum::<DVec3>() / p.len() as f64
}

/// A cloth lying on a slippery ground, a sphere resting on its middle: moving at 0.5 m/s in x,
/// the sphere drags the cloth along by friction (its velocity is what the cloth's tangential
/// velocity is pulled towards); standing still, it does not. After 1 s the moving sphere has
/// gone 0.5 m and the cloth's centre must follow it by more than 5 cm in x (measured 11 cm), stay within 2 cm
/// in z, and the still sphere's cloth must stay within 1 cm. (Friction pulls only the particles
/// under the sphere; the springs drag the rest, and the ground's friction of 0.05 holds them
/// back, so the cloth lags the sphere: 5 cm is a floor, not a prediction.)
#[test]
fn a_moving_sphere_drags_a_cloth_lying_on_the_ground() {
    let ctx = gpu();
    let run = |velocity: DVec3, fused: bool| -> DVec3 {
        let n = 12;
        let mut c = cloth(n, n, 0.04);
        for (i, p) in c.positions.iter_mut().enumerate() {
            *p = DVec3::new((i as u32 % n) as f64 * 0.04 - 0.22, 0.01, (i as u32 / n) as f64 * 0.04 - 0.22);
        }
        c.stiffness = [200.0, 50.0, 5.0];
        c.damping = 0.02;
        c.margin = 0.01;
        c.friction = 0.9;
        let mut s = scene(vec![c]);
        s.gravity = DVec3::new(0.0, -9.81, 0.0);
        s.substeps = 16;
        let motion = if velocity == DVec3::ZERO { Motion::Fixed } else { Motion::Velocity(velocity) };
        s.colliders = vec![
            ColliderModel {
                shape: Shape::Ground { height: 0.0 },
                friction: Some(0.05),
                motion: Motion::Fixed,
            },
            ColliderModel { motion, ..ColliderModel::sphere(DVec3::new(0.0, 0.165, 0.0), 0.15) },
        ];
        let mut gpu = GpuSim::new(&ctx, &s).unwrap();
        gpu.set_fused(fused);
        let start = centre(&gpu.read_states(&ctx).unwrap());
        for _ in 0..60 {
            gpu.step_frame(&ctx).unwrap();
        }
        let end = centre(&gpu.read_states(&ctx).unwrap());
        gpu.destroy(&ctx);
        end - start
    };
    for fused in [true, false] {
        let dragged = run(DVec3::new(0.5, 0.0, 0.0), fused);
        let still = run(DVec3::ZERO, fused);
        eprintln!("fused {fused}: moving sphere {dragged}, still sphere {still}");
        assert!(dragged.x > 0.05 && dragged.z.abs() < 0.02, "fused {fused}: the cloth moved {dragged}");
        assert!(
            still.x.abs() < 0.01 && still.z.abs() < 0.01,
            "fused {fused}: with a still sphere it moved {still}"
        );
    }
    assert_clean(&ctx);
}
