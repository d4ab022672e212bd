//! Graphics pipelines for dynamic rendering (no render pass objects).

use super::context::GpuContext;
use super::error::{Check, VkError};
use super::image::Format;
use super::pipeline::BindingSetLayout;
use ash::vk;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topology {
    Triangles,
    Lines,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexFormat {
    Float32x3,
    Float32x4,
}

/// One vertex buffer binding: its stride and (location, format, offset) attributes.
#[derive(Clone, Copy, Debug)]
pub struct VertexLayout<'a> {
    pub stride: u32,
    pub attributes: &'a [(u32, VertexFormat, u32)],
}

pub struct GraphicsDesc<'a> {
    pub name: &'a str,
    pub vertex: &'a [u32],
    pub fragment: &'a [u32],
    pub vertices: VertexLayout<'a>,
    pub topology: Topology,
    pub color: Format,
    pub depth: Format,
    /// Depth test on; writes only when `depth_write`.
    pub depth_write: bool,
    /// How the fragments combine with the target (anything but `Opaque` writes no depth
    /// unless `depth_write`).
    pub blend: Blend,
    pub set_layout: &'a BindingSetLayout,
    /// Bytes of push constants, visible to both stages.
    pub push_constant_bytes: u32,
}

/// How a pipeline's fragments combine with the colour target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Blend {
    /// Replace it.
    Opaque,
    /// Source alpha over it.
    Alpha,
    /// Keep the darker of the two, channel by channel: a layer drawn twice darkens once.
    Darker,
}

pub struct GraphicsPipeline {
    pub(crate) raw: vk::Pipeline,
    pub(crate) layout: vk::PipelineLayout,
}

