//! A cloth's contact with its own triangles against physics: a geometric invariant (no edge of
//! the cloth passes through one of its triangles: an exact segment-triangle test over every
//! edge the renderer draws, against every triangle that does not share a vertex with it) in a
//! cloth hung over its middle row whose two flaps swing through each other (particle against
//! particle contact let 170 to 193 edges through), and momentum conserved in a collision of
//! two layers. Both GPU paths (fused and per stage, with and without contact lists). On
//! lavapipe with validation and synchronization validation.

use crate::common;

use common::*;
use glam::DVec3;
use msdsim::sim::collider::{ColliderModel, Motion, Shape};
use msdsim::sim::cpu::CpuSim;
use msdsim::sim::gpu::GpuSim;
use msdsim::sim::model::{ObjectModel, SelfCollisionMethod, SimModel};
use msdsim::sim::turn::Turn;

/// Edges of the cloth (positions `x`, `cols` x `rows`) through one of its triangles that does
/// not share a vertex with them.
fn crossings(x: &[DVec3], cols: usize, rows: usize) -> usize {
    segments_through(x, &cloth_edges(cols, rows), x, &cloth_triangles(cols, rows), true)
}

/// Edges through a triangle none of whose vertices is within one grid step (in rows or
/// columns) of the edge's ends: a layer passing through another, as opposed to a fold sharper
/// than a cell, whose nearby pairs the rest-state filter leaves out.
fn layer_crossings(x: &[DVec3], cols: usize, rows: usize) -> usize {
    let near = |a: usize, b: usize| (a % cols).abs_diff(b % cols) <= 1 && (a / cols).abs_diff(b / cols) <= 1;
    let triangles = cloth_triangles(cols, rows);
    let apart = |e: &[usize; 2]| -> Vec<[usize; 3]> {
        triangles.iter().filter(|t| !e.iter().any(|&a| t.iter().any(|&b| near(a, b)))).copied().collect()
    };
    cloth_edges(cols, rows).iter().filter(|e| segments_through(x, &[**e], x, &apart(e), true) > 0).count()
}

/// `worst` (the most edges through triangles, the most through a layer) with positions `x`.
fn worst_counts(worst: (usize, usize), x: &[DVec3], cols: usize, rows: usize) -> (usize, usize) {
    let all = crossings(x, cols, rows);
    let layers = if all > 0 { layer_crossings(x, cols, rows) } else { 0 };
    (worst.0.max(all), worst.1.max(layers))
}

/// The GPU paths of `worst_crossings` (name, fused, contact lists forced on or off).
const FUSED: (&str, bool, Option<bool>) = ("fused", true, None);
const PER_STAGE_LISTS: (&str, bool, Option<bool>) = ("per stage, lists", false, Some(true));

