//! The simulation on Vulkan compute.
//!
//! Buffers per object: `state[0]` (A, the state between substeps and frames), `state[1]` (B, the
//! physics output), `surface` (what the renderer draws), `params`. Shared: `globals`, `spheres`.
//!
//! One frame is one command buffer:
//! ```text
//! for each substep:   physics      A -> B   (all objects)
//!                     barrier  B: ComputeWrite -> ComputeReadWrite   (constraints read B)
//!                              A: ComputeRead  -> ComputeWrite       (constraints overwrite A)
//!                     constraints  B -> A   (all objects)
//!                     barrier  A: ComputeWrite -> ComputeReadWrite   (next physics reads A)
//!                              B: ComputeRead  -> ComputeWrite       (next physics overwrites B)
//! surface stage:      cloth normals / rope vertices  A -> surface
//!                     barrier  surface: ComputeWrite -> the caller's consumer (compute, vertex input)
//! ```
//! Both hazards of the ping-pong are named explicitly: the read-after-write on the buffer just
//! written and the write-after-read on the buffer just read. Uploads and readbacks end with a
//! barrier back to compute, so frames recorded after them need no barrier of their own.

use super::gpu_types::{
    Globals, ObjectParams, Particle, SurfaceVertex, GUARD_NON_FINITE, OBJ_SELF_COLLISION, OBJ_SELF_HASH,
    OBJ_STRETCH_LIMIT,
};
use super::model::{ObjectKind, ObjectModel, ObjectShape, SelfCollisionMethod, SimModel};
use super::stability::GuardTrip;
use crate::error::UserError;
use crate::shaders::ShaderSet;
use crate::vk::{
    Access, BindingSet, BindingSetLayout, Buffer, BufferBarrier, BufferUsage, CommandSlot, ComputePipeline,
    DescriptorArena, DeviceInfo, GpuContext, MemoryKind, Recorder, Retired, TimestampPool, VkError,
};
use anyhow::{Context as _, Result};
use std::collections::HashMap;

/// Workgroup shape of the cloth stages (the paper's 16 x 16) and of the rope stages (1-D).
const CLOTH_GROUP: [u32; 2] = [16, 16];
const ROPE_GROUP: u32 = 64;
/// Bindings per set, in the order of `glsl/include/bindings.glsl`.
const BINDINGS: u32 = 12;
/// A cleared guard: no flags, no flagged particle.
const GUARD_CLEAR: [u32; 4] = [0, u32::MAX, 0, 0];
/// Spatial hash table sizes: the scan handles 8192 buckets per block and 8192 blocks.
const SCAN_BLOCK: u64 = 8192;
const MAX_TABLE: u64 = SCAN_BLOCK * SCAN_BLOCK;

/// Buckets of the spatial hash of an object of `particles` particles: a power of two, at
/// least twice the particle count (load factor <= 1/2), within the scan's capacity.
fn hash_table_size(particles: u64) -> u64 {
    (2 * particles).next_power_of_two().clamp(1024, MAX_TABLE)
}
/// Frames that may be in flight at once (each has its own timestamps).
pub const FRAME_SLOTS: usize = 2;

/// GPU time of one frame by stage, from timestamps [ms].
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct FrameTiming {
    pub total_ms: f64,
    pub physics_ms: f64,
    pub constraints_ms: f64,
    pub surface_ms: f64,
}

/// An object's state read back from the GPU.
#[derive(Debug, Clone)]
pub struct ObjectState {
    pub particles: Vec<Particle>,
    pub surface: Vec<SurfaceVertex>,
}

/// The compute pipelines: (shader, specialization constants) per slot of `Pipelines::list`.
/// The step shaders take their workgroup shape; the scan takes its phase.
const PIPELINE_SPECS: [(&str, &[u32]); 11] = [
    ("physics.comp", &CLOTH_GROUP),
    ("physics.comp", &[ROPE_GROUP, 1]),
    ("constraints.comp", &CLOTH_GROUP),
    ("constraints.comp", &[ROPE_GROUP, 1]),
    ("cloth_normals.comp", &[]),
    ("rope_vertices.comp", &[]),
    ("hash_scan.comp", &[0]),
    ("hash_scan.comp", &[1]),
    ("hash_scan.comp", &[2]),
    ("hash_scatter.comp", &[]),
    ("fused.comp", &[]),
];

/// Objects of at most this many particles (and no spatial hash) run all of a frame's substeps
/// in one single-workgroup dispatch (`fused.comp`). Measured on an H100 with the limit at
/// 4096 (docs/bench/h100/bench-fused-up-to-4096.md): fused wins at 256 particles (0.111 vs
/// 0.136 ms per frame), breaks even at 1024 and loses at 2500 (0.606 vs 0.191 ms), where one
/// workgroup on one SM, reading neighbours through L2, is slower than a dispatch per stage.
pub const FUSED_MAX: u32 = 512;

struct Pipelines {
    /// One per entry of `PIPELINE_SPECS`.
    list: Vec<ComputePipeline>,
}

impl Pipelines {
    fn new(ctx: &GpuContext, layout: &BindingSetLayout, shaders: &mut ShaderSet) -> Result<Self> {
        let mut list = Vec::with_capacity(PIPELINE_SPECS.len());
        let mut compiled: HashMap<&str, Vec<u32>> = HashMap::new();
        for (name, spec) in PIPELINE_SPECS {
            let pipeline = match compiled.get(name) {
                Some(w) => Ok(w.clone()),
                None => shaders.load_or_embedded(name),
            }
            .and_then(|words| {
                compiled.insert(name, words.clone());
                Self::create(ctx, layout, name, &words, spec)
            });
            match pipeline {
                Ok(p) => list.push(p),
                Err(e) => {
                    list.into_iter().for_each(|p: ComputePipeline| p.destroy(ctx));
                    return Err(e);
                }
            }
        }
        Ok(Self { list })
    }

    fn create(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        name: &str,
        words: &[u32],
        spec: &[u32],
    ) -> Result<ComputePipeline> {
        ComputePipeline::new(ctx, name, words, layout, spec)
            .with_context(|| format!("creating pipeline {name}"))
    }

