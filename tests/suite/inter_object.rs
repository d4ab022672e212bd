//! Objects touching each other, against physics: a rope dropped across a cloth held at its
//! corners comes to rest on it, from drop heights up to 2 m, without any node passing to the
//! far side; on cloths whose spacing is 2x and 4x its radius no rope segment passes through a
//! triangle (exact test), nor any edge of a cloth dropped on another or of a stack of four on
//! the ground; contact conserves momentum. On lavapipe with validation and synchronization
//! validation.

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::turn::Turn;

/// A 30 x 30 cloth (2.5 cm spacing, 0.73 m, 1.8 kg) pinned at its corners at y = 0.5 and a
/// 0.5 m rope (radius 2 cm) dropped across its middle from `drop` metres above it (0.1 and 2 m:
/// 1.4 and 6.3 m/s at impact). Contact keeps rope nodes 3 cm (rope radius + cloth margin) from
/// the cloth's triangles. At every frame each rope node must be on the upper side of the cloth: above the tangent
/// plane at the cloth particle nearest to it (the cloth's smoothed normal there, turned up);
/// a node that slipped through would be about 3 cm below it. At the end (2 s) the rope must
/// lie on the cloth: every node within 6 cm of that plane (not thrown off). (Friction 0,
/// the default here: it may slide.) The default tier drops it from 2 m; the exhaustive tier
/// from 0.1 m too.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_rope_dropped_on_a_cloth_rests_on_it() {
    rope_dropped_on_a_cloth(&[2.0]);
}

#[test]
#[ignore = "exhaustive tier: the same drop from lower"]
fn a_rope_dropped_gently_on_a_cloth_rests_on_it() {
    rope_dropped_on_a_cloth(&[0.1]);
}

fn rope_dropped_on_a_cloth(drops: &[f64]) {
    let ctx = gpu();
    for &drop in drops {
        let s = rope_over(held_cloth(30, 0.025, 0.5), 0.5 + drop, 0.02);
        let mut gpu = GpuSim::new(&ctx, &s).unwrap();
        let frames = 120;
        let mut lowest = f64::MAX;
        let (mut fastest, mut highest) = (0.0f64, 0.0f64);
        for f in 0..frames {
            gpu.step_frame(&ctx).unwrap();
            let states = gpu.read_states(&ctx).unwrap();
            let (cloth, rope) = (states[0].positions(), states[1].positions());
            for (k, node) in rope.iter().enumerate() {
                // The side of the cloth a node is on: along the cloth's normal (turned to point
                // up) at the cloth particle nearest to it.
                let (at, nearest) = cloth
                    .iter()
                    .enumerate()
                    .min_by(|a, b| a.1.distance(*node).total_cmp(&b.1.distance(*node)))
                    .unwrap();
                let normal = glam::Vec3::from_slice(&states[0].surface[at].normal[..3]).as_dvec3();
                let up = if normal.y < 0.0 { -normal } else { normal };
                let above = (*node - *nearest).dot(up);
                lowest = lowest.min(above);
                assert!(
                    above > 0.0,
                    "drop {drop} m, frame {f}: rope node {k} is {above:.4} m on the far side of the cloth"
                );
                if f == frames - 1 {
                    let speed = states[1].velocities()[k].length();
                    fastest = fastest.max(speed);
                    highest = highest.max(above);
                }
            }
        }
        eprintln!("drop {drop} m: lowest {lowest:.4} m; at the end highest {highest:.4} m, fastest {fastest:.3} m/s");
        assert!(highest < 0.06, "drop {drop} m: a rope node is {highest} m above the cloth at the end");
        gpu.destroy(&ctx);
    }
    assert_clean(&ctx);
}

/// Total linear momentum (sum of m v) of every object, with the masses the simulation uses
/// (rounded to f32).
fn momentum(model: &msdsim::sim::model::SimModel, velocities: &[Vec<DVec3>]) -> DVec3 {
    let p = |o: &msdsim::sim::model::ObjectModel, v: &Vec<DVec3>| {
        v.iter().sum::<DVec3>() * (o.mass as f32 as f64)
    };
    model.objects.iter().zip(velocities).map(|(o, v)| p(o, v)).sum()
}

