//! Contact between objects on the GPU: contact lists over every object's particles. Each
//! substep after all physics, `contact_begin.comp` (per object) writes the scene's entries
//! and notes whether the lists still hold; where they do not, one spatial hash over the
//! scene is built (`contact_hash.comp`'s count, the shared hash scan, its scatter: indirect
//! dispatches, of no workgroups while the lists hold) and `contact.comp` searches it and
//! lists each particle's pieces within the reach plus the skin, else walks the lists, into
//! the objects' contact sums, which their constraint stages read.
//! `glsl/include/contact_common.glsl` has the bindings and the lists' rule; the CPU twin is
//! `sim::cpu::inter_object`.

use super::batch::{Batches, Pass};
use super::hash::ListPolicy;
use super::object::{GpuObject, SCAN_BLOCK};
use super::pipelines::{Pipelines, Stage};
use super::BINDINGS;
use crate::error::UserError;
use crate::sim::gpu_types::ObjectParams;
use crate::sim::model::{ObjectModel, SimModel};
use crate::vk::{
    Access, BindingSet, BindingSetLayout, Buffer, BufferBarrier, BufferUsage, DescriptorArena, GpuContext,
    MemoryKind, Recorder, VkError,
};

/// The scene's contact hash: its buffers and the binding sets of its passes.
pub(super) struct SceneContact {
    /// `ObjectParams` with the table's `hash_mask` and `cell_inv`, the lists' skin in
    /// `self_distance` and the cell's 1 / edge with the lists off (no skin) in `margin`
    /// (binding 12; binding 1 of the scan's set).
    table: Buffer,
    /// Per object three rows (contact_common.glsl): first scene index, particle count, contact
    /// radius, mass; grid columns and rows where its triangles take part, whether it keeps its
    /// edges from edges, its corner reach; its friction, first work item and lanes.
    objects: Buffer,
    /// Per scene particle: its contacts' summed moves, in fixed point (binding 17).
    moves: Buffer,
    cell_rank: Buffer,
    pub counts: Buffer,
    starts: Buffer,
    sorted: Buffer,
    /// The same entries by scene index, then each particle's star box's lower and upper
    /// corners (binding 16; `star_box` in contact_common.glsl).
    particles: Buffer,
    /// Where each scene particle began the substep (binding 11; friction).
    begun: Buffer,
    block_sums: Buffer,
    /// Per scene particle: how many contacts with other objects it takes part in (binding 3),
    /// and its list, `PAIR_MAX` entries (binding 5).
    touches: Buffer,
    pairs: Buffer,
    /// Per scene particle: where the lists were built and its list's length (binding 18).
    built: Buffer,
    /// The substeps' control blocks (binding 19; `CONTROL_WORDS` each, two), then the
    /// counters, which each frame copies to `report` (host-visible) for `policy`.
    control: Buffer,
    report: Buffer,
    /// Whether the lists are on: off while most substeps rebuild them, which then cost more
    /// than a search without a skin (`ListPolicy`, as the per-stage self-contact lists).
    pub(super) policy: ListPolicy,
    /// Work items of contact.comp's passes over the scene: the cloths' from `work[0]` to
    /// `work[1]`, the ropes' from there to `work[2]`.
    work: [u32; 3],
    /// Whether some two cloths keep their edges apart (contact.comp's CLOTH_EDGES).
    cloth_edges: bool,
    /// Entries of a particle's list (`pair_max`).
    pair_max: u32,
    /// The scan's set; the first object's set, which the hash's passes use; each chunk's
    /// set of the batched layout (`batch.rs`), for contact_begin.comp and contact.comp: an
    /// object's own buffers at 1, 2, 14 and its state at the substep's start at 15.
    scan_set: BindingSet,
    hash_set: BindingSet,
    chunk_sets: Vec<BindingSet>,
    /// Objects a chunk set holds.
    chunk: u32,
}