/// The most crossing edges over `frames` frames of `s` (object 0), on each GPU path of `paths`
/// (name, fused, contact lists forced on or off).
fn worst_crossings(
    s: &SimModel,
    frames: u32,
    paths: &[(&'static str, bool, Option<bool>)],
) -> Vec<(&'static str, usize, u32, usize)> {
    let ctx = gpu();
    let (cols, rows) = (s.objects[0].dims[0] as usize, s.objects[0].dims[1] as usize);
    let mut out = Vec::new();
    for &(path, fused, lists) in paths {
        let mut gpu = GpuSim::new(&ctx, s).unwrap();
        gpu.set_fused(&ctx, fused).unwrap();
        gpu.force_contact_lists(lists);
        assert_eq!(gpu.runs_fused(0), fused, "{path}");
        let (mut worst, mut at, mut last) = (0, 0, 0);
        for f in 0..frames {
            gpu.step_frame(&ctx).unwrap();
            let n = crossings(&gpu.read_states(&ctx).unwrap()[0].positions(), cols, rows);
            if n > worst {
                (worst, at) = (n, f);
            }
            last = n;
        }
        gpu.destroy(&ctx);
        out.push((path, worst, at, last));
    }
    assert_clean(&ctx);
    out
}

/// A soft cloth of `cols` x `rows` particles 2.5 cm apart, with self-collision at half the
/// spacing (the default thickness).
fn soft_cloth(cols: u32, rows: u32) -> msdsim::sim::model::ObjectModel {
    soft_cloth_spaced(cols, rows, 0.025)
}

/// `soft_cloth` with its particles `spacing` apart.
fn soft_cloth_spaced(cols: u32, rows: u32, spacing: f64) -> msdsim::sim::model::ObjectModel {
    let mut c = cloth(cols, rows, spacing);
    c.stiffness = [400.0, 100.0, 0.5];
    c.damping = 0.01;
    c.drag = 0.002;
    c.mass = 0.002;
    c.stretch_limit = Some(0.1);
    c.self_distance = Some(0.5 * spacing);
    c.triangle_contact = true;
    c
}

/// A 21 x 21 cloth hanging in a vertical plane, held along its middle row: the upper flap,
/// nudged, falls over the held row, swings down through where the lower flap hangs and
/// pushes it along, both flaps swinging face to face. Fused (the path of a cloth this size);
/// per stage with and without contact lists is the exhaustive tier's.
#[test]
fn a_cloth_folding_over_its_middle_row_never_passes_through_itself() {
    cloth_folding_over_its_middle_row(&[FUSED]);
}

#[test]
#[ignore = "exhaustive tier: per stage with and without contact lists"]
fn a_cloth_folding_over_its_middle_row_never_passes_through_itself_per_stage() {
    cloth_folding_over_its_middle_row(&[PER_STAGE_LISTS, ("per stage", false, Some(false))]);
}

fn cloth_folding_over_its_middle_row(paths: &[(&'static str, bool, Option<bool>)]) {
    let n = 21u32;
    let mut c = soft_cloth(n, n);
    for (i, v) in c.velocities.iter_mut().enumerate() {
        if i < (n * (n / 2)) as usize {
            *v = DVec3::new(0.0, 0.0, 0.5);
        }
    }
    for col in 0..n {
        c.pinned[(col + (n / 2) * n) as usize] = true;
    }
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    let runs = worst_crossings(&s, 90, paths);
    println!("{runs:?}");
    assert!(runs.iter().all(|r| r.1 == 0), "edges through the cloth's own triangles: {runs:?}");
}

/// A `soft_cloth` strip of `dims` (columns, rows) particles `spacing` apart standing on end,
/// its top row at height `top`, leaning by `tilt` radians, over the ground (friction 0.5, its
/// margin 5 mm), under gravity.
fn standing_strip(dims: [usize; 2], spacing: f64, top: f64, tilt: f64) -> SimModel {
    let [cols, rows] = dims;
    let mut c = soft_cloth_spaced(cols as u32, rows as u32, spacing);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % cols) as f64, (i / cols) as f64);
        *p = DVec3::new(col * spacing - 0.05, top - row * spacing * tilt.cos(), row * spacing * tilt.sin());
    }
    c.margin = 0.005;
    c.friction = 0.5;
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    let ground = Shape::Ground { height: 0.0 };
    s.colliders =
        vec![ColliderModel { shape: ground, friction: None, motion: Motion::Fixed, turn: Turn::default() }];
    s
}

/// A 5 x 61 strip (2.5 cm spacing, 1.5 m long, thickness 12.5 mm) dropped on end from 10 cm
/// onto the ground, tilted 0.2 rad so that it folds (upright it stays in its plane): it
/// buckles as it lands, its top arriving at about 5 m/s, and piles in one-cell folds. A layer
/// landing on several others takes only its share of each contact in a pass over them (mass
/// splitting), so with one pass a substep it is stopped over several substeps, deeper than the
/// thickness, and passes: 283 crossing edges at worst on the f64 reference (281 on the GPU).
/// Four passes (the default `contact_iterations`) stop it within the substep but where the
/// folds are sharper than a cell or edges cross edges, which no vertex-triangle contact sees
/// (issue 26 is open on those): measured 10 on the reference and 6 on the GPU (fused), 14 and
/// 25 once the contact code was shared with edge pairs (the same sums in another order; where
/// it piles is chaotic: 23 to 32 in builds of the same model that differed in the order of
/// rounding; 38 and 26 since a resting contact's friction holds), so the bound, 60, leaves room
/// for another driver's rounding while staying far under one pass's count). With edges kept
/// from edges too (`self_contact = "triangles_and_edges"`: each share of a contact
/// over-relaxed, edge pairs where an edge is creased, counted from 1.33 h apart at rest) four
/// passes let fewer through: measured 0 on the reference and 0 on the GPU (fused). Where it
/// piles is chaotic: over 24 tilts from 0.02 to 0.48 rad at friction 0.3, 0.5 and 0.7 the
/// reference let none through in 68 of the 72 runs and 4 to 6 in four, each next to a fold
/// sharper than a cell, none through a layer (measured with the bound on each particle's move
/// that the truncation replaced; 185 edges in 16 runs without it, through layers in some), the
/// GPU per stage none at 11 tilts (docs/records/bench/cpu/edge-margin/, 6), so that bound is 15 and
/// none through a layer. The count changes in place. The default tier runs the GPU without
/// edges and the reference with them; the reference at one pass and at four without edges
/// (`one_contact_pass_lets_a_strip_pile_through`) and the GPU with edges are the exhaustive
/// tier's.
#[test]
fn contact_iterations_stop_a_strip_piling_on_itself() {
    let s = piling_strip();
    assert_eq!(s.contact_iterations, 4);
    let (four_edges, four_edges_layers) = reference_pile(&with_edges(&s), 4);
    let (gpu_four, _) = fused_pile(&s);
    println!(
        "crossing edges at worst: reference, four passes with edges {four_edges} \
         ({four_edges_layers} through a layer); GPU (fused), four {gpu_four}"
    );
    assert!(gpu_four <= 60, "four passes: {gpu_four} crossing edges (GPU)");
    assert!(four_edges <= 15, "four passes with edges: {four_edges} crossing edges (reference)");
    assert!(
        four_edges_layers == 0,
        "four passes with edges: {four_edges_layers} edges through a layer (reference)"
    );
}

/// The piling strip of `contact_iterations_stop_a_strip_piling_on_itself` with edges kept
/// from edges on the GPU (fused), as bounded there.
#[test]
#[ignore = "exhaustive tier: the pile with edge contact on the GPU"]
fn a_strip_piling_with_edge_contact_on_the_gpu_never_passes_a_layer() {
    let (edges, layers) = fused_pile(&with_edges(&piling_strip()));
    println!("crossing edges at worst: {edges} ({layers} through a layer)");
    assert!(
        edges <= 15 && layers == 0,
        "four passes with edges: {edges} crossing edges, {layers} through a layer"
    );
}

/// The piling strip's frames.
const PILE_FRAMES: usize = 45;

/// The 5 x 61 strip of `contact_iterations_stop_a_strip_piling_on_itself`, dropped on end.
fn piling_strip() -> SimModel {
    standing_strip([5, 61], 0.025, 1.6, 0.2)
}

/// `s` with edges kept from edges (`self_contact = "triangles_and_edges"`).
fn with_edges(s: &SimModel) -> SimModel {
    let mut m = s.clone();
    m.objects[0].edge_contact = true;
    m
}

/// The most crossing edges (all, through a layer) of the 5 x 61 piling strip `s` on the
/// reference at `passes` contact passes a substep.
fn reference_pile(s: &SimModel, passes: u32) -> (usize, usize) {
    let mut m = s.clone();
    m.contact_iterations = passes;
    let mut cpu = CpuSim::new(&m);
    (0..PILE_FRAMES).fold((0, 0), |worst, _| {
        cpu.step_frame();
        worst_counts(worst, &cpu.objects()[0].x, 5, 61)
    })
}

/// The same on the GPU, fused; then the pass count changes in place while more than one pass
/// stays (as the editor applies it), and one pass or more than one is a rebuild (the further
/// passes' pipelines).
fn fused_pile(m: &SimModel) -> (usize, usize) {
    let ctx = gpu();
    let mut g = GpuSim::new(&ctx, m).unwrap();
    g.set_fused(&ctx, true).unwrap();
    assert!(g.runs_fused(0));
    let mut worst = (0, 0);
    for _ in 0..PILE_FRAMES {
        g.step_frame(&ctx).unwrap();
        worst = worst_counts(worst, &g.read_states(&ctx).unwrap()[0].positions(), 5, 61);
    }
    let with = |k: u32| SimModel { contact_iterations: k, ..m.clone() };
    assert!(g.takes_params(&with(2)) && !g.takes_params(&with(1)));
    g.update_params(&with(2)).unwrap();
    g.step_frame(&ctx).unwrap();
    g.destroy(&ctx);
    assert_clean(&ctx);
    worst
}

/// On the reference, one contact pass a substep lets the piling strip of
/// `contact_iterations_stop_a_strip_piling_on_itself` through (measured 283 crossing edges)
/// and four stop it but for a few (the bound as that test's on the GPU).
#[test]
#[ignore = "exhaustive tier: the pile on the reference, at one pass and at four"]
fn one_contact_pass_lets_a_strip_pile_through() {
    let s = piling_strip();
    let ((one, _), (four, _)) = (reference_pile(&s, 1), reference_pile(&s, 4));
    println!("crossing edges at worst: one pass {one}, four {four}");
    assert!(one > 100, "one pass a substep should let the pile through (measured 283), not {one}");
    assert!(four <= 60, "four passes: {four} crossing edges");
}

/// The total momentum of velocities `v` over the mass of one particle.
fn momentum(v: &[DVec3]) -> DVec3 {
    v.iter().sum()
}

/// The largest change of object 0's momentum, relative to where it began, over `frames`
/// frames of `s` on the GPU path `fused`, and its velocities at the end.
fn momentum_change(
    ctx: &msdsim::vk::GpuContext,
    s: &SimModel,
    fused: bool,
    frames: u32,
) -> (f64, Vec<DVec3>) {
    let start = momentum(&s.objects[0].velocities);
    let mut g = GpuSim::new(ctx, s).unwrap();
    g.set_fused(ctx, fused).unwrap();
    let mut worst = 0.0f64;
    for _ in 0..frames {
        g.step_frame(ctx).unwrap();
        let v = g.read_states(ctx).unwrap()[0].velocities();
        worst = worst.max((momentum(&v) - start).length() / start.length());
    }
    let v = g.read_states(ctx).unwrap()[0].velocities();
    g.destroy(ctx);
    (worst, v)
}

/// Contact conserves momentum: a 13 x 10 cloth folded in two, its front layer thrown at the
/// back one at 3 m/s, the whole drifting sideways at 0.5 m/s, no gravity, pins or colliders.
/// Every contact moves the particle and the triangle's vertices by equal and opposite momenta
/// and springs act in pairs, so the total momentum stays what it was to f32 rounding (a
/// relative 1e-5 allowed, 9.3e-8 measured; the reference, in f64, 1e-9), while the layers do
/// collide (the front layer's 3 m/s towards the back falls under 2; measured 1.54, as the two
/// layers move on together). The reference and the GPU fused (the path of a cloth this size)
/// with triangles, the default contact; the exhaustive tier the per-stage path and both paths
/// with edges kept from edges too (whose pipelines take lavapipe a minute to compile).
#[test]
fn contact_between_layers_conserves_momentum() {
    layers_conserve_momentum(false, &[true]);
}

#[test]
#[ignore = "exhaustive tier: the other GPU paths, and edges"]
fn contact_between_layers_conserves_momentum_on_the_other_paths() {
    layers_conserve_momentum(false, &[false]);
    layers_conserve_momentum(true, &[true, false]);
}

fn layers_conserve_momentum(edges: bool, paths: &[bool]) {
    let mut c = cloth(13, 10, 0.05);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % 13) as f64, (i / 13) as i64);
        let (rows_down, z) = if row <= 4 { (row, 0.0) } else { (9 - row, 0.06) };
        *p = DVec3::new(col * 0.05, 1.0 - rows_down as f64 * 0.05, z);
    }
    for (i, v) in c.velocities.iter_mut().enumerate() {
        *v = DVec3::new(0.5, 0.0, if i >= 5 * 13 { -3.0 } else { 0.0 });
    }
    c.stiffness = [200.0, 50.0, 0.0];
    c.self_distance = Some(0.025);
    c.triangle_contact = true;
    c.edge_contact = edges;
    let s = scene(vec![c]);
    let front = |v: &[DVec3]| v[5 * 13..].iter().map(|v| v.z).sum::<f64>() / (5.0 * 13.0);
    let start = momentum(&s.objects[0].velocities);
    let ctx = gpu();
    for &fused in paths {
        let (worst, v) = momentum_change(&ctx, &s, fused, 20);
        println!("edges {edges}, fused {fused}: momentum change {worst:e}, front layer {} m/s", front(&v));
        assert!(worst <= 1e-5, "edges {edges}, fused {fused}: momentum changed by {worst:e} of itself");
        assert!(
            front(&v) > -2.0,
            "edges {edges}, fused {fused}: the layers did not collide ({} m/s)",
            front(&v)
        );
    }
    assert_clean(&ctx);
    let mut cpu = CpuSim::new(&s);
    for _ in 0..20 {
        cpu.step_frame();
    }
    let change = (momentum(&cpu.objects()[0].v) - start).length() / start.length();
    assert!(change <= 1e-9, "edges {edges}, reference: momentum changed by {change:e} of itself");
}

