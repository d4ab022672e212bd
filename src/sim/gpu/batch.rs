//! One dispatch a pass for a chunk of the objects stepped per stage: the physics, prediction,
//! solver and constraint shaders define BATCHED (glsl/include/batch.glsl), where each
//! per-object binding is an array of `chunk` descriptors, one an object, and workgroup z
//! takes object z of the chunk. A pass groups a chunk's objects by pipeline and push words,
//! so objects of one kind and features share a dispatch and its front-end cost, which
//! dominated scenes of many small objects; a mask in the push constants leaves out the
//! chunk's objects that take no part. The device's descriptor limits size the chunk (64
//! objects on a GPU; one on lavapipe, which allows 32 storage buffers a stage, where the
//! shaders run as they would per object).

use super::object::GpuObject;
use super::BINDINGS;
use crate::vk::{
    BindingKind, BindingSet, BindingSetLayout, Buffer, ComputePipeline, DescriptorArena, DeviceInfo,
    GpuContext, Recorder, VkError,
};

/// Objects a chunk holds at most (the push constants' mask has a bit for each).
const MAX_CHUNK: u32 = 64;
/// Bindings the scene's objects share (the globals, colliders and contact between objects'
/// tables: one descriptor each); the others are per object.
const SHARED_BINDINGS: [usize; 4] = [0, 4, 18, 19];

/// Objects in a chunk on `device`: as many as its storage buffer descriptors allow a stage.
pub(super) fn chunk_size(device: &DeviceInfo) -> u32 {
    let per_object = BINDINGS - SHARED_BINDINGS.len() as u32;
    let shared_storage = SHARED_BINDINGS.len() as u32 - 1;
    (device.max_stage_storage_buffers.saturating_sub(shared_storage) / per_object).clamp(1, MAX_CHUNK)
}

/// The descriptor count of each binding of a chunk's set.
pub(super) fn counts(chunk: u32) -> Vec<u32> {
    (0..BINDINGS as usize).map(|b| if SHARED_BINDINGS.contains(&b) { 1 } else { chunk }).collect()
}

/// The batched pipelines' binding set layout, and each chunk's sets in both directions.
pub(super) struct Batches {
    pub layout: BindingSetLayout,
    pub chunk: u32,
    /// [chunk][direction]
    sets: Vec<[BindingSet; 2]>,
}

impl Batches {
    pub(super) fn new_layout(ctx: &GpuContext, kinds: &[BindingKind]) -> Result<Self, VkError> {
        let chunk = chunk_size(ctx.info());
        let layout = BindingSetLayout::with_counts(ctx, kinds, &counts(chunk))?;
        Ok(Self { layout, chunk, sets: Vec::new() })
    }

    /// Chunks of `objects` objects.
    pub(super) fn chunks(&self, objects: usize) -> u32 {
        (objects as u32).div_ceil(self.chunk)
    }

    /// Allocates the chunks' sets: element k of a per-object binding is the chunk's object k
    /// (past the last, its first again).
    pub(super) fn allocate(
        &mut self,
        ctx: &GpuContext,
        arena: &mut DescriptorArena,
        shared: [&Buffer; 2],
        objects: &[GpuObject],
    ) -> Result<(), VkError> {
        for members in objects.chunks(self.chunk as usize) {
            let mut sets = [BindingSet::default(); 2];
            for (direction, set) in sets.iter_mut().enumerate() {
                let each: Vec<_> = members.iter().map(|o| o.bindings(shared, direction)).collect();
                *set = self.chunk_set(ctx, arena, &each)?;
            }
            self.sets.push(sets);
        }
        Ok(())
    }

    /// A chunk's set of the batched layout: element k of a per-object binding is `each[k]`'s
    /// (past the last, the first's); a shared binding is the first's.
    pub(super) fn chunk_set(
        &self,
        ctx: &GpuContext,
        arena: &mut DescriptorArena,
        each: &[[&Buffer; BINDINGS as usize]],
    ) -> Result<BindingSet, VkError> {
        let arrays: Vec<Vec<&Buffer>> = (0..BINDINGS as usize)
            .map(|b| match SHARED_BINDINGS.contains(&b) {
                true => vec![each[0][b]],
                false => (0..self.chunk as usize).map(|k| each.get(k).unwrap_or(&each[0])[b]).collect(),
            })
            .collect();
        arena.allocate_arrays(ctx, &self.layout, &arrays)
    }

    pub(super) fn destroy(self, ctx: &GpuContext) {
        self.layout.destroy(ctx);
    }
}

/// The dispatches of one pass, gathered per object and recorded grouped.
pub(super) struct Pass<'a> {
    items: Vec<Item<'a>>,
}

struct Item<'a> {
    object: usize,
    pipeline: &'a ComputePipeline,
    /// Workgroups along x and y (z is the object).
    groups: [u32; 2],
    push: [u32; 4],
}

impl<'a> Pass<'a> {
    pub(super) fn new() -> Self {
        Self { items: Vec::new() }
    }

    /// Object `object` (its index in the simulation) takes part with `pipeline` over `groups`
    /// workgroups, with its own push words.
    pub(super) fn add(
        &mut self,
        object: usize,
        pipeline: &'a ComputePipeline,
        groups: [u32; 3],
        push: &[u32],
    ) {
        debug_assert_eq!(groups[2], 1, "workgroup z is the object");
        let mut words = [0; 4];
        words[..push.len()].copy_from_slice(push);
        self.items.push(Item { object, pipeline, groups: [groups[0], groups[1]], push: words });
    }

    /// Records the pass in `direction` (0: A -> B): one dispatch per chunk, pipeline and push
    /// words, as many workgroups as its largest object and a layer for each of the chunk's
    /// objects up to the last taking part.
    pub(super) fn record(self, rec: &mut Recorder<'_>, batches: &Batches, direction: usize) {
        self.record_in(rec, batches.chunk, &|chunk| batches.sets[chunk][direction]);
    }

    /// Records the pass with chunks of `chunk` objects, chunk c's dispatches in set `set(c)`.
    pub(super) fn record_in(self, rec: &mut Recorder<'_>, chunk: u32, set: &dyn Fn(usize) -> BindingSet) {
        let size = chunk as usize;
        let mut done = vec![false; self.items.len()];
        for (i, first) in self.items.iter().enumerate() {
            if done[i] {
                continue;
            }
            let chunk = first.object / size;
            let (mut groups, mut mask) = ([0u32; 2], 0u64);
            for (j, other) in self.items.iter().enumerate().skip(i) {
                let same = other.object / size == chunk
                    && std::ptr::eq(other.pipeline, first.pipeline)
                    && other.push == first.push;
                if same && !done[j] {
                    done[j] = true;
                    groups = [groups[0].max(other.groups[0]), groups[1].max(other.groups[1])];
                    mask |= 1 << (other.object % size);
                }
            }
            let layers = 64 - mask.leading_zeros();
            let p = first.push;
            let push = [p[0], p[1], p[2], p[3], mask as u32, (mask >> 32) as u32];
            rec.dispatch_with(first.pipeline, set(chunk), [groups[0], groups[1], layers], &push);
        }
    }
}
