//! Compute pipelines and their binding sets (descriptor sets of buffers).

use super::buffer::Buffer;
use super::context::GpuContext;
use super::error::{Check, VkError};
use super::pipeline_cache::{CachedPipeline, PipelineKey};
use ash::vk;

/// What a binding holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BindingKind {
    /// A storage buffer read or written by compute shaders.
    ComputeStorage,
    /// A uniform buffer read by vertex and fragment shaders.
    GraphicsUniform,
    /// A uniform buffer read by compute shaders.
    ComputeUniform,
}

impl BindingKind {
    fn descriptor_type(self) -> vk::DescriptorType {
        match self {
            BindingKind::ComputeStorage => vk::DescriptorType::STORAGE_BUFFER,
            BindingKind::GraphicsUniform | BindingKind::ComputeUniform => vk::DescriptorType::UNIFORM_BUFFER,
        }
    }

    fn stages(self) -> vk::ShaderStageFlags {
        match self {
            BindingKind::ComputeStorage | BindingKind::ComputeUniform => vk::ShaderStageFlags::COMPUTE,
            BindingKind::GraphicsUniform => vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT,
        }
    }
}

/// A descriptor set layout: binding `i` holds `counts[i]` buffers (an array; one by default)
/// of `kinds[i]`.
pub struct BindingSetLayout {
    pub(crate) raw: vk::DescriptorSetLayout,
    kinds: Vec<BindingKind>,
    counts: Vec<u32>,
}

impl BindingSetLayout {
    /// `count` compute storage buffers at bindings 0..count.
    pub fn storage_buffers(ctx: &GpuContext, count: u32) -> Result<Self, VkError> {
        Self::new(ctx, &vec![BindingKind::ComputeStorage; count as usize])
    }

    pub fn new(ctx: &GpuContext, kinds: &[BindingKind]) -> Result<Self, VkError> {
        Self::with_counts(ctx, kinds, &vec![1; kinds.len()])
    }

    /// Binding `i` an array of `counts[i]` buffers of `kinds[i]`.
    pub fn with_counts(ctx: &GpuContext, kinds: &[BindingKind], counts: &[u32]) -> Result<Self, VkError> {
        assert_eq!(kinds.len(), counts.len(), "a count per binding");
        let bindings: Vec<_> = kinds
            .iter()
            .zip(counts)
            .enumerate()
            .map(|(i, (kind, &count))| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(i as u32)
                    .descriptor_type(kind.descriptor_type())
                    .descriptor_count(count)
                    .stage_flags(kind.stages())
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid device; destroyed in `destroy`.
        let raw = unsafe { ctx.device.create_descriptor_set_layout(&info, None) }
            .check("vkCreateDescriptorSetLayout")?;
        Ok(Self { raw, kinds: kinds.to_vec(), counts: counts.to_vec() })
    }

    pub fn count(&self) -> u32 {
        self.kinds.len() as u32
    }

    /// Descriptors in a set of this layout.
    pub fn descriptors(&self) -> u32 {
        self.counts.iter().sum()
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        // SAFETY: no pipeline layout is created from it after this, and sets using it are freed
        // with their arena.
        unsafe { ctx.device.destroy_descriptor_set_layout(self.raw, None) };
    }
}

/// A bound set of buffers; valid until its `DescriptorArena` is destroyed. The default is a
/// null set, never bound.
#[derive(Clone, Copy, Debug, Default)]
pub struct BindingSet {
    pub(crate) raw: vk::DescriptorSet,
}

/// A descriptor pool for a fixed number of binding sets.
pub struct DescriptorArena {
    raw: vk::DescriptorPool,
}

impl DescriptorArena {
    /// A pool for `max_sets` sets of up to `buffers_per_set` buffers of any kind.
    pub fn new(ctx: &GpuContext, max_sets: u32, buffers_per_set: u32) -> Result<Self, VkError> {
        Self::for_descriptors(ctx, max_sets, max_sets * buffers_per_set)
    }