/// A 13 x 10 cloth (5 cm apart) folded in two, its layers `gap` apart, the front one moving
/// towards the back at `speed` and sideways at a quarter of it, jittered by up to 2 mm,
/// contact against triangles at 3 cm with friction 0.5.
fn fold(gap: f64, speed: f64) -> SimModel {
    fold_of(0.05, 0.03, gap, speed)
}

/// The same fold with the particles `spacing` apart and contact at `h`.
fn fold_of(spacing: f64, h: f64, gap: f64, speed: f64) -> SimModel {
    let mut c = cloth(13, 10, spacing);
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % 13) as f64, (i / 13) as i64);
        let (rows_down, z) = if row <= 4 { (row, 0.0) } else { (9 - row, gap) };
        let k = i as u64 * 3;
        let jitter = DVec3::new(noise(k), noise(k + 1), noise(k + 2)) * 0.002;
        *p = DVec3::new(col * spacing, 1.0 - rows_down as f64 * spacing, z) + jitter;
    }
    for v in &mut c.velocities[5 * 13..] {
        *v = DVec3::new(0.25 * speed, 0.0, -speed);
    }
    c.stiffness = [60.0, 20.0, 0.0];
    c.friction = 0.5;
    c.self_distance = Some(h);
    c.triangle_contact = true;
    scene(vec![c])
}

/// The most contacts any particle of object 0 keeps at the start (the reference's: triangles,
/// and with edge contact edge pairs, nearer than its self-collision distance, not left out, by
/// their owners).
fn most_contacts(s: &SimModel) -> usize {
    let o = &s.objects[0];
    let mut count = vec![0; o.positions.len()];
    for c in msdsim::sim::cpu::self_contact::contacts(o, &o.positions) {
        count[c.owner()] += 1;
    }
    count.into_iter().max().unwrap_or(0)
}

/// The GPU against the CPU reference (which tests every particle against every triangle),
/// frame by frame from the same state: a fold whose layers start inside each other's thickness
/// (1.5 cm apart), one thrown together from 7 cm at 4 m/s (contact lists rebuilt within
/// frames), and a dense one (1 cm spacing, 1.9 cm thickness, layers 5 mm apart: particles with
/// up to 43 contacts, more than the 16 a particle keeps, which the apply pass finds again, and
/// more than the 32 past which per stage it applies them as it finds them); every search
/// (every pair, the hash; per stage with contact lists on and off) and
/// both paths; the thrown and the dense fold also with edges kept from edges (`edge_contact`).
/// Within 1e-4 m a frame (f32 against f64; the contacts' sums are exact integers on the GPU,
/// so every GPU path gives the same state, to 1e-6 m, 2e-5 with edges: below).
/// The default tier runs the hash fused; the exhaustive tier per stage with the lists and
/// without, and brute force.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn the_gpu_finds_the_contacts_the_reference_finds() {
    gpu_finds_the_contacts(&[(SelfCollisionMethod::Hash, true, None)]);
}

#[test]
#[ignore = "exhaustive tier: per stage with and without lists, and by brute force"]
fn the_gpu_finds_the_contacts_the_reference_finds_by_every_search() {
    gpu_finds_the_contacts(&[
        (SelfCollisionMethod::Hash, false, Some(true)),
        (SelfCollisionMethod::BruteForce, true, None),
        (SelfCollisionMethod::Hash, false, Some(false)),
    ]);
}

/// A cloth's search split among lanes (per stage with edge pairs: 8 lanes on a GPU, 1 on a
/// CPU driver) applies the same contacts as one lane, each once, and the moves are summed in
/// fixed point in any order: after 4 frames the states are the same bit for bit, with the
/// contact lists off (the find, apply and note passes split) and on (the note pass alone), in
/// a thrown fold and a dense one (particles with more contacts than the 16 slots, which the
/// apply pass's split search applies as it finds them).
#[test]
#[ignore = "exhaustive tier: 8 runs of 4 frames with edge contact"]
fn a_search_split_among_lanes_gives_the_state_of_one_lane() {
    let ctx = gpu();
    let scenes =
        [("thrown", with_edges(&fold(0.07, 4.0))), ("dense", with_edges(&fold_of(0.01, 0.019, 0.005, 0.0)))];
    for (name, s) in scenes {
        for lists in [Some(false), Some(true)] {
            let mut states = Vec::new();
            for lanes in [1, 8] {
                let mut g = GpuSim::new(&ctx, &s).unwrap();
                g.set_fused(&ctx, false).unwrap();
                g.force_contact_lists(lists);
                g.set_search_lanes(lanes);
                for _ in 0..4 {
                    g.step_frame(&ctx).unwrap();
                }
                states.push(g.read_states(&ctx).unwrap()[0].positions());
                g.destroy(&ctx);
            }
            let d = (states[0].iter().zip(&states[1])).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
            println!("{name} fold, lists {lists:?}: 8 lanes from 1 by {d:e} m");
            // (compared whole: a NaN differs from itself)
            assert!(states[0] == states[1], "{name} fold, lists {lists:?}: 8 lanes part from 1 by {d} m");
        }
    }
    assert_clean(&ctx);
}

