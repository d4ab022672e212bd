mod common;
use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::gpu::GpuSim;

#[test]
fn lists_diff() {
    let (cols, rows, sp) = (5usize, 61usize, 0.025);
    let tilt: f64 = std::env::var("TILT").map(|v| v.parse().unwrap()).unwrap_or(0.25);
    let mu: f64 = std::env::var("MU").map(|v| v.parse().unwrap()).unwrap_or(0.5);
    let mut c = cloth(cols as u32, rows as u32, sp);
    c.stiffness = [400.0, 100.0, 0.5];
    c.damping = 0.01;
    c.drag = 0.002;
    c.mass = 0.002;
    c.stretch_limit = Some(0.1);
    c.self_distance = Some(0.5 * sp);
    c.triangle_contact = true;
    c.edge_contact = true;
    for (i, p) in c.positions.iter_mut().enumerate() {
        let row = (i / cols) as f64;
        *p = DVec3::new((i % cols) as f64 * sp - 0.05, 0.1 + rows as f64 * sp - row * sp * tilt.cos(), row * sp * tilt.sin());
    }
    c.margin = 0.005;
    c.friction = mu;
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    let sub: u32 = std::env::var("SUB").map(|v| v.parse().unwrap()).unwrap_or(16);
    s.frame_dt = 1.0 / 60.0 / (16 / sub) as f64;
    s.substeps = sub;
    let frames: usize = std::env::var("FRAMES").map(|v| v.parse().unwrap()).unwrap_or(45);
    s.colliders = vec![ColliderModel { shape: Shape::Ground { height: 0.0 }, friction: None, motion: Motion::Fixed }];
    let ctx = gpu();
    let mut a = GpuSim::new(&ctx, &s).unwrap();
    let fused = std::env::var("FUSED").is_ok();
    a.set_fused(&ctx, fused).unwrap();
    a.force_contact_lists(Some(true));
    let mut b = GpuSim::new(&ctx, &s).unwrap();
    b.set_fused(&ctx, false).unwrap();
    b.force_contact_lists(Some(false));
    let mut sb = s.clone();
    sb.self_collision = msdsim::sim::model::SelfCollisionMethod::BruteForce;
    let mut bf = GpuSim::new(&ctx, &sb).unwrap();
    bf.set_fused(&ctx, false).unwrap();
    for f in 0..frames {
        bf.step_frame(&ctx).unwrap();
        let xbf = bf.read_states(&ctx).unwrap()[0].positions();
        a.step_frame(&ctx).unwrap();
        b.step_frame(&ctx).unwrap();
        let sa = a.read_states(&ctx).unwrap();
        let xa = sa[0].positions();
        let mut net = 0i64;
        let mut who = Vec::new();
        for (i, p) in sa[0].particles.iter().enumerate() {
            if p.vel[3] != 0.0 {
                let m = p.vel[3] as u32 - 1;
                net += (m / 1000) as i64 - (m % 1000) as i64;
                who.push((i, (m / 1000) as i64 - (m % 1000) as i64));
            }
        }
        if !who.is_empty() && (net != 0 || std::env::var("ALL").is_ok()) {
            println!("substep {f}: net walk - brute {net}: {who:?}");
        }
        let xb = b.read_states(&ctx).unwrap()[0].positions();
        let on_bf = (0..xa.len()).filter(|&i| xa[i] != xbf[i]).count();
        let off_bf = (0..xa.len()).filter(|&i| xb[i] != xbf[i]).count();
        if on_bf + off_bf > 0 { println!("frame {f}: differ from brute force: lists on {on_bf}, off {off_bf}"); }
        let (mut worst, mut at) = (0.0f64, 0usize);
        let mut differing = 0;
        for i in 0..xa.len() {
            let d = (xa[i] - xb[i]).length();
            if d > 0.0 { differing += 1; }
            if d > worst { worst = d; at = i; }
        }
        let ca = segments_through(&xa, &cloth_edges(cols, rows), &xa, &cloth_triangles(cols, rows), true);
        let cb = segments_through(&xb, &cloth_edges(cols, rows), &xb, &cloth_triangles(cols, rows), true);
        if differing > 0 && std::env::var("DUMP").is_ok() {
            let v: Vec<usize> = (0..xa.len()).filter(|&i| xa[i] != xb[i]).collect();
            println!("differing: {v:?}");
            let prev = std::fs::read_to_string("/tmp/prev_state.txt").unwrap_or_default();
            std::fs::write("/tmp/diverged_prev.txt", prev).unwrap();
            break;
        }
        std::fs::write("/tmp/prev_state.txt", xb.iter().map(|p| format!("{:.9} {:.9} {:.9}", p.x, p.y, p.z)).collect::<Vec<_>>().join("\n")).unwrap();
        println!("frame {f}: lists on {ca} off {cb} crossings; differ {differing} particles, most {worst:.3e} m at {at} (col {}, row {})", at % cols, at / cols);
    }
    a.destroy(&ctx);
    b.destroy(&ctx);
    bf.destroy(&ctx);
}
