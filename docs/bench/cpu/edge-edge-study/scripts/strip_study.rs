//! Study (not for main): the piling strip's crossings on the f64 reference, knobs through
//! MSD_MARGIN / MSD_EE, tilts and passes through STUDY_TILTS / STUDY_PASSES.
mod common;
use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::cpu::CpuSim;
use msdsim::sim::model::SimModel;

#[test]
#[ignore]
fn strip_study() {
    let tilts: Vec<f64> = std::env::var("STUDY_TILTS")
        .unwrap_or("0.05,0.2,0.4".into())
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let passes: Vec<u32> =
        std::env::var("STUDY_PASSES").unwrap_or("4".into()).split(',').map(|v| v.parse().unwrap()).collect();
    for &tilt in &tilts {
        for &k in &passes {
            let mut c = cloth(5, 61, 0.025);
            c.stiffness = [400.0, 100.0, 0.5];
            c.damping = 0.01;
            c.drag = 0.002;
            c.mass = 0.002;
            c.stretch_limit = Some(0.1);
            c.self_distance = Some(0.0125);
            c.triangle_contact = true;
            for (i, p) in c.positions.iter_mut().enumerate() {
                let row = (i / 5) as f64;
                *p = DVec3::new(
                    (i % 5) as f64 * 0.025 - 0.05,
                    1.6 - row * 0.025 * tilt.cos(),
                    row * 0.025 * tilt.sin(),
                );
            }
            c.margin = 0.005;
            c.friction = 0.5;
            let mut s = scene(vec![c]);
            s.gravity = DVec3::new(0.0, -9.81, 0.0);
            s.colliders = vec![ColliderModel {
                shape: Shape::Ground { height: 0.0 },
                friction: None,
                motion: Motion::Fixed,
            }];
            s.contact_iterations = k;
            if let Ok(n) = std::env::var("STUDY_SUBSTEPS") {
                s.substeps = n.parse().unwrap();
            }
            let mut cpu = CpuSim::new(&s);
            let (mut worst, mut last) = (0, 0);
            let t0 = std::time::Instant::now();
            for _ in 0..45 {
                cpu.step_frame();
                let x = &cpu.objects()[0].x;
                last = segments_through(x, &cloth_edges(5, 61), x, &cloth_triangles(5, 61), true);
                worst = worst.max(last);
            }
            let lowest = cpu.objects()[0].x.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
            println!("STUDY tilt {tilt} passes {k}: worst {worst}, last {last}, lowest {lowest:.4}({:.1} s)", t0.elapsed().as_secs_f64());
        }
    }
}

#[test]
#[ignore]
fn towel_study() {
    let mut c = cloth(40, 40, 1.2 / 39.0);
    c.self_distance = Some(0.02);
    c.triangle_contact = true;
    c.stiffness = [200.0, 40.0, 2.0];
    c.mass = 0.004;
    c.stretch_limit = Some(0.08);
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    let ctx = gpu();
    for lists in [false, true] {
        let mut g = msdsim::sim::gpu::GpuSim::new(&ctx, &s).unwrap();
        g.set_fused(false);
        g.force_contact_lists(Some(lists));
        let mut cpu = CpuSim::new(&s);
        for f in 0..3 {
            let t0 = std::time::Instant::now();
            g.step_frame(&ctx).unwrap();
            cpu.step_frame();
            let x = g.read_states(&ctx).unwrap()[0].positions();
            let d = x.iter().zip(&cpu.objects()[0].x).map(|(a, b)| (*a - *b).length()).fold(0.0f64, f64::max);
            println!("STUDY lists {lists} frame {f}: GPU parts from CPU by {d:e} m ({:.2} s)", t0.elapsed().as_secs_f64());
        }
        g.destroy(&ctx);
    }
    let mut cpu = CpuSim::new(&s);
    for f in 0..4 {
        let x = &cpu.objects()[0].x;
        let found = msdsim::sim::cpu::self_contact::contacts(&s.objects[0], x);
        let ee = found.iter().filter(|c| c.edges).count();
        let mut per = vec![0; x.len()];
        for c in &found {
            per[c.owner()] += 1;
        }
        println!("STUDY frame {f}: contacts {} (edge pairs {ee}), most per owner {}", found.len(), per.iter().max().unwrap());
        cpu.step_frame();
    }
}

