//! Contact between objects on the GPU: one spatial hash over every object's particles, built
//! each substep after all physics (`contact_count.comp` per object, the shared hash scan over
//! the scene's table, `contact_scatter.comp` per object) and queried per object
//! (`contact.comp`) into the object's contact sums, which its constraint stage reads.
//! `glsl/include/contact_common.glsl` has the bindings; the CPU twin is
//! `sim::cpu::inter_object`.

use super::object::{GpuObject, SCAN_BLOCK};
use super::pipelines::{Pipelines, Stage};
use super::BINDINGS;
use crate::sim::gpu_types::ObjectParams;
use crate::sim::model::SimModel;
use crate::vk::{
    Access, BindingSet, BindingSetLayout, Buffer, BufferBarrier, BufferUsage, DescriptorArena, GpuContext,
    MemoryKind, Recorder, VkError,
};

/// The scene's contact hash: its buffers and the binding sets of its passes.
pub(super) struct SceneContact {
    /// `ObjectParams` with the table's `hash_mask` and `cell_inv` (binding 12; binding 1 of
    /// the scan's set).
    table: Buffer,
    /// Per object three rows (contact_common.glsl): first scene index, particle count, contact
    /// radius, mass; grid columns and rows where its triangles take part, whether it looks for
    /// anything, its corner reach; its friction.
    objects: Buffer,
    /// Per scene particle: its contacts' summed moves, in fixed point (binding 17).
    moves: Buffer,
    cell_rank: Buffer,
    pub counts: Buffer,
    starts: Buffer,
    sorted: Buffer,
    /// The same entries by scene index (binding 16).
    particles: Buffer,
    /// Where each scene particle began the substep (binding 11; friction).
    begun: Buffer,
    block_sums: Buffer,
    /// Per scene particle: how many contacts with other objects it takes part in (binding 3),
    /// and the first `PAIR_MAX` contacts it found itself (binding 5).
    touches: Buffer,
    pairs: Buffer,
    /// Particles in the scene.
    total: u32,
    buckets: u32,
    /// The scan's set, and each object's set (the object's own buffers at 1, 2, 14 and its
    /// state at the substep's start at 15).
    scan_set: BindingSet,
    sets: Vec<BindingSet>,
}

/// Partners a particle keeps from the count pass (`PAIR_MAX` in contact.comp).
const PAIR_MAX: u64 = 8;

/// Binding sets `SceneContact::new` allocates for `objects` objects (one each and the scan's).
pub(super) fn sets_needed(model: &SimModel) -> u32 {
    if model.inter_object_contact() {
        model.objects.len() as u32 + 1
    } else {
        0
    }
}

