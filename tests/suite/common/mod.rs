//! Shared test harness: a validated GPU context that fails loudly without a device, model
//! builders, and GPU-vs-CPU comparison helpers.

pub mod crash;

use glam::DVec3;
use msdsim::sim::collider::ColliderModel;
use msdsim::sim::cpu::{CpuObject, CpuSim};
use msdsim::sim::gpu::{GpuSim, ObjectState};
use msdsim::sim::model::{
    default_ring_weights, ObjectKind, ObjectModel, SimModel, WindModel, DEFAULT_CONTACT_ITERATIONS,
};
use msdsim::vk::{ContextOptions, GpuContext};
use std::cell::RefCell;
use std::sync::{Arc, Mutex};

/// Gives SIGINT its default action back in this test's process, so that the children it
/// stops with SIGINT inherit that: a shell starts a background job (`scripts/test.sh &`) with
/// SIGINT ignored, a child keeps an ignored signal ignored (msdsim leaves it so, as programs
/// should), and the test then waited for a stop that never came.
pub fn default_sigint() {
    // SAFETY: sets a signal's disposition to its default; no handler runs.
    unsafe { libc::signal(libc::SIGINT, libc::SIG_DFL) };
}

/// A context with validation and synchronization validation. Panics (never skips) when no
/// Vulkan device or validation layer is available. A crash by a signal from here on prints
/// its test thread and stack (`crash`).
///
/// With `MSDSIM_TEST_SHARED_CONTEXT` set (scripts/test.sh, which runs a file's tests one after
/// another in one process) every test of the process shares one context, so that a pipeline
/// one test compiled is taken from its cache by the next.
pub fn gpu() -> Arc<GpuContext> {
    if std::env::var_os("MSDSIM_TEST_SHARED_CONTEXT").is_some() {
        let mut shared = SHARED.lock().unwrap_or_else(|e| e.into_inner());
        return shared.get_or_insert_with(|| Arc::new(new_context())).clone();
    }
    CONTEXT.with(|c| c.borrow_mut().get_or_insert_with(|| Arc::new(new_context())).clone())
}

/// The process's context where tests share one (`gpu`); kept to the process's end.
static SHARED: Mutex<Option<Arc<GpuContext>>> = Mutex::new(None);

thread_local! {
    /// The test thread's context: every `gpu()` of one test shares it, so that a pipeline one
    /// path or run compiled is taken from the context's cache by the next instead of compiled
    /// again (on lavapipe compiling the pipelines was over half of a test's time). Live
    /// allocations are counted over the whole test, validation messages since the last
    /// `assert_clean`. It goes with the test's thread.
    static CONTEXT: RefCell<Option<Arc<GpuContext>>> = const { RefCell::new(None) };
}

fn new_context() -> GpuContext {
    crash::install();
    let options = ContextOptions {
        validation: true,
        device: std::env::var("MSDSIM_DEVICE").ok(),
        ..Default::default()
    };
    GpuContext::new(&options).unwrap_or_else(|e| {
        panic!(
            "GPU tests need a Vulkan device and the validation layer (Debian: mesa-vulkan-drivers \
             vulkan-validationlayers libvulkan1), but creating the context failed: {e}"
        )
    })
}

/// Fails the test if validation reported anything or an allocation is still alive.
pub fn assert_clean(ctx: &GpuContext) {
    let (count, messages) = ctx.canary().take();
    assert_eq!(count, 0, "{count} validation message(s): {messages:#?}");
    let live = ctx.live_allocations();
    assert!(live.is_empty(), "allocations leaked: {live:?}");
}

