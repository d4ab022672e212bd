//! Colliders that move (kinematic bodies): their contacts follow their velocity, so friction
//! drags what they touch. On lavapipe with validation and synchronization validation, both GPU
//! paths (fused and per stage).

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::turn::Turn;

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
        let s = cloth_on_ground(velocity);
        let mut gpu = GpuSim::new(&ctx, &s).unwrap();
        gpu.set_fused(&ctx, fused).unwrap();
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

/// The test scene of the drag tests: a 12 x 12 cloth lying on a slippery ground, a sphere on
/// its middle moving at `velocity`.
fn cloth_on_ground(velocity: DVec3) -> msdsim::sim::model::SimModel {
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
            turn: Turn::default(),
        },
        ColliderModel { motion, ..ColliderModel::sphere(DVec3::new(0.0, 0.165, 0.0), 0.15) },
    ];
    s
}

/// Dragging a collider in the app: each frame the editor moves the sphere 0.5/60 m in x and
/// the simulation takes the new parameters in place (`update_params`, as the app does). The
/// sphere then moves during the frame rather than jumping, so the cloth under it is dragged as
/// by the sphere moving at 0.5 m/s: by more than 5 cm in 1 s (jumping, friction would see a
/// still sphere); let go, the cloth coasts to rest within 10 cm in the next second (measured
/// 4.1 cm; while the buffer kept the last drag's move, the sphere went on sweeping it 0.50 m).
#[test]
fn dragging_a_collider_drags_what_it_touches() {
    let ctx = gpu();
    let mut s = cloth_on_ground(DVec3::ZERO);
    let mut gpu = GpuSim::new(&ctx, &s).unwrap();
    let start = centre(&gpu.read_states(&ctx).unwrap());
    for _ in 0..60 {
        if let Shape::Sphere { center, .. } = &mut s.colliders[1].shape {
            center.x += 0.5 / 60.0;
        }
        gpu.update_params(&s).unwrap();
        gpu.step_frame(&ctx).unwrap();
    }
    let moved = centre(&gpu.read_states(&ctx).unwrap()) - start;
    // Let go: the sphere stays where it was left, and so does what it touched (the frame after
    // the last drag wrote the records at rest again; before, the last drag's move was kept and
    // the sphere went on dragging the cloth at 0.5 m/s).
    for _ in 0..60 {
        gpu.step_frame(&ctx).unwrap();
    }
    let after = centre(&gpu.read_states(&ctx).unwrap()) - start - moved;
    gpu.destroy(&ctx);
    eprintln!("dragged sphere: the cloth moved {moved}, then {after} after it was let go");
    assert!(moved.x > 0.05 && moved.z.abs() < 0.02, "the cloth moved {moved}");
    assert!(after.x.abs() < 0.1, "the cloth moved on by {after} after the drag ended");
    assert_clean(&ctx);
}

/// Discrete contact's speed limit (`sim::collider::contact_speed`), on both sides: two free
/// nodes shot at a capsule (radius 2 cm, margin 1 cm; the limit is (0.02 + 0.01) / dt = 28.8
/// m/s at 16 substeps of 1/60 s). At half the limit they stop on the near side; at three
/// times it they cross a capsule's width in one substep and come out on the far side, and
/// the simulation says so (the guard's contact-speed warning), which it does not at half.
#[test]
fn contact_speed_limit_holds_on_both_sides() {
    let ctx = gpu();
    for fused in [true, false] {
        for factor in [0.5, 3.0] {
            let mut r = rope(2, 0.1);
            r.positions = vec![DVec3::new(-0.5, 0.0, -0.05), DVec3::new(-0.5, 0.0, 0.05)];
            r.margin = 0.01;
            let mut s = scene(vec![r]);
            s.colliders = vec![ColliderModel {
                shape: Shape::Capsule {
                    a: DVec3::new(0.0, 0.0, -0.5),
                    b: DVec3::new(0.0, 0.0, 0.5),
                    radius: 0.02,
                },
                friction: None,
                motion: Motion::Fixed,
                turn: Turn::default(),
            }];
            let limit = msdsim::sim::collider::contact_speed(&s).expect("a capsule sets a limit");
            assert!((limit.speed - 0.03 / s.dt()).abs() < 1e-9, "{limit}");
            let speed = factor * limit.speed;
            s.objects[0].velocities.fill(DVec3::new(speed, 0.0, 0.0));
            let mut gpu = GpuSim::new(&ctx, &s).unwrap();
            gpu.set_fused(&ctx, fused).unwrap();
            for _ in 0..5 {
                gpu.step_frame(&ctx).unwrap();
            }
            let x = gpu.read_states(&ctx).unwrap()[0].positions();
            let warned = gpu.take_warning();
            gpu.destroy(&ctx);
            if factor < 1.0 {
                assert!(
                    x.iter().all(|p| p.x < -0.029),
                    "fused {fused}: at {speed:.1} m/s a node got through: {x:?}"
                );
                assert!(warned.is_none(), "fused {fused}: warned at {speed:.1} m/s: {warned:?}");
            } else {
                assert!(
                    x.iter().all(|p| p.x > 0.03),
                    "fused {fused}: at {speed:.1} m/s it did not tunnel: {x:?}"
                );
                let warned = warned.expect("a warning past the limit");
                assert!(warned.contains("faster than contacts are exact"), "{warned}");
            }
        }
    }
    assert_clean(&ctx);
}

