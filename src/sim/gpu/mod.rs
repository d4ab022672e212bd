//! The simulation on Vulkan compute.
//!
//! Buffers per object (`object.rs`): `state[0]` (A, the state between substeps and frames),
//! `state[1]` (B, the physics output), `surface` (what the renderer draws), `params`, and where
//! used the spatial hash and the iterative integrators' iterates. Shared: `globals`, `colliders`.
//!
//! One frame is one command buffer:
//! ```text
//! for each substep:   physics      A -> B   (all objects)
//!                       explicit integrators: one pass;
//!                       iterative ones: predict, then `iterations` solver passes, each
//!                       ordered after the one before by a barrier on the iterates
//!                     [the stretch limit's counts into B's velocity w, between barriers on B]
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

mod batch;
mod contact;
mod energy;
mod frames;
mod fused;
mod hash;
mod object;
mod pipelines;
mod step;
mod transfer;

use contact::SceneContact;
pub use frames::FrameTiming;
use fused::ObjectPlan;
pub use fused::{FusedLimits, FusedShape, FUSED_DEFAULT_SLOTS, FUSED_SLOTS};
pub use object::{check_fits, particles};

use super::gpu_types::{self, Globals, Particle, SurfaceVertex};
use super::model::{ObjectModel, SimModel};
use crate::shaders::ShaderSet;
use crate::vk::{
    Access, BindingKind, BindingSetLayout, Buffer, BufferBarrier, BufferUsage, CommandSlot, DescriptorArena,
    GpuContext, MemoryKind, Recorder, Retired, TimestampPool,
};
use anyhow::{Context as _, Result};
use object::{collider_data, globals, object_params, GpuObject};
use pipelines::{Pipelines, SelfPass, Stage};

/// Workgroup shape of the cloth stages (the paper's 16 x 16) and of the rope stages (1-D).
const CLOTH_GROUP: [u32; 2] = [16, 16];
const ROPE_GROUP: u32 = 64;
/// Lanes a particle's search is split among in the find, apply and note passes of a cloth
/// with edge pairs on a GPU (`self_pairs.comp`'s push constant `lanes`), side by side along the
/// grid's x: a wrung cloth's particle searches hundreds of candidates, each with up to 36 edge
/// pairs, and a cloth of a few thousand particles fills a fraction of the GPU. A CPU driver
/// runs every lane's invocation in turn, so there one lane.
const SEARCH_LANES: u32 = 8;
/// The most lanes `GpuSim::set_search_lanes` takes.
const MAX_SEARCH_LANES: u32 = 64;
/// Workgroups along x every Vulkan device dispatches (the minimum of maxComputeWorkGroupCount).
const MIN_WORKGROUP_COUNT: u32 = 65_535;
/// Bindings per set, in the order of `glsl/include/bindings.glsl`.
const BINDINGS: u32 = 20;

/// What each binding holds: the globals (0) are a uniform buffer, read by every invocation
/// alike (the driver folds its members into the instructions), the rest storage buffers. The
/// object's parameters (1) as a uniform buffer measured faster still on the H100 (a further
/// 13-23% on small scenes, docs/log.md) but made lavapipe's memory grow by about 100 MB
/// a second on the playground preset (not on simpler scenes), so they stay a storage buffer.
fn binding_kinds() -> Vec<BindingKind> {
    (0..BINDINGS)
        .map(|b| if b == 0 { BindingKind::ComputeUniform } else { BindingKind::ComputeStorage })
        .collect()
}
/// Bytes of one collider record (`Collider` in layout.glsl).
const COLLIDER_BYTES: u64 = std::mem::size_of::<crate::sim::collider::ColliderRecord>() as u64;
/// Collider records per `vkCmdUpdateBuffer` (it takes at most 65,536 bytes).
const UPDATE_RECORDS: usize = 65_536 / COLLIDER_BYTES as usize;
/// Frames that may be in flight at once (each has its own timestamps).
pub const FRAME_SLOTS: usize = 2;

/// An object's state read back from the GPU.
#[derive(Debug, Clone)]
pub struct ObjectState {
    pub particles: Vec<Particle>,
    pub surface: Vec<SurfaceVertex>,
}

impl ObjectState {
    /// Particle positions in f64 (for the CPU-side metrics).
    pub fn positions(&self) -> Vec<glam::DVec3> {
        self.particles.iter().map(|p| glam::Vec3::from_slice(&p.pos[..3]).as_dvec3()).collect()
    }

    /// Particle velocities in f64.
    pub fn velocities(&self) -> Vec<glam::DVec3> {
        self.particles.iter().map(|p| glam::Vec3::from_slice(&p.vel[..3]).as_dvec3()).collect()
    }
}