/// Entries of a particle's list (`PAIR_MAX` in contact.comp, `pair_max`). A longer list
/// overflows: the substep searches the hash again for its moves and the next rebuilds the
/// lists. Piles list dozens a particle between layers (docs/PERFORMANCE.md, "Contact notes,
/// and whose particle it is").
const PAIR_MAX: u64 = 64;
/// Where cloths keep their edges apart: a particle in a pile lists well over 64 pairs of
/// edges, and lists that overflow every substep cost more than none (docs/PERFORMANCE.md,
/// "Contact lists between objects").
const EDGE_PAIR_MAX: u64 = 256;

/// Entries of a particle's list in the scene of `model`.
pub(super) fn pair_max(model: &SimModel) -> u64 {
    if model.has_cloth_edges_between() {
        EDGE_PAIR_MAX
    } else {
        PAIR_MAX
    }
}

/// Words of a substep's control block (`CONTROL_WORDS` in contact_common.glsl), and where its
/// indirect dispatches are: contact_hash.comp's passes, the scan's.
const CONTROL_WORDS: u64 = 8;
const CONTROL_HASH: u64 = 1;
const CONTROL_SCAN: u64 = 4;
/// After the two blocks: substeps run with the lists on, and those that rebuilt them
/// (`CONTROL_COUNTERS`).
const CONTROL_COUNTERS: u64 = 2 * CONTROL_WORDS;
/// The pass word's bit that turns the lists off (`LISTS_OFF` in contact_common.glsl).
const LISTS_OFF: u32 = 32;
/// The lists go off for a while when more than this share of a frame's substeps rebuilt them:
/// a substep that walks them costs a fraction of one that searches, one that rebuilds them a
/// little more (its search reaches the skin further), so they pay while they last in most
/// substeps; where they overflow (dense piles) or everything moves half the skin a substep,
/// they do not (docs/PERFORMANCE.md, "Contact lists between objects").
const LISTS_OFF_SHARE: [u64; 2] = [3, 4];

/// Particles a scene with contact between objects may hold: contact.comp notes a particle's
/// scene index in 25 bits (NOTE_SHIFT).
const MAX_SCENE_PARTICLES: u64 = 1 << 25;

/// Refuses a scene whose objects touch each other and hold more particles than contact.comp
/// can index, or than the device can bind one buffer for (the notes, `PAIR_MAX` a particle,
/// are the largest; `max_buffer` is the device's largest storage buffer range).
pub(super) fn check_scene(model: &SimModel, max_buffer: u64) -> Result<(), UserError> {
    let total: u64 = model.objects.iter().map(|o| o.particle_count() as u64).sum();
    if !model.inter_object_contact() {
        return Ok(());
    }
    let most = MAX_SCENE_PARTICLES.min(max_buffer / (4 * pair_max(model)));
    if total > most {
        return Err(UserError(format!(
            "the scene has {total} particles: contact between objects handles at most {most} on this device (set sim.inter_object = false, or use fewer particles)"
        )));
    }
    Ok(())
}

/// Binding sets `SceneContact::new` allocates: of the step layout (the hash's and the
/// scan's), and of the batched layout (one a chunk of `chunk` objects).
pub(super) fn sets_needed(model: &SimModel, chunk: u32) -> (u32, u32) {
    if model.inter_object_contact() {
        (2, (model.objects.len() as u32).div_ceil(chunk))
    } else {
        (0, 0)
    }
}

/// The work items of contact.comp's passes 0 and 1 (`work_first` and `lanes_of` there): each
/// object's particles in `SimModel::contact_lanes` items, the cloths' first and then the
/// ropes' (a second dispatch, with the segment tests compiled in), each object's from a
/// multiple of its lanes (a node's lanes in whole subgroups). An object whose particles look
/// for nothing (a cloth with only ropes around: their segments find its vertices) has none.
/// One lane each where lanes would need more workgroups than one dispatch allows, and on a CPU
/// driver, whose lanes run one after another: there each lane's walk of the node's 8 buckets
/// costs what the node's whole search costs alone (lavapipe, the playground's rope: 64 lanes
/// 716 ms a frame at 32 substeps, 8 lanes 250, one 190; docs/log.md).
struct WorkLayout {
    first: Vec<u32>,
    lanes: Vec<u32>,
    /// The cloths' items from `bounds[0]` (0), the ropes' from `bounds[1]` to `bounds[2]`.
    bounds: [u32; 3],
}

