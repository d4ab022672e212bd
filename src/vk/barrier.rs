//! The one barrier helper: call sites say which accesses must be ordered (`Access` -> `Access`),
//! and this file alone maps accesses to synchronization2 stage and access masks.

use super::buffer::Buffer;
use super::image::ImageRef;
use ash::vk;

/// One kind of use of a resource.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// A compute shader reads a storage buffer.
    ComputeRead,
    /// A compute shader writes a storage buffer.
    ComputeWrite,
    /// A compute shader reads or writes a storage buffer (ping-pong state between substeps).
    ComputeReadWrite,
    /// A compute shader reads or writes a storage buffer that also holds indirect dispatches.
    ComputeOrIndirect,
    /// A transfer reads the buffer (copy source).
    TransferRead,
    /// A transfer writes the buffer (copy destination, fill).
    TransferWrite,
    /// The host reads mapped memory after a fence.
    HostRead,
    /// Vertex attribute fetch.
    VertexInput,
    /// Index fetch.
    IndexInput,
    /// Uniform buffer read by the vertex or fragment shader.
    GraphicsUniformRead,
    /// Uniform buffer read by a compute shader.
    ComputeUniformRead,
    /// A swapchain image just acquired: ordered after the acquire semaphore's wait at the
    /// colour-output stage, contents undefined.
    Acquired,
    /// Colour attachment of a rendering pass (load or clear, then write).
    ColorAttachment,
    /// Depth attachment of a rendering pass.
    DepthAttachment,
    /// Handed to the presentation engine.
    Present,
}

impl Access {
    pub(crate) fn masks(self) -> (vk::PipelineStageFlags2, vk::AccessFlags2) {
        use vk::{AccessFlags2 as A, PipelineStageFlags2 as S};
        match self {
            Access::ComputeRead => (S::COMPUTE_SHADER, A::SHADER_STORAGE_READ),
            Access::ComputeWrite => (S::COMPUTE_SHADER, A::SHADER_STORAGE_WRITE),
            Access::ComputeReadWrite => (S::COMPUTE_SHADER, A::SHADER_STORAGE_READ | A::SHADER_STORAGE_WRITE),
            Access::ComputeOrIndirect => (
                S::COMPUTE_SHADER | S::DRAW_INDIRECT,
                A::SHADER_STORAGE_READ | A::SHADER_STORAGE_WRITE | A::INDIRECT_COMMAND_READ,
            ),
            Access::TransferRead => (S::COPY, A::TRANSFER_READ),
            // (copies, and the fills and updates that synchronization2 counts as clears)
            Access::TransferWrite => (S::ALL_TRANSFER, A::TRANSFER_WRITE),
            Access::HostRead => (S::HOST, A::HOST_READ),
            Access::VertexInput => (S::VERTEX_ATTRIBUTE_INPUT, A::VERTEX_ATTRIBUTE_READ),
            Access::IndexInput => (S::INDEX_INPUT, A::INDEX_READ),
            Access::GraphicsUniformRead => (S::VERTEX_SHADER | S::FRAGMENT_SHADER, A::UNIFORM_READ),
            Access::ComputeUniformRead => (S::COMPUTE_SHADER, A::UNIFORM_READ),
            Access::Acquired => (S::COLOR_ATTACHMENT_OUTPUT, A::NONE),
            Access::ColorAttachment => {
                (S::COLOR_ATTACHMENT_OUTPUT, A::COLOR_ATTACHMENT_READ | A::COLOR_ATTACHMENT_WRITE)
            }
            Access::DepthAttachment => (
                S::EARLY_FRAGMENT_TESTS | S::LATE_FRAGMENT_TESTS,
                A::DEPTH_STENCIL_ATTACHMENT_READ | A::DEPTH_STENCIL_ATTACHMENT_WRITE,
            ),
            Access::Present => (S::NONE, A::NONE),
        }
    }

    /// The image layout an access needs (buffers ignore it).
    pub(crate) fn layout(self) -> vk::ImageLayout {
        use vk::ImageLayout as L;
        match self {
            Access::TransferRead => L::TRANSFER_SRC_OPTIMAL,
            Access::TransferWrite => L::TRANSFER_DST_OPTIMAL,
            Access::ColorAttachment => L::COLOR_ATTACHMENT_OPTIMAL,
            Access::DepthAttachment => L::DEPTH_ATTACHMENT_OPTIMAL,
            Access::Present => L::PRESENT_SRC_KHR,
            Access::ComputeRead
            | Access::ComputeWrite
            | Access::ComputeReadWrite
            | Access::ComputeOrIndirect => L::GENERAL,
            _ => L::UNDEFINED,
        }
    }
}

/// Orders the `src` accesses to an image before the `dst` accesses, moving it between their
/// layouts; `discard` starts from an undefined layout (previous contents are not kept).
#[derive(Clone, Copy)]
pub struct ImageBarrier {
    pub image: ImageRef,
    pub src: Access,
    pub dst: Access,
    pub discard: bool,
}

impl ImageBarrier {
    pub fn new(image: ImageRef, src: Access, dst: Access) -> Self {
        Self { image, src, dst, discard: false }
    }

    /// A barrier that throws away the previous contents (old layout undefined).
    pub fn discarding(image: ImageRef, src: Access, dst: Access) -> Self {
        Self { image, src, dst, discard: true }
    }

    pub(crate) fn to_vk(self) -> vk::ImageMemoryBarrier2<'static> {
        let (src_stage, src_access) = self.src.masks();
        let (dst_stage, dst_access) = self.dst.masks();
        let old = if self.discard || self.src == Access::Acquired {
            vk::ImageLayout::UNDEFINED
        } else {
            self.src.layout()
        };
        vk::ImageMemoryBarrier2::default()
            .src_stage_mask(src_stage)
            .src_access_mask(src_access)
            .dst_stage_mask(dst_stage)
            .dst_access_mask(dst_access)
            .old_layout(old)
            .new_layout(self.dst.layout())
            .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .image(self.image.raw)
            .subresource_range(
                vk::ImageSubresourceRange::default()
                    .aspect_mask(self.image.aspect)
                    .level_count(1)
                    .layer_count(1),
            )
    }
}

/// Orders the `src` accesses to a buffer before the `dst` accesses.
#[derive(Clone, Copy)]
pub struct BufferBarrier<'a> {
    pub buffer: &'a Buffer,
    pub src: Access,
    pub dst: Access,
}

impl<'a> BufferBarrier<'a> {
    pub fn new(buffer: &'a Buffer, src: Access, dst: Access) -> Self {
        Self { buffer, src, dst }
    }

    pub(crate) fn to_vk(self) -> vk::BufferMemoryBarrier2<'static> {
        let (src_stage, src_access) = self.src.masks();
        let (dst_stage, dst_access) = self.dst.masks();
        vk::BufferMemoryBarrier2::default()
            .src_stage_mask(src_stage)
            .src_access_mask(src_access)
            .dst_stage_mask(dst_stage)
            .dst_access_mask(dst_access)
            .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .buffer(self.buffer.raw)
            .offset(0)
            .size(vk::WHOLE_SIZE)
    }
}