pub struct GpuSim {
    pipelines: Pipelines,
    layout: BindingSetLayout,
    arena: DescriptorArena,
    globals: Buffer,
    colliders: Buffer,
    objects: Vec<GpuObject>,
    /// The batched step pipelines' layout and each chunk of objects' sets (`batch.rs`).
    batches: batch::Batches,
    /// Contact between objects: the scene's hash over every object's particles (`contact.rs`).
    contact: Option<SceneContact>,
    /// Command buffers of the headless frames (`frames.rs`), one per frame in flight, and
    /// whether each holds a submitted frame whose timing and guard are not read yet.
    slots: Vec<CommandSlot>,
    unread: Vec<bool>,
    /// One pool per frame slot (empty when the device has no timestamps).
    timestamps: Vec<TimestampPool>,
    stage_timing: bool,
    /// Objects whose layout fits the device's shared memory run their substeps fused into one
    /// dispatch (`fused.rs`).
    fused: bool,
    /// The self-contact features an object may have and still run fused (by default
    /// `fused::default_fused_contact`, which says why; `set_fused(true)`: all).
    fuse_contact: u32,
    /// Lanes of a cloth's self-contact search with edge pairs per stage (`SEARCH_LANES`, or 1
    /// on a CPU driver; `set_search_lanes`).
    search_lanes: u32,
    /// The implicit method per stage: objects of more workgroups than this have their dot
    /// products' partial sums totalled by a pass of one workgroup (`step.rs`).
    cg_totals_above: u32,
    /// What the fused layouts are planned within.
    limits: FusedLimits,
    /// Whether the surface stage writes the surface buffers (else it only runs the guard).
    drawn: bool,
    frames: u64,
    /// The simulated time at frame 0 [s] (`continue_at`; kept continuous when frame_dt changes).
    start: f64,
    /// How far each collider was moved by `update_params` since the last frame (the app's
    /// editor dragging it): the next frame moves it there during the frame.
    dragged: Vec<glam::DVec3>,
    /// The last frame recorded a dragged collider's move: the next writes its records again,
    /// where it is (else the buffer kept the move, and it swept the same way every frame).
    drag_recorded: bool,
    /// The state was uploaded after the last recorded frame (`take_surface_stale`).
    surface_stale: bool,
    /// Whether the contact-speed warning was given, and the warning not yet taken.
    warned: bool,
    warning: Option<String>,
    /// The guard's energy check (`energy.rs`).
    energy: energy::EnergyWatch,
    /// Particle writes (object, index, value) applied at the start of the next recorded frame.
    pending_writes: Vec<(usize, u32, Particle)>,
    /// The fused kernel's self-collision contact lists may not match the state or parameters
    /// any more: the next frame marks them invalid first (`record_cleared`).
    lists_stale: bool,
    /// The iterative methods' BDF2 histories do not belong to the state or the substep any
    /// more (a new state, another dt): the next frame clears them first, and every particle's
    /// next substep starts afresh (`sim::cpu::integrators::inertial`).
    history_stale: bool,
    /// The model the simulation runs, without particles (substeps, integrator, the guard's
    /// reports).
    model: SimModel,
}

/// The scene-independent parts of a `GpuSim`, each present once created, so a failure part-way
/// frees exactly what exists.
#[derive(Default)]
struct Parts {
    layout: Option<BindingSetLayout>,
    batches: Option<batch::Batches>,
    pipelines: Option<Pipelines>,
    arena: Option<DescriptorArena>,
    globals: Option<Buffer>,
    colliders: Option<Buffer>,
    slots: Vec<CommandSlot>,
    timestamps: Vec<TimestampPool>,
}

