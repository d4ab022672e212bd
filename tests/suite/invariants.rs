//! Invariants of the GPU simulation, checked on lavapipe with validation and synchronization
//! validation (any message fails the test).

use crate::common;

use common::*;
use glam::DVec3;

fn pos(p: &msdsim::sim::gpu_types::Particle) -> DVec3 {
    DVec3::new(p.pos[0] as f64, p.pos[1] as f64, p.pos[2] as f64)
}

/// Pinned particles keep their exact initial position (bit for bit) and zero velocity, with
/// every force and constraint acting around them.
#[test]
fn pinned_particles_do_not_move() {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    c.stiffness = [80.0, 20.0, 5.0];
    c.stretch_limit = Some(0.05);
    c.self_distance = Some(0.02);
    c.friction = 0.5;
    c.margin = 0.01;
    for col in 0..13 {
        c.pinned[col] = true;
    }
    c.pinned[5 * 13 + 4] = true;
    let pinned: Vec<(usize, [f32; 3])> = c
        .pinned
        .iter()
        .enumerate()
        .filter(|(_, p)| **p)
        .map(|(i, _)| (i, c.positions[i].as_vec3().to_array()))
        .collect();
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.wind = Some(wind([0.3, 0.8, 1.0], [0.0, 0.0, -1.0], 0.05, 0.4, 0.8));
    s.colliders = vec![sphere([0.3, 0.7, 0.1], 0.15)];
    run_gpu(&ctx, &s, 30, |f, states| {
        for &(i, x0) in &pinned {
            let p = states[0].particles[i];
            assert_eq!([p.pos[0], p.pos[1], p.pos[2]], x0, "frame {f}: pinned particle {i} moved");
            assert_eq!(p.vel, [0.0; 4], "frame {f}: pinned particle {i} has velocity");
        }
    });
    assert_clean(&ctx);
}

/// A cloth at its rest shape with no gravity, wind or initial velocity feels only rounding-level
/// forces (spring lengths equal rest lengths to f32 precision, ~3e-9 m on 5 cm springs), so after
/// 480 substeps no particle may have moved 1e-6 m.
#[test]
fn cloth_at_rest_without_gravity_stays_at_rest() {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    c.stiffness = [400.0, 100.0, 40.0];
    c.damping = 0.01;
    c.drag = 0.01;
    c.stretch_limit = Some(0.1);
    c.self_distance = Some(0.02);
    let x0 = c.positions.clone();
    run_gpu(&ctx, &scene(vec![c]), 30, |f, states| {
        for (p, x0) in states[0].particles.iter().zip(&x0) {
            let moved = pos(p).distance(x0.as_vec3().as_dvec3());
            assert!(moved < 1e-6, "frame {f}: a particle moved {moved} m");
        }
    });
    assert_clean(&ctx);
}

/// After every frame (which ends with a constraint stage) no particle is closer to a sphere's
/// centre than radius + margin, up to f32 rounding of the projection (1e-6 m). The cloth is
/// thrown at four separate spheres at 3 m/s.
#[test]
fn no_particle_inside_a_sphere_after_the_constraint_stage() {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    for (i, p) in c.positions.iter_mut().enumerate() {
        *p = DVec3::new((i % 13) as f64 * 0.05 - 0.3, 0.6, (i / 13) as f64 * 0.05 - 0.2);
    }
    c.velocities.fill(DVec3::new(0.0, -3.0, 0.0));
    c.stiffness = [80.0, 20.0, 2.0];
    c.margin = 0.01;
    c.friction = 0.2;
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.colliders = vec![
        sphere([-0.15, 0.2, 0.0], 0.12),
        sphere([0.15, 0.25, 0.05], 0.1),
        sphere([0.0, 0.1, 0.15], 0.08),
        sphere([0.25, 0.0, -0.15], 0.1),
    ];
    let spheres = s.colliders.clone();
    let mut contacts = 0;
    run_gpu(&ctx, &s, 30, |f, states| {
        for p in &states[0].particles {
            for sp in &spheres {
                let d = sp.shape.distance(pos(p)).0;
                assert!(d >= 0.01 - 1e-6, "frame {f}: a particle is {} m inside a sphere's margin", 0.01 - d);
                contacts += (d < 0.01 + 1e-3) as usize;
            }
        }
    });
    assert!(contacts > 0, "the cloth never touched a sphere");
    assert_clean(&ctx);
}