impl WorkLayout {
    fn new(model: &SimModel, particles: &[u32], max_groups: u64, in_lanes: bool) -> Self {
        let layout = |lanes: &dyn Fn(usize) -> u32| {
            let mut first = vec![0u32; particles.len()];
            let mut lane_counts = vec![0u32; particles.len()];
            let mut bounds = [0u64; 3];
            let mut work = 0u64;
            for (side, ropes) in [false, true].into_iter().enumerate() {
                for (q, o) in model.objects.iter().enumerate() {
                    if o.contact_triangles() == ropes {
                        continue;
                    }
                    // Its particles look for another cloth's triangles, or it is a rope.
                    let looks = ropes
                        || model
                            .objects
                            .iter()
                            .enumerate()
                            .any(|(p, other)| p != q && other.contact_triangles());
                    let l = if looks { lanes(q) } else { 0 };
                    if l > 0 {
                        work = work.div_ceil(l as u64) * l as u64;
                    }
                    first[q] = work as u32;
                    lane_counts[q] = l;
                    work += particles[q] as u64 * l as u64;
                }
                bounds[side + 1] = work;
            }
            (first, lane_counts, bounds)
        };
        let fits = |b: [u64; 3]| (b[1] - b[0]).div_ceil(256).max((b[2] - b[1]).div_ceil(256)) <= max_groups;
        let (mut first, mut lanes, mut bounds) = layout(&|q| model.contact_lanes(q));
        if !in_lanes || !fits(bounds) {
            (first, lanes, bounds) = layout(&|_| 1);
        }
        Self { first, lanes, bounds: bounds.map(|b| b as u32) }
    }
}

/// Whether a rope node's search is split among lanes by default on the device of `ctx`: on a
/// GPU, not on a CPU driver (`WorkLayout`).
fn in_lanes(ctx: &GpuContext) -> bool {
    ctx.info().kind != crate::vk::DeviceKind::Cpu
}

impl super::GpuSim {
    /// Splits each rope node's search for contacts between objects among lanes, as on a GPU
    /// (`true`), or gives it one lane (as on a CPU driver), whatever the device's default; for
    /// tests, so that a CPU driver runs the GPUs' layout too. Waits for the frames in flight.
    pub fn set_contact_lanes(&mut self, ctx: &GpuContext, lanes: bool) -> anyhow::Result<()> {
        let Some(contact) = self.contact.as_mut() else { return Ok(()) };
        ctx.wait_idle()?;
        Ok(contact.set_lanes(ctx, &self.model, &self.objects, lanes)?)
    }

    /// The contact lists between objects' counters since the state or the parameters last
    /// changed from outside: rounds run with the lists on (a round a substep, or one an
    /// iteration: `SimModel::contact_rounds`), and those that rebuilt them;
    /// `None` without contact between objects. Waits for the frames in flight.
    pub fn contact_list_counters(&mut self, ctx: &GpuContext) -> anyhow::Result<Option<[u32; 2]>> {
        self.wait_all(ctx)?;
        Ok(self.contact.as_ref().map(|c| c.counters()).transpose()?)
    }
}