impl Parts {
    fn create(
        &mut self,
        ctx: &GpuContext,
        model: &SimModel,
        shaders: &mut ShaderSet,
        plans: &[ObjectPlan],
    ) -> Result<()> {
        let layout = self.layout.insert(BindingSetLayout::new(ctx, &binding_kinds())?);
        // (the step stages once a frame runs them: `GpuSim::ensure_pipelines`)
        let (later, now): (Vec<Stage>, Vec<Stage>) =
            Stage::needed(model, plans).into_iter().partition(|s| s.deferred(model));
        let batches = self.batches.insert(batch::Batches::new_layout(ctx, &binding_kinds())?);
        self.pipelines =
            Some(Pipelines::new(ctx, [&*layout, &batches.layout], batches.chunk, shaders, &now, &later)?);
        let n = model.objects.len() as u32;
        let (contact_sets, contact_chunk_sets) = contact::sets_needed(model, batches.chunk);
        let (sets, chunk_sets) = (2 * n + contact_sets, 2 * batches.chunks(n as usize) + contact_chunk_sets);
        let descriptors = sets * BINDINGS + chunk_sets * batches.layout.descriptors();
        self.arena = Some(DescriptorArena::for_descriptors(ctx, sets + chunk_sets, descriptors)?);
        let globals_size = std::mem::size_of::<Globals>() as u64;
        // (each frame writes the turbulence's phases in its commands: `record_wind_phases`)
        let globals_usage = BufferUsage::UNIFORM | BufferUsage::TRANSFER_DST;
        self.globals = Some(Buffer::new(ctx, "globals", globals_size, globals_usage, MemoryKind::Upload)?);
        // The records, then the mesh colliders' triangles (`object::mesh_words`).
        let mesh_bytes = 16 * object::mesh_word_count(model);
        let colliders_size = COLLIDER_BYTES * model.colliders.len().max(1) as u64 + mesh_bytes;
        self.colliders = Some(Buffer::new(
            ctx,
            "colliders",
            colliders_size,
            BufferUsage::STORAGE | BufferUsage::TRANSFER_DST,
            MemoryKind::Upload,
        )?);
        for slot in 0..FRAME_SLOTS {
            self.slots.push(CommandSlot::new(ctx, &format!("frame[{slot}]"))?);
        }
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
        for s in self.slots {
            s.destroy(ctx);
        }
        if let Some(b) = self.colliders {
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
        if let Some(b) = self.batches {
            b.destroy(ctx);
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
        Self::build(ctx, model, shaders, FusedLimits::for_device(ctx.info()))
    }

    /// Like `new`, with the fused layouts planned within `limits` (themselves within the
    /// device's shared memory and `FUSED_SLOTS`): more particles per thread than the default,
    /// or less shared memory (the velocity window in passes), for tests and measurements; with
    /// shaders from `shaders`.
    pub fn with_fused_limits(
        ctx: &GpuContext,
        model: &SimModel,
        limits: FusedLimits,
        shaders: &mut ShaderSet,
    ) -> Result<Self> {
        let limits = limits.within(ctx.info());
        Self::build(ctx, model, shaders, limits)
    }

    fn build(
        ctx: &GpuContext,
        model: &SimModel,
        shaders: &mut ShaderSet,
        limits: FusedLimits,
    ) -> Result<Self> {
        check_fits(ctx.info(), &model.objects.iter().map(ObjectModel::shape).collect::<Vec<_>>())?;
        contact::check_scene(model, ctx.info().max_storage_buffer_range)?;
        object::check_meshes(model, ctx.info().max_storage_buffer_range)?;
        for o in &model.objects {
            crate::sim::cloth_mesh::check_model(o, model).map_err(crate::error::UserError)?;
        }
        let plans: Vec<ObjectPlan> = model.objects.iter().map(|o| ObjectPlan::of(o, model, limits)).collect();
        let mut parts = Parts::default();
        if let Err(e) = parts.create(ctx, model, shaders, &plans) {
            parts.destroy(ctx);
            return Err(e);
        }
        let Parts {
            layout: Some(layout),
            batches: Some(batches),
            pipelines: Some(pipelines),
            arena: Some(arena),
            globals: Some(globals),
            colliders: Some(colliders),
            slots,
            timestamps,
        } = parts
        else {
            unreachable!("Parts::create fills every part or fails")
        };
        let mut sim = Self {
            pipelines,
            layout,
            batches,
            arena,
            globals,
            colliders,
            objects: Vec::new(),
            contact: None,
            unread: vec![false; slots.len()],
            slots,
            timestamps,
            stage_timing: true,
            fused: true,
            fuse_contact: fused::default_fused_contact(ctx.info()),
            search_lanes: match ctx.info().kind {
                crate::vk::DeviceKind::Cpu => 1,
                _ => SEARCH_LANES,
            },
            cg_totals_above: step::CG_TOTALS_ABOVE,
            limits,
            drawn: true,
            frames: 0,
            start: 0.0,
            pending_writes: Vec::new(),
            lists_stale: true,
            history_stale: true,
            warned: false,
            warning: None,
            energy: Default::default(),
            surface_stale: false,
            dragged: Vec::new(),
            drag_recorded: false,
            model: model.without_particles(),
        };
        // From here `sim` owns everything created; on error it is destroyed whole.
        match sim.populate(ctx, model, &plans) {
            Ok(()) => Ok(sim),
            Err(e) => {
                let _ = ctx.wait_idle();
                sim.destroy(ctx);
                Err(e)
            }
        }
    }

    fn populate(&mut self, ctx: &GpuContext, model: &SimModel, plans: &[ObjectPlan]) -> Result<()> {
        self.globals.write(0, &[globals(model, 0.0)])?;
        self.colliders.write(0, &collider_data(model, 0.0))?;
        let meshes = object::mesh_words(model);
        if !meshes.is_empty() {
            self.colliders.write(COLLIDER_BYTES * model.colliders.len().max(1) as u64, &meshes)?;
        }
        for (o, &plan) in model.objects.iter().zip(plans) {
            let shared = [&self.globals, &self.colliders];
            let obj = GpuObject::new(ctx, &self.layout, &mut self.arena, shared, o, model, plan)
                .with_context(|| format!("allocating {} '{}'", o.kind.label(), o.name))?;
            self.objects.push(obj);
        }
        let shared = [&self.globals, &self.colliders];
        self.batches.allocate(ctx, &mut self.arena, shared, &self.objects)?;
        self.contact = SceneContact::new(
            ctx,
            &self.layout,
            &self.batches,
            &mut self.arena,
            shared,
            model,
            &self.objects,
        )?;
        let initial: Vec<Vec<Particle>> =
            model.objects.iter().map(|o| particles(o, model.frame_dt)).collect();
        self.upload_states(ctx, &initial)
    }

    /// Records one frame (all substeps and the surface stage) into `rec`. `surface_consumer` is
    /// the access that reads the surface buffers after this frame (vertex input when drawing);
    /// `slot` (below `FRAME_SLOTS`) picks the timestamp pool, read back with `read_timing`
    /// after this submission's fence. Pending particle writes are applied first. Fails where a
    /// pipeline the frame runs for the first time does not compile (`ensure_pipelines`).
    pub fn record_frame(
        &mut self,
        rec: &mut Recorder<'_>,
        surface_consumer: Access,
        slot: usize,
    ) -> Result<()> {
        self.ensure_pipelines(rec.context())?;
        let dragged = std::mem::take(&mut self.dragged);
        let after_drag =
            std::mem::replace(&mut self.drag_recorded, dragged.iter().any(|d| *d != glam::DVec3::ZERO));
        let lists_stale = std::mem::take(&mut self.lists_stale) || !self.pending_writes.is_empty();
        if let Some(c) = self.contact.as_mut().filter(|_| lists_stale) {
            // (the frame clears the contact counters, `record_frame_start`)
            c.policy.restart();
        }
        let history_stale = std::mem::take(&mut self.history_stale);
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
            // A written particle loses its BDF2 history (the state no longer follows from it).
            let around = |src, dst| -> Vec<BufferBarrier<'_>> {
                (touched.iter().map(|&o| &objects[o]))
                    .flat_map(|o| [Some(&o.state[0]), o.solver.as_ref().map(|s| &s.history)])
                    .flatten()
                    .map(|b| BufferBarrier::new(b, src, dst))
                    .collect()
            };
            rec.barrier(&around(Access::ComputeReadWrite, Access::TransferWrite));
            for (o, index, p) in self.pending_writes.drain(..) {
                let size = std::mem::size_of::<Particle>() as u64;
                rec.update_buffer(&objects[o].state[0], index as u64 * size, bytemuck::bytes_of(&p));
                if let Some(s) = &objects[o].solver {
                    // Its x_n - x_{n-1} zeroed, with the w that marks it valid (H_DX, first).
                    rec.update_buffer(&s.history, 16 * index as u64, &[0u8; 16]);
                }
            }
            rec.barrier(&around(Access::TransferWrite, Access::ComputeReadWrite));
        }
        let lists = (self.objects.iter()).filter(|_| lists_stale).filter_map(|o| {
            // The lists and the control blocks, not the counters after them.
            let (control, blocks) = object::list_control_range(o.particles as u64);
            Some((o.self_list.as_ref()?, control + blocks, transfer::LISTS_INVALID))
        });
        // A cloth's contact sums start at zero (the constraints clear them after each read).
        let pairs = (self.objects.iter())
            .filter(|_| lists_stale)
            .filter_map(|o| o.self_pairs.as_ref().map(|p| (p, p.size(), 0)));
        let histories = (self.objects.iter())
            .filter_map(|o| o.solver.as_ref().map(|s| &s.history).filter(|_| history_stale))
            .map(|h| (h, h.size(), 0));
        transfer::record_cleared(rec, &lists.chain(pairs).chain(histories).collect::<Vec<_>>());
        self.record_list_control_cleared(rec);
        if let Some(c) = &self.contact {
            c.record_frame_start(rec, lists_stale);
        }
        self.record_collider_motion(rec, &dragged, after_drag);
        self.record_wind_phases(rec);
        self.record_pin_motion(rec);
        let stages = self.stage_timing;
        // Small objects: every substep in one dispatch each. The state ends in A, as on the
        // per-stage path; the barrier orders it (and B) for the surface stage and next frame.
        // On a device that ends long loops early (lavapipe), in several dispatches of
        // `substeps_per_dispatch` substeps (the kernel's push constants: the first substep and
        // how many), each ordered after the one before.
        let fused: Vec<&GpuObject> = self.objects.iter().filter(|o| self.is_fused(o)).collect();
        let chunk = self.limits.chunk(fused.iter().map(|o| o.plan.features), self.model.substeps);
        let mut first = 0;
        while !fused.is_empty() && first < self.model.substeps {
            let count = chunk.min(self.model.substeps - first);
            for o in &fused {
                if let Some(shape) = o.plan.fused {
                    rec.dispatch_with(
                        self.pipelines.get(Stage::Fused(self.model.integrator, o.plan.features, shape)),
                        o.sets[0],
                        [1, 1, 1],
                        &[first, count],
                    );
                }
            }
            rec.barrier(
                &fused
                    .iter()
                    .flat_map(|o| [&o.state[0], &o.state[1]].into_iter().chain(o.scratch()))
                    .map(|b| BufferBarrier::new(b, Access::ComputeReadWrite, Access::ComputeReadWrite))
                    .collect::<Vec<_>>(),
            );
            first += count;
        }
        let stepped = fused.len() < self.objects.len();
        for s in 0..self.model.substeps {
            if !stepped {
                break;
            }
            rec.barrier(&self.hash_barriers_at_physics(true));
            self.record_physics(rec, s);
            if let Some(pool) = ts.filter(|_| stages) {
                rec.timestamp(pool, 1 + 2 * s);
            }
            let mut after_physics = self.ping_pong_barriers(1);
            after_physics.extend(self.hash_barriers_at_physics(false));
            rec.barrier(&after_physics);
            self.record_hash_build(rec, s);
            if let Some(c) = &self.contact {
                // (the substep's last round: `record_physics` ran the others)
                let rounds = self.model.contact_rounds();
                c.record(rec, &self.pipelines, &self.objects, s * rounds + rounds - 1);
            }
            self.record_self_pairs(rec, s);
            self.record_stretch_counts(rec);
            let mut constraints = batch::Pass::new();
            for (k, o) in self.objects.iter().enumerate().filter(|(_, o)| !self.is_fused(o)) {
                let stage = Stage::Constraints(o.kind, o.plan.features, self.lists_on(o));
                constraints.add(k, self.pipelines.get(stage), o.step_groups, &[s]);
            }
            constraints.record(rec, &self.batches, 1);
            self.record_truncation(rec, s);
            if let Some(pool) = ts.filter(|_| stages) {
                rec.timestamp(pool, 2 + 2 * s);
            }
            rec.barrier(&self.ping_pong_barriers(0));
        }
        if let Some(pool) = ts.filter(|_| stages && !stepped) {
            // All fused: the simulation time counts as physics, the stages are not separable;
            // only the end of the first substep's physics (the whole pass) and of the last
            // substep are written (read_timing reads those; writing every substep's two cost
            // lavapipe 0.03 ms each).
            rec.timestamp(pool, 1);
            rec.timestamp(pool, 2 * self.model.substeps);
        }
        self.record_surface(rec, surface_consumer);
        if let Some(pool) = ts {
            rec.timestamp(pool, 1 + 2 * self.model.substeps);
        }
        self.frames += 1;
        self.surface_stale = false;
        for o in &mut self.objects {
            o.lists.frame();
        }
        if let Some(c) = &mut self.contact {
            c.record_frame_end(rec);
            c.policy.frame();
        }
        Ok(())
    }