/// A deterministic pseudo-random number in [-1, 1) from an integer seed.
pub fn noise(seed: u64) -> f64 {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15).wrapping_add(0xD1B5_4A32_D192_ED03);
    x ^= x >> 31;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 29;
    (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// Random offsets of up to `amplitude` per coordinate.
pub fn jitter(positions: &mut [DVec3], amplitude: f64, seed: u64) {
    for (i, p) in positions.iter_mut().enumerate() {
        let s = seed.wrapping_mul(1000).wrapping_add(3 * i as u64);
        *p += DVec3::new(noise(s), noise(s + 1), noise(s + 2)) * amplitude;
    }
}

/// An object with every feature off: no springs, drag, friction, limits or pins.
fn plain(kind: ObjectKind, name: String, dims: [u32; 2], spacing: f64, positions: Vec<DVec3>) -> ObjectModel {
    let n = positions.len();
    ObjectModel {
        kind,
        name,
        dims,
        spacing: [spacing, spacing],
        stiffness: [0.0; 3],
        rest_scale: [1.0; 3],
        seam: 0.0,
        damping: 0.0,
        mass: 0.01,
        drag: 0.0,
        friction: 0.0,
        margin: 0.01,
        stretch_limit: None,
        self_distance: None,
        triangle_contact: false,
        edge_contact: false,
        rope_radius: 0.01,
        ring_weights: default_ring_weights(),
        positions,
        velocities: vec![DVec3::ZERO; n],
        pinned: vec![false; n],
        pin_motion: Default::default(),
        pin_groups: Vec::new(),
        pin_group: Vec::new(),
        mesh: None,
    }
}

/// A flat cloth in the xy-plane (rows going down -y) with every feature off.
pub fn cloth(cols: u32, rows: u32, spacing: f64) -> ObjectModel {
    let positions = (0..cols * rows)
        .map(|i| DVec3::new((i % cols) as f64 * spacing, 1.0 - (i / cols) as f64 * spacing, 0.0))
        .collect();
    let mut c = plain(ObjectKind::Cloth, format!("cloth{cols}x{rows}"), [cols, rows], spacing, positions);
    c.margin = 0.0;
    c
}

/// Columns and rows of `stiff_cloth`, and its spacing [m].
pub const STIFF_N: u32 = 12;
pub const STIFF_SPACING: f64 = 0.025;

/// The stiff cloth of the large-step tests: 12 x 12 particles 2.5 cm apart, 1 g each, lying
/// flat at y = 1 and held at its four corners, springs k (structural), k / 2 (shear), k / 10
/// (bending), no dashpots, air drag 0.01 N s/m, under gravity at one substep a frame.
pub fn stiff_cloth(k: f64) -> SimModel {
    let mut c = cloth(STIFF_N, STIFF_N, STIFF_SPACING);
    for p in &mut c.positions {
        *p = DVec3::new(p.x, 1.0, 1.0 - p.y);
    }
    c.mass = 1e-3;
    c.stiffness = [k, k / 2.0, k / 10.0];
    c.damping = 0.0;
    c.drag = 0.01;
    let n = STIFF_N;
    for i in [0, n - 1, n * (n - 1), n * n - 1] {
        c.pinned[i as usize] = true;
    }
    let mut m = scene(vec![c]);
    m.gravity = DVec3::new(0.0, -9.81, 0.0);
    m.substeps = 1;
    m
}

/// A straight rope along +x with every feature off.
pub fn rope(nodes: u32, spacing: f64) -> ObjectModel {
    let positions = (0..nodes).map(|i| DVec3::new(i as f64 * spacing - 0.5, 1.0, 0.0)).collect();
    let mut r = plain(ObjectKind::Rope, format!("rope{nodes}"), [nodes, 1], spacing, positions);
    // (as scene::build makes every rope: self-collision, when on, between its segments)
    r.triangle_contact = true;
    r
}

/// A scene with the given objects, no gravity, no wind, no spheres, 16 substeps per 1/60 s.
pub fn scene(objects: Vec<ObjectModel>) -> SimModel {
    SimModel {
        gravity: DVec3::ZERO,
        frame_dt: 1.0 / 60.0,
        substeps: 16,
        wind: None,
        colliders: Vec::new(),
        objects,
        self_collision: Default::default(),
        max_speed: 100.0,
        // Off: most scenes here are built to test other things, some violently (layers started
        // inside each other's thickness); tests/suite/guard.rs turns it on.
        max_strain: 0.0,
        max_energy_gain: 0.0,
        integrator: Default::default(),
        iterations: 10,
        relaxation: 1.0,
        // Off unless a test turns it on: the multi-object scenes here test other things, on
        // both GPU paths (inter-object contact runs per stage).
        inter_object: false,
        inter_object_edges: true,
        contact_iterations: DEFAULT_CONTACT_ITERATIONS,
    }
}

pub fn sphere(center: [f64; 3], radius: f64) -> ColliderModel {
    ColliderModel::sphere(DVec3::from_array(center), radius)
}

/// A wind cone from `origin` along `direction` with the given full-force and attenuation
/// half-angles (radians).
pub fn wind(origin: [f64; 3], direction: [f64; 3], force: f64, full: f64, att: f64) -> WindModel {
    WindModel {
        origin: DVec3::from_array(origin),
        direction: DVec3::from_array(direction).normalize(),
        force,
        cos_full: full.cos(),
        cos_att: att.cos(),
        air: None,
    }
}

/// Largest distance between GPU and CPU positions, velocities and surface (positions and
/// normals) over all objects.
#[derive(Debug, Default, Clone, Copy)]
pub struct Deviation {
    pub position: f64,
    pub velocity: f64,
    pub surface: f64,
    pub normal: f64,
}

impl Deviation {
    pub fn max(self, o: Deviation) -> Deviation {
        Deviation {
            position: self.position.max(o.position),
            velocity: self.velocity.max(o.velocity),
            surface: self.surface.max(o.surface),
            normal: self.normal.max(o.normal),
        }
    }
}

pub fn v3(a: [f32; 4]) -> DVec3 {
    DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64)
}

