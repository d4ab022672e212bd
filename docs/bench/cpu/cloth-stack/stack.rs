mod common;
use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::cpu::CpuSim;

fn free_cloth(n: u32, spacing: f64, y: f64, shift: DVec3) -> msdsim::sim::model::ObjectModel {
    let mut c = cloth(n, n, spacing);
    let half = 0.5 * (n - 1) as f64 * spacing;
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i as u32 % n) as f64, (i as u32 / n) as f64);
        *p = DVec3::new(col * spacing - half, y, row * spacing - half) + shift;
    }
    c.stiffness = [1000.0, 250.0, 5.0];
    c.mass = 0.002 * (spacing / 0.025).powi(2);
    c.damping = 0.02;
    c.drag = 0.002 * (spacing / 0.025).powi(2);
    c.margin = std::env::var("MARGIN").map(|s| s.parse().unwrap()).unwrap_or(0.005);
    c.friction = 0.5;
    c
}

#[test]
fn stack() {
    let layers: usize = std::env::var("LAYERS").map(|s| s.parse().unwrap()).unwrap_or(5);
    let gap: f64 = std::env::var("GAP").map(|s| s.parse().unwrap()).unwrap_or(0.03);
    let n = 11u32;
    let objects: Vec<_> = (0..layers)
        .map(|k| free_cloth(n, 0.03, 0.05 + gap * k as f64, DVec3::new(0.007 * k as f64, 0.0, 0.011 * k as f64)))
        .collect();
    let mut s = scene(objects);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    s.colliders = vec![ColliderModel { shape: Shape::Ground { height: 0.0 }, friction: None, motion: Motion::Fixed }];
    let (t, e) = (cloth_triangles(n as usize, n as usize), cloth_edges(n as usize, n as usize));
    let through = |x: &[Vec<DVec3>]| {
        let mut k = 0;
        for a in 0..x.len() {
            for b in 0..x.len() {
                if a != b {
                    k += segments_through(&x[a], &e, &x[b], &t, false);
                }
            }
        }
        k
    };
    let mean_y = |x: &[Vec<DVec3>]| x.iter().map(|o| o.iter().map(|p| p.y).sum::<f64>() / o.len() as f64).collect::<Vec<_>>();
    let frames: usize = std::env::var("FRAMES").map(|s| s.parse().unwrap()).unwrap_or(60);
    let mut cpu = CpuSim::new(&s);
    let mut worst = 0;
    for _ in 0..frames {
        cpu.step_frame();
        let x: Vec<Vec<DVec3>> = cpu.objects().iter().map(|o| o.x.clone()).collect();
        worst = worst.max(through(&x));
    }
    let x: Vec<Vec<DVec3>> = cpu.objects().iter().map(|o| o.x.clone()).collect();
    println!("reference: worst {worst} edges through another cloth; mean heights at the end {:?}", mean_y(&x));
    let ctx = gpu();
    let mut worst = 0;
    let mut last = Vec::new();
    run_gpu(&ctx, &s, frames, |_, st| {
        let x: Vec<Vec<DVec3>> = st.iter().map(|o| o.positions()).collect();
        worst = worst.max(through(&x));
        last = x;
    });
    println!("GPU: worst {worst} edges through another cloth; mean heights at the end {:?}", mean_y(&last));
    assert_clean(&ctx);
}