#[test]
#[ignore]
fn dense_study() {
    let spacing = 0.01;
    let mut c = cloth(13, 10, spacing);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % 13) as f64, (i / 13) as i64);
        let (rows_down, z) = if row <= 4 { (row, 0.0) } else { (9 - row, 0.005) };
        let k = i as u64 * 3;
        let jitter = DVec3::new(noise(k), noise(k + 1), noise(k + 2)) * 0.002;
        *p = DVec3::new(col * spacing, 1.0 - rows_down as f64 * spacing, 0.005f64.min(if row <= 4 { 0.0 } else { 0.005 })) + jitter;
    }
    let speed: f64 = std::env::var("STUDY_SPEED").ok().and_then(|v| v.parse().ok()).unwrap_or(0.0);
    for v in c.velocities[5 * 13..].iter_mut().filter(|_| speed != 0.0) {
        *v = DVec3::new(0.25 * speed, 0.0, -speed);
    }
    c.stiffness = [60.0, 20.0, 0.0];
    c.friction = std::env::var("STUDY_MU").ok().and_then(|v| v.parse().ok()).unwrap_or(0.5);
    c.self_distance = Some(0.019);
    c.triangle_contact = true;
    let mut s = scene(vec![c]);
    if let Ok(n) = std::env::var("STUDY_SUBSTEPS") {
        s.substeps = n.parse().unwrap();
    }
    if let Ok(dt) = std::env::var("STUDY_DT") {
        s.frame_dt = dt.parse().unwrap();
    }
    if std::env::var("STUDY_BRUTE").is_ok() {
        s.self_collision = msdsim::sim::model::SelfCollisionMethod::BruteForce;
    }
    s.contact_iterations = std::env::var("STUDY_PASSES").ok().and_then(|v| v.parse().ok()).unwrap_or(1);
    let ctx = gpu();
    let mut g = msdsim::sim::gpu::GpuSim::new(&ctx, &s).unwrap();
    g.set_fused(std::env::var("STUDY_STAGED").is_err());
    let mut cpu = CpuSim::new(&s);
    let frames: usize = std::env::var("STUDY_FRAMES").ok().and_then(|v| v.parse().ok()).unwrap_or(1);
    for f in 0..frames - 1 {
        g.step_frame(&ctx).unwrap();
        cpu.step_frame();
        let st = g.read_states(&ctx).unwrap();
        let x = st[0].positions();
        let d = x.iter().zip(&cpu.objects()[0].x).map(|(a, b)| (*a - *b).length()).fold(0.0f64, f64::max);
        println!("STUDY frame {f}: {d:e}");
        cpu.set_state(0, x, st[0].velocities());
    }
    g.step_frame(&ctx).unwrap();
    cpu.step_frame();
    let x = g.read_states(&ctx).unwrap()[0].positions();
    let (mut worst, mut at) = (0.0, 0);
    for (i, (a, b)) in x.iter().zip(&cpu.objects()[0].x).enumerate() {
        if (*a - *b).length() > worst {
            worst = (*a - *b).length();
            at = i;
        }
    }
    println!("STUDY worst {worst:e} at particle {at}: GPU {:?} CPU {:?}", x[at], cpu.objects()[0].x[at]);
    let gv = g.read_states(&ctx).unwrap()[0].velocities();
    let (mut vw, mut vat) = (0.0, 0);
    for (i, (a, b)) in gv.iter().zip(&cpu.objects()[0].v).enumerate() {
        if (*a - *b).length() > vw {
            vw = (*a - *b).length();
            vat = i;
        }
    }
    println!("STUDY velocity worst {vw:e} at {vat}: GPU {:?} CPU {:?}", gv[vat], cpu.objects()[0].v[vat]);
    let at = vat;
    let found = msdsim::sim::cpu::self_contact::contacts(&s.objects[0], &s.objects[0].positions);
    let mut by = vec![0; x.len()];
    for c in &found {
        by[c.owner()] += 1;
    }
    for c in found.iter().filter(|c| c.particles.contains(&at)) {
        println!("STUDY contact {:?} edges {} w {:?} overlap {:.4} (owner has {})", c.particles, c.edges, c.weights, c.overlap, by[c.owner()]);
    }
}

#[test]
#[ignore]
fn dense_chaos() {
    let spacing = 0.01;
    let mut c = cloth(13, 10, spacing);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % 13) as f64, (i / 13) as i64);
        let (rows_down, z) = if row <= 4 { (row, 0.0) } else { (9 - row, 0.005) };
        let k = i as u64 * 3;
        let jitter = DVec3::new(noise(k), noise(k + 1), noise(k + 2)) * 0.002;
        *p = DVec3::new(col * spacing, 1.0 - rows_down as f64 * spacing, z) + jitter;
    }
    c.stiffness = [60.0, 20.0, 0.0];
    c.friction = 0.5;
    c.self_distance = Some(0.019);
    c.triangle_contact = true;
    let s = scene(vec![c]);
    let mut a = CpuSim::new(&s);
    let mut b = CpuSim::new(&s);
    let mut x = b.objects()[0].x.clone();
    x[60].x += 1e-7;
    let v = b.objects()[0].v.clone();
    b.set_state(0, x.iter().map(|p| glam::Vec3::new(p.x as f32, p.y as f32, p.z as f32)).collect::<Vec<_>>().as_slice().iter().map(|p| DVec3::new(p.x as f64, p.y as f64, p.z as f64)).collect(), v);
    a.step_frame();
    b.step_frame();
    let d = a.objects()[0].x.iter().zip(&b.objects()[0].x).map(|(p, q)| (*p - *q).length()).fold(0.0f64, f64::max);
    println!("STUDY chaos: CPU against CPU with positions rounded to f32 and one moved 1e-7 m: {d:e} m after a frame");
}

