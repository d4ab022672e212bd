mod common;
use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::cpu::CpuSim;

#[test]
fn probe() {
    let tilts: Vec<f64> =
        std::env::var("TILTS").unwrap_or("0.2".into()).split(',').map(|t| t.parse().unwrap()).collect();
    let edges = std::env::var("EDGEC").is_ok();
    let mu: f64 = std::env::var("MU").map(|m| m.parse().unwrap()).unwrap_or(0.5);
    let cols: usize = std::env::var("COLS").map(|v| v.parse().unwrap()).unwrap_or(5);
    let rows: usize = std::env::var("ROWS").map(|v| v.parse().unwrap()).unwrap_or(61);
    let sp: f64 = std::env::var("SP").map(|v| v.parse().unwrap()).unwrap_or(0.025);
    for tilt in tilts {
        let mut c = soft(cols as u32, rows as u32, sp);
        for (i, p) in c.positions.iter_mut().enumerate() {
            let row = (i / cols) as f64;
            *p = DVec3::new(
                (i % cols) as f64 * sp - 0.05,
                0.1 + rows as f64 * sp - row * sp * tilt.cos(),
                row * sp * tilt.sin(),
            );
        }
        c.margin = 0.005;
        c.friction = mu;
        c.edge_contact = edges;
        let mut s = scene(vec![c]);
        s.gravity = DVec3::new(0.0, -9.81, 0.0);
        s.colliders = vec![ColliderModel {
            shape: Shape::Ground { height: 0.0 },
            friction: None,
            motion: Motion::Fixed,
        }];
        if let Ok(path) = std::env::var("GPU") {
            let ctx = gpu();
            let mut g = msdsim::sim::gpu::GpuSim::new(&ctx, &s).unwrap();
            g.set_fused(&ctx, path == "fused").unwrap();
            if std::env::var("LISTS").is_ok() {
                g.force_contact_lists(Some(true));
            }
            let (mut worst, mut far, mut last) = (0, 0, 0);
            for f in 0..45 {
                g.step_frame(&ctx).unwrap();
                let states = g.read_states(&ctx).unwrap();
                let x = states[0].positions();
                last = segments_through(&x, &cloth_edges(cols, rows), &x, &cloth_triangles(cols, rows), true);
                worst = worst.max(last);
                if std::env::var("TRACE").is_ok() {
                    let vmax = states[0].velocities().iter().map(|v| v.length()).fold(0.0, f64::max);
                    let low = x.iter().map(|p| p.y).fold(f64::MAX, f64::min);
                    println!(
                        "  frame {f} crossings {last} hist {:?} vmax {vmax:.3} lowest {low:.4}",
                        far_crossings(&x, cols, rows)
                    );
                }
                if last > 0 {
                    far = far.max(far_crossings(&x, cols, rows)[2..].iter().sum::<usize>());
                }
            }
            g.destroy(&ctx);
            println!("tilt {tilt:.2} GPU {path} worst {worst} far {far} last {last}");
            continue;
        }
        let mut cpu = CpuSim::new(&s);
        let (mut worst, mut last) = (0, 0);
        let mut far = [0usize; 6];
        let frames: usize = std::env::var("FRAMES").map(|v| v.parse().unwrap()).unwrap_or(45);
        let (mut ke, mut vmax) = (0.0, 0.0f64);
        for f in 0..frames {
            cpu.step_frame();
            if f + 15 >= frames {
                let v = &cpu.objects()[0].v;
                ke += v.iter().map(|v| 0.5 * 0.002 * v.length_squared()).sum::<f64>() / 15.0;
                vmax = vmax.max(v.iter().map(|v| v.length()).fold(0.0, f64::max));
            }
            last = segments_through(
                &cpu.objects()[0].x,
                &cloth_edges(cols, rows),
                &cpu.objects()[0].x,
                &cloth_triangles(cols, rows),
                true,
            );
            if last > worst {
                far = far_crossings(&cpu.objects()[0].x, cols, rows);
            }
            worst = worst.max(last);
        }
        let top = cpu.objects()[0].x.iter().map(|p| p.y).fold(0.0, f64::max);
        let x = &cpu.objects()[0].x;
        let hist = far_crossings(x, cols, rows);
        println!("tilt {tilt:.2} worst {worst} last {last} top {top:.3} by grid distance {hist:?} worst's by grid distance {far:?} ke(last 15) {ke:.3e} vmax {vmax:.3}");
    }
}

fn soft(cols: u32, rows: u32, sp: f64) -> msdsim::sim::model::ObjectModel {
    let mut c = cloth(cols, rows, sp);
    c.stiffness = [400.0, 100.0, 0.5];
    c.damping = 0.01;
    c.drag = 0.002;
    c.mass = 0.002;
    c.stretch_limit = Some(0.1);
    c.self_distance = Some(0.5 * sp);
    c.triangle_contact = true;
    c
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