    /// Creates the pipelines the next frame runs that are not created yet: the fused kernels
    /// of the objects that run fused, and every step stage once some object runs per stage.
    pub(super) fn ensure_pipelines(&mut self, ctx: &GpuContext) -> Result<()> {
        if self.pipelines.all_created() {
            return Ok(());
        }
        let method = self.model.integrator;
        let fused: Vec<Stage> = (self.objects.iter().filter(|o| self.is_fused(o)))
            .filter_map(|o| o.plan.fused.map(|shape| Stage::Fused(method, o.plan.features, shape)))
            .collect();
        let stepped = self.objects.iter().any(|o| !self.is_fused(o));
        let layouts = [&self.layout, &self.batches.layout];
        self.pipelines.ensure(ctx, layouts, self.batches.chunk, |s| match s {
            Stage::Fused(..) => fused.contains(s),
            _ => stepped,
        })
    }

    /// The passes of the objects' contact with their own surface (a cloth's triangles, a
    /// rope's segments) on the per-stage path
    /// (`self_pairs.comp`), after the spatial hash's build: find, apply, then for each further
    /// contact iteration a move of the physics output and a re-application; each ordered after
    /// the one before and before the constraints by a barrier on the objects' scratch buffers,
    /// on the state the constraints write (which the passes read: where each particle began
    /// the substep, for friction) and on the physics output (which the moves write).
    fn record_self_pairs(&self, rec: &mut Recorder<'_>, substep: u32) {
        let cloths: Vec<&GpuObject> =
            self.objects.iter().filter(|o| !self.is_fused(o) && o.self_pairs.is_some()).collect();
        if cloths.is_empty() {
            return;
        }
        // The find pass writes the further passes' indirect dispatch into self_pairs (with one
        // pass there are none, and the barriers leave the indirect stage out).
        let pairs = if self.model.contact_iterations > 1 {
            Access::ComputeOrIndirect
        } else {
            Access::ComputeReadWrite
        };
        let mut barriers: Vec<BufferBarrier<'_>> =
            cloths.iter().flat_map(|o| o.scratch_barriers_with(pairs)).collect();
        // (sets[1] reads state[1] and writes state[0], binding 3)
        barriers.extend(
            cloths.iter().map(|o| BufferBarrier::new(&o.state[0], Access::ComputeRead, Access::ComputeWrite)),
        );
        // The moves between passes write the physics output, which the passes, the hash's
        // build, contact between objects and the constraints read (the passes' shader may
        // write it in every pass, as validation sees it).
        let outputs: Vec<BufferBarrier<'_>> = cloths
            .iter()
            .map(|o| BufferBarrier::new(&o.state[1], Access::ComputeReadWrite, Access::ComputeReadWrite))
            .collect();
        rec.barrier(&outputs);
        barriers.extend(outputs);
        let again = [SelfPass::Move, SelfPass::Reapply];
        let passes = [SelfPass::Find, SelfPass::Apply]
            .into_iter()
            .chain((1..self.model.contact_iterations).flat_map(|_| again));
        for pass in passes {
            for o in &cloths {
                let lists = self.lists_on(o) && matches!(pass, SelfPass::Find | SelfPass::Apply);
                let stage = Stage::SelfPairs(o.plan.features, lists, pass);
                let pipeline = self.pipelines.get(stage);
                // (the find and apply passes split alike: the apply pass reads the find's slots)
                let lanes = self.lanes_of(o, o.hash.is_some() && !self.lists_on(o));
                let push = [substep, lanes];
                match (pass, &o.self_pairs) {
                    // Only in a substep where some particle found a contact.
                    (SelfPass::Move | SelfPass::Reapply, Some(args)) => {
                        let offset = object::further_passes_offset(o.particles as u64);
                        rec.dispatch_indirect(pipeline, o.sets[1], args, offset, &push);
                    }
                    _ => {
                        let [x, y, z] = o.step_groups;
                        rec.dispatch_with(pipeline, o.sets[1], [x * lanes, y, z], &push)
                    }
                }
            }
            rec.barrier(&barriers);
        }
    }

