mod common;
use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::cpu::CpuSim;
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::model::SimModel;

fn crossings(x: &[DVec3], cols: usize, rows: usize) -> usize {
    segments_through(x, &cloth_edges(cols, rows), x, &cloth_triangles(cols, rows), true)
}

#[test]
fn strip() {
    let tilts: Vec<f64> = std::env::var("TILTS").map(|s| s.split(',').map(|t| t.parse().unwrap()).collect()).unwrap_or(vec![0.2]);
    let passes: Vec<u32> = std::env::var("PASSES").map(|s| s.split(',').map(|t| t.parse().unwrap()).collect()).unwrap_or(vec![4, 8]);
    let ctx = gpu();
    for tilt in tilts {
        let mut c = cloth(5, 61, 0.025);
        c.stiffness = [400.0, 100.0, 0.5];
        c.damping = 0.01;
        c.drag = 0.002;
        c.mass = 0.002;
        c.stretch_limit = Some(0.1);
        c.self_distance = Some(0.0125);
        c.triangle_contact = true;
        c.edge_contact = true;
        for (i, p) in c.positions.iter_mut().enumerate() {
            let row = (i / 5) as f64;
            *p = DVec3::new((i % 5) as f64 * 0.025 - 0.05, 1.6 - row * 0.025 * tilt.cos(), row * 0.025 * tilt.sin());
        }
        c.margin = 0.005;
        c.friction = 0.5;
        let mut s = scene(vec![c]);
        s.gravity = DVec3::new(0.0, -9.81, 0.0);
        let ground = Shape::Ground { height: 0.0 };
        s.colliders = vec![ColliderModel { shape: ground, friction: None, motion: Motion::Fixed }];
        for &k in &passes {
            let m = SimModel { contact_iterations: k, ..s.clone() };
            let mut cpu = CpuSim::new(&m);
            let r = (0..45).map(|_| { cpu.step_frame(); crossings(&cpu.objects()[0].x, 5, 61) }).max().unwrap();
            let mut g_out = vec![];
            for fused in [false, true] {
                let mut g = GpuSim::new(&ctx, &m).unwrap();
                g.set_fused(&ctx, fused).unwrap();
                let w = (0..45).map(|_| { g.step_frame(&ctx).unwrap(); crossings(&g.read_states(&ctx).unwrap()[0].positions(), 5, 61) }).max().unwrap();
                g.destroy(&ctx);
                g_out.push(w);
            }
            println!("tilt {tilt} passes {k}: reference {r}, per stage {}, fused {}", g_out[0], g_out[1]);
        }
    }
    assert_clean(&ctx);
}