pub fn deviation(gpu: &[ObjectState], cpu: &[CpuObject]) -> Deviation {
    let mut d = Deviation::default();
    for (g, c) in gpu.iter().zip(cpu) {
        for (p, (x, v)) in g.particles.iter().zip(c.x.iter().zip(&c.v)) {
            d.position = d.position.max(v3(p.pos).distance(*x));
            d.velocity = d.velocity.max(v3(p.vel).distance(*v));
        }
        for (s, (x, n)) in g.surface.iter().zip(&c.surface) {
            d.surface = d.surface.max(v3(s.pos).distance(*x));
            d.normal = d.normal.max(v3(s.normal).distance(*n));
        }
    }
    d
}

/// How the reference follows the GPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Both run from the initial state for all frames (for smooth dynamics).
    FreeRunning,
    /// After every frame the reference restarts from the GPU's state (read back exactly), so
    /// each frame's 16 substeps are compared from a common start (for chaotic contact scenes).
    Resync,
}

/// Runs `frames` frames on the GPU and the CPU reference, comparing after every frame; returns
/// the largest deviation seen and the final GPU state.
pub fn compare(
    ctx: &GpuContext,
    model: &SimModel,
    frames: usize,
    mode: Mode,
) -> (Deviation, Vec<ObjectState>) {
    compare_path(ctx, model, frames, mode, true)
}

/// `compare` with the fused small-object path on or off (off: every object per stage).
pub fn compare_path(
    ctx: &GpuContext,
    model: &SimModel,
    frames: usize,
    mode: Mode,
    fused: bool,
) -> (Deviation, Vec<ObjectState>) {
    compare_with(ctx, model, frames, mode, &|gpu| gpu.set_fused(ctx, fused).expect("the fused kernels"))
}