    /// Lanes a cloth's self-contact search with edge pairs is split among per stage (by
    /// default `SEARCH_LANES` on a GPU, 1 on a CPU driver; at most `MAX_SEARCH_LANES`); for
    /// tests and measurements.
    pub fn set_search_lanes(&mut self, lanes: u32) {
        self.search_lanes = lanes.clamp(1, MAX_SEARCH_LANES);
    }

    /// Lanes object `o`'s self-contact passes split each particle's search among
    /// (`self_pairs.comp`'s push constant `lanes`): `search_lanes` for a cloth with edge pairs
    /// whose pass `searches` the hash or by brute force (a find or apply pass that builds or
    /// walks the contact lists keeps each particle's list in one lane), where the wider
    /// dispatch fits the workgroup count every device allows; else 1.
    fn lanes_of(&self, o: &GpuObject, searches: bool) -> u32 {
        let fits = o.step_groups[0].saturating_mul(self.search_lanes) <= MIN_WORKGROUP_COUNT;
        if searches && fits && gpu_types::has_cloth_edge_pairs(o.plan.features) {
            self.search_lanes
        } else {
            1
        }
    }

    /// The passes after the constraint stage of the cloths that keep their edges apart
    /// (`self_pairs.comp`'s, glsl/include/self_contact.glsl's note_truncation): with the
    /// spatial hash, the hash built again from where the particles began the substep (count,
    /// scan, scatter), then the note and truncate passes; each ordered after the writes before
    /// it and before the reads after it by a barrier on the state, the scratch and the hash
    /// buffers.
    fn record_truncation(&self, rec: &mut Recorder<'_>, substep: u32) {
        let cloths: Vec<&GpuObject> = (self.objects.iter())
            .filter(|o| !self.is_fused(o) && o.self_pairs.is_some())
            .filter(|o| crate::sim::gpu_types::has_cloth_edge_pairs(o.plan.features))
            .collect();
        if cloths.is_empty() {
            return;
        }
        let barriers: Vec<BufferBarrier<'_>> = (cloths.iter())
            .flat_map(|o| o.scratch())
            // (the passes' shader may write the physics output too, as validation sees it)
            .chain(cloths.iter().flat_map(|o| &o.state))
            .chain(cloths.iter().filter_map(|o| o.hash.as_deref()).flat_map(|h| h.buffers()))
            .map(|b| BufferBarrier::new(b, Access::ComputeReadWrite, Access::ComputeReadWrite))
            .collect();
        // (the hash of the starts: count, scan, scatter)
        let hashed: Vec<(&GpuObject, u32)> =
            cloths.iter().filter_map(|o| o.hash.as_deref().map(|h| (*o, h.buckets))).collect();
        let per_particle = |o: &GpuObject| [o.particles.div_ceil(256), 1, 1];
        for stage in [Stage::TruncationHash(false), Stage::HashScan, Stage::TruncationHash(true)] {
            rec.barrier(&barriers);
            for &(o, buckets) in &hashed {
                let groups = match stage {
                    Stage::HashScan => [buckets.div_ceil(object::SCAN_BLOCK as u32), 1, 1],
                    _ => per_particle(o),
                };
                rec.dispatch(self.pipelines.get(stage), o.sets[1], groups);
            }
        }
        for pass in [SelfPass::Note, SelfPass::Truncate] {
            rec.barrier(&barriers);
            for o in &cloths {
                let pipeline = self.pipelines.get(Stage::SelfPairs(o.plan.features, false, pass));
                let lanes = if pass == SelfPass::Note { self.lanes_of(o, true) } else { 1 };
                let [x, y, z] = o.step_groups;
                rec.dispatch_with(pipeline, o.sets[1], [x * lanes, y, z], &[substep, lanes]);
            }
        }
        rec.barrier(&barriers);
    }