/// ... on each (search, fused, contact lists forced) of `paths`.
fn gpu_finds_the_contacts(paths: &[(SelfCollisionMethod, bool, Option<bool>)]) {
    let ctx = gpu();
    let dense = fold_of(0.01, 0.019, 0.005, 0.0);
    let most = most_contacts(&dense);
    println!("dense fold: at most {most} contacts a particle");
    assert!(most > 32, "the dense fold should give particles more than 32 contacts, not {most}");
    let (thrown, edges_dense) = (fold(0.07, 4.0), with_edges(&dense));
    let scenes = [
        ("inside", fold(0.015, 0.0)),
        ("thrown edges", with_edges(&thrown)),
        ("thrown", thrown),
        ("dense", dense),
        ("dense edges", edges_dense),
    ];
    for (name, s) in scenes {
        let mut states = Vec::new();
        for &(method, fused, lists) in paths {
            let mut m = s.clone();
            m.self_collision = method;
            let mut g = GpuSim::new(&ctx, &m).unwrap();
            g.set_fused(&ctx, fused).unwrap();
            g.force_contact_lists(lists);
            let mut cpu = CpuSim::new(&m);
            let mut worst = 0.0f64;
            for _ in 0..8 {
                g.step_frame(&ctx).unwrap();
                cpu.step_frame();
                let st = g.read_states(&ctx).unwrap();
                let x = st[0].positions();
                worst =
                    (x.iter().zip(&cpu.objects()[0].x)).map(|(a, b)| a.distance(*b)).fold(worst, f64::max);
                cpu.set_state(0, x, st[0].velocities());
            }
            println!("{name} {method:?} fused {fused} lists {lists:?}: {worst:e} m");
            assert!(
                worst <= 1e-4,
                "{name} {method:?} fused {fused} lists {lists:?}: {worst} m from the reference"
            );
            states.push(g.read_states(&ctx).unwrap()[0].positions());
            g.destroy(&ctx);
        }
        // (With edges each move is truncated, scaled whole by the fraction that keeps its
        // normal approach out of the gap: the kernels' f32 rounding, about 1e-7 m apart, moves
        // that fraction by its ratio to the approach, so the paths part by up to 7e-6 m in 8
        // frames of the thrown fold.)
        let paths_within = if s.objects[0].edge_contact { 2e-5 } else { 1e-6 };
        for x in &states[1..] {
            let d = x.iter().zip(&states[0]).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
            assert!(d <= paths_within, "{name}: GPU paths part by {d} m");
        }
    }
    assert_clean(&ctx);
}

/// A fused frame of many substeps equals the per-stage path on lavapipe too: lavapipe ends an
/// invocation's loops after 65,535 iterations of all of them together, and the fused kernel ran
/// a frame's substeps in one dispatch; past the limit the dispatch's writes were lost and the
/// frame left the state as it was, silently, while the contact sums it had added stayed (the
/// 33 x 33 towel with triangles lost its frame at 112 substeps and ran away at 128; this dense
/// fold loses a frame of 250 substeps or more, measured with the limit left unhandled: 12 mm
/// from the per-stage path, the whole of the fold's motion). It now runs 8 substeps a dispatch
/// on such a device. The dense fold (more than 16 contacts a particle: long searches), one frame
/// of 320 substeps of 0.1 ms (past the 250 at which it lost its frame), both paths from the same state; the contacts' sums are exact
/// integers, so within 1e-6 m (measured on lavapipe: 0). With edge contact a fused dispatch runs
/// one substep there (its search's loops are longer): the strip and the GPU-against-reference
/// tests run it so.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_fused_frame_of_many_substeps_equals_the_per_stage_path() {
    let ctx = gpu();
    let mut m = fold_of(0.01, 0.019, 0.005, 0.0);
    m.substeps = 320;
    m.frame_dt = 320.0 * 1e-4;
    let mut x = Vec::new();
    for fused in [true, false] {
        let mut g = GpuSim::new(&ctx, &m).unwrap();
        g.set_fused(&ctx, fused).unwrap();
        assert_eq!(g.runs_fused(0), fused);
        g.step_frame(&ctx).unwrap();
        x.push(g.read_states(&ctx).unwrap()[0].positions());
        g.destroy(&ctx);
    }
    let d = x[0].iter().zip(&x[1]).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    let moved = x[1].iter().zip(&m.objects[0].positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    println!("fused against per stage after 320 substeps: {d:e} m (the fold moved up to {moved:e} m)");
    assert!(moved > 1e-3, "the fold should move, not {moved} m");
    assert!(d <= 1e-6, "the fused frame of 320 substeps parts from the per-stage one by {d} m");
    assert_clean(&ctx);
}

/// Coulomb friction between a cloth's layers, against the impulse form of Coulomb's law: a
/// 13 x 20 cloth folded in two (5 cm apart, soft springs), its layers 3.5 cm apart and half a
/// cell across, approaching at vn = 2 m/s and sliding past each other at vt = 1 m/s along the
/// fold, no gravity, contact at 3 cm. A perfectly inelastic collision of two equal layers takes
/// a normal impulse of half a layer's mass times vn; friction takes at most mu times that
/// tangentially, so their relative sliding speed after it is max(0, vt - mu vn) whatever the
/// step: 1 (mu 0), 0.5 (mu 0.25), 0 (mu 0.8: they stick). Measured on the layers' middles
/// (rows 2 to 4 from the far edges, columns 4 to 8, which the fold's pull has not reached)
/// after two frames, at 8 and 32 substeps, both GPU paths (and the reference at 8), within
/// 0.1 m/s (10% of vt). Measured: 1.069 / 1.042, 0.571 / 0.542, -0.003 / -0.005 at 8 / 32
/// substeps (since the contact iterations; 1.076 / 1.047, 0.578 / 0.546 before): even without
/// friction the layers gain 4-7% of sliding speed, because each
/// triangle's thickness has rounded edges, and a particle that has just slid across the edge
/// between two flat triangles is also pushed by the one it left, along its motion
/// (docs/ACCURACY.md). The layers do not bounce: approaching within 0.05 m/s after (measured
/// -0.010 to -0.004; 0.5 to 1 m/s apart before the overlap a substep's approach made was
/// undone with its velocity and the rest in position only). Momentum, the whole drifting at
/// 0.5 m/s, is conserved as without friction (relative 1e-5; measured up to 1.7e-6). With edge
/// contact too (per stage and the reference; each contact's share over-relaxed by 1.5, which
/// the branch measured bouncing 0.15 m/s at 32 substeps before edge pairs were gated on a
/// crease): 1.067 / 1.046, 0.571 / 0.539, -0.007 / -0.022, the layers parting at 0.011 to
/// 0.034 m/s, within the same bounds. One test runs 8 substeps, the other 32 (both in the
/// exhaustive tier).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn friction_between_layers_takes_at_most_mu_times_the_normal_impulse() {
    friction_between_layers(&[8]);
}

#[test]
#[ignore = "exhaustive tier: 32 substeps"]
fn friction_between_layers_at_more_substeps() {
    friction_between_layers(&[32]);
}

fn friction_between_layers(substep_counts: &[u32]) {
    // ... and with edge contact (per stage, its default path), whose over-relaxed shares may
    // bounce (see above).
    let cases: [(bool, &[bool]); 2] = [(false, &[true, false]), (true, &[false])];
    layers_slide_as_coulomb_says(&cases, substep_counts, &|c| c);
}

/// The cloth of the friction tests between layers: columns, rows.
const LAYERS_DIMS: (usize, usize) = (13, 20);
/// Their layers' approaching and sliding speeds (m/s).
const LAYERS_VN: f64 = 2.0;
const LAYERS_VT: f64 = 1.0;

/// Folds object `c` (LAYERS_DIMS, 5 cm apart, its rest shape taken already) in two along its
/// middle, its layers 3.5 cm apart and moving as the friction tests between layers have it:
/// approaching at LAYERS_VN, sliding past each other at LAYERS_VT along the fold, the whole
/// drifting at 0.5 m/s. The front layer lies half a cell across, so that its particles meet
/// the back layer's triangles inside, where the surface is flat, not at its vertices.
fn fold_into_layers(c: &mut ObjectModel) {
    let (cols, rows) = LAYERS_DIMS;
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % cols) as f64, i / cols);
        let (down, shift, z) = if row < rows / 2 { (row, 0.0, 0.0) } else { (rows - 1 - row, 0.025, 0.035) };
        *p = DVec3::new(col * 0.05 + shift, 1.0 - down as f64 * 0.05 - shift, z);
    }
    for (i, v) in c.velocities.iter_mut().enumerate() {
        let side = if i / cols < rows / 2 { -0.5 } else { 0.5 };
        *v = DVec3::new(0.0, 0.5, 0.0) + DVec3::new(LAYERS_VT * side, 0.0, -LAYERS_VN * side);
    }
}

