mod common;
use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::cpu::CpuSim;
use msdsim::sim::model::SimModel;

fn crossings(x: &[DVec3], cols: usize, rows: usize) -> usize {
    segments_through(x, &cloth_edges(cols, rows), x, &cloth_triangles(cols, rows), true)
}

#[test]
fn strip_sweep() {
    let tilts: Vec<f64> = (1..=24).map(|k| k as f64 * 0.02).collect();
    let modes: Vec<bool> = std::env::var("MODES").map(|s| s.split(',').map(|t| t == "1").collect()).unwrap_or(vec![false, true]);
    for edges in modes.clone() {
        let mut out = Vec::new();
        for &tilt in &tilts {
            let mut c = cloth(5, 61, 0.025);
            c.stiffness = [400.0, 100.0, 0.5];
            c.damping = 0.01;
            c.drag = 0.002;
            c.mass = 0.002;
            c.stretch_limit = Some(0.1);
            c.self_distance = Some(0.0125);
            c.triangle_contact = true;
            c.edge_contact = edges;
            for (i, p) in c.positions.iter_mut().enumerate() {
                let row = (i / 5) as f64;
                *p = DVec3::new((i % 5) as f64 * 0.025 - 0.05, 1.6 - row * 0.025 * tilt.cos(), row * 0.025 * tilt.sin());
            }
            c.margin = 0.005;
            c.friction = std::env::var("MU").map(|s| s.parse().unwrap()).unwrap_or(0.5);
            let mut s = scene(vec![c]);
            s.gravity = DVec3::new(0.0, -9.81, 0.0);
            let ground = Shape::Ground { height: 0.0 };
            s.colliders = vec![ColliderModel { shape: ground, friction: None, motion: Motion::Fixed }];
            let m = SimModel { contact_iterations: 4, ..s.clone() };
            let mut cpu = CpuSim::new(&m);
            let r = (0..45).map(|_| { cpu.step_frame(); crossings(&cpu.objects()[0].x, 5, 61) }).max().unwrap();
            out.push(r);
        }
        println!("edges {edges}: reference worst crossings over 24 tilts: {out:?} sum {} zero {}", out.iter().sum::<usize>(), out.iter().filter(|&&k| k == 0).count());
    }
}