    /// The stretch limit's counts of the objects with one on the per-stage path
    /// (`stretch_count.comp`): written into the physics output, after every pass that reads or
    /// moves it and before the constraint stage reads them.
    fn record_stretch_counts(&self, rec: &mut Recorder<'_>) {
        let limited: Vec<(usize, &GpuObject)> = (self.objects.iter().enumerate())
            .filter(|(_, o)| {
                !self.is_fused(o) && o.plan.features & crate::sim::gpu_types::FEATURE_STRETCH != 0
            })
            .collect();
        if limited.is_empty() {
            return;
        }
        // (every object's stepped per stage: validation takes a batched dispatch to write
        // every output of its chunk, the pass's shader declaring them writable)
        let outputs: Vec<BufferBarrier<'_>> = (self.objects.iter().filter(|o| !self.is_fused(o)))
            .map(|o| BufferBarrier::new(&o.state[1], Access::ComputeReadWrite, Access::ComputeReadWrite))
            .collect();
        rec.barrier(&outputs);
        let mut counts = batch::Pass::new();
        for &(k, o) in &limited {
            counts.add(
                k,
                self.pipelines.get(Stage::StretchCount(o.kind, o.plan.features)),
                o.step_groups,
                &[],
            );
        }
        counts.record(rec, &self.batches, 1);
        rec.barrier(&outputs);
    }

    /// The surface stage alone: cloth normals and rope tube vertices from the current state
    /// (and the guard), ordered after `surface_consumer`'s last reads and before its next.
    /// `record_frame` ends with it; on its own it shows a state uploaded while the simulation
    /// is paused (a reset), without simulating.
    pub fn record_surface(&self, rec: &mut Recorder<'_>, surface_consumer: Access) {
        // The previous frame's consumer may still read the surface: order it before the rewrite.
        let surfaces = |src, dst| -> Vec<_> {
            self.objects.iter().map(|o| BufferBarrier::new(&o.surface, src, dst)).collect()
        };
        rec.barrier(&surfaces(surface_consumer, Access::ComputeWrite));
        for o in &self.objects {
            // (a mesh cloth's normals' workgroups are not its steps')
            let (stage, groups) = if self.drawn || o.mesh {
                (Stage::Surface(o.kind, self.drawn, o.mesh), o.surface_groups)
            } else {
                (Stage::Surface(o.kind, false, false), o.step_groups)
            };
            rec.dispatch(self.pipelines.get(stage), o.sets[0], groups);
        }
        let mut end = surfaces(Access::ComputeWrite, surface_consumer);
        end.extend(
            self.objects.iter().map(|o| BufferBarrier::new(&o.guard, Access::ComputeWrite, Access::HostRead)),
        );
        rec.barrier(&end);
    }

    /// Whether the state was replaced since the last recorded frame (`upload_states`), so the
    /// surface buffers show an older one: a paused app records `record_surface` once.
    pub fn take_surface_stale(&mut self) -> bool {
        std::mem::take(&mut self.surface_stale)
    }