impl SceneContact {
    /// The scene's hash for `model`'s objects (`gpu`, in order), or `None` when the objects do
    /// not touch each other. Cells are `SimModel::contact_cell`, so a query finds everything a
    /// contact needs in the 2 x 2 x 2 block of cells nearest to it.
    pub fn new(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        batches: &Batches,
        arena: &mut DescriptorArena,
        shared: [&Buffer; 2],
        model: &SimModel,
        gpu: &[GpuObject],
    ) -> Result<Option<Self>, VkError> {
        if !model.inter_object_contact() {
            return Ok(None);
        }
        let total: u64 = gpu.iter().map(|o| o.particles as u64).sum();
        let buckets = super::object::hash_table_size(total);
        let cell = model.contact_cell();
        let mut table_params: ObjectParams = bytemuck::Zeroable::zeroed();
        table_params.hash_mask = buckets as u32 - 1;
        table_params.cell_inv = (1.0 / cell) as f32;
        table_params.self_distance = model.contact_skin() as f32;
        table_params.margin = (1.0 / model.contact_cell_without_skin()) as f32;
        let (work, rows) = Self::rows(ctx, model, gpu, in_lanes(ctx));
        let (storage, gpu_only) = (BufferUsage::STORAGE, MemoryKind::GpuOnly);
        let transfer = BufferUsage::TRANSFER_SRC | BufferUsage::TRANSFER_DST;
        let specs = [
            ("table", std::mem::size_of::<ObjectParams>() as u64, storage, MemoryKind::Upload),
            ("objects", 16 * rows.len() as u64, storage, MemoryKind::Upload),
            ("moves", 16 * total, storage, gpu_only),
            ("cell_rank", 8 * total, storage, gpu_only),
            ("counts", 4 * (buckets + 1), storage | BufferUsage::TRANSFER_DST, gpu_only),
            ("starts", 4 * (buckets + 1), storage, gpu_only),
            ("sorted", 16 * total, storage, gpu_only),
            ("particles", 3 * 16 * total, storage, gpu_only),
            ("begun", 16 * total, storage, gpu_only),
            ("block_sums", 4 * buckets.div_ceil(SCAN_BLOCK), storage, gpu_only),
            ("touches", 4 * total, storage, gpu_only),
            ("pairs", 4 * pair_max(model) * total, storage, gpu_only),
            ("built", 16 * total, storage | BufferUsage::TRANSFER_DST, gpu_only),
            ("control", 4 * (CONTROL_COUNTERS + 2), storage | transfer | BufferUsage::INDIRECT, gpu_only),
            ("report", 8, BufferUsage::TRANSFER_DST, MemoryKind::Readback),
        ];
        let [table, objects, moves, cell_rank, counts, starts, sorted, particles, begun, block_sums, touches, pairs, built, control, report] =
            super::object::buffers(ctx, "contact", specs)?;
        let mut contact = Self {
            table,
            objects,
            moves,
            cell_rank,
            counts,
            starts,
            sorted,
            particles,
            begun,
            block_sums,
            touches,
            pairs,
            built,
            control,
            report,
            policy: ListPolicy::default(),
            work,
            cloth_edges: model.has_cloth_edges_between(),
            pair_max: pair_max(model) as u32,
            scan_set: BindingSet::default(),
            hash_set: BindingSet::default(),
            chunk_sets: Vec::new(),
            chunk: batches.chunk,
        };
        let result = (|| -> Result<(), VkError> {
            contact.table.write(0, &[table_params])?;
            contact.objects.write(0, &rows)?;
            let [globals, colliders] = shared;
            let c = &contact;
            let mut each = Vec::new();
            for o in gpu {
                let p = &o.placeholder;
                let touch = o.contact.as_ref().unwrap_or(p);
                let bindings = [
                    globals,
                    &o.params,
                    &o.state[1],
                    &c.touches,
                    colliders,
                    &c.pairs,
                    &c.cell_rank,
                    &c.counts,
                    &c.starts,
                    &c.sorted,
                    &c.block_sums,
                    &c.begun,
                    &c.table,
                    &c.objects,
                    touch,
                    &o.state[0],
                    &c.particles,
                    &c.moves,
                    &c.built,
                    &c.control,
                ];
                debug_assert_eq!(bindings.len() as u32, BINDINGS);
                each.push(bindings);
            }
            let hash_set = arena.allocate(ctx, layout, &each[0])?;
            let chunk_sets = (each.chunks(batches.chunk as usize))
                .map(|members| batches.chunk_set(ctx, arena, members))
                .collect::<Result<Vec<_>, _>>()?;
            let p = &gpu[0].placeholder;
            let bindings = [
                globals,
                &c.table,
                p,
                p,
                colliders,
                p,
                p,
                &c.counts,
                &c.starts,
                p,
                &c.block_sums,
                p,
                p,
                p,
                p,
                p,
                p,
                p,
                p,
                p,
            ];
            debug_assert_eq!(bindings.len() as u32, BINDINGS);
            let scan_set = arena.allocate(ctx, layout, &bindings)?;
            contact.hash_set = hash_set;
            contact.chunk_sets = chunk_sets;
            contact.scan_set = scan_set;
            Ok(())
        })();
        match result {
            Ok(()) => Ok(Some(contact)),
            Err(e) => {
                contact.destroy(ctx);
                Err(e)
            }
        }
    }

