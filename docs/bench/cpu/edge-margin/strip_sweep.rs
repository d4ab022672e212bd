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
    let modes: Vec<bool> =
        std::env::var("MODES").map(|s| s.split(',').map(|t| t == "1").collect()).unwrap_or(vec![false, true]);
    for edges in modes.clone() {
        let mut out = Vec::new();
        let mut fars = Vec::new();
        let mut lasts = Vec::new();
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
                *p = DVec3::new(
                    (i % 5) as f64 * 0.025 - 0.05,
                    1.6 - row * 0.025 * tilt.cos(),
                    row * 0.025 * tilt.sin(),
                );
            }
            c.margin = 0.005;
            c.friction = std::env::var("MU").map(|s| s.parse().unwrap()).unwrap_or(0.5);
            let mut s = scene(vec![c]);
            s.gravity = DVec3::new(0.0, -9.81, 0.0);
            let ground = Shape::Ground { height: 0.0 };
            s.colliders = vec![ColliderModel { shape: ground, friction: None, motion: Motion::Fixed }];
            let m = SimModel { contact_iterations: 4, ..s.clone() };
            let mut cpu = CpuSim::new(&m);
            let mut r = 0;
            let mut far = 0;
            let mut last = 0;
            for _ in 0..45 {
                cpu.step_frame();
                let x = &cpu.objects()[0].x;
                last = crossings(x, 5, 61);
                r = r.max(last);
                if last > 0 {
                    let h = far_crossings(x, 5, 61);
                    far = far.max(h[2..].iter().sum::<usize>());
                }
            }
            out.push(r);
            fars.push(far);
            lasts.push(last);
        }
        println!("edges {edges}: reference worst crossings over 24 tilts: {out:?} sum {} zero {}\n far (grid >= 2) {fars:?}\n last {lasts:?}", out.iter().sum::<usize>(), out.iter().filter(|&&k| k == 0).count());
    }
}
fn far_crossings(x: &[DVec3], cols: usize, rows: usize) -> [usize; 6] {
    let mut hist = [0usize; 6];
    for e in cloth_edges(cols, rows) {
        for t in cloth_triangles(cols, rows) {
            if t.contains(&e[0]) || t.contains(&e[1]) {
                continue;
            }
            if segment_through(x[e[0]], x[e[1]], t.map(|k| x[k])) {
                let g = e
                    .iter()
                    .flat_map(|&a| {
                        t.iter().map(move |&b| {
                            ((a % cols) as i64 - (b % cols) as i64)
                                .abs()
                                .max(((a / cols) as i64 - (b / cols) as i64).abs())
                        })
                    })
                    .min()
                    .unwrap();
                hist[(g as usize).min(5)] += 1;
            }
        }
    }
    hist
}