    /// Rebuilds the pipelines of the `changed` shaders that compile; returns the names
    /// reloaded and the replaced pipelines (still possibly in use by frames in flight).
    fn reload(
        &mut self,
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        shaders: &mut ShaderSet,
        changed: &[String],
    ) -> (Vec<String>, Vec<Retired>) {
        let mut reloaded = Vec::new();
        let mut retired = Vec::new();
        for name in changed {
            let slots: Vec<usize> =
                (0..PIPELINE_SPECS.len()).filter(|&i| PIPELINE_SPECS[i].0 == name).collect();
            if slots.is_empty() {
                continue;
            }
            let Ok(words) = shaders.load(name) else { continue }; // error recorded in `shaders`
            let mut fresh = Vec::new();
            for &i in &slots {
                match Self::create(ctx, layout, name, &words, PIPELINE_SPECS[i].1) {
                    Ok(p) => fresh.push((i, p)),
                    Err(e) => log::error!("shader {name}: {e:#}"),
                }
            }
            if fresh.len() == slots.len() {
                for (i, p) in fresh {
                    retired.push(Retired::Compute(std::mem::replace(&mut self.list[i], p)));
                }
                reloaded.push(name.clone());
            } else {
                fresh.into_iter().for_each(|(_, p)| p.destroy(ctx));
            }
        }
        (reloaded, retired)
    }

    fn physics(&self, kind: ObjectKind) -> &ComputePipeline {
        &self.list[kind as usize]
    }

    fn constraints(&self, kind: ObjectKind) -> &ComputePipeline {
        &self.list[2 + kind as usize]
    }

    fn surface(&self, kind: ObjectKind) -> &ComputePipeline {
        &self.list[4 + kind as usize]
    }

    fn hash_scan(&self, phase: usize) -> &ComputePipeline {
        &self.list[6 + phase]
    }

    fn hash_scatter(&self) -> &ComputePipeline {
        &self.list[9]
    }

    fn fused(&self) -> &ComputePipeline {
        &self.list[10]
    }

    fn destroy(self, ctx: &GpuContext) {
        for p in self.list {
            p.destroy(ctx);
        }
    }
}

struct GpuObject {
    kind: ObjectKind,
    particles: u32,
    surface_len: u32,
    step_groups: [u32; 3],
    surface_groups: [u32; 3],
    params: Buffer,
    state: [Buffer; 2],
    surface: Buffer,
    /// The spatial hash, or a placeholder bound in its place.
    hash: HashStorage,
    /// The runtime guard (flags, first flagged particle), host-visible, read after each frame.
    guard: Buffer,
    /// [A -> B (physics), B -> A (constraints, hash passes); surface uses set 0 (reads A)].
    sets: [BindingSet; 2],
}

/// What an object binds at the spatial hash bindings.
enum HashStorage {
    Buffers(Box<HashBuffers>),
    /// A 16-byte buffer bound at all five bindings of an object without a spatial hash. The
    /// shaders reach it only behind a flag, but may (statically) write it, so it is ordered
    /// like the state buffers; one per object, so objects' dispatches never share it.
    Placeholder(Buffer),
}

impl HashStorage {
    fn buffers(&self) -> Option<&HashBuffers> {
        match self {
            HashStorage::Buffers(h) => Some(h),
            HashStorage::Placeholder(_) => None,
        }
    }
}

/// The spatial hash of one object (bindings 6..=10).
struct HashBuffers {
    cell_rank: Buffer,
    counts: Buffer,
    starts: Buffer,
    sorted: Buffer,
    block_sums: Buffer,
    buckets: u32,
}

impl HashBuffers {
    fn new(ctx: &GpuContext, name: &str, particles: u64) -> Result<Self> {
        let buckets = hash_table_size(particles);
        let storage = BufferUsage::STORAGE;
        let specs = [
            ("cell_rank", 8 * particles, storage),
            ("counts", 4 * buckets, storage | BufferUsage::TRANSFER_DST),
            ("starts", 4 * (buckets + 1), storage),
            ("sorted", 16 * particles, storage),
            ("block_sums", 4 * buckets.div_ceil(SCAN_BLOCK), storage),
        ];
        let mut made = Vec::with_capacity(specs.len());
        for (suffix, size, usage) in specs {
            match Buffer::new(ctx, &format!("{name}.hash.{suffix}"), size, usage, MemoryKind::GpuOnly) {
                Ok(b) => made.push(b),
                Err(e) => {
                    made.into_iter().for_each(|b| b.destroy(ctx));
                    return Err(e.into());
                }
            }
        }
        let Ok([cell_rank, counts, starts, sorted, block_sums]) = <[Buffer; 5]>::try_from(made) else {
            unreachable!("one buffer per spec")
        };
        Ok(Self { cell_rank, counts, starts, sorted, block_sums, buckets: buckets as u32 })
    }

    fn buffers(&self) -> [&Buffer; 5] {
        [&self.cell_rank, &self.counts, &self.starts, &self.sorted, &self.block_sums]
    }

    fn destroy(self, ctx: &GpuContext) {
        for b in [self.cell_rank, self.counts, self.starts, self.sorted, self.block_sums] {
            b.destroy(ctx);
        }
    }
}

pub struct GpuSim {
    pipelines: Pipelines,
    layout: BindingSetLayout,
    arena: DescriptorArena,
    globals: Buffer,
    spheres: Buffer,
    objects: Vec<GpuObject>,
    slot: CommandSlot,
    /// One pool per frame slot (empty when the device has no timestamps).
    timestamps: Vec<TimestampPool>,
    self_collision: SelfCollisionMethod,
    stage_timing: bool,
    /// Small objects run their substeps fused into one dispatch (see `FUSED_MAX`).
    fused: bool,
    substeps: u32,
    frame_dt: f64,
    frames: u64,
    /// Particle writes (object, index, value) applied at the start of the next recorded frame.
    pending_writes: Vec<(usize, u32, Particle)>,
    /// The model the simulation runs, without particles (for the guard's reports).
    model: SimModel,
}

