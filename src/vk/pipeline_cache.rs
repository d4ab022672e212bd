//! The compute pipelines a context has created, kept for reuse: a simulation created again
//! with the same shaders and specialization (`integrator = "auto"` creates one for every
//! setting it tries, the app one on every rebuild, a test one per path) takes the pipelines
//! already compiled instead of compiling them again, which on lavapipe takes seconds for the
//! larger kernels. A Vulkan `VkPipelineCache` would do the same only where the driver fills
//! it (lavapipe's of Mesa 22.3 keeps nothing).

use super::pipeline::BindingKind;
use ash::vk;
use std::collections::HashMap;
use std::sync::Arc;

/// What makes two compute pipelines the same: their SPIR-V, their specialization constants and
/// the kinds of their binding set (the pipeline layout is made from those alone).
#[derive(Clone, PartialEq, Eq, Hash)]
pub(crate) struct PipelineKey {
    pub spirv: Arc<[u32]>,
    pub specialization: Vec<(u32, u32)>,
    pub kinds: Vec<BindingKind>,
    /// ... and their descriptor counts.
    pub counts: Vec<u32>,
}

/// A pipeline with the layouts it was created with (its own binding set layout, identically
/// defined to its users': sets allocated from theirs are compatible with it).
pub(crate) struct CachedPipeline {
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    pub set_layout: vk::DescriptorSetLayout,
    /// How many `ComputePipeline`s hold it now.
    users: u32,
    /// When it was last taken (`PipelineCache::clock`), to drop the longest unused first.
    last_used: u64,
}

impl CachedPipeline {
    pub fn new(raw: vk::Pipeline, layout: vk::PipelineLayout, set_layout: vk::DescriptorSetLayout) -> Self {
        Self { raw, layout, set_layout, users: 0, last_used: 0 }
    }
}

/// Pipelines no one holds that the cache keeps (a hot-reloaded shader's old pipelines, a
/// calibration's other integrators): past this many the longest unused are destroyed.
const KEPT_UNUSED: usize = 64;

#[derive(Default)]
pub(crate) struct PipelineCache {
    entries: HashMap<PipelineKey, CachedPipeline>,
    clock: u64,
}

impl PipelineCache {
    /// The pipeline and layout of `key`, now held once more, when the cache has it.
    pub fn take(&mut self, key: &PipelineKey) -> Option<(vk::Pipeline, vk::PipelineLayout)> {
        self.clock += 1;
        let entry = self.entries.get_mut(key)?;
        entry.users += 1;
        entry.last_used = self.clock;
        Some((entry.raw, entry.layout))
    }

    /// Adds a pipeline just created for `key`, held once.
    pub fn insert(&mut self, key: PipelineKey, mut entry: CachedPipeline) {
        self.clock += 1;
        entry.users = 1;
        entry.last_used = self.clock;
        self.entries.insert(key, entry);
    }

    /// One holder of pipeline `raw` lets it go; returns the pipelines to destroy now: the
    /// longest unused past `KEPT_UNUSED`.
    pub fn release(&mut self, raw: vk::Pipeline) -> Vec<CachedPipeline> {
        let Some(entry) = self.entries.values_mut().find(|e| e.raw == raw) else {
            return Vec::new();
        };
        entry.users = entry.users.saturating_sub(1);
        let mut unused: Vec<(u64, PipelineKey)> = (self.entries.iter())
            .filter(|(_, e)| e.users == 0)
            .map(|(k, e)| (e.last_used, k.clone()))
            .collect();
        if unused.len() <= KEPT_UNUSED {
            return Vec::new();
        }
        unused.sort_by_key(|(t, _)| *t);
        let excess = unused.len() - KEPT_UNUSED;
        unused.into_iter().take(excess).filter_map(|(_, k)| self.entries.remove(&k)).collect()
    }

    /// Every pipeline, for the context's teardown.
    pub fn drain(&mut self) -> Vec<CachedPipeline> {
        self.entries.drain().map(|(_, e)| e).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ash::vk::Handle;

    fn key(n: u32) -> PipelineKey {
        PipelineKey {
            spirv: vec![0x0723_0203, n].into(),
            specialization: vec![(0, n)],
            kinds: vec![BindingKind::ComputeStorage],
            counts: vec![1],
        }
    }

    fn entry(n: u64) -> CachedPipeline {
        CachedPipeline::new(
            vk::Pipeline::from_raw(n),
            vk::PipelineLayout::from_raw(n),
            vk::DescriptorSetLayout::from_raw(n),
        )
    }

    /// A pipeline is shared while held, kept once unused, and only the longest unused past
    /// `KEPT_UNUSED` are given back for destruction, never one still held.
    #[test]
    fn held_pipelines_are_shared_and_only_the_longest_unused_are_dropped() {
        let mut cache = PipelineCache::default();
        cache.insert(key(0), entry(1));
        assert_eq!(cache.take(&key(0)).map(|(p, _)| p.as_raw()), Some(1));
        assert!(cache.take(&key(1)).is_none());
        assert!(cache.release(vk::Pipeline::from_raw(1)).is_empty());
        assert!(cache.release(vk::Pipeline::from_raw(1)).is_empty(), "kept unused");
        for n in 1..=KEPT_UNUSED as u32 {
            cache.insert(key(n), entry(n as u64 + 1));
        }
        // All held but pipeline 1; releasing them one by one leaves KEPT_UNUSED + 1 unused at
        // the end, and the longest unused, pipeline 1, goes.
        let mut dropped = Vec::new();
        for n in 1..=KEPT_UNUSED as u64 {
            dropped.extend(cache.release(vk::Pipeline::from_raw(n + 1)).into_iter().map(|e| e.raw.as_raw()));
        }
        assert_eq!(dropped, [1]);
        assert!(cache.take(&key(0)).is_none() && cache.take(&key(1)).is_some());
        assert_eq!(cache.drain().len(), KEPT_UNUSED);
    }
}