/// The friction tests between layers: for each case (edge contact or not, the GPU paths to run:
/// fused or not), mu 0, 0.25 and 0.8 and each of `substep_counts`, a LAYERS_DIMS cloth (soft
/// springs, contact with its triangles at 3 cm) made into the object tested by `object`, then
/// folded by `fold_into_layers`, run two frames on each path and, at 8 substeps, on the
/// reference: the relative sliding speed of the layers' middles (rows 2 to 4 from the far
/// edges, columns 4 to 8) within 0.1 m/s of max(0, vt - mu vn), their approach within 0.05 m/s
/// of 0, the momentum within 1e-5.
pub fn layers_slide_as_coulomb_says(
    cases: &[(bool, &[bool])],
    substep_counts: &[u32],
    object: &dyn Fn(ObjectModel) -> ObjectModel,
) {
    let (cols, rows) = LAYERS_DIMS;
    // (folded after `object`, which may take the rest shape from the flat cloth)
    let layers = |mu: f64, substeps: u32, edges: bool| {
        let mut c = cloth(cols as u32, rows as u32, 0.05);
        c.stiffness = [50.0, 10.0, 1.0];
        c.self_distance = Some(0.03);
        c.triangle_contact = true;
        c.edge_contact = edges;
        c.friction = mu;
        let mut c = object(c);
        fold_into_layers(&mut c);
        let mut s = scene(vec![c]);
        s.substeps = substeps;
        s
    };
    // Relative sliding and approaching speeds of the layers' middles (front minus back).
    let relative = |v: &[DVec3]| {
        let mean = |rows: std::ops::RangeInclusive<usize>| {
            let picked: Vec<DVec3> = rows.flat_map(|r| (4..=8).map(move |c| v[c + r * cols])).collect();
            picked.iter().sum::<DVec3>() / picked.len() as f64
        };
        let d = mean(rows - 5..=rows - 3) - mean(2..=4);
        (d.x, -d.z)
    };
    // (each particle by its mass: a mesh cloth's lumped by area, lighter at its border)
    let momentum = |o: &msdsim::sim::model::ObjectModel, v: &[DVec3]| {
        v.iter().enumerate().map(|(i, v)| *v * o.mass_of(i)).sum::<DVec3>()
    };
    let ctx = gpu();
    let mut failures = Vec::new();
    for &(edges, paths) in cases {
        for mu in [0.0, 0.25, 0.8] {
            let expected = f64::max(0.0, LAYERS_VT - mu * LAYERS_VN);
            for &substeps in substep_counts {
                let s = layers(mu, substeps, edges);
                let start = momentum(&s.objects[0], &s.objects[0].velocities);
                let mut runs = Vec::new();
                for &fused in paths {
                    let mut g = GpuSim::new(&ctx, &s).unwrap();
                    g.set_fused(&ctx, fused).unwrap();
                    assert_eq!(g.runs_fused(0), fused);
                    g.step_frame(&ctx).unwrap();
                    g.step_frame(&ctx).unwrap();
                    runs.push((
                        if fused { "fused" } else { "per stage" },
                        g.read_states(&ctx).unwrap()[0].velocities(),
                    ));
                    g.destroy(&ctx);
                }
                if substeps == 8 {
                    let mut cpu = CpuSim::new(&s);
                    cpu.step_frame();
                    cpu.step_frame();
                    runs.push(("reference", cpu.objects()[0].v.clone()));
                }
                for (path, v) in runs {
                    let (slide, approach) = relative(&v);
                    let change = (momentum(&s.objects[0], &v) - start).length() / start.length();
                    let path = if edges { format!("{path}, edges") } else { path.to_string() };
                    println!(
                        "mu {mu}, {substeps} substeps, {path}: sliding {slide:.4} m/s (closed form \
                         {expected}), approaching {approach:.4} m/s, momentum {change:e}"
                    );
                    if (slide - expected).abs() > 0.1 || approach.abs() > 0.05 || change > 1e-5 {
                        failures.push(format!(
                            "mu {mu}, {substeps} substeps, {path}: {slide}, {approach}, {change:e}"
                        ));
                    }
                }
            }
        }
    }
    assert_clean(&ctx);
    assert!(failures.is_empty(), "sliding speed (m/s), approach (m/s), momentum: {failures:#?}");
}

/// The least distance between two segments of the rope at `x` that share no node.
fn closest_segments(x: &[DVec3]) -> f64 {
    let mut least = f64::MAX;
    for a in 0..x.len() - 1 {
        for b in a + 2..x.len() - 1 {
            let (s, u) = msdsim::sim::cpu::self_contact::segment_nearest(x[a], x[a + 1], x[b], x[b + 1]);
            least = least.min(x[a].lerp(x[a + 1], s).distance(x[b].lerp(x[b + 1], u)));
        }
    }
    least
}

/// A free rope of 40 nodes 5 cm apart, 1 cm thick (radius 5 mm: the nodes ten radii apart),
/// self-collision at its thickness: as capsules (`capsules`) or, as the paper has it, node
/// against node.
fn coarse_rope(capsules: bool) -> msdsim::sim::model::ObjectModel {
    let mut r = rope(40, 0.05);
    r.stiffness = [800.0, 0.0, 2.0];
    r.damping = 0.01;
    r.rope_radius = 0.005;
    r.margin = 0.005;
    r.self_distance = Some(0.01);
    r.triangle_contact = capsules;
    r
}

/// A rope's self-collision keeps its segments apart as capsules: the coarse rope above dropped
/// on end from 2 m onto the floor (tilted 0.15 rad so that it coils), friction 0.5, piling for
/// 1.5 s. Node against node, segments pass through each other between the nodes (the closest
/// two that share no node meet: 0 measured, on the reference); as capsules, no two come nearer
/// than half the thickness on the reference and on both GPU paths (measured: 0.76 h on the
/// reference, 0.83 and 0.84 h on the GPU; a pile's Jacobi passes leave some overlap, and a
/// segment passing through another would bring them to 0). The GPU fused (a small rope's
/// path) here; per stage in the exhaustive tier.
#[test]
fn a_rope_piling_on_the_floor_never_passes_through_itself() {
    rope_piling(&[true]);
}

#[test]
#[ignore = "exhaustive tier: the pile per stage"]
fn a_rope_piling_on_the_floor_never_passes_through_itself_per_stage() {
    rope_piling(&[false]);
}