/// A cloth dropped at 1 m/s onto a rod thinner than its spacing (a capsule of 4 mm radius,
/// the cloth's margin 5 mm, spacing 2.5 cm) lying between two particle columns: the particles
/// pass 12.5 mm from the rod's axis, beyond the 9 mm they keep from it, so only its edges can
/// hold it (before edges were tested it fell through). At every frame, every row's edge that
/// spans the rod must cross above it (its point over the axis higher than the axis), and at
/// the end (1 s) the cloth must hang on the rod: its centre within 5 cm below it, not fallen.
/// On the CPU reference and both GPU paths.
#[test]
fn a_rod_thinner_than_the_spacing_holds_a_cloth() {
    let ctx = gpu();
    let n = 12u32;
    let h = 0.025;
    let rod_x = 5.5 * h; // between columns 5 and 6
    let rod_y = 0.3;
    let mut c = cloth(n, n, h);
    for (i, p) in c.positions.iter_mut().enumerate() {
        *p = DVec3::new((i as u32 % n) as f64 * h, rod_y + 0.02, (i as u32 / n) as f64 * h - 0.1375);
    }
    c.velocities.fill(DVec3::new(0.0, -1.0, 0.0));
    c.stiffness = [400.0, 100.0, 1.0];
    c.damping = 0.01;
    c.mass = 0.002;
    c.margin = 0.005;
    c.friction = 0.3;
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.colliders = vec![ColliderModel {
        shape: Shape::Capsule {
            a: DVec3::new(rod_x, rod_y, -0.5),
            b: DVec3::new(rod_x, rod_y, 0.5),
            radius: 0.004,
        },
        friction: None,
        motion: Motion::Fixed,
        turn: Turn::default(),
    }];
    assert!(msdsim::sim::collider::edges_needed(&s.objects[0], &s.colliders));
    // The lowest crossing over the rod's axis, over every row, relative to the axis.
    let crossing = |x: &[DVec3]| -> f64 {
        (0..n as usize)
            .map(|row| {
                let (a, b) = (x[row * n as usize + 5], x[row * n as usize + 6]);
                let t = ((rod_x - a.x) / (b.x - a.x)).clamp(0.0, 1.0);
                a.lerp(b, t).y - rod_y
            })
            .fold(f64::MAX, f64::min)
    };
    for (path, frames_x) in every_path_each_frame(&ctx, &s, 60) {
        let lowest = frames_x.iter().map(|x| crossing(x)).fold(f64::MAX, f64::min);
        let end = frames_x.last().unwrap();
        let centre = end.iter().map(|p| p.y).sum::<f64>() / end.len() as f64 - rod_y;
        eprintln!(
            "{path}: lowest crossing {lowest:.4} m over the rod's axis; centre at the end {centre:.4} m"
        );
        assert!(lowest > 0.0, "{path}: the cloth passed through the rod ({lowest:.4} m)");
        assert!(centre > -0.05, "{path}: the cloth fell off the rod (centre {centre:.3} m)");
    }
    assert_clean(&ctx);
}

/// A rebuild that carries the state over (the app's editor changing the substep count) goes
/// on at the same simulated time, so a moving collider stays where it was: the cloth dragged
/// by the sphere at 0.5 m/s for 0.5 s, then rebuilt at 32 substeps for 0.5 s more, ends
/// within 1 mm of the run that was not rebuilt (lavapipe: 6.8e-5 m, the substep count's own
/// difference; with the clock restarted the sphere jumps back 0.25 m and the cloth ends
/// 1.3e-2 m away). A new frame_dt taken in place keeps the time continuous too.
#[test]
fn a_rebuild_keeps_the_time_and_the_colliders_motion() {
    let ctx = gpu();
    let s = cloth_on_ground(DVec3::new(0.5, 0.0, 0.0));
    let mut whole = GpuSim::new(&ctx, &s).unwrap();
    for _ in 0..30 {
        whole.step_frame(&ctx).unwrap();
    }
    let mut finer = s.clone();
    finer.substeps = 32;
    let mut rebuilt = GpuSim::new(&ctx, &finer).unwrap();
    rebuilt.continue_at(whole.time());
    let particles: Vec<_> = whole.read_states(&ctx).unwrap().iter().map(|o| o.particles.clone()).collect();
    rebuilt.upload_states(&ctx, &particles).unwrap();
    for _ in 0..30 {
        whole.step_frame(&ctx).unwrap();
        rebuilt.step_frame(&ctx).unwrap();
    }
    let (a, b) = (centre(&whole.read_states(&ctx).unwrap()), centre(&rebuilt.read_states(&ctx).unwrap()));
    eprintln!("not rebuilt {a}, rebuilt {b}: {:.2e} m apart", (a - b).length());
    assert!((a - b).length() < 1e-3, "the rebuilt run's cloth is {:.3} m from the other's", (a - b).length());
    assert!((rebuilt.time() - 1.0).abs() < 1e-9, "rebuilt at t = 0.5 s, 30 frames on: {}", rebuilt.time());
    let before = rebuilt.time();
    let mut slower = finer.clone();
    slower.frame_dt *= 2.0;
    ctx.wait_idle().unwrap();
    rebuilt.update_params(&slower).unwrap();
    assert!(
        (rebuilt.time() - before).abs() < 1e-12,
        "a new frame_dt moved the clock {before} -> {}",
        rebuilt.time()
    );
    rebuilt.step_frame(&ctx).unwrap();
    assert!((rebuilt.time() - before - slower.frame_dt).abs() < 1e-12);
    whole.destroy(&ctx);
    rebuilt.destroy(&ctx);
    assert_clean(&ctx);
}