/// A rope (20 g nodes, radius 2 cm) thrown at 2 m/s into a free 12 x 12 cloth (5 g particles,
/// 2.5 cm spacing), and a tilted free 7 x 7 cloth (8 g particles) thrown the same way into it
/// (each cloth's particles against the other's triangles, and their edges against each other's,
/// `edge_contact`), friction 0.5 (its corrections are
/// equal and opposite too), no gravity, pins, drag, stretch
/// limit or self-collision: nothing outside the two objects acts on them, so their total
/// momentum must stay what it was, to 1e-5 of it (the f32 floor of the GPU's velocity sums
/// over 320 substeps (20 frames) is about 1e-6; before each contact's moves were split equally among its
/// particles, a rope node pushed by several cloth particles took one push and each of them a
/// full one: +47% in such a scene). The contact must happen: the cloth takes at least a tenth
/// of the momentum. The GPU (per stage, where touching objects run) and the f64 reference
/// each against the conservation law.
#[test]
fn contact_between_objects_conserves_momentum() {
    let ctx = gpu();
    let n = 12;
    let mut c = cloth(n, n, 0.025);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i as u32 % n) as f64, (i as u32 / n) as f64);
        *p = DVec3::new(col * 0.025 - 0.1375, 0.5, row * 0.025 - 0.1375);
    }
    c.stiffness = [400.0, 100.0, 2.0];
    c.mass = 0.005;
    c.damping = 0.01;
    c.margin = 0.01;
    c.friction = 0.5;
    let mut r = rope(8, 0.025);
    for (i, p) in r.positions.iter_mut().enumerate() {
        *p = DVec3::new(i as f64 * 0.025 - 0.0875, 0.6, 0.013);
    }
    r.velocities.fill(DVec3::new(0.3, -2.0, 0.1));
    r.stiffness = [800.0, 0.0, 5.0];
    r.damping = 0.02;
    r.rope_radius = 0.02;
    r.mass = 0.02;
    r.friction = 0.5;
    let mut top = cloth(7, 7, 0.025);
    for (i, p) in top.positions.iter_mut().enumerate() {
        let (col, row) = ((i % 7) as f64, (i / 7) as f64);
        *p = DVec3::new(col * 0.025 - 0.07, 0.6 + 0.01 * col, row * 0.025 - 0.06);
    }
    top.velocities.fill(DVec3::new(0.3, -2.0, 0.1));
    top.stiffness = [400.0, 100.0, 2.0];
    top.mass = 0.008;
    top.damping = 0.01;
    top.margin = 0.01;
    top.friction = 0.5;
    top.edge_contact = true;
    // Two free ropes crossing at the middle of a segment of each, their nodes 6 cm apart and
    // 2 cm thick (node against node, before segments, they passed through each other).
    let (mut below, mut across) = (coarse_rope(10, 0.5), coarse_rope(10, 0.53));
    below.pinned.fill(false);
    across.pinned.fill(false);
    for p in across.positions.iter_mut() {
        *p = DVec3::new(0.0, p.y, p.x);
    }
    across.velocities.fill(DVec3::new(0.3, -2.0, 0.1));
    for rope in [&mut below, &mut across] {
        rope.friction = 0.5;
        rope.drag = 0.0;
    }
    // The rope thrown again with stretch limits on both (1%: the knock stretches springs past
    // it): the limit's moves are equal and opposite too (it changed the momentum by 2.2% when
    // each end took the mean of its own stretched springs).
    let (mut limited, mut limited_rope) = (c.clone(), r.clone());
    limited.stretch_limit = Some(0.01);
    limited_rope.stretch_limit = Some(0.01);
    for (name, target, thrown) in [
        ("rope", c.clone(), r),
        ("cloth", c, top),
        ("rope across a rope", below, across),
        ("stretch-limited rope", limited, limited_rope),
    ] {
        let mut s = scene(vec![target, thrown]);
        s.inter_object = true;
        let rounded = |o: &msdsim::sim::model::ObjectModel| -> Vec<DVec3> {
            o.velocities.iter().map(|v| v.as_vec3().as_dvec3()).collect()
        };
        let before = momentum(&s, &[rounded(&s.objects[0]), rounded(&s.objects[1])]);
        let frames = 20;
        let mut gpu = GpuSim::new(&ctx, &s).unwrap();
        let mut cpu = msdsim::sim::cpu::CpuSim::new(&s);
        let (mut worst_gpu, mut worst_cpu) = (0.0f64, 0.0f64);
        let mut cloth_share = 0.0f64;
        for _ in 0..frames {
            gpu.step_frame(&ctx).unwrap();
            cpu.step_frame();
            let states = gpu.read_states(&ctx).unwrap();
            let v: Vec<Vec<DVec3>> = states.iter().map(|o| o.velocities()).collect();
            worst_gpu = worst_gpu.max((momentum(&s, &v) - before).length() / before.length());
            let v: Vec<Vec<DVec3>> = cpu.objects().iter().map(|o| o.v.clone()).collect();
            worst_cpu = worst_cpu.max((momentum(&s, &v) - before).length() / before.length());
            let cloth_p = v[0].iter().sum::<DVec3>() * s.objects[0].mass;
            cloth_share = cloth_share.max(cloth_p.length() / before.length());
        }
        gpu.destroy(&ctx);
        eprintln!(
            "{name} thrown: momentum change GPU {worst_gpu:.2e}, CPU {worst_cpu:.2e} of it; the cloth took {cloth_share:.2}"
        );
        assert!(
            cloth_share > 0.1,
            "{name}: hardly touched the cloth: it took {cloth_share:.3} of the momentum"
        );
        assert!(worst_cpu < 1e-9, "{name}: the reference changed the momentum by {worst_cpu:.2e} of it");
        assert!(worst_gpu < 1e-5, "{name}: the GPU changed the momentum by {worst_gpu:.2e} of it");
    }
    assert_clean(&ctx);
}

