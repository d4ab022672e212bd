//! The one barrier helper: call sites say which accesses must be ordered (`Access` -> `Access`),
//! and this file alone maps accesses to synchronization2 stage and access masks.

use super::buffer::Buffer;
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
}

impl Access {
    pub(crate) fn masks(self) -> (vk::PipelineStageFlags2, vk::AccessFlags2) {
        use vk::{AccessFlags2 as A, PipelineStageFlags2 as S};
        match self {
            Access::ComputeRead => (S::COMPUTE_SHADER, A::SHADER_STORAGE_READ),
            Access::ComputeWrite => (S::COMPUTE_SHADER, A::SHADER_STORAGE_WRITE),
            Access::ComputeReadWrite => (S::COMPUTE_SHADER, A::SHADER_STORAGE_READ | A::SHADER_STORAGE_WRITE),
            Access::TransferRead => (S::COPY, A::TRANSFER_READ),
            Access::TransferWrite => (S::COPY, A::TRANSFER_WRITE),
            Access::HostRead => (S::HOST, A::HOST_READ),
            Access::VertexInput => (S::VERTEX_ATTRIBUTE_INPUT, A::VERTEX_ATTRIBUTE_READ),
            Access::IndexInput => (S::INDEX_INPUT, A::INDEX_READ),
        }
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