/// The rope pile above on the GPU paths `fused` (true: fused) against the references.
fn rope_piling(fused_paths: &[bool]) {
    let piling = |capsules: bool| {
        let mut r = coarse_rope(capsules);
        let tilt: f64 = 0.15;
        for (i, p) in r.positions.iter_mut().enumerate() {
            let k = i as f64 * 0.05;
            *p = DVec3::new(k * tilt.sin(), 2.05 - k * tilt.cos(), 0.3 * k * tilt.sin());
        }
        r.drag = 0.005;
        r.friction = 0.5;
        r.stretch_limit = Some(0.05);
        let mut s = scene(vec![r]);
        s.gravity = DVec3::new(0.0, -9.81, 0.0);
        let ground = Shape::Ground { height: 0.0 };
        s.colliders = vec![ColliderModel {
            shape: ground,
            friction: None,
            motion: Motion::Fixed,
            turn: Turn::default(),
        }];
        s
    };
    let (frames, h) = (90, 0.01);
    let reference = |s: &SimModel| {
        let mut cpu = CpuSim::new(s);
        (0..frames)
            .map(|_| {
                cpu.step_frame();
                closest_segments(&cpu.objects()[0].x)
            })
            .fold(f64::MAX, f64::min)
    };
    let nodes = reference(&piling(false));
    let s = piling(true);
    let capsules = reference(&s);
    let ctx = gpu();
    let mut on_gpu = Vec::new();
    for &fused in fused_paths {
        let mut g = GpuSim::new(&ctx, &s).unwrap();
        g.set_fused(&ctx, fused).unwrap();
        assert_eq!(g.runs_fused(0), fused);
        let mut closest = f64::MAX;
        for _ in 0..frames {
            g.step_frame(&ctx).unwrap();
            closest = closest.min(closest_segments(&g.read_states(&ctx).unwrap()[0].positions()));
        }
        g.destroy(&ctx);
        on_gpu.push(closest);
    }
    assert_clean(&ctx);
    println!("closest segments: node against node {nodes:.4} m; capsules: reference {capsules:.4}, GPU (fused: {fused_paths:?}) {on_gpu:.4?} (h {h})");
    assert!(
        nodes < 0.1 * h,
        "node against node the segments should pass through each other, closest {nodes}"
    );
    assert!(capsules > 0.5 * h, "reference: two segments came {capsules} m close (thickness {h})");
    for (fused, d) in fused_paths.iter().zip(on_gpu) {
        assert!(d > 0.5 * h, "GPU (fused: {fused}): two segments came {d} m close (thickness {h})");
    }
}

/// A rope's contact with itself conserves momentum and the GPU follows the reference: the
/// coarse rope (50 nodes) laid out with one straight part of 19 nodes across another, 10 cm
/// above it and at right angles (each crossing the other between two nodes), the upper part
/// thrown down at 2 m/s, the whole drifting at 0.5 m/s, no gravity, friction 0.5, no stretch
/// limit (its mean is not equal and opposite). Springs act in pairs and each contact moves its
/// four nodes by equal and opposite momenta, so the total stays what it was to f32 rounding
/// (1e-5 of it allowed, 1.4e-7 measured; the reference 1e-8: 4.5e-9 measured, the same without
/// any contact, the springs' stiff joint left to the integrator), while the parts do collide (the upper
/// one's middle stops falling faster than the lower one's by half of 2 m/s). Both GPU paths
/// within 1e-4 m of the reference over each frame from the GPU's state (the tolerance of
/// gpu_vs_cpu.rs's contact comparisons; measured 8.4e-7 m. Run freely the two part by 2.3e-4
/// m in 20 frames without any contact: the joint between the parts, laid out shorter than its
/// rest length, whips).
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_rope_colliding_with_itself_conserves_momentum() {
    let mut r = coarse_rope(true);
    let nodes = 50;
    let (lower_end, upper_start) = (DVec3::new(0.45, 1.0, 0.0), DVec3::new(0.025, 1.1, -0.425));
    r.dims = [nodes, 1];
    r.pinned = vec![false; nodes as usize];
    (r.positions, r.velocities) = (0..nodes as usize)
        .map(|k| match k {
            0..=18 => (DVec3::new(-0.45 + 0.05 * k as f64, 1.0, 0.0), DVec3::X * 0.5),
            19..=30 => {
                let f = (k - 18) as f64 / 13.0;
                (lower_end.lerp(upper_start, f), DVec3::new(0.5, -2.0 * f, 0.0))
            }
            _ => (upper_start + DVec3::Z * 0.05 * (k - 31) as f64, DVec3::new(0.5, -2.0, 0.0)),
        })
        .unzip();
    r.friction = 0.5;
    let s = scene(vec![r]);
    // How much faster the upper part's middle still falls than the lower part's.
    let approach = |v: &[DVec3]| v[8].y + v[9].y - v[39].y - v[40].y;
    let start = momentum(&s.objects[0].velocities);
    let ctx = gpu();
    for fused in [true, false] {
        let (worst, v) = momentum_change(&ctx, &s, fused, 20);
        println!("fused {fused}: momentum change {worst:e}, approach {} m/s", approach(&v) / 2.0);
        assert!(worst <= 1e-5, "fused {fused}: momentum changed by {worst:e} of itself");
        assert!(
            approach(&v) / 2.0 < 1.0,
            "fused {fused}: the parts did not collide ({} m/s)",
            approach(&v) / 2.0
        );
        let (d, _) = compare_path(&ctx, &s, 20, Mode::Resync, fused);
        println!("fused {fused}: {d:?} from the reference");
        assert!(d.position < 1e-4, "fused {fused}: {} m from the reference", d.position);
    }
    assert_clean(&ctx);
    let mut cpu = CpuSim::new(&s);
    for _ in 0..20 {
        cpu.step_frame();
    }
    let change = (momentum(&cpu.objects()[0].v) - start).length() / start.length();
    assert!(change <= 1e-8, "reference: momentum changed by {change:e} of itself");
}

/// A rope sliding along itself stops where Coulomb's friction says: a rope of 2.5 cm segments,
/// 1 cm thick, whose first 30 nodes are held straight along x (the rail), the next ones held
/// out of the way and then straight up, and whose last 12 lie free on the rail, touching it,
/// sliding along it at `v` under gravity. Friction mu between the rope's segments decelerates
/// them by mu g, so they stop after v^2 / (2 mu g). The free part hangs from the held part by
/// one soft spring (2 N/m, standing up from it: 0.2% of the friction force at the stop), so
/// the stop is within 10% of the closed form (the tolerance) on the reference and both
/// GPU paths, at 8, 16 and 64 substeps (measured 3.8 to 5.7% long, the same on every path: a
/// node's friction is shared among its contacts, so a substep undoes slightly less than the
/// whole slip). `tilt`: the rail tilted by that angle about z, the free part on it alike.
fn sliding_rope(mu: f64, v: f64, substeps: u32, tilt: f64) -> SimModel {
    let (s, h) = (0.025, 0.01);
    let (rail, away, up) = (30usize, 8usize, 2usize);
    let nodes = rail + away + up + FREE_NODES;
    let mut r = rope(nodes as u32, s);
    let start = 0.1;
    // along the rail, and across it (up): the rail tilted by `tilt` about z
    let (along, across) = (DVec3::new(tilt.cos(), tilt.sin(), 0.0), DVec3::new(-tilt.sin(), tilt.cos(), 0.0));
    let (mut positions, mut pinned, mut velocities) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..nodes {
        let (p, held) = if k < rail {
            (DVec3::Y + along * (k as f64 * s), true)
        } else if k < rail + away {
            // (held 0.5 m away from everything)
            (DVec3::new((k - rail) as f64 * s, 1.5, 0.5), true)
        } else if k < rail + away + up {
            // straight above the first free node, a segment's length apart each
            let above = (rail + away + up - k) as f64;
            (DVec3::Y + along * start + across * (h + above * s), true)
        } else {
            (DVec3::Y + along * (start + (k - rail - away - up) as f64 * s) + across * h, false)
        };
        positions.push(p);
        pinned.push(held);
        velocities.push(if held { DVec3::ZERO } else { along * v });
    }
    (r.positions, r.pinned, r.velocities) = (positions, pinned, velocities);
    r.stiffness = [2.0, 0.0, 0.1];
    r.damping = 0.0;
    r.drag = 0.0;
    r.rope_radius = 0.5 * h;
    r.margin = 0.5 * h;
    r.self_distance = Some(h);
    r.friction = mu;
    let mut sc = scene(vec![r]);
    sc.gravity = DVec3::new(0.0, -9.81, 0.0);
    sc.substeps = substeps;
    sc
}