/// A cloth `n` x `n` at `spacing`, flat at height y centred on x = z = 0, held at its corners,
/// with a constant areal density (0.002 kg per 2.5 cm square) and a 1 cm contact margin.
fn held_cloth(n: u32, spacing: f64, y: f64) -> msdsim::sim::model::ObjectModel {
    let mut c = cloth(n, n, spacing);
    let half = 0.5 * (n - 1) as f64 * spacing;
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i as u32 % n) as f64, (i as u32 / n) as f64);
        *p = DVec3::new(col * spacing - half, y, row * spacing - half);
    }
    for corner in [0, n - 1, n * (n - 1), n * n - 1] {
        c.pinned[corner as usize] = true;
    }
    c.stiffness = [1000.0, 250.0, 5.0];
    c.mass = 0.002 * (spacing / 0.025).powi(2);
    c.damping = 0.02;
    c.drag = 0.002 * (spacing / 0.025).powi(2);
    c.margin = 0.01;
    c
}

/// `cloth` and a 0.5 m rope (21 nodes, radius 2 cm, 10 g nodes) along x at height y and depth
/// z above it, under gravity, touching each other.
fn rope_over(cloth: msdsim::sim::model::ObjectModel, y: f64, z: f64) -> msdsim::sim::model::SimModel {
    let mut r = rope(21, 0.025);
    for (i, p) in r.positions.iter_mut().enumerate() {
        *p = DVec3::new(i as f64 * 0.025 - 0.25, y, z);
    }
    r.stiffness = [800.0, 0.0, 5.0];
    r.damping = 0.02;
    r.drag = 0.005;
    r.rope_radius = 0.02;
    r.mass = 0.01;
    let mut s = scene(vec![cloth, r]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    s
}

/// How far each of `points` is above the cloth (positions `x`, `cols` x `rows`) straight
/// below or above it (the height over the triangle its xz position falls in; points outside
/// the cloth's outline are left out).
fn heights_above(points: &[DVec3], x: &[DVec3], cols: usize, rows: usize) -> Vec<f64> {
    let tris = cloth_triangles(cols, rows);
    points
        .iter()
        .filter_map(|p| {
            tris.iter().find_map(|t| {
                let [a, b, c] = t.map(|k| x[k]);
                let xz = |v: DVec3| glam::DVec2::new(v.x, v.z);
                let (e1, e2, q) = (xz(b - a), xz(c - a), xz(*p - a));
                let det = e1.perp_dot(e2);
                if det.abs() < 1e-12 {
                    return None;
                }
                let (u, v) = (q.perp_dot(e2) / det, e1.perp_dot(q) / det);
                (u >= 0.0 && v >= 0.0 && u + v <= 1.0)
                    .then_some(p.y - (a.y + u * (b.y - a.y) + v * (c.y - a.y)))
            })
        })
        .collect()
}

/// A rope (radius 2 cm, nodes 2.5 cm apart, 0.5 m) dropped 10 cm onto a cloth held at its
/// corners whose spacing is 2x and 4x the rope's radius (4 and 8 cm), along the middle of a
/// row of cells, where particle contact had holes wider than the rope (3 and 2 segments
/// through the cloth, 21 nodes below). Contact is against the cloth's triangles: no rope
/// segment may pass through a cloth triangle at any frame (exact segment-triangle test), and
/// at the end (1.5 s) every node over the cloth must be above it by at most 6 cm (lying on
/// it: the reach is 3 cm).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_rope_stays_on_a_coarse_cloth() {
    let ctx = gpu();
    for (n, spacing) in [(17u32, 0.04), (9, 0.08)] {
        let s = rope_over(held_cloth(n, spacing, 0.5), 0.6, 0.5 * spacing);
        let (cols, rows) = (n as usize, n as usize);
        let (tris, segments): (Vec<_>, Vec<_>) =
            (cloth_triangles(cols, rows), (0..20).map(|k| [k, k + 1]).collect());
        let mut worst = 0;
        let mut heights = Vec::new();
        run_gpu(&ctx, &s, 90, |_, states| {
            let (cloth, rope) = (states[0].positions(), states[1].positions());
            worst = worst.max(segments_through(&rope, &segments, &cloth, &tris, false));
            heights = heights_above(&rope, &cloth, cols, rows);
        });
        let (low, high) = heights.iter().fold((f64::MAX, f64::MIN), |(l, h), &y| (l.min(y), h.max(y)));
        eprintln!(
            "spacing {spacing} m: at most {worst} rope segments through the cloth; at the end {} nodes over it, {low:.4} to {high:.4} m above",
            heights.len()
        );
        assert_eq!(worst, 0, "spacing {spacing} m: rope segments passed through the cloth");
        assert!(
            heights.len() >= 10,
            "spacing {spacing} m: the rope left the cloth ({} nodes over it)",
            heights.len()
        );
        assert!(
            low > 0.0 && high < 0.06,
            "spacing {spacing} m: nodes {low:.4} to {high:.4} m above the cloth"
        );
    }
    assert_clean(&ctx);
}