    /// Starts the simulated time again from zero (a reset to the initial state).
    pub fn reset_time(&mut self) {
        // (Its interval counts from frame 0 again.)
        self.energy = Default::default();
        (self.frames, self.start) = (0, 0.0);
    }

    /// Goes on from simulated time `t` (a rebuilt simulation carrying another's state), so that
    /// moving colliders stay where that one had them.
    pub fn continue_at(&mut self, t: f64) {
        self.energy.restart();
        self.start = t - self.frames as f64 * self.model.frame_dt;
    }

    /// Moving colliders: this frame's records (where each is at the frame's start, its velocity
    /// over the frame), written in the command stream so frames in flight keep their own.
    /// Scenes whose colliders all stay put record nothing, but in the frame after a drag
    /// (`after_drag`), which puts the dragged ones back at rest where they are.
    fn record_collider_motion(&self, rec: &mut Recorder<'_>, dragged: &[glam::DVec3], after_drag: bool) {
        if !self.model.colliders.iter().any(|c| c.is_moving())
            && dragged.iter().all(|d| *d == glam::DVec3::ZERO)
            && !after_drag
        {
            return;
        }
        let t0 = self.time();
        let mut data: Vec<_> = (self.model.colliders.iter().enumerate())
            .map(|(i, c)| c.gpu_dragged(t0, self.model.frame_dt, dragged.get(i).copied().unwrap_or_default()))
            .collect();
        object::place_meshes(&self.model, &mut data);
        rec.barrier(&[BufferBarrier::new(&self.colliders, Access::ComputeRead, Access::TransferWrite)]);
        for (i, chunk) in data.chunks(UPDATE_RECORDS).enumerate() {
            let offset = (i * UPDATE_RECORDS) as u64 * COLLIDER_BYTES;
            rec.update_buffer(&self.colliders, offset, bytemuck::cast_slice(chunk));
        }
        rec.barrier(&[BufferBarrier::new(&self.colliders, Access::TransferWrite, Access::ComputeRead)]);
    }