/// Bytes of GPU memory an object needs: two state buffers, the surface, the parameters (and
/// the spatial hash, counted for every object: an upper bound).
fn object_bytes(o: &ObjectShape) -> u64 {
    let n = o.particle_count();
    2 * n * std::mem::size_of::<Particle>() as u64
        + o.surface_count() * std::mem::size_of::<SurfaceVertex>() as u64
        + std::mem::size_of::<ObjectParams>() as u64
        + 24 * n
        + 8 * hash_table_size(n)
        + 4
}

fn gib(bytes: u64) -> String {
    format!("{:.2} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// Refuses objects the device cannot hold or dispatch. Needs only the shapes, so callers can
/// check before building particle arrays.
pub fn check_fits(info: &DeviceInfo, shapes: &[ObjectShape]) -> Result<(), UserError> {
    let total: u64 = shapes.iter().map(object_bytes).sum();
    if total > info.device_local_bytes {
        return Err(UserError(format!(
            "the scene is too large for the device: it needs {} of GPU memory, {} has {}",
            gib(total),
            info.name,
            gib(info.device_local_bytes)
        )));
    }
    for o in shapes {
        let what = format!("{} '{}' ({} x {})", o.kind.label(), o.name, o.dims[0], o.dims[1]);
        let state = o.particle_count() * std::mem::size_of::<Particle>() as u64;
        let surface = o.surface_count() * std::mem::size_of::<SurfaceVertex>() as u64;
        if state.max(surface) > info.max_storage_buffer_range {
            return Err(UserError(format!(
                "{what} is too large for the device: one buffer would be {}, {} binds at most {}",
                gib(state.max(surface)),
                info.name,
                gib(info.max_storage_buffer_range),
            )));
        }
        if step_groups(o)
            .iter()
            .chain(&surface_groups(o))
            .zip(info.max_workgroup_count.iter().cycle())
            .any(|(g, max)| g > max)
        {
            return Err(UserError(format!(
                "{what} is too large for the device: it needs more workgroups than one dispatch allows"
            )));
        }
    }
    Ok(())
}

fn step_groups(o: &ObjectShape) -> [u32; 3] {
    match o.kind {
        ObjectKind::Cloth => [o.dims[0].div_ceil(CLOTH_GROUP[0]), o.dims[1].div_ceil(CLOTH_GROUP[1]), 1],
        ObjectKind::Rope => [o.dims[0].div_ceil(ROPE_GROUP), 1, 1],
    }
}

fn surface_groups(o: &ObjectShape) -> [u32; 3] {
    match o.kind {
        ObjectKind::Cloth => step_groups(o),
        ObjectKind::Rope => [o.surface_count().div_ceil(ROPE_GROUP as u64) as u32, 1, 1],
    }
}

fn f3(v: glam::DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

fn globals(model: &SimModel) -> Globals {
    let wind = model.wind;
    Globals {
        gravity: f3(model.gravity),
        dt: model.dt() as f32,
        wind_origin: wind.map(|w| f3(w.origin)).unwrap_or_default(),
        wind_force: wind.map(|w| w.force as f32).unwrap_or(0.0),
        wind_dir: wind.map(|w| f3(w.direction)).unwrap_or([0.0, 0.0, 1.0]),
        wind_cos_full: wind.map(|w| w.cos_full as f32).unwrap_or(1.0),
        wind_cos_att: wind.map(|w| w.cos_att as f32).unwrap_or(1.0),
        wind_enabled: wind.is_some() as u32,
        sphere_count: model.spheres.len() as u32,
        substeps: model.substeps,
        guard_speed: model.max_speed as f32,
        pad1: 0,
        pad2: 0,
        pad3: 0,
    }
}

fn object_params(o: &ObjectModel, method: SelfCollisionMethod) -> ObjectParams {
    let mut flags = 0;
    if o.stretch_limit.is_some() {
        flags |= OBJ_STRETCH_LIMIT;
    }
    if o.self_distance.is_some() {
        flags |= OBJ_SELF_COLLISION;
        if method == SelfCollisionMethod::Hash {
            flags |= OBJ_SELF_HASH;
        }
    }
    let buckets = hash_table_size(o.particle_count() as u64) as u32;
    let cell = 2.0 * o.self_distance.unwrap_or(1.0).max(1e-6);
    ObjectParams {
        dims: o.dims,
        spacing: o.spacing.map(|s| s as f32),
        stiffness: [o.stiffness[0] as f32, o.stiffness[1] as f32, o.stiffness[2] as f32, o.damping as f32],
        rest_scale: [o.rest_scale[0] as f32, o.rest_scale[1] as f32, o.rest_scale[2] as f32, 0.0],
        mass: o.mass as f32,
        drag: o.drag as f32,
        stretch_limit: o.stretch_limit.unwrap_or(0.0) as f32,
        friction: o.friction as f32,
        margin: o.margin as f32,
        self_distance: o.self_distance.unwrap_or(0.0) as f32,
        rope_radius: o.rope_radius as f32,
        flags,
        ring_weights: o.ring_weights.map(|w| w.map(|x| x as f32)),
        hash_mask: buckets - 1,
        cell_inv: (1.0 / cell) as f32,
        pad0: 0,
        pad1: 0,
    }
}

fn sphere_data(model: &SimModel) -> Vec<[f32; 4]> {
    model
        .spheres
        .iter()
        .map(|s| [s.center.x as f32, s.center.y as f32, s.center.z as f32, s.radius as f32])
        .collect()
}

/// The initial particles of an object (positions, velocities, pinned flags).
pub fn particles(o: &ObjectModel) -> Vec<Particle> {
    o.positions
        .iter()
        .zip(&o.velocities)
        .zip(&o.pinned)
        .map(|((x, v), &pinned)| {
            let x = x.as_vec3();
            let v = if pinned { glam::Vec3::ZERO } else { v.as_vec3() };
            Particle { pos: [x.x, x.y, x.z, pinned as u32 as f32], vel: [v.x, v.y, v.z, 0.0] }
        })
        .collect()
}

/// The scene-independent parts of a `GpuSim`, each present once created, so a failure part-way
/// frees exactly what exists.
#[derive(Default)]
struct Parts {
    layout: Option<BindingSetLayout>,
    pipelines: Option<Pipelines>,
    arena: Option<DescriptorArena>,
    globals: Option<Buffer>,
    spheres: Option<Buffer>,
    slot: Option<CommandSlot>,
    timestamps: Vec<TimestampPool>,
}

impl Parts {
    fn create(&mut self, ctx: &GpuContext, model: &SimModel, shaders: &mut ShaderSet) -> Result<()> {
        let layout = self.layout.insert(BindingSetLayout::storage_buffers(ctx, BINDINGS)?);
        self.pipelines = Some(Pipelines::new(ctx, layout, shaders)?);
        self.arena = Some(DescriptorArena::new(ctx, 2 * model.objects.len() as u32, BINDINGS)?);
        let globals_size = std::mem::size_of::<Globals>() as u64;
        self.globals =
            Some(Buffer::new(ctx, "globals", globals_size, BufferUsage::STORAGE, MemoryKind::Upload)?);
        let spheres_size = 16 * model.spheres.len().max(1) as u64;
        self.spheres =
            Some(Buffer::new(ctx, "spheres", spheres_size, BufferUsage::STORAGE, MemoryKind::Upload)?);
        self.slot = Some(CommandSlot::new(ctx, "frame")?);
        for _ in 0..FRAME_SLOTS {
            match TimestampPool::new(ctx, 2 * model.substeps + 2)? {
                Some(pool) => self.timestamps.push(pool),
                None => break,
            }
        }
        Ok(())
    }

    fn destroy(self, ctx: &GpuContext) {
        for t in self.timestamps {
            t.destroy(ctx);
        }
        if let Some(s) = self.slot {
            s.destroy(ctx);
        }
        if let Some(b) = self.spheres {
            b.destroy(ctx);
        }
        if let Some(b) = self.globals {
            b.destroy(ctx);
        }
        if let Some(a) = self.arena {
            a.destroy(ctx);
        }
        if let Some(p) = self.pipelines {
            p.destroy(ctx);
        }
        if let Some(l) = self.layout {
            l.destroy(ctx);
        }
    }
}

impl GpuSim {
    /// Allocates and uploads the scene with the embedded shaders. Fails with a `UserError`
    /// when it cannot fit the device. On any failure everything created so far is freed.
    pub fn new(ctx: &GpuContext, model: &SimModel) -> Result<Self> {
        Self::with_shaders(ctx, model, &mut ShaderSet::embedded())
    }

    /// Like `new`, with shaders from `shaders` (a watched directory for hot reload).
    pub fn with_shaders(ctx: &GpuContext, model: &SimModel, shaders: &mut ShaderSet) -> Result<Self> {
        check_fits(ctx.info(), &model.objects.iter().map(ObjectModel::shape).collect::<Vec<_>>())?;
        let mut parts = Parts::default();
        if let Err(e) = parts.create(ctx, model, shaders) {
            parts.destroy(ctx);
            return Err(e);
        }
        let Parts {
            layout: Some(layout),
            pipelines: Some(pipelines),
            arena: Some(arena),
            globals: Some(globals),
            spheres: Some(spheres),
            slot: Some(slot),
            timestamps,
        } = parts
        else {
            unreachable!("Parts::create fills every part or fails")
        };
        let mut sim = Self {
            pipelines,
            layout,
            arena,
            globals,
            spheres,
            objects: Vec::new(),
            slot,
            timestamps,
            self_collision: model.self_collision,
            stage_timing: true,
            fused: true,
            substeps: model.substeps,
            frame_dt: model.frame_dt,
            frames: 0,
            pending_writes: Vec::new(),
            model: model.without_particles(),
        };
        // From here `sim` owns everything created; on error it is destroyed whole.
        match sim.populate(ctx, model) {
            Ok(()) => Ok(sim),
            Err(e) => {
                let _ = ctx.wait_idle();
                sim.destroy(ctx);
                Err(e)
            }
        }
    }

    fn populate(&mut self, ctx: &GpuContext, model: &SimModel) -> Result<()> {
        self.globals.write(0, &[globals(model)])?;
        self.spheres.write(0, &sphere_data(model))?;
        for o in &model.objects {
            let obj = self.create_object(ctx, o)?;
            self.objects.push(obj);
        }
        let initial: Vec<Vec<Particle>> = model.objects.iter().map(particles).collect();
        self.upload_states(ctx, &initial)
    }

    fn create_object(&mut self, ctx: &GpuContext, o: &ObjectModel) -> Result<GpuObject> {
        let context = || format!("allocating {} '{}'", o.kind.label(), o.name);
        let state_bytes = o.particle_count() as u64 * std::mem::size_of::<Particle>() as u64;
        let state_usage = BufferUsage::STORAGE | BufferUsage::TRANSFER_SRC | BufferUsage::TRANSFER_DST;
        let specs = [
            ("params", std::mem::size_of::<ObjectParams>() as u64, BufferUsage::STORAGE, MemoryKind::Upload),
            ("state_a", state_bytes, state_usage, MemoryKind::GpuOnly),
            ("state_b", state_bytes, state_usage, MemoryKind::GpuOnly),
            (
                "surface",
                o.surface_count() as u64 * std::mem::size_of::<SurfaceVertex>() as u64,
                BufferUsage::STORAGE | BufferUsage::VERTEX | BufferUsage::TRANSFER_SRC,
                MemoryKind::GpuOnly,
            ),
        ];
        let mut made = Vec::with_capacity(specs.len());
        for (suffix, size, usage, memory) in specs {
            match Buffer::new(ctx, &format!("{}.{suffix}", o.name), size, usage, memory) {
                Ok(b) => made.push(b),
                Err(e) => {
                    made.into_iter().for_each(|b| b.destroy(ctx));
                    return Err(anyhow::Error::new(e).context(context()));
                }
            }
        }
        let Ok([mut params, a, b, surface]) = <[Buffer; 4]>::try_from(made) else {
            unreachable!("one buffer per spec")
        };
        let hash = if o.self_distance.is_some() && self.self_collision == SelfCollisionMethod::Hash {
            HashBuffers::new(ctx, &o.name, o.particle_count() as u64)
                .map(|h| HashStorage::Buffers(Box::new(h)))
        } else {
            Buffer::new(
                ctx,
                &format!("{}.hash.placeholder", o.name),
                16,
                BufferUsage::STORAGE,
                MemoryKind::GpuOnly,
            )
            .map(HashStorage::Placeholder)
            .map_err(anyhow::Error::from)
        };
        let hash = match hash {
            Ok(h) => h,
            Err(e) => {
                [params, a, b, surface].into_iter().for_each(|b| b.destroy(ctx));
                return Err(e.context(context()));
            }
        };
        let guard =
            Buffer::new(ctx, &format!("{}.guard", o.name), 16, BufferUsage::STORAGE, MemoryKind::Readback);
        let mut guard = match guard {
            Ok(g) => g,
            Err(e) => {
                [params, a, b, surface].into_iter().for_each(|b| b.destroy(ctx));
                match hash {
                    HashStorage::Buffers(h) => h.destroy(ctx),
                    HashStorage::Placeholder(p) => p.destroy(ctx),
                }
                return Err(anyhow::Error::new(e).context(context()));
            }
        };
        let sets = (|| -> Result<[BindingSet; 2], VkError> {
            guard.write(0, &GUARD_CLEAR)?;
            params.write(0, &[object_params(o, self.self_collision)])?;
            let [cell_rank, counts, starts, sorted, blocks] = match &hash {
                HashStorage::Buffers(h) => h.buffers(),
                HashStorage::Placeholder(p) => [p; 5],
            };
            let shared = [&self.globals, &params];
            let tail = [&self.spheres, &surface, cell_rank, counts, starts, sorted, blocks, &guard];
            let set = |arena: &mut DescriptorArena, from: &Buffer, to: &Buffer| {
                let bindings: Vec<&Buffer> =
                    shared.iter().copied().chain([from, to]).chain(tail.iter().copied()).collect();
                arena.allocate(ctx, &self.layout, &bindings)
            };
            let forward = set(&mut self.arena, &a, &b)?;
            let backward = set(&mut self.arena, &b, &a)?;
            Ok([forward, backward])
        })();
        match sets {
            Ok(sets) => Ok(GpuObject {
                kind: o.kind,
                particles: o.particle_count() as u32,
                surface_len: o.surface_count() as u32,
                step_groups: step_groups(&o.shape()),
                surface_groups: surface_groups(&o.shape()),
                params,
                state: [a, b],
                surface,
                hash,
                guard,
                sets,
            }),
            Err(e) => {
                [params, a, b, surface, guard].into_iter().for_each(|b| b.destroy(ctx));
                match hash {
                    HashStorage::Buffers(h) => h.destroy(ctx),
                    HashStorage::Placeholder(p) => p.destroy(ctx),
                }
                Err(anyhow::Error::new(e).context(context()))
            }
        }
    }

    /// The objects that use the spatial hash, with their hash buffers.
    fn hashed(&self) -> Vec<(&GpuObject, &HashBuffers)> {
        self.objects.iter().filter_map(|o| o.hash.buffers().map(|h| (o, h))).collect()
    }

    /// Barriers of the spatial hash buffers around the physics stage, which counts into them:
    /// `before` (after the previous constraints) or after it.
    fn hash_barriers_at_physics(&self, before: bool) -> Vec<BufferBarrier<'_>> {
        self.hashed()
            .into_iter()
            .flat_map(|(_, h)| {
                if before {
                    // The scan zeroed the counts; the scatter read the ranks.
                    vec![
                        BufferBarrier::new(&h.counts, Access::ComputeWrite, Access::ComputeReadWrite),
                        BufferBarrier::new(&h.cell_rank, Access::ComputeRead, Access::ComputeWrite),
                    ]
                } else {
                    // The scan reads the counts and rewrites the starts the last query read.
                    vec![
                        BufferBarrier::new(&h.counts, Access::ComputeWrite, Access::ComputeReadWrite),
                        BufferBarrier::new(&h.cell_rank, Access::ComputeWrite, Access::ComputeRead),
                        BufferBarrier::new(&h.starts, Access::ComputeRead, Access::ComputeWrite),
                        BufferBarrier::new(&h.block_sums, Access::ComputeRead, Access::ComputeWrite),
                    ]
                }
            })
            .collect()
    }

    /// The rest of the spatial hash after the physics stage counted the particles: the scan
    /// (one dispatch for tables of one block, else three) and the scatter, each ordered after
    /// the one before by a barrier on exactly the buffers it reads.
    fn record_hash_build(&self, rec: &mut Recorder<'_>) {
        let hashed = self.hashed();
        if hashed.is_empty() {
            return;
        }
        let each = |f: &dyn Fn(&HashBuffers) -> Vec<BufferBarrier<'_>>| -> Vec<BufferBarrier<'_>> {
            hashed.iter().flat_map(|(_, h)| f(h)).collect()
        };
        for (o, h) in &hashed {
            rec.dispatch(
                self.pipelines.hash_scan(0),
                o.sets[1],
                [h.buckets.div_ceil(SCAN_BLOCK as u32), 1, 1],
            );
        }
        let multi: Vec<_> = hashed.iter().filter(|(_, h)| h.buckets as u64 > SCAN_BLOCK).collect();
        if !multi.is_empty() {
            rec.barrier(&each(&|h| {
                vec![
                    BufferBarrier::new(&h.starts, Access::ComputeWrite, Access::ComputeReadWrite),
                    BufferBarrier::new(&h.block_sums, Access::ComputeWrite, Access::ComputeReadWrite),
                ]
            }));
            for (o, _) in &multi {
                rec.dispatch(self.pipelines.hash_scan(1), o.sets[1], [1, 1, 1]);
            }
            rec.barrier(&each(&|h| {
                vec![BufferBarrier::new(&h.block_sums, Access::ComputeWrite, Access::ComputeRead)]
            }));
            for (o, h) in &multi {
                rec.dispatch(self.pipelines.hash_scan(2), o.sets[1], [(h.buckets + 1).div_ceil(512), 1, 1]);
            }
        }
        rec.barrier(&each(&|h| {
            vec![
                BufferBarrier::new(&h.starts, Access::ComputeWrite, Access::ComputeRead),
                BufferBarrier::new(&h.sorted, Access::ComputeRead, Access::ComputeWrite),
            ]
        }));
        for (o, _) in &hashed {
            rec.dispatch(self.pipelines.hash_scatter(), o.sets[1], [o.particles.div_ceil(256), 1, 1]);
        }
        rec.barrier(&each(&|h| {
            vec![BufferBarrier::new(&h.sorted, Access::ComputeWrite, Access::ComputeRead)]
        }));
    }

    /// Replaces every object's state (positions, velocities, pins) with `states[i]`.
    pub fn upload_states(&mut self, ctx: &GpuContext, states: &[Vec<Particle>]) -> Result<()> {
        anyhow::ensure!(states.len() == self.objects.len(), "one state per object");
        for (s, o) in states.iter().zip(&self.objects) {
            anyhow::ensure!(s.len() == o.particles as usize, "state size does not match the object");
        }
        let bytes: u64 = states.iter().map(|s| std::mem::size_of_val(s.as_slice()) as u64).sum();
        let mut staging =
            Buffer::new(ctx, "upload staging", bytes, BufferUsage::TRANSFER_SRC, MemoryKind::Upload)?;
        self.slot.wait(ctx)?;
        let result = (|| -> Result<(), VkError> {
            let mut offset = 0;
            for s in states {
                staging.write(offset, s)?;
                offset += std::mem::size_of_val(s.as_slice()) as u64;
            }
            ctx.one_shot("upload", |rec| {
                let mut offset = 0;
                for (s, o) in states.iter().zip(&self.objects) {
                    let size = std::mem::size_of_val(s.as_slice()) as u64;
                    rec.copy_buffer_region(&staging, offset, &o.state[0], 0, size);
                    offset += size;
                }
                // The spatial hash counts start at zero (the scan re-zeroes them every substep).
                let hashed = self.hashed();
                rec.barrier(
                    &hashed
                        .iter()
                        .map(|(_, h)| {
                            BufferBarrier::new(&h.counts, Access::ComputeReadWrite, Access::TransferWrite)
                        })
                        .collect::<Vec<_>>(),
                );
                for (_, h) in &hashed {
                    rec.fill_buffer(&h.counts, 0);
                }
                let to_compute: Vec<_> = self
                    .objects
                    .iter()
                    .map(|o| BufferBarrier::new(&o.state[0], Access::TransferWrite, Access::ComputeReadWrite))
                    .chain(hashed.iter().map(|(_, h)| {
                        BufferBarrier::new(&h.counts, Access::TransferWrite, Access::ComputeReadWrite)
                    }))
                    .collect();
                rec.barrier(&to_compute);
                Ok(())
            })
        })();
        staging.destroy(ctx);
        result.context("uploading the simulation state")
    }

    /// Records one frame (all substeps and the surface stage) into `rec`. `surface_consumer` is
    /// the access that reads the surface buffers after this frame (vertex input when drawing);
    /// `slot` (below `FRAME_SLOTS`) picks the timestamp pool, read back with `read_timing`
    /// after this submission's fence. Pending particle writes are applied first.
    pub fn record_frame(&mut self, rec: &mut Recorder<'_>, surface_consumer: Access, slot: usize) {
        let ts = self.timestamps.get(slot);
        if let Some(pool) = ts {
            rec.reset_timestamps(pool);
            rec.timestamp(pool, 0);
        }
        if !self.pending_writes.is_empty() {
            let objects = &self.objects;
            let touched: Vec<usize> = {
                let mut t: Vec<usize> = self.pending_writes.iter().map(|w| w.0).collect();
                t.sort_unstable();
                t.dedup();
                t
            };
            let around = |src, dst| -> Vec<BufferBarrier<'_>> {
                touched.iter().map(|&o| BufferBarrier::new(&objects[o].state[0], src, dst)).collect()
            };
            rec.barrier(&around(Access::ComputeReadWrite, Access::TransferWrite));
            for (o, index, p) in self.pending_writes.drain(..) {
                let size = std::mem::size_of::<Particle>() as u64;
                rec.update_buffer(&objects[o].state[0], index as u64 * size, bytemuck::bytes_of(&p));
            }
            rec.barrier(&around(Access::TransferWrite, Access::ComputeReadWrite));
        }
        let stages = self.stage_timing;
        // Small objects: every substep in one dispatch each. The state ends in A, as on the
        // per-stage path; the barrier orders it (and B) for the surface stage and next frame.
        let fused: Vec<&GpuObject> = self.objects.iter().filter(|o| self.is_fused(o)).collect();
        for o in &fused {
            rec.dispatch(self.pipelines.fused(), o.sets[0], [1, 1, 1]);
        }
        if !fused.is_empty() {
            rec.barrier(
                &fused
                    .iter()
                    .flat_map(|o| {
                        let placeholder = match &o.hash {
                            HashStorage::Placeholder(b) => Some(b),
                            HashStorage::Buffers(_) => None,
                        };
                        [&o.state[0], &o.state[1]].into_iter().chain(placeholder).map(|b| {
                            BufferBarrier::new(b, Access::ComputeReadWrite, Access::ComputeReadWrite)
                        })
                    })
                    .collect::<Vec<_>>(),
            );
        }
        let stepped = fused.len() < self.objects.len();
        for s in 0..self.substeps {
            if !stepped {
                break;
            }
            rec.barrier(&self.hash_barriers_at_physics(true));
            for o in self.objects.iter().filter(|o| !self.is_fused(o)) {
                rec.dispatch(self.pipelines.physics(o.kind), o.sets[0], o.step_groups);
            }
            if let Some(pool) = ts.filter(|_| stages) {
                rec.timestamp(pool, 1 + 2 * s);
            }
            let mut after_physics = self.ping_pong_barriers(1);
            after_physics.extend(self.hash_barriers_at_physics(false));
            rec.barrier(&after_physics);
            self.record_hash_build(rec);
            for o in self.objects.iter().filter(|o| !self.is_fused(o)) {
                rec.dispatch(self.pipelines.constraints(o.kind), o.sets[1], o.step_groups);
            }
            if let Some(pool) = ts.filter(|_| stages) {
                rec.timestamp(pool, 2 + 2 * s);
            }
            rec.barrier(&self.ping_pong_barriers(0));
        }
        if let Some(pool) = ts.filter(|_| stages && !stepped) {
            // All fused: the simulation time counts as physics, the stages are not separable.
            for s in 0..self.substeps {
                rec.timestamp(pool, 1 + 2 * s);
                rec.timestamp(pool, 2 + 2 * s);
            }
        }
        // The previous frame's consumer may still read the surface: order it before the rewrite.
        let surfaces = |src, dst| -> Vec<_> {
            self.objects.iter().map(|o| BufferBarrier::new(&o.surface, src, dst)).collect()
        };
        rec.barrier(&surfaces(surface_consumer, Access::ComputeWrite));
        for o in &self.objects {
            rec.dispatch(self.pipelines.surface(o.kind), o.sets[0], o.surface_groups);
        }
        if let Some(pool) = ts {
            rec.timestamp(pool, 1 + 2 * self.substeps);
        }
        let mut end = surfaces(Access::ComputeWrite, surface_consumer);
        end.extend(
            self.objects.iter().map(|o| BufferBarrier::new(&o.guard, Access::ComputeWrite, Access::HostRead)),
        );
        rec.barrier(&end);
        self.frames += 1;
    }

    /// Rebuilds the pipelines of the `changed` shaders (names like "physics.comp") from
    /// `shaders`. A shader that fails keeps its running pipeline (the error is in `shaders`).
    /// Returns the shaders reloaded and the replaced pipelines, which frames recorded before
    /// this call may still use: destroy them once those frames have completed.
    pub fn reload(
        &mut self,
        ctx: &GpuContext,
        shaders: &mut ShaderSet,
        changed: &[String],
    ) -> (Vec<String>, Vec<Retired>) {
        self.pipelines.reload(ctx, &self.layout, shaders, changed)
    }

    /// With `false`, every object takes the per-stage path (the reference for the fused one).
    pub fn set_fused(&mut self, on: bool) {
        self.fused = on;
    }

    /// Whether object `o` runs fused substeps.
    fn is_fused(&self, o: &GpuObject) -> bool {
        self.fused && o.particles <= FUSED_MAX && matches!(o.hash, HashStorage::Placeholder(_))
    }

    /// With `false`, frames carry only a start and an end timestamp (the per-stage timestamps
    /// between dispatches are left out, so the total is not inflated by them); the stage times
    /// then read as zero.
    pub fn set_stage_timing(&mut self, on: bool) {
        self.stage_timing = on;
    }

    /// Writes one particle (position, velocity, pinned flag) at the start of the next frame.
    pub fn set_particle(&mut self, object: usize, index: u32, particle: Particle) {
        if self.objects.get(object).is_some_and(|o| index < o.particles) {
            self.pending_writes.retain(|w| (w.0, w.1) != (object, index));
            self.pending_writes.push((object, index, particle));
        }
    }

    /// Rewrites the parameters (gravity, dt, wind, spheres, per-object parameters) of a model with
    /// the same objects and sphere count. The caller makes sure no frame in flight reads them
    /// (wait idle first).
    pub fn update_params(&mut self, model: &SimModel) -> Result<()> {
        anyhow::ensure!(
            model.objects.len() == self.objects.len() && model.spheres.len() <= self.sphere_capacity(),
            "the scene's objects or spheres changed: rebuild the simulation instead"
        );
        anyhow::ensure!(
            model.substeps == self.substeps,
            "the substep count changed: rebuild the simulation instead"
        );
        self.globals.write(0, &[globals(model)])?;
        self.spheres.write(0, &sphere_data(model))?;
        for (gpu, o) in self.objects.iter_mut().zip(&model.objects) {
            anyhow::ensure!(o.dims[0] * o.dims[1] == gpu.particles, "object '{}' changed size", o.name);
            gpu.params.write(0, &[object_params(o, model.self_collision)])?;
        }
        self.frame_dt = model.frame_dt;
        self.model = model.without_particles();
        Ok(())
    }

    fn sphere_capacity(&self) -> usize {
        (self.spheres.size() / 16) as usize
    }

    /// The surface buffer of object `i` (vertex buffer of `SurfaceVertex`) and its vertex count.
    pub fn surface(&self, i: usize) -> (&Buffer, u32) {
        (&self.objects[i].surface, self.objects[i].surface_len)
    }

    pub fn object_count(&self) -> usize {
        self.objects.len()
    }

    /// Barriers after a stage that wrote `state[written]` and read the other state buffer (and
    /// the placeholders of objects without a spatial hash, which the shaders may write).
    fn ping_pong_barriers(&self, written: usize) -> Vec<BufferBarrier<'_>> {
        self.objects
            .iter()
            .filter(|o| !self.is_fused(o))
            .flat_map(|o| {
                let placeholder = match &o.hash {
                    HashStorage::Placeholder(b) => {
                        Some(BufferBarrier::new(b, Access::ComputeReadWrite, Access::ComputeReadWrite))
                    }
                    HashStorage::Buffers(_) => None,
                };
                [
                    BufferBarrier::new(&o.state[written], Access::ComputeWrite, Access::ComputeReadWrite),
                    BufferBarrier::new(&o.state[1 - written], Access::ComputeRead, Access::ComputeWrite),
                ]
                .into_iter()
                .chain(placeholder)
            })
            .collect()
    }

    /// Simulates one frame headless and waits for it; returns its GPU timing when available.
    pub fn step_frame(&mut self, ctx: &GpuContext) -> Result<Option<FrameTiming>> {
        self.slot.wait(ctx)?;
        let mut rec = self.slot.begin(ctx)?;
        self.record_frame(&mut rec, Access::ComputeReadWrite, 0);
        self.slot.submit(ctx, rec)?;
        self.slot.wait(ctx)?;
        if let Some(trip) = self.check_guard()? {
            return Err(trip.into());
        }
        self.read_timing(ctx, 0)
    }

    /// Reads the runtime guard of every object (after the fence of the last recorded frame):
    /// the first object whose state went non-finite or ran away, as a report with advice. The
    /// guard is cleared, so a resumed simulation reports again only if it trips again.
    pub fn check_guard(&mut self) -> Result<Option<GuardTrip>> {
        for (i, o) in self.objects.iter_mut().enumerate() {
            let [flags, first] = o.guard.read::<u32>(2)?[..] else { unreachable!("two words read") };
            if flags != 0 {
                o.guard.write(0, &GUARD_CLEAR)?;
                let time = self.frames as f64 * self.frame_dt;
                return Ok(Some(GuardTrip::new(&self.model, i, first, flags & GUARD_NON_FINITE != 0, time)));
            }
        }
        Ok(None)
    }

    /// Per-stage GPU time of the last frame recorded with timestamp `slot`, after its fence.
    pub fn read_timing(&self, ctx: &GpuContext, slot: usize) -> Result<Option<FrameTiming>> {
        let Some(pool) = self.timestamps.get(slot) else { return Ok(None) };
        let ms = |a: f64, b: f64| (b - a).max(0.0) * 1e-6;
        let last = 1 + 2 * self.substeps;
        let mut timing = FrameTiming::default();
        if self.stage_timing {
            let t = pool.read_ns(ctx, last + 1)?;
            for s in 0..self.substeps as usize {
                timing.physics_ms += ms(t[2 * s], t[2 * s + 1]);
                timing.constraints_ms += ms(t[2 * s + 1], t[2 * s + 2]);
            }
            timing.surface_ms = ms(t[last as usize - 1], t[last as usize]);
            timing.total_ms = ms(t[0], t[last as usize]);
        } else {
            // Only the first and the last timestamps were written.
            let start = pool.read_range_ns(ctx, 0, 1)?;
            let end = pool.read_range_ns(ctx, last, 1)?;
            timing.total_ms = ms(start[0], end[0]);
        }
        Ok(Some(timing))
    }

    /// Copies every object's state and surface back to the host.
    pub fn read_states(&mut self, ctx: &GpuContext) -> Result<Vec<ObjectState>> {
        self.slot.wait(ctx)?;
        let p = std::mem::size_of::<Particle>() as u64;
        let s = std::mem::size_of::<SurfaceVertex>() as u64;
        let bytes: u64 = self.objects.iter().map(|o| o.particles as u64 * p + o.surface_len as u64 * s).sum();
        let readback = Buffer::new(ctx, "readback", bytes, BufferUsage::TRANSFER_DST, MemoryKind::Readback)?;
        let result = (|| -> Result<Vec<ObjectState>> {
            ctx.one_shot("readback", |rec| {
                let to_copy: Vec<_> = self
                    .objects
                    .iter()
                    .flat_map(|o| {
                        [
                            BufferBarrier::new(&o.state[0], Access::ComputeWrite, Access::TransferRead),
                            BufferBarrier::new(&o.surface, Access::ComputeWrite, Access::TransferRead),
                        ]
                    })
                    .collect();
                rec.barrier(&to_copy);
                let mut offset = 0;
                for o in &self.objects {
                    rec.copy_buffer_region(&o.state[0], 0, &readback, offset, o.particles as u64 * p);
                    offset += o.particles as u64 * p;
                    rec.copy_buffer_region(&o.surface, 0, &readback, offset, o.surface_len as u64 * s);
                    offset += o.surface_len as u64 * s;
                }
                let back: Vec<_> = self
                    .objects
                    .iter()
                    .flat_map(|o| {
                        [
                            BufferBarrier::new(&o.state[0], Access::TransferRead, Access::ComputeReadWrite),
                            BufferBarrier::new(&o.surface, Access::TransferRead, Access::ComputeWrite),
                        ]
                    })
                    .chain([BufferBarrier::new(&readback, Access::TransferWrite, Access::HostRead)])
                    .collect();
                rec.barrier(&back);
                Ok(())
            })?;
            let words: Vec<u8> = readback.read::<u8>(bytes as usize)?;
            let mut at = 0usize;
            let mut take = |len: usize| {
                let slice = &words[at..at + len];
                at += len;
                slice
            };
            Ok(self
                .objects
                .iter()
                .map(|o| ObjectState {
                    particles: bytemuck::pod_collect_to_vec(take(o.particles as usize * p as usize)),
                    surface: bytemuck::pod_collect_to_vec(take(o.surface_len as usize * s as usize)),
                })
                .collect())
        })();
        readback.destroy(ctx);
        result.context("reading the simulation state back")
    }

    /// Simulated time so far [s].
    pub fn time(&self) -> f64 {
        self.frames as f64 * self.frame_dt
    }

    pub fn frames(&self) -> u64 {
        self.frames
    }

    pub fn substeps_done(&self) -> u64 {
        self.frames * self.substeps as u64
    }

    /// Frees everything after waiting for the last frame.
    pub fn destroy(mut self, ctx: &GpuContext) {
        if self.slot.wait(ctx).is_err() {
            let _ = ctx.wait_idle();
        }
        for o in self.objects {
            o.params.destroy(ctx);
            let [a, b] = o.state;
            a.destroy(ctx);
            b.destroy(ctx);
            o.surface.destroy(ctx);
            o.guard.destroy(ctx);
            match o.hash {
                HashStorage::Buffers(h) => h.destroy(ctx),
                HashStorage::Placeholder(b) => b.destroy(ctx),
            }
        }
        Parts {
            layout: Some(self.layout),
            pipelines: Some(self.pipelines),
            arena: Some(self.arena),
            globals: Some(self.globals),
            spheres: Some(self.spheres),
            slot: Some(self.slot),
            timestamps: self.timestamps,
        }
        .destroy(ctx);
    }
}