/// A cloth 11 x 11 at 4 cm dropped 10 cm onto a 17 x 17 one at 4 cm held at its corners, both
/// with a 1 cm margin, so their spacing is twice the 2 cm they keep apart (particle contact let
/// 123 edges through and 121 particles below). No edge of either may pass through a triangle
/// of the other at any frame (exact segment-triangle test), and at the end (0.67 s) every
/// particle of the small cloth must be above the large one.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_cloth_stays_on_a_cloth() {
    let ctx = gpu();
    let big = held_cloth(17, 0.04, 0.5);
    let mut small = held_cloth(11, 0.04, 0.6);
    small.pinned.fill(false);
    for p in &mut small.positions {
        *p += DVec3::new(0.013, 0.0, 0.021);
    }
    let mut s = scene(vec![big, small]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    let (tb, eb) = (cloth_triangles(17, 17), cloth_edges(17, 17));
    let (ts, es) = (cloth_triangles(11, 11), cloth_edges(11, 11));
    let mut worst = 0;
    let mut heights = Vec::new();
    run_gpu(&ctx, &s, 40, |_, states| {
        let (b, sm) = (states[0].positions(), states[1].positions());
        worst = worst
            .max(segments_through(&sm, &es, &b, &tb, false) + segments_through(&b, &eb, &sm, &ts, false));
        heights = heights_above(&sm, &b, 17, 17);
    });
    let (low, high) = heights.iter().fold((f64::MAX, f64::MIN), |(l, h), &y| (l.min(y), h.max(y)));
    eprintln!("at most {worst} edges through the other cloth; at the end {} particles over it, {low:.4} to {high:.4} m above", heights.len());
    assert_eq!(worst, 0, "edges passed through the other cloth");
    assert_eq!(heights.len(), 121, "the small cloth slid off");
    assert!(low > 0.0, "a particle of the small cloth is {low:.4} m below the large one");
    assert_clean(&ctx);
}

/// A rope of `nodes` nodes 6 cm apart along x at height y, centred on x = 0 (no node there:
/// the middle of a segment), 1 cm thick (reach 2 cm against another such rope: a third of the
/// spacing, so node against node two of them would pass each other), 10 g nodes, friction 0.5,
/// held at its ends.
fn coarse_rope(nodes: u32, y: f64) -> msdsim::sim::model::ObjectModel {
    let mut r = rope(nodes, 0.06);
    let half = 0.5 * (nodes - 1) as f64 * 0.06;
    for (i, p) in r.positions.iter_mut().enumerate() {
        *p = DVec3::new(i as f64 * 0.06 - half, y, 0.0);
    }
    r.pinned[0] = true;
    r.pinned[nodes as usize - 1] = true;
    r.stiffness = [2000.0, 0.0, 0.0];
    r.damping = 0.02;
    r.drag = 0.005;
    r.rope_radius = 0.01;
    r.mass = 0.01;
    r.friction = 0.5;
    r
}