#[test]
#[ignore]
fn dense_frames() {
    let spacing = 0.01;
    let mut c = cloth(13, 10, spacing);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % 13) as f64, (i / 13) as i64);
        let (rows_down, z) = if row <= 4 { (row, 0.0) } else { (9 - row, 0.005) };
        let k = i as u64 * 3;
        let jitter = DVec3::new(noise(k), noise(k + 1), noise(k + 2)) * 0.002;
        *p = DVec3::new(col * spacing, 1.0 - rows_down as f64 * spacing, z) + jitter;
    }
    c.stiffness = [60.0, 20.0, 0.0];
    c.friction = 0.5;
    c.self_distance = Some(0.019);
    c.triangle_contact = true;
    let mut s = scene(vec![c]);
    s.self_collision = msdsim::sim::model::SelfCollisionMethod::BruteForce;
    s.contact_iterations = 1;
    let n: u32 = std::env::var("STUDY_SUBSTEPS").ok().and_then(|v| v.parse().ok()).unwrap_or(5);
    let dt = 0.00104167;
    let whole = SimModel { substeps: n, frame_dt: n as f64 * dt, ..s.clone() };
    let single = SimModel { substeps: 1, frame_dt: dt, ..s.clone() };
    let ctx = gpu();
    let mut ga = msdsim::sim::gpu::GpuSim::new(&ctx, &whole).unwrap();
    let mut gb = msdsim::sim::gpu::GpuSim::new(&ctx, &single).unwrap();
    ga.step_frame(&ctx).unwrap();
    for _ in 0..n {
        gb.step_frame(&ctx).unwrap();
    }
    let (xa, xb) = (ga.read_states(&ctx).unwrap()[0].positions(), gb.read_states(&ctx).unwrap()[0].positions());
    let mut ca = CpuSim::new(&whole);
    let mut cb = CpuSim::new(&single);
    ca.step_frame();
    for _ in 0..n {
        cb.step_frame();
    }
    let d = |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).map(|(p, q)| (*p - *q).length()).fold(0.0f64, f64::max);
    println!("STUDY {n} substeps: GPU frame vs GPU single {:e}; CPU frame vs CPU single {:e}; GPU vs CPU frame {:e}; single {:e}",
        d(&xa, &xb), d(&ca.objects()[0].x, &cb.objects()[0].x), d(&xa, &ca.objects()[0].x), d(&xb, &cb.objects()[0].x));
}

#[test]
#[ignore]
fn towel_census() {
    let scene = msdsim::scene::load(std::path::Path::new("presets/towel.toml"), &[]).unwrap();
    let s = msdsim::scene::to_model(&scene);
    let ctx = gpu();
    let mut g = msdsim::sim::gpu::GpuSim::new(&ctx, &s).unwrap();
    let frames: usize = std::env::var("STUDY_FRAMES").ok().and_then(|v| v.parse().ok()).unwrap_or(60);
    let o = &s.objects[0];
    let h = o.self_distance.unwrap();
    for f in 1..=frames {
        g.step_frame(&ctx).unwrap();
        if f % 20 != 0 {
            continue;
        }
        let x = g.read_states(&ctx).unwrap()[0].positions();
        let found = msdsim::sim::cpu::self_contact::contacts(o, &x);
        let ee = found.iter().filter(|c| c.edges).count();
        let mut per = vec![0usize; x.len()];
        let mut per_ee = vec![0usize; x.len()];
        for c in &found {
            per[c.owner()] += 1;
            if c.edges {
                per_ee[c.owner()] += 1;
            }
        }
        let over = per.iter().filter(|&&n| n > 16).count();
        let inc = per.iter().filter(|&&n| n > 0).count();
        let mut o2 = o.clone();
        o2.self_distance = Some(2.0 * h);
        let wide = msdsim::sim::cpu::self_contact::contacts(&o2, &x);
        let mut perw = vec![0usize; x.len()];
        for c in &wide {
            perw[c.owner()] += 1;
        }
        let overw = perw.iter().filter(|&&n| n > 32).count();
        println!(
            "STUDY frame {f}: contacts {} (edge pairs {ee}) in {inc} owners, most {} (ee {}), over 16: {over}; within 2h {} most {} over 32: {overw}",
            found.len(),
            per.iter().max().unwrap(),
            per_ee.iter().max().unwrap(),
            wide.len(),
            perw.iter().max().unwrap()
        );
    }
    g.destroy(&ctx);
}
