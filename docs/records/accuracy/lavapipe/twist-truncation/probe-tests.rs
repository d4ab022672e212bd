
#[test]
#[ignore]
fn zz_twist_cpu_count() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/twist.toml");
    let extra: Vec<String> =
        std::env::var("TWIST_SET").map(|v| v.split(';').map(String::from).collect()).unwrap_or_default();
    let scene = msdsim::scene::load(&path, &extra).unwrap();
    let s = msdsim::scene::to_model(&scene);
    let mut cpu = CpuSim::new(&s);
    let frames: usize = std::env::var("FRAMES").map(|v| v.parse().unwrap()).unwrap_or(120);
    let t0 = std::time::Instant::now();
    for f in 0..frames {
        cpu.step_frame();
        if f >= 78 && f % 6 == 0 || f + 1 == frames {
            let x = &cpu.objects()[0].x;
            eprintln!("frame {f}: {} layers {} ({:.0?})", crossings(x, 50, 50), layer_crossings(x, 50, 50), t0.elapsed());
        }
    }
}

#[test]
#[ignore]
fn zz_twist_cpu_probe() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/twist.toml");
    let extra: Vec<String> =
        std::env::var("TWIST_SET").map(|v| v.split(';').map(String::from).collect()).unwrap_or_default();
    let scene = msdsim::scene::load(&path, &extra).unwrap();
    let s = msdsim::scene::to_model(&scene);
    let mut cpu = CpuSim::new(&s);
    let (cols, rows) = (50usize, 50usize);
    let start: usize = std::env::var("START").map(|v| v.parse().unwrap()).unwrap_or(84);
    for _ in 0..start {
        cpu.step_frame();
    }
    let edges = cloth_edges(cols, rows);
    let tris = cloth_triangles(cols, rows);
    for step in 0..100 {
        let before = cpu.objects()[0].x.clone();
        cpu.substep();
        let x = cpu.objects()[0].x.clone();
        let mut found = Vec::new();
        if crossings(&x, cols, rows) == 0 {
            continue;
        }
        for e in &edges {
            for t in &tris {
                if e.iter().any(|a| t.contains(a)) {
                    continue;
                }
                if segments_through(&x, &[*e], &x, &[*t], true) > 0 {
                    found.push((*e, *t));
                }
            }
        }
        if found.is_empty() {
            continue;
        }
        eprintln!("substep {step}: {found:?}");
        let mv = |k: usize| (x[k] - before[k]).length();
        for &(e, t) in found.iter().take(3) {
            let w = msdsim::sim::cpu::self_contact::triangle_nearest;
            for (tag, p) in [("before", &before), ("after", &x)] {
                let d_vt: Vec<f64> = e
                    .iter()
                    .map(|&a| {
                        let b = w(p[a], p[t[0]], p[t[1]], p[t[2]]);
                        (p[a] - (p[t[0]] * b.x + p[t[1]] * b.y + p[t[2]] * b.z)).length()
                    })
                    .collect();
                let d_ee: Vec<f64> = [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]]
                    .iter()
                    .map(|f| {
                        let (s_, u) = msdsim::sim::cpu::self_contact::segment_nearest(p[e[0]], p[e[1]], p[f[0]], p[f[1]]);
                        (p[e[0]].lerp(p[e[1]], s_) - p[f[0]].lerp(p[f[1]], u)).length()
                    })
                    .collect();
                eprintln!("  {tag} e {e:?} t {t:?}: vt {d_vt:.4?} ee {d_ee:.4?}");
            }
            eprintln!("  moves e {:.4} {:.4} t {:.4} {:.4} {:.4}", mv(e[0]), mv(e[1]), mv(t[0]), mv(t[1]), mv(t[2]));
        }
        break;
    }
}