/// `compare_path` that also checks the first object runs on the path asked for (fused, or per
/// stage), where a fused run that fell back to per stage would compare the wrong path.
pub fn compare_fused(
    ctx: &GpuContext,
    model: &SimModel,
    frames: usize,
    fused: bool,
) -> (Deviation, Vec<ObjectState>) {
    compare_with(ctx, model, frames, Mode::Resync, &|gpu| {
        gpu.set_fused(ctx, fused).expect("the fused kernels");
        assert_eq!(gpu.runs_fused(0), fused, "the object runs fused: {fused}");
    })
}

/// `compare_path` with the GPU simulation set up by `setup` before the first frame.
pub fn compare_with(
    ctx: &GpuContext,
    model: &SimModel,
    frames: usize,
    mode: Mode,
    setup: &dyn Fn(&mut GpuSim),
) -> (Deviation, Vec<ObjectState>) {
    let mut gpu = GpuSim::new(ctx, model).expect("creating the GPU simulation");
    setup(&mut gpu);
    let mut cpu = CpuSim::new(model);
    let mut worst = Deviation::default();
    let mut last = Vec::new();
    for _ in 0..frames {
        gpu.step_frame(ctx).expect("GPU frame");
        cpu.step_frame();
        last = gpu.read_states(ctx).expect("readback");
        worst = worst.max(deviation(&last, cpu.objects()));
        if mode == Mode::Resync {
            for (i, state) in last.iter().enumerate() {
                cpu.set_state(i, state.positions(), state.velocities());
            }
        }
    }
    gpu.destroy(ctx);
    (worst, last)
}

/// The final positions and velocities of the model's first object on the CPU reference and on
/// the GPU's fused and per-stage paths ("cpu", "gpu fused", "gpu per stage"), after `frames`
/// frames.
pub fn every_path(
    ctx: &GpuContext,
    m: &SimModel,
    frames: usize,
) -> Vec<(&'static str, Vec<DVec3>, Vec<DVec3>)> {
    let mut cpu = CpuSim::new(m);
    for _ in 0..frames {
        cpu.step_frame();
    }
    let o = &cpu.objects()[0];
    let mut out = vec![("cpu", o.x.clone(), o.v.clone())];
    for (label, fused) in [("gpu fused", true), ("gpu per stage", false)] {
        let mut gpu = GpuSim::new(ctx, m).expect("creating the GPU simulation");
        gpu.set_fused(ctx, fused).unwrap();
        for _ in 0..frames {
            gpu.step_frame(ctx).expect("GPU frame");
        }
        let states: Vec<ObjectState> = gpu.read_states(ctx).expect("readback");
        gpu.destroy(ctx);
        out.push((label, states[0].positions(), states[0].velocities()));
    }
    out
}

/// The first object's positions after each of `frames` frames: (label, per frame) on the CPU
/// reference ("cpu"), the fused kernel ("gpu fused") and the per-stage path ("gpu per stage").
pub fn every_path_each_frame(
    ctx: &GpuContext,
    m: &SimModel,
    frames: usize,
) -> Vec<(&'static str, Vec<Vec<DVec3>>)> {
    let mut cpu = CpuSim::new(m);
    let mut out = vec![(
        "cpu",
        (0..frames)
            .map(|_| {
                cpu.step_frame();
                cpu.objects()[0].x.clone()
            })
            .collect(),
    )];
    for (label, fused) in [("gpu fused", true), ("gpu per stage", false)] {
        let mut gpu = GpuSim::new(ctx, m).expect("creating the GPU simulation");
        gpu.set_fused(ctx, fused).unwrap();
        let runs = (0..frames)
            .map(|_| {
                gpu.step_frame(ctx).expect("GPU frame");
                gpu.read_states(ctx).expect("readback")[0].positions()
            })
            .collect();
        gpu.destroy(ctx);
        out.push((label, runs));
    }
    out
}

/// Runs the GPU simulation alone for `frames` frames, calling `each` with the state after each.
pub fn run_gpu(
    ctx: &GpuContext,
    model: &SimModel,
    frames: usize,
    mut each: impl FnMut(usize, &[ObjectState]),
) {
    let mut gpu = GpuSim::new(ctx, model).expect("creating the GPU simulation");
    for f in 0..frames {
        gpu.step_frame(ctx).expect("GPU frame");
        let states = gpu.read_states(ctx).expect("readback");
        each(f, &states);
    }
    gpu.destroy(ctx);
}

