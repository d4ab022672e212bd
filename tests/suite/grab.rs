//! Grabbing a particle with the mouse: the pick finds the particle under a ray, and the GPU
//! write path (`GpuSim::set_particle`, applied inside the next frame's command buffer) holds a
//! grabbed particle at its target and frees it on release. Validation and synchronization
//! validation are on.

use crate::common;

use common::*;
use glam::{DVec3, Vec3};
use msdsim::app::{pick, PickRay};
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::gpu_types::Particle;

#[test]
fn a_ray_picks_the_particle_under_it_and_misses_empty_space() {
    let ctx = gpu();
    let c = cloth(13, 9, 0.05);
    let model = scene(vec![c.clone()]);
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    let states = sim.read_states(&ctx).unwrap();
    let target = c.positions[4 * 13 + 6].as_vec3();
    let origin = target + Vec3::new(0.003, 0.002, 2.0);
    // 45 degrees over 800 pixels: a pick radius of 12 pixels is 2.3 cm at 2 m.
    let pixel = 2.0 * (45f32.to_radians() * 0.5).tan() / 800.0;
    let ray = |origin: Vec3, dir: Vec3| PickRay { origin, dir, pixel };
    let hit = pick(&states, ray(origin, (target - origin).normalize()), &[0.0], f32::INFINITY);
    assert_eq!(hit.map(|h| (h.0, h.1)), Some((0, 4 * 13 + 6)), "{hit:?}");
    assert!((hit.unwrap().2 - 2.0).abs() < 0.01, "depth along the ray");
    assert!(pick(&states, ray(Vec3::new(5.0, 5.0, 2.0), Vec3::NEG_Z), &[0.0], f32::INFINITY).is_none());
    sim.destroy(&ctx);
    assert_clean(&ctx);
}

#[test]
fn a_grabbed_particle_follows_its_target_and_is_released() {
    let ctx = gpu();
    let mut c = cloth(13, 9, 0.05);
    c.stiffness = [200.0, 50.0, 10.0];
    c.drag = 0.01;
    for col in 0..13 {
        c.pinned[col] = true;
    }
    let mut model = scene(vec![c.clone()]);
    model.gravity = DVec3::new(0.0, -9.81, 0.0);
    let mut sim = GpuSim::new(&ctx, &model).unwrap();
    let grabbed = 8 * 13 + 6; // bottom middle
    let start = c.positions[grabbed].as_vec3();
    let mut target = start;
    for frame in 0..20 {
        target += Vec3::new(0.0, 0.0, 0.01); // drag towards +z, 1 cm per frame
        let held = Particle { pos: [target.x, target.y, target.z, 1.0], vel: [0.0; 4] };
        sim.set_particle(0, grabbed as u32, held);
        sim.step_frame(&ctx).unwrap();
        let p = sim.read_states(&ctx).unwrap()[0].particles[grabbed];
        assert_eq!([p.pos[0], p.pos[1], p.pos[2]], target.to_array(), "frame {frame}: held at the target");
    }
    let states = sim.read_states(&ctx).unwrap();
    let neighbour = states[0].particles[7 * 13 + 6];
    assert!(neighbour.pos[2] > 0.05, "the neighbour follows the drag: z = {}", neighbour.pos[2]);
    // Release: unpinned, it falls back under gravity and the springs.
    sim.set_particle(0, grabbed as u32, Particle { pos: [target.x, target.y, target.z, 0.0], vel: [0.0; 4] });
    for _ in 0..10 {
        sim.step_frame(&ctx).unwrap();
    }
    let p = sim.read_states(&ctx).unwrap()[0].particles[grabbed];
    assert_eq!(p.pos[3], 0.0, "released particles are free");
    assert!(p.pos[2] < target.z - 0.02, "released, it swings back: z = {} (was {})", p.pos[2], target.z);
    sim.destroy(&ctx);
    assert_clean(&ctx);
}