/// The free nodes of `sliding_rope`, its last.
const FREE_NODES: usize = 12;

/// The mean of the free part of `sliding_rope` in `a` (its positions or velocities).
fn free_part(a: &[DVec3]) -> DVec3 {
    a[a.len() - FREE_NODES..].iter().sum::<DVec3>() / FREE_NODES as f64
}

#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_rope_sliding_along_itself_stops_where_coulomb_says() {
    let (mu, v, frames) = (0.5, 0.3, 30);
    let closed = v * v / (2.0 * mu * 9.81);
    let mut failures = Vec::new();
    let ctx = gpu();
    for substeps in [8, 16, 64] {
        let s = sliding_rope(mu, v, substeps, 0.0);
        let x0 = free_part(&s.objects[0].positions).x;
        let mut cpu = CpuSim::new(&s);
        for _ in 0..frames {
            cpu.step_frame();
        }
        let (x, speed) = (free_part(&cpu.objects()[0].x).x, free_part(&cpu.objects()[0].v).x);
        let mut stops = vec![("reference", x - x0, speed)];
        for fused in [true, false] {
            let mut g = GpuSim::new(&ctx, &s).unwrap();
            g.set_fused(&ctx, fused).unwrap();
            assert_eq!(g.runs_fused(0), fused);
            for _ in 0..frames {
                g.step_frame(&ctx).unwrap();
            }
            let state = &g.read_states(&ctx).unwrap()[0];
            let (x, speed) = (free_part(&state.positions()).x, free_part(&state.velocities()).x);
            g.destroy(&ctx);
            stops.push((if fused { "GPU fused" } else { "GPU per stage" }, x - x0, speed));
        }
        for (path, stop, speed) in stops {
            println!("{substeps} substeps, {path}: stopped after {stop:.5} m (closed form {closed:.5}), speed {speed:.1e} m/s");
            if (stop / closed - 1.0).abs() > 0.1 || speed.abs() > 1e-3 {
                failures.push((substeps, path, stop, speed));
            }
        }
    }
    assert_clean(&ctx);
    assert!(failures.is_empty(), "closed form {closed} m: {failures:?}");
}

/// The free part of `sliding_rope` laid at rest on the rail tilted by 20 and 35 degrees,
/// friction 0.5 (the friction angle 26.6 degrees): at 35 it slides down with g (sin a - mu cos
/// a) within 10% (measured 1.6 to 2.2% under), from its mean speed along the rail at 0.05 and
/// 0.15 s (after its first contacts settle, and before the soft spring it hangs from pulls
/// with more than a few percent of the net force); at 20 it stays: measured 0.1 to 0.2 mm/s at
/// 0.15 s (0.3 to 0.4 at 8 substeps, under 0.1 at 64: the residue of four Jacobi passes, first
/// order in the step), so the bound is 0.2% of the frictionless speed there (0.50 m/s), 1 mm/s;
/// when a resting contact's friction was scaled by its small count weight it crept at a steady
/// 5.5 to 6.5 mm/s at any substep count (docs/log.md). Reference and both GPU paths, 16
/// substeps.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_rope_on_itself_sticks_below_the_friction_angle_and_slides_above() {
    let mu = 0.5;
    let ctx = gpu();
    let mut failures = Vec::new();
    for degrees in [20.0f64, 35.0] {
        let a = degrees.to_radians();
        let s = sliding_rope(mu, 0.0, 16, a);
        let coulomb = 9.81 * (a.sin() - mu * a.cos()).max(0.0);
        let frictionless = 9.81 * a.sin();
        // the mean speed down the rail after 3 and after 9 frames
        let mut speeds = Vec::new();
        let along = DVec3::new(a.cos(), a.sin(), 0.0);
        let down = |v: &[DVec3]| -free_part(v).dot(along);
        let mut cpu = CpuSim::new(&s);
        let mut at = Vec::new();
        for f in 1..=9 {
            cpu.step_frame();
            if f == 3 || f == 9 {
                at.push(down(&cpu.objects()[0].v));
            }
        }
        speeds.push(("reference", at));
        for fused in [true, false] {
            let mut g = GpuSim::new(&ctx, &s).unwrap();
            g.set_fused(&ctx, fused).unwrap();
            let mut at = Vec::new();
            for f in 1..=9 {
                g.step_frame(&ctx).unwrap();
                if f == 3 || f == 9 {
                    at.push(down(&g.read_states(&ctx).unwrap()[0].velocities()));
                }
            }
            g.destroy(&ctx);
            speeds.push((if fused { "GPU fused" } else { "GPU per stage" }, at));
        }
        for (path, at) in speeds {
            let accel = (at[1] - at[0]) / 0.1;
            println!("{degrees} degrees, {path}: {:.4} and {:.4} m/s down: {accel:.3} m/s^2 (Coulomb {coulomb:.3}, frictionless {frictionless:.3})", at[0], at[1]);
            let ok = if coulomb == 0.0 {
                at[1].abs() < 0.002 * frictionless * 0.15
            } else {
                (accel / coulomb - 1.0).abs() <= 0.1
            };
            if !ok {
                failures.push((degrees, path, at[1], accel, coulomb));
            }
        }
    }
    assert_clean(&ctx);
    assert!(failures.is_empty(), "{failures:?}");
}

/// An 8 x 50 strip (2 cm spacing, h = 1 cm, half the spacing; the piling strip's material)
/// with edge contact, dropped on end from 10 cm onto the ground, tilted `tilt`: the most edges
/// through its triangles and the most through a layer (layer_crossings) over 45 frames on the
/// f64 reference.
fn wide_strip_crossings(tilt: f64) -> (usize, usize) {
    let (cols, rows, spacing) = (8usize, 50usize, 0.02);
    let mut s = standing_strip([cols, rows], spacing, 0.1 + rows as f64 * spacing, tilt);
    s.objects[0].edge_contact = true;
    let mut cpu = CpuSim::new(&s);
    (0..45).fold((0, 0), |worst, _| {
        cpu.step_frame();
        worst_counts(worst, &cpu.objects()[0].x, cols, rows)
    })
}

/// A pile's layers land faster than contacts found once a substep stop them (the strip's top
/// at about 5 m/s moves 5 mm a substep against h = 10 mm): with edge contact each particle's
/// move in a substep, its colliders' part too, is cut short at planes between the sides of the
/// pairs near at the substep's start (`TRUNCATION_GAP` in glsl/include/self_contact.glsl), so
/// that no two sides meet within it. A strip the other tests do not use, at three tilts: no
/// edge through a layer, and at most a few through the triangles next to it where a fold is
/// sharper than a cell. Measured with the bound on each move that the truncation replaced (0.4
/// of its contacts' distance): 2, 0 and 2 edges, none through a layer (without it 23, 4 and 27,
/// of which 11, 0 and 6 through a layer); over the eight tilts from 0.05 to 0.4 rad none
/// through a layer, 2 to 10 next to a fold at three (docs/records/bench/cpu/edge-margin/, 6).
/// The default tier drops it at 0.25 rad (the most edges through without the truncation).
#[test]
fn a_wide_strip_piling_with_edge_contact_never_passes_through_a_layer() {
    wide_strip_holds(&[0.25]);
}

#[test]
#[ignore = "exhaustive tier: the wide strip at its two other tilts"]
fn a_wide_strip_piling_with_edge_contact_never_passes_through_a_layer_at_other_tilts() {
    wide_strip_holds(&[0.1, 0.15]);
}

fn wide_strip_holds(tilts: &[f64]) {
    let worst: Vec<(usize, usize)> = tilts.iter().map(|&t| wide_strip_crossings(t)).collect();
    println!("crossing edges at worst (all, through a layer) at tilts {tilts:?}: {worst:?}");
    let held = worst.iter().all(|&(all, layers)| all <= 15 && layers == 0);
    assert!(held, "edges through the strip's triangles (all, through a layer): {worst:?}");
}