/// Copies a folder tree (a shader folder to edit in a test).
pub fn copy_dir(from: &std::path::Path, to: &std::path::Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// The line of physics_body.glsl that `broken` edits.
pub const BROKEN_LINE: &str = "v += force * (g.dt / m);";

/// physics_body.glsl with a typo that fails to compile (`forse` for `force`); panics when the
/// text no longer has the line edited, so a test cannot silently write the file unchanged.
pub fn broken(physics_body: &str) -> String {
    let line = BROKEN_LINE;
    assert!(physics_body.contains(line), "physics_body.glsl no longer has `{line}`: update the test");
    physics_body.replace(line, "v += forse * (g.dt / m);")
}

/// A chain of 10 nodes, 5 cm apart, hanging straight down from a pin at its top at its rest
/// lengths, with structural springs only (100 N/m), weak dashpots and a drag that settles it
/// within a second (c / 2m = 15 /s, about the lowest longitudinal mode's frequency), at 64
/// substeps per 1/60 s frame with `method` (XPBD 1 iteration, the others 4).
pub fn hanging_chain(method: msdsim::sim::model::Integrator) -> SimModel {
    let mut r = rope(10, 0.05);
    for (i, p) in r.positions.iter_mut().enumerate() {
        *p = DVec3::new(0.0, 1.0 - 0.05 * i as f64, 0.0);
    }
    r.pinned[0] = true;
    r.stiffness = [100.0, 0.0, 0.0];
    r.damping = 0.01;
    r.drag = 0.3;
    let mut m = scene(vec![r]);
    m.gravity = DVec3::new(0.0, -9.81, 0.0);
    m.substeps = 64;
    m.integrator = method;
    m.iterations = method.few_iterations();
    m
}

/// The largest relative difference between each spring's stretch in `x` and the closed form
/// of a chain at rest: spring s (nodes s, s + 1) carries the weight W_s of the nodes below it
/// and stretches by W_s / k.
pub fn static_stretch_error(model: &SimModel, x: &[DVec3]) -> f64 {
    let o = &model.objects[0];
    let n = x.len();
    (0..n - 1)
        .map(|s| {
            let weight = (n - 1 - s) as f64 * o.mass * model.gravity.length();
            let expected = weight / o.stiffness[0];
            let stretch = x[s + 1].distance(x[s]) - o.spacing[0];
            (stretch - expected).abs() / expected
        })
        .fold(0.0, f64::max)
}

/// A small valid preset for the binary's tests: a pinned 5 x 4 cloth, a 6-node rope and a sphere.
pub const GOOD: &str = r#"
[sim]
substeps = 4
[[sphere]]
center = [0.0, 0.0, 0.0]
radius = 0.2
[[cloth]]
name = "c"
resolution = [5, 4]
size = [0.4, 0.3]
origin = [-0.2, 0.5, 0.0]
mass = 0.01
stiffness = { structural = 100.0, shear = 20.0, bending = 5.0 }
pin = "top_row"
[[rope]]
name = "r"
nodes = 6
start = [0.0, 0.6, 0.1]
end = [0.3, 0.6, 0.1]
mass = 0.01
stiffness = 100.0
radius = 0.01
"#;

/// Whether segment (p, q) passes through triangle (a, b, c) (Moller-Trumbore on the segment;
/// touching counts, a segment in the triangle's plane does not).
pub fn segment_through(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (e1, e2, dir) = (b - a, c - a, q - p);
    let h = dir.cross(e2);
    let det = e1.dot(h);
    if det.abs() < 1e-18 {
        return false;
    }
    let s = p - a;
    let u = s.dot(h) / det;
    let qv = s.cross(e1);
    let v = dir.dot(qv) / det;
    let t = e2.dot(qv) / det;
    (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&t)
}

/// The triangles of a cloth grid as the renderer draws them (src/render/mesh.rs), two a cell.
pub fn cloth_triangles(cols: usize, rows: usize) -> Vec<[usize; 3]> {
    let mut t = Vec::new();
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            let a = c + r * cols;
            t.push([a, a + cols, a + 1]);
            t.push([a + 1, a + cols, a + cols + 1]);
        }
    }
    t
}