impl GraphicsPipeline {
    pub fn new(ctx: &GpuContext, desc: &GraphicsDesc<'_>) -> Result<Self, VkError> {
        let module = |code: &[u32]| {
            // SAFETY: valid device; modules are destroyed after pipeline creation below.
            unsafe {
                ctx.device.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(code), None)
            }
            .check("vkCreateShaderModule")
        };
        let vert = module(desc.vertex)?;
        let frag = match module(desc.fragment) {
            Ok(m) => m,
            Err(e) => {
                // SAFETY: unused module.
                unsafe { ctx.device.destroy_shader_module(vert, None) };
                return Err(e);
            }
        };
        let ranges = [vk::PushConstantRange {
            stage_flags: vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT,
            offset: 0,
            size: desc.push_constant_bytes,
        }];
        let set_layouts = [desc.set_layout.raw];
        let mut layout_info = vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts);
        if desc.push_constant_bytes > 0 {
            layout_info = layout_info.push_constant_ranges(&ranges);
        }
        let result = (|| {
            // SAFETY: valid device and set layout.
            let layout = unsafe { ctx.device.create_pipeline_layout(&layout_info, None) }
                .check("vkCreatePipelineLayout")?;
            let stages = [
                vk::PipelineShaderStageCreateInfo::default()
                    .stage(vk::ShaderStageFlags::VERTEX)
                    .module(vert)
                    .name(c"main"),
                vk::PipelineShaderStageCreateInfo::default()
                    .stage(vk::ShaderStageFlags::FRAGMENT)
                    .module(frag)
                    .name(c"main"),
            ];
            let bindings = [vk::VertexInputBindingDescription {
                binding: 0,
                stride: desc.vertices.stride,
                input_rate: vk::VertexInputRate::VERTEX,
            }];
            let attributes: Vec<_> = desc
                .vertices
                .attributes
                .iter()
                .map(|&(location, format, offset)| vk::VertexInputAttributeDescription {
                    location,
                    binding: 0,
                    format: match format {
                        VertexFormat::Float32x3 => vk::Format::R32G32B32_SFLOAT,
                        VertexFormat::Float32x4 => vk::Format::R32G32B32A32_SFLOAT,
                    },
                    offset,
                })
                .collect();
            let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
                .vertex_binding_descriptions(&bindings)
                .vertex_attribute_descriptions(&attributes);
            let assembly =
                vk::PipelineInputAssemblyStateCreateInfo::default().topology(match desc.topology {
                    Topology::Triangles => vk::PrimitiveTopology::TRIANGLE_LIST,
                    Topology::Lines => vk::PrimitiveTopology::LINE_LIST,
                });
            let viewport = vk::PipelineViewportStateCreateInfo::default().viewport_count(1).scissor_count(1);
            let raster = vk::PipelineRasterizationStateCreateInfo::default()
                .polygon_mode(vk::PolygonMode::FILL)
                .cull_mode(vk::CullModeFlags::NONE)
                .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
                .line_width(1.0);
            let multisample = vk::PipelineMultisampleStateCreateInfo::default()
                .rasterization_samples(vk::SampleCountFlags::TYPE_1);
            let depth = vk::PipelineDepthStencilStateCreateInfo::default()
                .depth_test_enable(true)
                .depth_write_enable(desc.depth_write)
                .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL);
            let attachment = vk::PipelineColorBlendAttachmentState::default()
                .color_write_mask(vk::ColorComponentFlags::RGBA);
            let attachment = match desc.blend {
                Blend::Alpha => attachment
                    .blend_enable(true)
                    .src_color_blend_factor(vk::BlendFactor::SRC_ALPHA)
                    .dst_color_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                    .color_blend_op(vk::BlendOp::ADD)
                    .src_alpha_blend_factor(vk::BlendFactor::ZERO)
                    .dst_alpha_blend_factor(vk::BlendFactor::ONE)
                    .alpha_blend_op(vk::BlendOp::ADD),
                // MIN ignores the factors: the darker of the two, channel by channel.
                Blend::Darker => attachment
                    .blend_enable(true)
                    .src_color_blend_factor(vk::BlendFactor::ONE)
                    .dst_color_blend_factor(vk::BlendFactor::ONE)
                    .color_blend_op(vk::BlendOp::MIN)
                    .src_alpha_blend_factor(vk::BlendFactor::ZERO)
                    .dst_alpha_blend_factor(vk::BlendFactor::ONE)
                    .alpha_blend_op(vk::BlendOp::ADD),
                Blend::Opaque => attachment,
            };
            let attachments = [attachment];
            let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&attachments);
            let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
            let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
            let color_formats = [desc.color.to_vk()];
            let mut rendering = vk::PipelineRenderingCreateInfo::default()
                .color_attachment_formats(&color_formats)
                .depth_attachment_format(desc.depth.to_vk());
            let info = vk::GraphicsPipelineCreateInfo::default()
                .stages(&stages)
                .vertex_input_state(&vertex_input)
                .input_assembly_state(&assembly)
                .viewport_state(&viewport)
                .rasterization_state(&raster)
                .multisample_state(&multisample)
                .depth_stencil_state(&depth)
                .color_blend_state(&blend)
                .dynamic_state(&dynamic)
                .layout(layout)
                .push_next(&mut rendering);
            // SAFETY: all referenced state lives until the call returns.
            match unsafe { ctx.device.create_graphics_pipelines(vk::PipelineCache::null(), &[info], None) } {
                Ok(p) => Ok((p[0], layout)),
                Err((_, e)) => {
                    // SAFETY: the layout is unused.
                    unsafe { ctx.device.destroy_pipeline_layout(layout, None) };
                    Err(VkError::from_call("vkCreateGraphicsPipelines", e))
                }
            }
        })();
        // SAFETY: pipeline creation has finished with the modules.
        unsafe {
            ctx.device.destroy_shader_module(vert, None);
            ctx.device.destroy_shader_module(frag, None);
        }
        let (raw, layout) = result?;
        ctx.set_name(raw, desc.name);
        Ok(Self { raw, layout })
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        // SAFETY: no pending submission uses the pipeline (callers wait or defer the release).
        unsafe {
            ctx.device.destroy_pipeline(self.raw, None);
            ctx.device.destroy_pipeline_layout(self.layout, None);
        }
    }
}