/// How far rope `upper` is above rope `lower` where they cross seen from above (the heights of
/// their segments at the crossing of their xz projections; the highest, since the ends of a rope
/// draped over another may swing under it; `None` where they do not cross).
fn height_over(upper: &[DVec3], lower: &[DVec3]) -> Option<f64> {
    let xz = |v: DVec3| glam::DVec2::new(v.x, v.z);
    let mut highest: Option<f64> = None;
    for u in upper.windows(2) {
        for l in lower.windows(2) {
            let (p, r, q, s) = (xz(u[0]), xz(u[1] - u[0]), xz(l[0]), xz(l[1] - l[0]));
            let det = r.perp_dot(s);
            if det.abs() < 1e-12 {
                continue;
            }
            let (t, v) = ((q - p).perp_dot(s) / det, (q - p).perp_dot(r) / det);
            if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&v) {
                let over = u[0].lerp(u[1], t).y - l[0].lerp(l[1], v).y;
                highest = Some(highest.map_or(over, |h| h.max(over)));
            }
        }
    }
    highest
}

/// A free rope dropped 3 cm across a held one, both with nodes 6 cm apart and 1 cm thick,
/// crossing at the middle of a segment of each (node against node they passed through each
/// other: the nearest nodes are 4.2 cm apart, the reach 2 cm). Contact between ropes is
/// capsule against capsule: at every frame the upper rope must be above the lower where they
/// cross, and at the end (1.5 s) rest on it, its axis the reach (2 cm) above the lower's, within
/// 5 mm (the ropes sag and swing).
#[test]
fn a_rope_stays_on_a_coarse_rope() {
    let ctx = gpu();
    let lower = coarse_rope(10, 0.5);
    let mut upper = coarse_rope(10, 0.53);
    upper.pinned.fill(false);
    for p in upper.positions.iter_mut() {
        *p = DVec3::new(0.0, p.y, p.x);
    }
    let mut s = scene(vec![lower, upper]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    let mut lowest = f64::MAX;
    let mut last = None;
    run_gpu(&ctx, &s, 90, |f, states| {
        let over = height_over(&states[1].positions(), &states[0].positions());
        let over = over.unwrap_or_else(|| panic!("frame {f}: the ropes no longer cross"));
        assert!(over > 0.0, "frame {f}: the upper rope is {over:.4} m below the lower where they cross");
        lowest = lowest.min(over);
        last = Some(over);
    });
    let last = last.unwrap();
    eprintln!("upper rope over the lower: at least {lowest:.4} m, at the end {last:.4} m (reach 0.02)");
    assert!((last - 0.02).abs() < 0.005, "the upper rope rests {last:.4} m over the lower, not the reach");
    assert_clean(&ctx);
}

/// A 13 x 13 cloth (2.5 cm spacing, 5 mm margin) dropped 3 cm onto a line: a rope held at its
/// ends, 5 mm thick, its nodes 10 cm apart (four cells; under the cloth three of them), lying
/// along the middle of a row of cells. The cloth's particles are kept from the rope's segments,
/// not only its nodes from the cloth's triangles: no rope segment may pass through a cloth
/// triangle at any frame (exact test), and at the end (1 s) the cloth hangs on the line: its
/// highest particle over it by at most 2 cm (the reach is 1 cm), two rows or more on either side.
#[test]
fn a_cloth_hangs_on_a_line() {
    let ctx = gpu();
    let n = 13u32;
    let s = line_scene();
    let tris = cloth_triangles(n as usize, n as usize);
    let segments: Vec<[usize; 2]> = (0..6).map(|k| [k, k + 1]).collect();
    let mut worst = 0;
    let (mut top, mut sides) = (0.0, (0, 0));
    run_gpu(&ctx, &s, 60, |_, states| {
        let (line, cloth) = (states[0].positions(), states[1].positions());
        worst = worst.max(segments_through(&line, &segments, &cloth, &tris, false));
        // The line's height and depth under the cloth's highest particle.
        let p = cloth.iter().copied().max_by(|a, b| a.y.total_cmp(&b.y)).unwrap();
        let t = ((p.x + 0.3) / 0.1).clamp(0.0, 5.999);
        let (k, f) = (t as usize, t.fract());
        let under = line[k].lerp(line[k + 1], f);
        top = p.y - under.y;
        sides =
            (cloth.iter().filter(|c| c.z < under.z).count(), cloth.iter().filter(|c| c.z > under.z).count());
    });
    eprintln!(
        "at most {worst} rope segments through the cloth; at the end its highest particle {top:.4} m over the line, {} and {} particles on either side",
        sides.0, sides.1
    );
    assert_eq!(worst, 0, "rope segments passed through the cloth");
    assert!(top > 0.0 && top < 0.02, "the cloth does not hang on the line: its top is {top:.4} m over it");
    assert!(
        sides.0 >= 26 && sides.1 >= 26,
        "the cloth slid off the line: {sides:?} particles on either side"
    );
    assert_clean(&ctx);
}

/// A line (a rope held at its ends, 5 mm thick, its nodes 10 cm apart) and a 13 x 13 cloth 3 cm
/// above it (see `a_cloth_hangs_on_a_line`).
fn line_scene() -> msdsim::sim::model::SimModel {
    let mut line = rope(7, 0.1);
    for (i, p) in line.positions.iter_mut().enumerate() {
        *p = DVec3::new(i as f64 * 0.1 - 0.3, 0.5, 0.0);
    }
    line.pinned[0] = true;
    line.pinned[6] = true;
    line.stiffness = [5000.0, 0.0, 0.0];
    line.damping = 0.02;
    line.rope_radius = 0.005;
    line.mass = 0.01;
    let n = 13u32;
    let mut c = held_cloth(n, 0.025, 0.53);
    c.pinned.fill(false);
    for p in &mut c.positions {
        *p += DVec3::new(0.0125, 0.0, 0.0125);
    }
    c.margin = 0.005;
    c.friction = 0.8;
    line.friction = 0.8;
    let mut s = scene(vec![line, c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    s
}

/// Three free 7 x 7 cloths at 3 cm, thin (margin 2 mm: they keep 4 mm apart) and keeping their
/// edges from each other's as every scene does by default (`inter_object_edges`), lying flat 2 cm above each other from 5 cm over the
/// ground and shifted (7 mm, 11 mm) a layer so that their vertices do not line up, fall onto
/// the ground and each other (the top one at about 1.3 m/s, 1.3 mm a substep). No edge of any
/// may pass through a triangle of another at any frame (exact segment-triangle test), and at
/// the end (0.5 s) each lies above the one below: its mean height at least 80% of the reach
/// above that one's (measured 95% to 98%: one pass of contact between objects a substep leaves
/// a layer under several others its share of each contact, so a stack settles a little inside
/// its thickness). Without the edge pairs (`inter_object_edges = false`, the only behaviour
/// before 2026-12-03 unless a cloth asked for edge contact) 4 edges pass (particles kept from
/// triangles only: two layers crossing edge over edge between their vertices;
/// docs/records/bench/cpu/cloth-stack).
#[test]
fn a_stack_of_thin_cloths_rests_without_passing() {
    use msdsim::sim::collider::{ColliderModel, Motion, Shape};
    let (n, layers, margin) = (7u32, 3usize, 0.002);
    let objects = (0..layers)
        .map(|k| {
            let mut c = held_cloth(n, 0.03, 0.05 + 0.02 * k as f64);
            c.pinned.fill(false);
            for p in &mut c.positions {
                *p += DVec3::new(0.007 * k as f64, 0.0, 0.011 * k as f64);
            }
            c.margin = margin;
            c.friction = 0.5;
            c
        })
        .collect();
    let mut s = scene(objects);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    let ground = Shape::Ground { height: 0.0 };
    s.colliders =
        vec![ColliderModel { shape: ground, friction: None, motion: Motion::Fixed, turn: Turn::default() }];
    stack_rests(&s, [n, n], 30, 2.0 * margin);
}

/// Runs the stack `s` of cloths of `grid` particles on the GPU for `frames` frames: no edge of
/// any may pass through a triangle of another at any frame (exact segment-triangle test), and
/// at the end each (in the order of `s.objects`, lowest first) lies above the one below by at
/// least 80% of the `reach`, mean height against mean height.
fn stack_rests(s: &msdsim::sim::model::SimModel, grid: [u32; 2], frames: usize, reach: f64) {
    let [cols, rows] = grid.map(|g| g as usize);
    let (t, e) = (cloth_triangles(cols, rows), cloth_edges(cols, rows));
    let ctx = gpu();
    let mut worst = 0;
    let mut heights = Vec::new();
    run_gpu(&ctx, s, frames, |_, states| {
        let x: Vec<Vec<DVec3>> = states.iter().map(|o| o.positions()).collect();
        for (a, xa) in x.iter().enumerate() {
            for (b, xb) in x.iter().enumerate() {
                if a != b {
                    worst = worst.max(segments_through(xa, &e, xb, &t, false));
                }
            }
        }
        heights = x.iter().map(|o| o.iter().map(|p| p.y).sum::<f64>() / o.len() as f64).collect();
    });
    let gaps: Vec<f64> = heights.windows(2).map(|h| (h[1] - h[0]) / reach).collect();
    eprintln!("at most {worst} edges through another layer; mean heights at the end {heights:?}, gaps {gaps:?} of the reach");
    assert_eq!(worst, 0, "edges passed through another layer");
    assert!(gaps.iter().all(|&g| g >= 0.8), "a layer sank into the one below: gaps {gaps:?} of the reach");
    assert_clean(&ctx);
}

/// Two free 7 x 7 cloths at 3 cm (margin 1 mm: they keep 2 mm apart), lying flat 2.5 mm apart
/// (just outside each other's reach) and shifted (7 mm, 11 mm), the upper thrown at the lower
/// at 3.4 m/s, no gravity: 3.5 mm a substep (16 a frame), more than the reach, so a pair crosses
/// within one substep and a contact that pushed along the nearest points' offset at the
/// substep's end pushed it on through the other cloth. A pair that crossed is pushed back to the
/// side it began on: no edge of either may pass through a triangle of the other at any frame
/// (exact segment-triangle test), and after 10 frames the upper cloth lies above the lower,
/// on the GPU and on the reference. Measured: none through, the upper cloth 6.3 cm above the
/// lower (they part at 0.4 m/s, a tenth of the approach, as they do at 1.6 m/s where nothing
/// crosses); pushed on through before, the upper cloth ended 63 cm below the lower (and no edge
/// through it at a frame's end).
#[test]
fn a_cloth_thrown_faster_than_the_reach_a_substep_stays_on_its_side() {
    let (n, spacing, margin) = (7u32, 0.03, 0.001);
    let layer = |y: f64, shift: DVec3| {
        let mut c = held_cloth(n, spacing, y);
        c.pinned.fill(false);
        c.positions.iter_mut().for_each(|p| *p += shift);
        c.margin = margin;
        c.friction = 0.3;
        c
    };
    let mut upper = layer(0.5025, DVec3::new(0.007, 0.0, 0.011));
    upper.velocities.fill(DVec3::new(0.0, -3.4, 0.0));
    let mut s = scene(vec![layer(0.5, DVec3::ZERO), upper]);
    s.inter_object = true;
    let per_substep = 3.4 * s.dt();
    assert!(per_substep > 2.0 * margin, "{per_substep} m a substep: within the reach");
    let (t, e) = (cloth_triangles(n as usize, n as usize), cloth_edges(n as usize, n as usize));
    let through = |x: &[Vec<DVec3>]| {
        segments_through(&x[0], &e, &x[1], &t, false) + segments_through(&x[1], &e, &x[0], &t, false)
    };
    let above = |x: &[Vec<DVec3>]| {
        let mean = |o: &[DVec3]| o.iter().map(|p| p.y).sum::<f64>() / o.len() as f64;
        mean(&x[1]) - mean(&x[0])
    };
    let frames = 10;
    let ctx = gpu();
    let (mut worst, mut gpu_above) = (0, 0.0);
    run_gpu(&ctx, &s, frames, |_, states| {
        let x: Vec<Vec<DVec3>> = states.iter().map(|o| o.positions()).collect();
        worst = worst.max(through(&x));
        gpu_above = above(&x);
    });
    assert_clean(&ctx);
    let mut cpu = msdsim::sim::cpu::CpuSim::new(&s);
    let mut cpu_worst = 0;
    for _ in 0..frames {
        cpu.step_frame();
        let x: Vec<Vec<DVec3>> = cpu.objects().iter().map(|o| o.x.clone()).collect();
        cpu_worst = cpu_worst.max(through(&x));
    }
    let x: Vec<Vec<DVec3>> = cpu.objects().iter().map(|o| o.x.clone()).collect();
    let cpu_above = above(&x);
    eprintln!(
        "{per_substep:.4} m a substep: edges through the other cloth at most {worst} (GPU), {cpu_worst} (reference); \
         the upper cloth {gpu_above:.4} m above the lower (GPU), {cpu_above:.4} (reference)"
    );
    assert_eq!((worst, cpu_worst), (0, 0), "edges passed through the other cloth (GPU, reference)");
    assert!(
        gpu_above > 0.0 && cpu_above > 0.0,
        "the upper cloth went through: {gpu_above}, {cpu_above} m above"
    );
}

/// Eight free cards of 4 x 5 particles (63 x 84 mm, 0.18 g: poker cards at Newton's
/// `cloth_poker_cards`' weight, stiffness and reach), lying flat 1 mm apart and shifted 3 mm a
/// card, dropped 1 mm onto the ground at VBD 10 x 10 (Newton's stack of cloths; its cards run
/// 20 x 10). At the end (8 frames, 0.13 s) each card must lie above the one below by at least
/// 80% of the reach (0.8 mm; as the thin cloths' stack) and no edge pass through another card
/// at any frame. Measured: none through, gaps 96% to 125% of the reach (the top card still
/// settling); with one contact round a substep (`SimModel::contact_rounds`) 17 edges
/// through, gaps -12% to 42%.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_stack_of_cards_stands_at_the_substeps_users_run() {
    use msdsim::sim::collider::{ColliderModel, Motion, Shape};
    use msdsim::sim::integrator::Integrator;
    let (cols, rows, cards, margin) = (4u32, 5u32, 8usize, 0.0004);
    let objects = (0..cards)
        .map(|k| {
            let mut c = cloth(cols, rows, 0.021);
            c.positions = (0..cols * rows)
                .map(|i| {
                    let (x, z) = ((i % cols) as f64 * 0.021, (i / cols) as f64 * 0.021);
                    DVec3::new(x + 0.003 * k as f64, 0.001 * (k + 1) as f64, z - 0.002 * k as f64)
                })
                .collect();
            c.mass = 1.8e-4 / (cols * rows) as f64;
            c.stiffness = [1000.0, 1000.0, 100.0];
            c.damping = 0.001;
            c.margin = margin;
            c.friction = 0.3;
            c
        })
        .collect();
    let mut s = scene(objects);
    s.gravity = DVec3::new(0.0, -9.8, 0.0);
    s.inter_object = true;
    s.integrator = Integrator::Vbd;
    s.substeps = 10;
    s.iterations = 10;
    let ground = Shape::Ground { height: 0.0 };
    s.colliders = vec![ColliderModel {
        shape: ground,
        friction: Some(0.3),
        motion: Motion::Fixed,
        turn: Turn::default(),
    }];
    stack_rests(&s, [cols, rows], 8, 2.0 * margin);
}

/// A free 7 x 7 cloth (3 cm spacing, 1 cm margin) thrown flat at 3.4 m/s onto the ground from
/// 5 cm, another cloth 5 m aside so that contact between objects is on, VBD at 10 iterations:
/// the colliders act inside the iterations (`SimModel::contact_rounds`) and must stop the
/// cloth as the constraint stage does, without a bounce: from the frame after it lands no
/// particle may move up faster than 3% of the impact speed, and at the end (0.25 s) every
/// particle lies within 1 mm of the margin above the ground. When the history kept the
/// colliders' moves, or the velocity took them over h, it bounced back at 1.0 to 1.8 m/s.
#[test]
fn a_cloth_thrown_on_the_ground_does_not_bounce_with_contact_rounds() {
    use msdsim::sim::collider::{ColliderModel, Motion, Shape};
    use msdsim::sim::integrator::Integrator;
    let (n, margin, speed) = (7u32, 0.01, 3.4);
    let layer = |x: f64| {
        let mut c = held_cloth(n, 0.03, 0.05);
        c.pinned.fill(false);
        c.positions.iter_mut().for_each(|p| p.x += x);
        c.margin = margin;
        c.friction = 0.5;
        c.velocities.fill(DVec3::new(0.0, -speed, 0.0));
        c
    };
    let mut s = scene(vec![layer(0.0), layer(5.0)]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    s.inter_object = true;
    s.integrator = Integrator::Vbd;
    s.iterations = 10;
    let ground = Shape::Ground { height: 0.0 };
    s.colliders =
        vec![ColliderModel { shape: ground, friction: None, motion: Motion::Fixed, turn: Turn::default() }];
    assert_eq!(s.contact_rounds(), 10);
    let ctx = gpu();
    let (mut landed, mut rising, mut off) = (None, 0.0f64, 0.0f64);
    run_gpu(&ctx, &s, 15, |f, states| {
        let x = states[0].positions();
        let v = states[0].velocities();
        let low = x.iter().map(|p| p.y).fold(f64::MAX, f64::min);
        if landed.is_none() && low < margin + 1e-3 {
            landed = Some(f);
        }
        if landed.is_some_and(|l| f > l) {
            rising = rising.max(v.iter().map(|v| v.y).fold(f64::MIN, f64::max));
        }
        off = x.iter().map(|p| (p.y - margin).abs()).fold(0.0, f64::max);
    });
    eprintln!("landed at frame {landed:?}; then rising at most {rising:.4} m/s; at the end within {off:.5} m of the margin");
    assert!(landed.is_some(), "the cloth never reached the ground");
    assert!(rising < 0.03 * speed, "the cloth bounced: {rising} m/s up after landing");
    assert!(off < 1e-3, "the cloth is {off} m off its margin above the ground at the end");
    assert_clean(&ctx);
}