    /// contact.comp's rows of each object (where its particles begin in the scene, its grid,
    /// columns 0 when it touches by its segments, radius, mass, whether it keeps its edges from
    /// edges, corner reach, friction and work items) and the bounds of its passes' work items,
    /// each rope node's search split among lanes or not (`lanes`, `WorkLayout`).
    fn rows(ctx: &GpuContext, model: &SimModel, gpu: &[GpuObject], lanes: bool) -> ([u32; 3], Vec<[f32; 4]>) {
        let particles: Vec<u32> = gpu.iter().map(|g| g.particles).collect();
        let work = WorkLayout::new(model, &particles, ctx.info().max_workgroup_count[0] as u64, lanes);
        let mut first = 0u32;
        let bits = f32::from_bits;
        // (row 1's z: it keeps its edges from every other cloth's, `keeps_cloth_edges_apart`)
        let edges_apart = |o: &ObjectModel| o.edge_contact || model.inter_object_edges;
        let rows = (model.objects.iter().zip(gpu).enumerate())
            .flat_map(|(q, (o, g))| {
                let grid = if o.contact_triangles() { o.dims } else { [0, 0] };
                let rows = [
                    [bits(first), bits(g.particles), o.contact_radius() as f32, o.mass as f32],
                    [bits(grid[0]), bits(grid[1]), edges_apart(o) as u32 as f32, o.corner_reach() as f32],
                    [o.friction as f32, bits(work.first[q]), bits(work.lanes[q]), 0.0],
                ];
                first += g.particles;
                rows
            })
            .collect();
        (work.bounds, rows)
    }

    /// Splits a particle's search among lanes (`SimModel::contact_lanes`) or not, whatever
    /// the device's default (`in_lanes`); no frame may be in flight.
    fn set_lanes(
        &mut self,
        ctx: &GpuContext,
        model: &SimModel,
        gpu: &[GpuObject],
        lanes: bool,
    ) -> Result<(), VkError> {
        let (work, rows) = Self::rows(ctx, model, gpu, lanes);
        self.objects.write(0, &rows)?;
        self.work = work;
        Ok(())
    }

    /// Zeroes the control blocks when a frame starts (each substep's last pass zeroes the
    /// next one's; this also starts a frame after one of an odd number of substeps at the right
    /// parity), and with `stale` (the state or the parameters changed outside the shaders)
    /// makes every list invalid: built at infinity, so the first substep rebuilds them (and
    /// zeroes the counters).
    pub fn record_frame_start(&self, rec: &mut Recorder<'_>, stale: bool) {
        // (stale, the counters too: they count from the last change)
        let mut buffers =
            vec![(&self.control, if stale { self.control.size() } else { 4 * CONTROL_COUNTERS }, 0)];
        if stale {
            buffers.push((&self.built, self.built.size(), super::transfer::LISTS_INVALID));
        }
        let around =
            |src, dst| buffers.iter().map(|(b, ..)| BufferBarrier::new(b, src, dst)).collect::<Vec<_>>();
        rec.barrier(&around(Access::ComputeOrIndirect, Access::TransferWrite));
        for (b, bytes, word) in &buffers {
            rec.fill_range(b, 0, *bytes, *word);
        }
        rec.barrier(&around(Access::TransferWrite, Access::ComputeOrIndirect));
    }

    /// contact.comp's pipeline for the ropes' items (`segments`), or the cloths' items and the
    /// objects' sums.
    fn stage(&self, segments: bool) -> Stage {
        Stage::Contact { segments, cloth_edges: self.cloth_edges && !segments, pair_max: self.pair_max }
    }