/// The edges of a cloth grid as drawn: rows, columns and each cell's diagonal from (c + 1, r)
/// to (c, r + 1).
pub fn cloth_edges(cols: usize, rows: usize) -> Vec<[usize; 2]> {
    let mut e = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            let a = c + r * cols;
            if c + 1 < cols {
                e.push([a, a + 1]);
            }
            if r + 1 < rows {
                e.push([a, a + cols]);
            }
            if c + 1 < cols && r + 1 < rows {
                e.push([a + 1, a + cols]);
            }
        }
    }
    e
}

/// Segments (`edges` of positions `ex`) through a triangle (`tris` of positions `tx`) that
/// shares no vertex with them (`same`: the two are one object), tested exactly after a bounding
/// box check.
pub fn segments_through(
    ex: &[DVec3],
    edges: &[[usize; 2]],
    tx: &[DVec3],
    tris: &[[usize; 3]],
    same: bool,
) -> usize {
    segments_through_except(ex, edges, tx, tris, |i, j, t| same && (t.contains(&i) || t.contains(&j)))
}

/// Segments (`edges` of positions `ex`) through a triangle (`tris` of positions `tx`) other
/// than those `skip(i, j, triangle)` leaves out for the segment from i to j, tested exactly
/// after a bounding box check: the triangles sorted by their boxes' low x, each segment against
/// those that begin before it ends.
pub fn segments_through_except(
    ex: &[DVec3],
    edges: &[[usize; 2]],
    tx: &[DVec3],
    tris: &[[usize; 3]],
    skip: impl Fn(usize, usize, &[usize; 3]) -> bool,
) -> usize {
    // (a NaN would sort before every box and end the sweep at once: none counted)
    assert!(ex.iter().chain(tx).all(|p| p.is_finite()), "positions that are not finite");
    let bounds: Vec<(DVec3, DVec3)> = tris
        .iter()
        .map(|t| {
            let p = t.map(|k| tx[k]);
            (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
        })
        .collect();
    let mut order: Vec<usize> = (0..tris.len()).collect();
    order.sort_by(|&a, &b| bounds[a].0.x.total_cmp(&bounds[b].0.x));
    edges
        .iter()
        .filter(|&&[i, j]| {
            let (lo, hi) = (ex[i].min(ex[j]), ex[i].max(ex[j]));
            order.iter().take_while(|&&t| bounds[t].0.x <= hi.x).any(|&t| {
                let (tlo, thi) = bounds[t];
                lo.cmple(thi).all()
                    && tlo.cmple(hi).all()
                    && !skip(i, j, &tris[t])
                    && segment_through(ex[i], ex[j], tris[t].map(|k| tx[k]))
            })
        })
        .count()
}

/// The block from `lo` to `hi`: its 8 corners (corner i at the high side in x, y, z by bits 0,
/// 1, 2 of i) and its 6 faces, quads wound counter-clockwise seen from outside.
pub fn block(lo: DVec3, hi: DVec3) -> (Vec<DVec3>, [[usize; 4]; 6]) {
    let corners = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    (corners, [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]])
}

/// `block`'s faces as triangles (each quad split along its first diagonal), its corners
/// numbered from `first`.
pub fn block_triangles(first: usize) -> Vec<[usize; 3]> {
    let (_, quads) = block(DVec3::ZERO, DVec3::ONE);
    quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]].map(|t| t.map(|k| k + first)))
        .collect()
}