/// A scene symmetric under x -> -x (cloth centred over a sphere, symmetric pins, wind in the
/// symmetry plane, all features on) stays symmetric: particle (c, r) mirrors (12 - c, r).
/// Mirrored particles sum their springs in mirrored order, so rounding differs (1e-8 m per
/// substep); we allow 1e-5 m after 240 substeps.
#[test]
fn mirror_symmetric_scene_stays_symmetric() {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    for (i, p) in c.positions.iter_mut().enumerate() {
        *p = DVec3::new((i % 13) as f64 * 0.05 - 0.3, 0.5, (i / 13) as f64 * 0.05 - 0.2);
    }
    c.stiffness = [80.0, 20.0, 5.0];
    c.damping = 0.01;
    c.drag = 0.01;
    c.stretch_limit = Some(0.1);
    c.self_distance = Some(0.02);
    c.friction = 0.3;
    c.margin = 0.01;
    c.pinned[0] = true;
    c.pinned[12] = true;
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.colliders = vec![sphere([0.0, 0.3, 0.0], 0.15)];
    s.wind = Some(wind([0.0, 1.0, 0.5], [0.0, -1.0, -0.5], 0.02, 0.5, 0.9));
    let mut worst: f64 = 0.0;
    run_gpu(&ctx, &s, 15, |_, states| {
        let p = &states[0].particles;
        for r in 0..9 {
            for col in 0..13 {
                let (a, b) = (pos(&p[r * 13 + col]), pos(&p[r * 13 + 12 - col]));
                worst = worst.max(a.distance(DVec3::new(-b.x, b.y, b.z)));
            }
        }
    });
    println!("largest asymmetry: {worst:e} m");
    assert!(worst < 1e-5, "the scene lost its symmetry by {worst} m");
    assert_clean(&ctx);
}

/// A 1 m cloth dropped from 0.6 m onto a low table (a turned box) next to a capsule, over a ground:
/// at every frame no particle is nearer to any collider than its margin minus 1 mm. (Each
/// collider's projection is exact, up to f32 rounding; the millimetre allows for where two
/// colliders meet and the second projection moves a particle towards the first.) Both paths:
/// fused in one workgroup and a dispatch per stage. Contacts with each collider are counted, so
/// the test fails if the cloth misses one.
#[test]
fn no_particle_within_the_margin_of_a_ground_box_or_capsule() {
    use msdsim::sim::collider::{ColliderModel, Motion, Shape};
    use msdsim::sim::turn::Turn;
    let ctx = gpu();
    let mut c = cloth(20, 20, 0.05);
    for (i, p) in c.positions.iter_mut().enumerate() {
        *p = DVec3::new((i % 20) as f64 * 0.05 - 0.55, 0.6, (i / 20) as f64 * 0.05 - 0.475);
    }
    c.stiffness = [200.0, 50.0, 5.0];
    c.damping = 0.02;
    c.margin = 0.01;
    c.friction = 0.4;
    c.stretch_limit = Some(0.1);
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.substeps = 16;
    s.colliders = vec![
        ColliderModel {
            shape: Shape::Ground { height: 0.0 },
            friction: Some(0.8),
            motion: Motion::Fixed,
            turn: Turn::default(),
        },
        ColliderModel {
            shape: Shape::Box {
                center: DVec3::new(-0.2, 0.1, 0.0),
                half_extents: DVec3::new(0.2, 0.1, 0.25),
                rotation: glam::DQuat::from_rotation_y(0.3),
            },
            friction: None,
            motion: Motion::Fixed,
            turn: Turn::default(),
        },
        ColliderModel {
            shape: Shape::Capsule {
                a: DVec3::new(0.2, 0.1, -0.3),
                b: DVec3::new(0.25, 0.12, 0.3),
                radius: 0.08,
            },
            friction: None,
            motion: Motion::Fixed,
            turn: Turn::default(),
        },
    ];
    for fused in [true, false] {
        let mut gpu = msdsim::sim::gpu::GpuSim::new(&ctx, &s).unwrap();
        gpu.set_fused(&ctx, fused).unwrap();
        let mut contacts = [0usize; 3];
        let mut worst = f64::MAX;
        for f in 0..90 {
            gpu.step_frame(&ctx).unwrap();
            for p in &gpu.read_states(&ctx).unwrap()[0].particles {
                for (k, collider) in s.colliders.iter().enumerate() {
                    let d = collider.shape.distance(pos(p)).0;
                    worst = worst.min(d);
                    assert!(d >= 0.01 - 1e-3, "fused {fused}, frame {f}: a particle {d} m from collider {k}");
                    contacts[k] += (d < 0.01 + 1e-3) as usize;
                }
            }
        }
        gpu.destroy(&ctx);
        assert!(contacts.iter().all(|&n| n > 0), "fused {fused}: contacts per collider {contacts:?}");
        eprintln!("fused {fused}: contacts {contacts:?}, nearest {worst:.6} m (margin 0.01)");
    }
    assert_clean(&ctx);
}