/// The fused kernel's contact lists hold a cloth's edge pairs only where an edge was creased
/// (its sag past CREASE_LIST, creases.glsl) when they were built, and stay while every particle
/// is within half the skin of where they were built; but an edge bends further than its ends
/// move, so an edge that creased past CREASE_FROM meanwhile had its pairs missed until the next
/// build. The 5 x 61 piling strip at friction 0.3, tilted 0.1 rad from 1.625 m (where the probe
/// of docs/records/bench/cpu/edge-margin/ drops it), fused with edge contact, let 89 edges through its
/// triangles so, 98 through a layer; the lists are now built again when an edge creases that
/// they hold no pairs of (`creased_past_lists`). Measured: 2, none through a layer (per stage,
/// whose lists are off while the strip moves: 0). Bounds as the other piling tests'. The
/// default tier's `contact_iterations_stop_a_strip_piling_on_itself` piles the same strip
/// fused with edge contact (without friction).
#[test]
#[ignore = "exhaustive tier: the default tier piles this strip fused with edges, without friction"]
fn the_fused_lists_follow_edges_that_crease() {
    let mut s = standing_strip([5, 61], 0.025, 0.1 + 61.0 * 0.025, 0.1);
    s.objects[0].edge_contact = true;
    s.objects[0].friction = 0.3;
    let ctx = gpu();
    let mut g = GpuSim::new(&ctx, &s).unwrap();
    g.set_fused(&ctx, true).unwrap();
    assert!(g.runs_fused(0));
    let mut worst = (0, 0);
    for _ in 0..45 {
        g.step_frame(&ctx).unwrap();
        worst = worst_counts(worst, &g.read_states(&ctx).unwrap()[0].positions(), 5, 61);
    }
    g.destroy(&ctx);
    assert_clean(&ctx);
    println!("crossing edges at worst (all, through a layer): {worst:?}");
    assert!(
        worst.0 <= 15 && worst.1 == 0,
        "edges through the strip's triangles (all, through a layer): {worst:?}"
    );
}

/// A 6 x 12 cloth (the piling strip's material, 2 cm spacing) folded over its middle into two
/// layers 8 mm apart (h = 1 cm, so they touch and truncate each other's moves at the plane
/// between them, each move held to 5 mm a substep) lying on a box that rises at 8 m/s (8.3 mm
/// a substep), with edge contact: the box must carry both layers. The truncation would hold
/// the bottom layer back inside the box, so a particle it moved meets its colliders again.
/// Measured: no particle below the box's top on the reference or on the GPU (per stage, edge
/// contact's path); without the colliders after the cut (then the bound on each move that the
/// truncation replaced) the box passed through the cloth (2.9 m below its top after 20 frames). Tolerance 1 mm, a fifth of
/// the margin that keeps the cloth above the box.
#[test]
#[ignore = "exhaustive tier: kept out of the default tier's 10-minute budget"]
fn a_rising_box_carries_a_folded_cloth_with_edge_contact() {
    let (cols, rows, spacing, speed) = (6usize, 12usize, 0.02, 8.0);
    let mut c = soft_cloth_spaced(cols as u32, rows as u32, spacing);
    c.edge_contact = true;
    c.margin = 0.005;
    c.friction = 0.5;
    for (i, p) in c.positions.iter_mut().enumerate() {
        let (col, row) = ((i % cols) as f64 * spacing, i / cols);
        let (y, along) = if row < rows / 2 { (0.005, row) } else { (0.013, rows - 1 - row) };
        *p = DVec3::new(col, y, along as f64 * spacing);
    }
    let mut s = scene(vec![c]);
    s.gravity = DVec3::new(0.0, -9.81, 0.0);
    let center = DVec3::new(0.05, -0.05, 0.05);
    let shape =
        Shape::Box { center, half_extents: DVec3::new(0.3, 0.05, 0.3), rotation: glam::DQuat::IDENTITY };
    let motion = Motion::Velocity(DVec3::new(0.0, speed, 0.0));
    s.colliders = vec![ColliderModel { shape, friction: None, motion, turn: Turn::default() }];
    let frames = 20;
    let below = |frame: usize, x: &[DVec3]| {
        let top = speed * (frame + 1) as f64 / 60.0;
        top - x.iter().map(|p| p.y).fold(f64::INFINITY, f64::min)
    };
    let mut cpu = CpuSim::new(&s);
    let reference = (0..frames).fold(f64::MIN, |worst, f| {
        cpu.step_frame();
        worst.max(below(f, &cpu.objects()[0].x))
    });
    let ctx = gpu();
    let mut g = GpuSim::new(&ctx, &s).unwrap();
    let gpu_worst = (0..frames).fold(f64::MIN, |worst, f| {
        g.step_frame(&ctx).unwrap();
        worst.max(below(f, &g.read_states(&ctx).unwrap()[0].positions()))
    });
    g.destroy(&ctx);
    assert_clean(&ctx);
    println!("deepest below the box's top: reference {reference:.4} m, GPU {gpu_worst:.4} m");
    assert!(
        reference < 0.001 && gpu_worst < 0.001,
        "below the box's top: {reference} (reference), {gpu_worst} (GPU) m"
    );
}

/// The twist preset (NVIDIA Newton's cloth_twist set-up: 1 m wide, 1.5 m between handles that
/// turn 300 degrees each, opposite ways, over 5 s) over its whole run (300 frames): the cloth is
/// wrung into a rope lying on itself, its layers squeezed together without limit, and no edge
/// passes through one of its triangles at any frame's end (the exact test, every frame), on
/// the path the preset runs (per stage, since edge contact runs there, its contact lists off
/// since its pins move). Before each move was truncated by the pairs near at a substep's start, its
/// layers crossed from frame 82 (1,988 edges at worst; docs/records/accuracy/lavapipe/
/// twist-truncation/). On a CPU driver it returns at once, saying so: there its 300 frames
/// take past 20 minutes with validation (the reference's test below runs everywhere); run it
/// on a GPU (MSDSIM_DEVICE; the H100 run is in that record).
#[test]
#[ignore = "exhaustive tier: 300 frames of a 50 x 50 cloth wrung onto itself"]
fn the_twist_preset_never_passes_through_itself() {
    if gpu().info().kind == msdsim::vk::DeviceKind::Cpu {
        eprintln!("the twist's 300 frames run on a GPU, not a CPU driver: not run here");
        return;
    }
    let runs = worst_crossings(&twist_preset(), 300, &[("per stage", false, None)]);
    println!("{runs:?}");
    assert!(runs.iter().all(|r| r.1 == 0), "edges through the twisted cloth's triangles: {runs:?}");
}

/// The same on the f64 reference, whose pairs near at a substep's start are found by a search
/// of its own (`near_pairs` in sim::cpu::self_contact), not from contact lists.
#[test]
#[ignore = "exhaustive tier: 300 frames of a 50 x 50 cloth wrung onto itself, on the reference"]
fn the_twist_preset_never_passes_through_itself_on_the_reference() {
    let s = twist_preset();
    let mut cpu = CpuSim::new(&s);
    let (mut worst, mut at) = (0, 0);
    for f in 0..300 {
        cpu.step_frame();
        let n = crossings(&cpu.objects()[0].x, 50, 50);
        if n > worst {
            (worst, at) = (n, f);
        }
    }
    assert_eq!(worst, 0, "edges through the twisted cloth's triangles: {worst} at frame {at}");
}

fn twist_preset() -> SimModel {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/twist.toml");
    let scene = msdsim::scene::load(&path, &[]).expect("the twist preset loads");
    msdsim::scene::to_model(&scene)
}