    /// A pool for `max_sets` sets of `descriptors` buffers in all, of any kind.
    pub fn for_descriptors(ctx: &GpuContext, max_sets: u32, descriptors: u32) -> Result<Self, VkError> {
        let count = descriptors.max(1);
        let sizes = [
            vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: count },
            vk::DescriptorPoolSize { ty: vk::DescriptorType::UNIFORM_BUFFER, descriptor_count: count },
        ];
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(max_sets.max(1)).pool_sizes(&sizes);
        // SAFETY: valid device; destroyed in `destroy`.
        let raw =
            unsafe { ctx.device.create_descriptor_pool(&info, None) }.check("vkCreateDescriptorPool")?;
        Ok(Self { raw })
    }

    /// Allocates a set binding `buffers[i]` at binding `i`.
    pub fn allocate(
        &mut self,
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        buffers: &[&Buffer],
    ) -> Result<BindingSet, VkError> {
        assert_eq!(buffers.len(), layout.kinds.len(), "binding count must match the layout");
        let arrays: Vec<Vec<&Buffer>> = buffers.iter().map(|&b| vec![b]).collect();
        self.allocate_arrays(ctx, layout, &arrays)
    }

    /// Allocates a set of `layout` whose binding `i` holds `buffers[i]` (as many as the
    /// layout's count for it).
    pub fn allocate_arrays(
        &mut self,
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        buffers: &[Vec<&Buffer>],
    ) -> Result<BindingSet, VkError> {
        assert_eq!(buffers.len(), layout.kinds.len(), "binding count must match the layout");
        for (b, &count) in buffers.iter().zip(&layout.counts) {
            assert_eq!(b.len() as u32, count, "a buffer per array element");
        }
        let layouts = [layout.raw];
        let info = vk::DescriptorSetAllocateInfo::default().descriptor_pool(self.raw).set_layouts(&layouts);
        // SAFETY: the pool and layout belong to this device.
        let raw = unsafe { ctx.device.allocate_descriptor_sets(&info) }.check("vkAllocateDescriptorSets")?[0];
        let infos: Vec<Vec<vk::DescriptorBufferInfo>> = buffers
            .iter()
            .map(|array| {
                let info = |b: &&Buffer| vk::DescriptorBufferInfo {
                    buffer: b.raw,
                    offset: 0,
                    range: vk::WHOLE_SIZE,
                };
                array.iter().map(info).collect()
            })
            .collect();
        let writes: Vec<_> = infos
            .iter()
            .enumerate()
            .map(|(i, info)| {
                vk::WriteDescriptorSet::default()
                    .dst_set(raw)
                    .dst_binding(i as u32)
                    .descriptor_type(layout.kinds[i].descriptor_type())
                    .buffer_info(info)
            })
            .collect();
        // SAFETY: the set was just allocated and is not in use by the GPU.
        unsafe { ctx.device.update_descriptor_sets(&writes, &[]) };
        Ok(BindingSet { raw })
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        // SAFETY: no pending submission uses the sets (callers wait first).
        unsafe { ctx.device.destroy_descriptor_pool(self.raw, None) };
    }
}

/// Bytes of push constants every compute pipeline layout offers (`Recorder::dispatch_with`).
pub const COMPUTE_PUSH_BYTES: u32 = 32;

/// A compute pipeline with its own pipeline layout (one binding set, `COMPUTE_PUSH_BYTES` of
/// push constants, which shaders may leave undeclared).
pub struct ComputePipeline {
    pub(crate) raw: vk::Pipeline,
    pub(crate) layout: vk::PipelineLayout,
}

impl ComputePipeline {
    /// Builds a pipeline from SPIR-V; `specialization[i]` is the u32 constant with id `i`. One
    /// this context created before from the same SPIR-V, constants and binding kinds is taken
    /// from its cache instead (`pipeline_cache`).
    pub fn new(
        ctx: &GpuContext,
        name: &str,
        spirv: &[u32],
        set_layout: &BindingSetLayout,
        specialization: &[u32],
    ) -> Result<Self, VkError> {
        let constants: Vec<(u32, u32)> = (0..).zip(specialization.iter().copied()).collect();
        Self::with_constants(ctx, name, spirv, set_layout, &constants)
    }