impl SceneContact {
    /// The scene's hash for `model`'s objects (`gpu`, in order), or `None` when the objects do
    /// not touch each other. Cells are `SimModel::contact_cell`, so a query finds everything a
    /// contact needs in the 2 x 2 x 2 block of cells nearest to it.
    pub fn new(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
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
        let mut first = 0u32;
        let rows: Vec<[f32; 4]> = model
            .objects
            .iter()
            .zip(gpu)
            .enumerate()
            .flat_map(|(q, (o, g))| {
                let grid = if o.contact_triangles() { o.dims } else { [0, 0] };
                // Whether its particles look for anything (`looks` in contact.comp): another
                // object's triangles, or, neither being a cloth, another object's particles.
                let mut others = model.objects.iter().enumerate().filter(|&(k, _)| k != q).map(|(_, p)| p);
                let looks = others.any(|p| p.contact_triangles() || !o.contact_triangles()) as u32;
                let bits = f32::from_bits;
                let rows = [
                    [bits(first), bits(g.particles), o.contact_radius() as f32, o.mass as f32],
                    [bits(grid[0]), bits(grid[1]), bits(looks), o.corner_reach() as f32],
                    [o.friction as f32, 0.0, 0.0, 0.0],
                ];
                first += g.particles;
                rows
            })
            .collect();
        let (storage, gpu_only) = (BufferUsage::STORAGE, MemoryKind::GpuOnly);
        let specs = [
            ("table", std::mem::size_of::<ObjectParams>() as u64, storage, MemoryKind::Upload),
            ("objects", 16 * rows.len() as u64, storage, MemoryKind::Upload),
            ("moves", 16 * total, storage, gpu_only),
            ("cell_rank", 8 * total, storage, gpu_only),
            ("counts", 4 * (buckets + 1), storage | BufferUsage::TRANSFER_DST, gpu_only),
            ("starts", 4 * (buckets + 1), storage, gpu_only),
            ("sorted", 16 * total, storage, gpu_only),
            ("particles", 16 * total, storage, gpu_only),
            ("begun", 16 * total, storage, gpu_only),
            ("block_sums", 4 * buckets.div_ceil(SCAN_BLOCK), storage, gpu_only),
            ("touches", 4 * total, storage, gpu_only),
            ("pairs", 4 * PAIR_MAX * total, storage, gpu_only),
        ];
        let [table, objects, moves, cell_rank, counts, starts, sorted, particles, begun, block_sums, touches, pairs] =
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
            total: total as u32,
            buckets: buckets as u32,
            scan_set: BindingSet::default(),
            sets: Vec::new(),
        };
        let result = (|| -> Result<(), VkError> {
            contact.table.write(0, &[table_params])?;
            contact.objects.write(0, &rows)?;
            let [globals, colliders] = shared;
            let c = &contact;
            let mut sets = Vec::new();
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
                ];
                debug_assert_eq!(bindings.len() as u32, BINDINGS);
                sets.push(arena.allocate(ctx, layout, &bindings)?);
            }
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
            ];
            debug_assert_eq!(bindings.len() as u32, BINDINGS);
            let scan_set = arena.allocate(ctx, layout, &bindings)?;
            contact.sets = sets;
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

    /// Records the substep's contacts after every object's physics (its output ordered for
    /// reading) and before the constraints: count (which also clears the contact counts and
    /// moves), scan, scatter, then contact.comp's passes: the counts and the moves over the
    /// scene's particles, then each object's sums. Each is ordered after the one before by
    /// barriers on exactly the buffers it uses; the contact sums are ordered for the
    /// constraint stage at the end.
    pub fn record(&self, rec: &mut Recorder<'_>, pipelines: &Pipelines, objects: &[GpuObject]) {
        let b = BufferBarrier::new;
        let each_object = |rec: &mut Recorder<'_>, stage: Stage, pass: u32| {
            for (k, (o, &set)) in objects.iter().zip(&self.sets).enumerate() {
                let groups = [o.particles.div_ceil(256), 1, 1];
                rec.dispatch_with(pipelines.get(stage), set, groups, &[k as u32, pass]);
            }
        };
        // Over the scene's particles (any object's set holds the scene's buffers).
        let scene = |rec: &mut Recorder<'_>, pass: u32| {
            let groups = [self.total.div_ceil(256), 1, 1];
            rec.dispatch_with(pipelines.get(Stage::Contact), self.sets[0], groups, &[0, pass]);
        };
        // The last scan zeroed the counts; the last substep's passes used the ranks, contact
        // counts and moves that the count pass rewrites.
        rec.barrier(&[
            b(&self.counts, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.cell_rank, Access::ComputeRead, Access::ComputeWrite),
            b(&self.touches, Access::ComputeReadWrite, Access::ComputeWrite),
            b(&self.moves, Access::ComputeReadWrite, Access::ComputeWrite),
        ]);
        each_object(rec, Stage::ContactCount, 0);
        // The scan reads the counts and rewrites the starts the last query read.
        rec.barrier(&[
            b(&self.counts, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.cell_rank, Access::ComputeWrite, Access::ComputeRead),
            b(&self.starts, Access::ComputeRead, Access::ComputeWrite),
            b(&self.block_sums, Access::ComputeRead, Access::ComputeReadWrite),
        ]);
        let blocks = self.buckets.div_ceil(SCAN_BLOCK as u32);
        rec.dispatch(pipelines.get(Stage::HashScan), self.scan_set, [blocks, 1, 1]);
        rec.barrier(&[
            b(&self.starts, Access::ComputeWrite, Access::ComputeRead),
            b(&self.block_sums, Access::ComputeWrite, Access::ComputeRead),
            b(&self.sorted, Access::ComputeRead, Access::ComputeWrite),
            b(&self.particles, Access::ComputeRead, Access::ComputeWrite),
            b(&self.begun, Access::ComputeRead, Access::ComputeWrite),
        ]);
        each_object(rec, Stage::ContactScatter, 0);
        rec.barrier(&[
            b(&self.sorted, Access::ComputeWrite, Access::ComputeRead),
            b(&self.particles, Access::ComputeWrite, Access::ComputeRead),
            b(&self.begun, Access::ComputeWrite, Access::ComputeRead),
            b(&self.touches, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.moves, Access::ComputeWrite, Access::ComputeReadWrite),
            b(&self.pairs, Access::ComputeReadWrite, Access::ComputeReadWrite),
        ]);
        // contact.comp's passes share one shader, which uses the counts, moves and pairs with
        // atomics or writes: each pass is ordered as reading and writing all three.
        let between = [
            b(&self.touches, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.moves, Access::ComputeReadWrite, Access::ComputeReadWrite),
            b(&self.pairs, Access::ComputeReadWrite, Access::ComputeReadWrite),
        ];
        scene(rec, 0);
        rec.barrier(&between);
        scene(rec, 1);
        let sums: Vec<_> = objects.iter().filter_map(|o| o.contact.as_ref()).collect();
        let mut before: Vec<_> =
            sums.iter().map(|c| b(c, Access::ComputeRead, Access::ComputeWrite)).collect();
        before.extend(between);
        rec.barrier(&before);
        each_object(rec, Stage::Contact, 2);
        // The constraint stage reads the sums and writes the states the scatter read.
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
        ] {
            buffer.destroy(ctx);
        }
    }
}