    /// Moving pins: how each such object's pins move over this frame into its parameters,
    /// written in the command stream (as the colliders' records) so frames in flight keep
    /// their own. Objects whose pins stay put record nothing.
    fn record_pin_motion(&self, rec: &mut Recorder<'_>) {
        let moving: Vec<(&GpuObject, &crate::sim::model::ObjectModel)> =
            (self.objects.iter()).zip(&self.model.objects).filter(|(_, o)| o.pins_move()).collect();
        if moving.is_empty() {
            return;
        }
        let around = |src, dst| -> Vec<BufferBarrier<'_>> {
            moving.iter().map(|(gpu, _)| BufferBarrier::new(&gpu.params, src, dst)).collect()
        };
        rec.barrier(&around(Access::ComputeRead, Access::TransferWrite));
        let offset = std::mem::offset_of!(crate::sim::gpu_types::ObjectParams, pins) as u64;
        for (gpu, o) in &moving {
            // (each group's velocity, pivot and turn, one after the other)
            let record = object::pin_record(o, &self.model, self.time());
            rec.update_buffer(&gpu.params, offset, bytemuck::cast_slice(&record));
        }
        rec.barrier(&around(Access::TransferWrite, Access::ComputeRead));
    }

    /// The wind's turbulence: its phases at this frame's start, written in the command stream
    /// (as the colliders' records) so frames in flight keep their own; the shaders add the
    /// time since (glsl/include/air.glsl). Scenes without turbulence record nothing.
    fn record_wind_phases(&self, rec: &mut Recorder<'_>) {
        let Some(turbulence) = object::turbulence(&self.model) else { return };
        let (_, gusts) = turbulence.gpu(self.time());
        let offset = std::mem::offset_of!(Globals, wind_gusts) as u64;
        rec.barrier(&[BufferBarrier::new(&self.globals, Access::ComputeUniformRead, Access::TransferWrite)]);
        rec.update_buffer(&self.globals, offset, bytemuck::cast_slice(&gusts));
        rec.barrier(&[BufferBarrier::new(&self.globals, Access::TransferWrite, Access::ComputeUniformRead)]);
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
        self.lists_stale = true; // a changed fused.comp may build other lists
        self.pipelines.reload(ctx, [&self.layout, &self.batches.layout], self.batches.chunk, shaders, changed)
    }

    /// With `false` nothing reads the surface buffers (a headless run): the surface stage only
    /// runs the guard, and `read_states` returns the surface of the last drawn frame.
    pub fn set_drawn(&mut self, on: bool) {
        self.drawn = on;
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
            self.energy.restart();
            self.pending_writes.retain(|w| (w.0, w.1) != (object, index));
            self.pending_writes.push((object, index, particle));
        }
    }

    /// Whether `model` differs from the running one only in what `update_params` rewrites: the
    /// same objects, collider capacity, substep count, integrator and self-collision method, and
    /// the same compiled-in features and fused layouts, more than one contact pass on both or
    /// neither (the further passes' pipelines), the same cloths keeping their edges apart
    /// (contact between objects' pipelines, lists and rows). Otherwise rebuild the simulation.
    pub fn takes_params(&self, model: &SimModel) -> bool {
        let edges = |m: &SimModel| {
            (m.inter_object_edges, m.objects.iter().map(|o| o.edge_contact).collect::<Vec<_>>())
        };
        model.objects.len() == self.objects.len()
            && edges(model) == edges(&self.model)
            && (model.contact_iterations > 1) == (self.model.contact_iterations > 1)
            && model.colliders.len() <= self.collider_capacity()
            && same_meshes(model, &self.model)
            && model.substeps == self.model.substeps
            && model.integrator == self.model.integrator
            && model.self_collision == self.model.self_collision
            && (model.objects.iter().zip(&self.model.objects)).all(|(new, old)| {
                new.pins_move() == old.pins_move()
                    && new.pin_groups.len() == old.pin_groups.len()
                    // (a mesh cloth's rest lengths are in its lists)
                    && (new.mesh == old.mesh && (new.mesh.is_none() || new.rest_scale == old.rest_scale))
            })
            && self.objects.iter().zip(&model.objects).all(|(gpu, o)| {
                o.particle_count() as u32 == gpu.particles
                    && ObjectPlan::of(o, model, self.limits) == gpu.plan
            })
    }

    /// Rewrites the parameters (gravity, dt, wind, colliders, per-object parameters) of a model
    /// that `takes_params`. The caller makes sure no frame in flight reads them (wait idle
    /// first).
    pub fn update_params(&mut self, model: &SimModel) -> Result<()> {
        anyhow::ensure!(
            self.takes_params(model),
            "the objects, colliders, substeps, integrator, self-collision method or the features in use changed: rebuild the simulation instead"
        );
        self.globals.write(0, &[globals(model, self.time())])?;
        self.colliders.write(0, &collider_data(model, self.time()))?;
        // Colliders the edit moved (the same ones, in the same order): moved during the next
        // frame rather than jumping (see `record_collider_motion`).
        self.dragged = if model.colliders.len() == self.model.colliders.len() {
            model
                .colliders
                .iter()
                .zip(&self.model.colliders)
                .map(|(new, old)| {
                    let same = new.shape.kind() == old.shape.kind();
                    if same {
                        new.shape.reference_point() - old.shape.reference_point()
                    } else {
                        glam::DVec3::ZERO
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        for (gpu, o) in self.objects.iter_mut().zip(&model.objects) {
            let params = object_params(o, model);
            gpu.params.write(0, &[params])?;
            gpu.searches = object::searches(&params);
            gpu.rigid_start = object::rigid_start(&params);
        }
        self.history_stale |= model.dt() != self.model.dt();
        let now = self.time();
        self.model = model.without_particles();
        self.continue_at(now);
        self.lists_stale = true;
        Ok(())
    }

    /// Records the collider buffer holds (with mesh colliders it holds their triangles too,
    /// and `same_meshes` keeps the count of records as it is).
    fn collider_capacity(&self) -> usize {
        (self.colliders.size() / COLLIDER_BYTES) as usize
    }

    /// The surface buffer of object `i` (vertex buffer of `SurfaceVertex`) and its vertex count.
    pub fn surface(&self, i: usize) -> (&Buffer, u32) {
        (&self.objects[i].surface, self.objects[i].surface_len)
    }

    pub fn object_count(&self) -> usize {
        self.objects.len()
    }

    /// Barriers after a stage that wrote `state[written]` and read the other state buffer (and
    /// the scratch buffers: placeholders, which the shaders may write, and solver iterates).
    fn ping_pong_barriers(&self, written: usize) -> Vec<BufferBarrier<'_>> {
        self.objects
            .iter()
            .filter(|o| !self.is_fused(o))
            .flat_map(|o| {
                [
                    BufferBarrier::new(&o.state[written], Access::ComputeWrite, Access::ComputeReadWrite),
                    BufferBarrier::new(&o.state[1 - written], Access::ComputeRead, Access::ComputeWrite),
                ]
                .into_iter()
                .chain(o.scratch_barriers())
            })
            .collect()
    }

    /// Simulated time so far [s].
    pub fn time(&self) -> f64 {
        self.start + self.frames as f64 * self.model.frame_dt
    }

    pub fn frames(&self) -> u64 {
        self.frames
    }

    pub fn substeps_done(&self) -> u64 {
        self.frames * self.model.substeps as u64
    }

    /// Frees everything after waiting for the last frame.
    pub fn destroy(mut self, ctx: &GpuContext) {
        if self.wait_all(ctx).is_err() {
            let _ = ctx.wait_idle();
        }
        if let Some(c) = self.contact {
            c.destroy(ctx);
        }
        for o in self.objects {
            o.destroy(ctx);
        }
        Parts {
            layout: Some(self.layout),
            batches: Some(self.batches),
            pipelines: Some(self.pipelines),
            arena: Some(self.arena),
            globals: Some(self.globals),
            colliders: Some(self.colliders),
            slots: self.slots,
            timestamps: self.timestamps,
        }
        .destroy(ctx);
    }
}

/// Whether two models have the same mesh colliders (the same shared meshes at the same
/// places among their colliders, so that the collider buffer's triangles serve both).
fn same_meshes(a: &SimModel, b: &SimModel) -> bool {
    use crate::sim::collider::Shape;
    let meshes = |m: &SimModel| -> Vec<(usize, usize)> {
        (m.colliders.iter().enumerate())
            .filter_map(|(i, c)| match c.shape {
                Shape::Mesh { ref mesh, .. } => Some((i, std::sync::Arc::as_ptr(mesh) as usize)),
                _ => None,
            })
            .collect()
    };
    let (ma, mb) = (meshes(a), meshes(b));
    ma == mb && (ma.is_empty() || a.colliders.len() == b.colliders.len())
}