    /// `new` with the constants as (id, value) pairs.
    pub fn with_constants(
        ctx: &GpuContext,
        name: &str,
        spirv: &[u32],
        set_layout: &BindingSetLayout,
        specialization: &[(u32, u32)],
    ) -> Result<Self, VkError> {
        let key = PipelineKey {
            spirv: spirv.into(),
            specialization: specialization.to_vec(),
            kinds: set_layout.kinds.clone(),
            counts: set_layout.counts.clone(),
        };
        if let Some((raw, layout)) = ctx.pipeline_cache().take(&key) {
            return Ok(Self { raw, layout });
        }
        let entry = Self::create(ctx, name, spirv, set_layout, specialization)?;
        let created = Self { raw: entry.raw, layout: entry.layout };
        ctx.pipeline_cache().insert(key, entry);
        Ok(created)
    }

    /// Compiles the pipeline, with a binding set layout of its own like `like` (the cache may
    /// keep it after the caller's layout is gone).
    fn create(
        ctx: &GpuContext,
        name: &str,
        spirv: &[u32],
        like: &BindingSetLayout,
        specialization: &[(u32, u32)],
    ) -> Result<CachedPipeline, VkError> {
        let set_layout = BindingSetLayout::with_counts(ctx, &like.kinds, &like.counts)?;
        let module_info = vk::ShaderModuleCreateInfo::default().code(spirv);
        // SAFETY: valid device; the module is destroyed below, after pipeline creation.
        let module = match unsafe { ctx.device.create_shader_module(&module_info, None) } {
            Ok(m) => m,
            Err(e) => {
                set_layout.destroy(ctx);
                return Err(VkError::from_call("vkCreateShaderModule", e));
            }
        };
        let set_layouts = [set_layout.raw];
        let ranges = [vk::PushConstantRange {
            stage_flags: vk::ShaderStageFlags::COMPUTE,
            offset: 0,
            size: COMPUTE_PUSH_BYTES,
        }];
        let layout_info =
            vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts).push_constant_ranges(&ranges);
        // SAFETY: valid device and set layout.
        let layout = match unsafe { ctx.device.create_pipeline_layout(&layout_info, None) } {
            Ok(l) => l,
            Err(e) => {
                // SAFETY: the module and set layout are unused.
                unsafe { ctx.device.destroy_shader_module(module, None) };
                set_layout.destroy(ctx);
                return Err(VkError::from_call("vkCreatePipelineLayout", e));
            }
        };
        let entries: Vec<_> = (0..)
            .zip(specialization)
            .map(|(i, &(id, _))| vk::SpecializationMapEntry { constant_id: id, offset: 4 * i, size: 4 })
            .collect();
        let values: Vec<u32> = specialization.iter().map(|&(_, v)| v).collect();
        let data: &[u8] = bytemuck::cast_slice(&values);
        let spec = vk::SpecializationInfo::default().map_entries(&entries).data(data);
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(c"main")
            .specialization_info(&spec);
        let info = [vk::ComputePipelineCreateInfo::default().stage(stage).layout(layout)];
        // SAFETY: all referenced objects are live for the call; the module may be destroyed after.
        let created = unsafe { ctx.device.create_compute_pipelines(vk::PipelineCache::null(), &info, None) };
        // SAFETY: pipeline creation has finished with the module.
        unsafe { ctx.device.destroy_shader_module(module, None) };
        match created {
            Ok(p) => {
                ctx.set_name(p[0], name);
                Ok(CachedPipeline::new(p[0], layout, set_layout.raw))
            }
            Err((_, e)) => {
                // SAFETY: the layouts are unused.
                unsafe { ctx.device.destroy_pipeline_layout(layout, None) };
                set_layout.destroy(ctx);
                Err(VkError::from_call("vkCreateComputePipelines", e))
            }
        }
    }

    /// Lets the pipeline go: the context's cache keeps it for another user, or destroys it
    /// when it keeps too many unused.
    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        let dropped = ctx.pipeline_cache().release(self.raw);
        dropped.into_iter().for_each(|p| destroy_cached(ctx, p));
    }
}

/// Destroys a pipeline the cache let go (no pending submission uses it: its last holder
/// released it after its work, as `ComputePipeline::destroy` requires).
pub(crate) fn destroy_cached(ctx: &GpuContext, p: CachedPipeline) {
    // SAFETY: no pending submission uses the pipeline or its layouts.
    unsafe {
        ctx.device.destroy_pipeline(p.raw, None);
        ctx.device.destroy_pipeline_layout(p.layout, None);
        ctx.device.destroy_descriptor_set_layout(p.set_layout, None);
    }
}