/// The rope's tube frame is rotation-minimising: a rope that runs along x, turns down into a
/// near-vertical run (wobbling by a millimetre, where the paper's frame, side = forward x world
/// up, spins about the rope from node to node) and turns back along x. Between neighbouring
/// nodes the tube's side direction turns by no more than the rope's own direction does (plus
/// 1e-3 rad of f32 rounding), and every ring keeps the tube's radius.
#[test]
fn the_rope_tube_neither_twists_nor_pinches() {
    use msdsim::vk::Access;
    let ctx = gpu();
    let mut r = rope(40, 0.05);
    for (i, p) in r.positions.iter_mut().enumerate() {
        let wobble = 0.001 * (i as f64 * 2.1).sin();
        *p = match i {
            0..=9 => DVec3::new(i as f64 * 0.05, 1.0, 0.0),
            10..=29 => DVec3::new(0.45 + wobble, 1.0 - (i - 9) as f64 * 0.05, 0.001 * (i as f64 * 1.3).cos()),
            _ => DVec3::new(0.45 + (i - 29) as f64 * 0.05, 0.0, 0.0),
        };
    }
    r.rope_radius = 0.02;
    let s = scene(vec![r]);
    let mut sim = msdsim::sim::gpu::GpuSim::new(&ctx, &s).unwrap();
    assert!(sim.take_surface_stale());
    ctx.one_shot("surface", |rec| {
        sim.record_surface(rec, Access::ComputeReadWrite);
        Ok(())
    })
    .unwrap();
    let state = &sim.read_states(&ctx).unwrap()[0];
    sim.destroy(&ctx);
    let x = state.positions();
    let n = x.len();
    let unit = |v: DVec3| v.normalize_or_zero();
    let forward = |i: usize| {
        let to_next = if i + 1 < n { unit(x[i + 1] - x[i]) } else { DVec3::ZERO };
        let from_prev = if i > 0 { unit(x[i] - x[i - 1]) } else { DVec3::ZERO };
        unit(to_next + from_prev)
    };
    let ring = msdsim::sim::gpu_types::ROPE_RING;
    let side = |i: usize| {
        let v = glam::Vec3::from_slice(&state.surface[i * ring].pos[..3]).as_dvec3();
        v - x[i]
    };
    for (i, &at) in x.iter().enumerate() {
        for k in 0..ring {
            let v = glam::Vec3::from_slice(&state.surface[i * ring + k].pos[..3]).as_dvec3();
            let radius = (v - at).length();
            assert!((radius - 0.02).abs() < 1e-5, "node {i} vertex {k}: radius {radius}");
        }
    }
    for i in 0..n - 1 {
        let turned = unit(side(i)).angle_between(unit(side(i + 1)));
        let bent = forward(i).angle_between(forward(i + 1));
        assert!(
            turned <= bent + 1e-3,
            "nodes {i}-{}: the side turned {turned} rad, the rope {bent} rad",
            i + 1
        );
    }
    assert_clean(&ctx);
}