    /// Copies the counters to `report` at the end of a frame.
    pub fn record_frame_end(&self, rec: &mut Recorder<'_>) {
        rec.barrier(&[BufferBarrier::new(&self.control, Access::ComputeOrIndirect, Access::TransferRead)]);
        rec.copy_buffer_region(&self.control, 4 * CONTROL_COUNTERS, &self.report, 0, 8);
        rec.barrier(&[
            BufferBarrier::new(&self.control, Access::TransferRead, Access::ComputeOrIndirect),
            BufferBarrier::new(&self.report, Access::TransferWrite, Access::HostRead),
        ]);
    }

    /// The counters as the last finished frame left them (substeps run with the lists on, and
    /// rebuilt).
    fn counters(&self) -> Result<[u32; 2], VkError> {
        let words = self.report.read::<u32>(2)?;
        Ok([words[0], words[1]])
    }

    /// After the fence of the last recorded frame: the policy takes the counters.
    pub fn observe(&mut self, substeps: u32) -> Result<(), VkError> {
        if self.policy.on() {
            let counters = self.counters()?;
            self.policy.observe_share(counters, substeps, LISTS_OFF_SHARE);
        }
        Ok(())
    }

    /// Records a round of contacts (`round` counts them through the frame: a substep's, or
    /// one an iteration with `SimModel::contact_rounds`) after every object's physics or
    /// iteration (its output ordered for reading) and before the constraints or the next
    /// iteration: each object's entries (which also clear the
    /// contact counts and moves, and note whether the lists hold), the hash's count, scan and
    /// scatter (indirect: no workgroups while the lists hold), then contact.comp's passes: the
    /// counts and the moves over the scene's particles, then each object's sums. Each is
    /// ordered after the one before by barriers on exactly the buffers it uses; the contact
    /// sums are ordered for the constraint stage at the end.
    pub fn record(&self, rec: &mut Recorder<'_>, pipelines: &Pipelines, objects: &[GpuObject], round: u32) {
        let b = BufferBarrier::new;
        // (the push constants' pass word: the round's parity, and LISTS_OFF)
        let parity = (round & 1) << 4 | if self.policy.on() { 0 } else { LISTS_OFF };
        // A chunk of objects a dispatch, each its particles (the push constants' first word is
        // the chunk's first object).
        let each_object = |rec: &mut Recorder<'_>, stage: Stage, pass: u32| {
            let mut batch = Pass::new();
            for (k, o) in objects.iter().enumerate() {
                let first = k as u32 / self.chunk * self.chunk;
                batch.add(
                    k,
                    pipelines.get(stage),
                    [o.particles.div_ceil(256), 1, 1],
                    &[first, pass | parity],
                );
            }
            batch.record_in(rec, self.chunk, &|c| self.chunk_sets[c]);
        };
        // Over the scene's work items, the cloths' then the ropes', as the first chunk's layer 0
        // (any set holds the scene's buffers).
        let scene = |rec: &mut Recorder<'_>, pass: u32| {
            for (segments, range) in [(false, &self.work[0..2]), (true, &self.work[1..3])] {
                let items = range[1] - range[0];
                if items > 0 {
                    let groups = [items.div_ceil(256), 1, 1];
                    let push = [0, pass | parity, range[0], range[1], 1, 0];
                    rec.dispatch_with(pipelines.get(self.stage(segments)), self.chunk_sets[0], groups, &push);
                }
            }
        };
        // This round's control block and its indirect dispatches.
        let block = (round & 1) as u64 * CONTROL_WORDS;
        let indirect = |rec: &mut Recorder<'_>, stage: Stage, set: BindingSet, word: u64, pass: u32| {
            rec.dispatch_indirect(
                pipelines.get(stage),
                set,
                &self.control,
                4 * (block + word),
                &[0, pass | parity],
            );
        };
        // The last substep's passes used the entries, contact counts and moves that the first
        // pass rewrites, and the lists and control blocks it reads.
        rec.barrier(&[
            b(&self.particles, Access::ComputeRead, Access::ComputeWrite),
            b(&self.begun, Access::ComputeRead, Access::ComputeWrite),
            b(&self.touches, Access::ComputeReadWrite, Access::ComputeWrite),
            b(&self.moves, Access::ComputeReadWrite, Access::ComputeWrite),
            b(&self.built, Access::ComputeReadWrite, Access::ComputeRead),
            b(&self.control, Access::ComputeOrIndirect, Access::ComputeOrIndirect),
        ]);
        each_object(rec, Stage::ContactBegin, 0);
        // The count reads the entries and the dispatches; the last scan zeroed the counts.
        // (Its shader also holds the scatter's stores: each of its passes is ordered as
        // writing the hash's slots too.)
        rec.barrier(&[
            b(&self.control, Access::ComputeOrIndirect, Access::ComputeOrIndirect),
            b(&self.particles, Access::ComputeWrite, Access::ComputeRead),
            b(&self.counts, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.cell_rank, Access::ComputeRead, Access::ComputeWrite),
            b(&self.built, Access::ComputeRead, Access::ComputeWrite),
            b(&self.sorted, Access::ComputeRead, Access::ComputeWrite),
        ]);
        indirect(rec, Stage::ContactHash, self.hash_set, CONTROL_HASH, 0);
        // The scan reads the counts and rewrites the starts the last search read.
        rec.barrier(&[
            b(&self.counts, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.cell_rank, Access::ComputeWrite, Access::ComputeRead),
            b(&self.starts, Access::ComputeRead, Access::ComputeWrite),
            b(&self.block_sums, Access::ComputeRead, Access::ComputeReadWrite),
        ]);
        indirect(rec, Stage::HashScan, self.scan_set, CONTROL_SCAN, 0);
        rec.barrier(&[
            b(&self.starts, Access::ComputeWrite, Access::ComputeRead),
            b(&self.block_sums, Access::ComputeWrite, Access::ComputeRead),
            b(&self.sorted, Access::ComputeWrite, Access::ComputeWrite),
            b(&self.built, Access::ComputeWrite, Access::ComputeWrite),
            b(&self.counts, Access::ComputeWrite, Access::ComputeReadWrite),
        ]);
        indirect(rec, Stage::ContactHash, self.hash_set, CONTROL_HASH, 1);
        rec.barrier(&[
            b(&self.sorted, Access::ComputeWrite, Access::ComputeRead),
            b(&self.begun, Access::ComputeWrite, Access::ComputeRead),
            b(&self.built, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.touches, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.moves, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.pairs, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.control, Access::ComputeOrIndirect, Access::ComputeOrIndirect),
        ]);
        // contact.comp's passes share one shader, which uses the counts, moves, lists, where
        // they were built and the control blocks with atomics or writes: each pass is ordered
        // as reading and writing all five.
        let between = [
            b(&self.touches, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.moves, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.pairs, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.built, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.control, Access::ComputeOrIndirect, Access::ComputeOrIndirect),
        ];
        scene(rec, 0);
        rec.barrier(&between);
        scene(rec, 1);
        let sums: Vec<_> = objects.iter().filter_map(|o| o.contact.as_ref()).collect();
        let mut before: Vec<_> =
            sums.iter().map(|c| b(c, Access::ComputeRead, Access::ComputeWrite)).collect();
        before.extend(between);
        rec.barrier(&before);
        // (it also zeroes the next substep's control block)
        each_object(rec, self.stage(false), 2);
        // The constraint stage reads the sums and writes the states the entries were read from.
        let mut after: Vec<_> =
            sums.iter().map(|c| b(c, Access::ComputeWrite, Access::ComputeRead)).collect();
        after.extend(objects.iter().map(|o| b(&o.state[0], Access::ComputeRead, Access::ComputeReadWrite)));
        rec.barrier(&after);
    }

    pub fn destroy(self, ctx: &GpuContext) {
        for buffer in [
            self.table,
            self.objects,
            self.moves,
            self.cell_rank,
            self.counts,
            self.starts,
            self.sorted,
            self.particles,
            self.begun,
            self.block_sums,
            self.touches,
            self.pairs,
            self.built,
            self.control,
            self.report,
        ] {
            buffer.destroy(ctx);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{check_scene, WorkLayout};
    use crate::sim::model::{SimModel, CLOTH_EDGE_LANES, CONTACT_LANES};

    fn rope_on_cloth() -> SimModel {
        let path = std::path::Path::new("presets/rope_on_cloth.toml");
        crate::scene::to_model(&crate::scene::load(path, &[]).expect("the preset loads"))
    }

    /// The cloths' items first (one each, or lanes each where cloths keep their edges apart),
    /// then a rope node's lanes from a multiple of the lanes; a cloth with only ropes around
    /// has none; one lane each when the lanes would need
    /// more workgroups than one dispatch allows or on a CPU driver.
    #[test]
    fn work_items_put_the_cloths_first_and_a_searching_particle_in_lanes() {
        let model = rope_on_cloth();
        let w = WorkLayout::new(&model, &[900, 21], u64::MAX, true);
        assert_eq!(
            (w.lanes.as_slice(), w.bounds),
            ([0, CONTACT_LANES].as_slice(), [0, 0, 21 * CONTACT_LANES])
        );

        // The rope first, then two cloths (which now look for each other's triangles), their
        // edges not kept apart.
        let mut model = rope_on_cloth();
        let (cloth, rope) = (model.objects[0].clone(), model.objects[1].clone());
        model.objects = vec![rope, cloth.clone(), cloth];
        model.inter_object_edges = false;
        let w = WorkLayout::new(&model, &[21, 900, 900], u64::MAX, true);
        let rope_first = 1800u32.div_ceil(CONTACT_LANES) * CONTACT_LANES;
        assert_eq!(w.first, [rope_first, 0, 900]);
        assert_eq!(w.lanes, [CONTACT_LANES, 1, 1]);
        assert_eq!(w.bounds, [0, 1800, rope_first + 21 * CONTACT_LANES]);

        // Where the cloths keep their edges apart (by default, or as one of them asks), each
        // cloth particle in its lanes too.
        model.objects[1].edge_contact = true;
        let w = WorkLayout::new(&model, &[21, 900, 900], u64::MAX, true);
        assert_eq!(w.lanes, [CONTACT_LANES, CLOTH_EDGE_LANES, CLOTH_EDGE_LANES]);
        model.objects[1].edge_contact = false;
        model.inter_object_edges = true;
        let w = WorkLayout::new(&model, &[21, 900, 900], u64::MAX, true);
        let rope_first = (1800 * CLOTH_EDGE_LANES).div_ceil(CONTACT_LANES) * CONTACT_LANES;
        assert_eq!(w.first, [rope_first, 0, 900 * CLOTH_EDGE_LANES]);
        assert_eq!(w.lanes, [CONTACT_LANES, CLOTH_EDGE_LANES, CLOTH_EDGE_LANES]);

        // The rope's 21 x 64 items need 6 groups of 256: with at most 2, one lane each.
        let w = WorkLayout::new(&rope_on_cloth(), &[900, 21], 2, true);
        assert_eq!((w.lanes.as_slice(), w.bounds), ([0, 1].as_slice(), [0, 0, 21]));
        // ... and where lanes are not asked for (a CPU driver).
        let w = WorkLayout::new(&rope_on_cloth(), &[900, 21], u64::MAX, false);
        assert_eq!((w.lanes.as_slice(), w.bounds), ([0, 1].as_slice(), [0, 0, 21]));
    }

    /// A scene larger than contact.comp's notes can index is refused with a clear line; the
    /// same scene with its objects kept apart is not.
    #[test]
    fn a_scene_too_large_for_contact_between_objects_is_refused() {
        let mut model = rope_on_cloth();
        assert!(check_scene(&model, u64::MAX).is_ok());
        model.objects[0].dims = [16384, 16384];
        let error = check_scene(&model, u64::MAX).expect_err("2^28 particles are refused").0;
        assert!(error.contains("contact between objects handles at most 33554432"), "{error}");
        // A device binding at most 128 MiB a buffer (lavapipe's range): 2^19 particles' notes.
        model.objects[0].dims = [1024, 1025];
        let error = check_scene(&model, 1 << 27).expect_err("past the buffer range").0;
        assert!(error.contains("at most 524288 on this device"), "{error}");
        model.inter_object = false;
        assert!(check_scene(&model, u64::MAX).is_ok());
    }
}
