//! Buffers: a raw handle plus a named gpu-allocator allocation, freed by `destroy`.

use super::context::GpuContext;
use super::error::{Check, VkError};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

/// Where a buffer's memory lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemoryKind {
    /// Device-local; reached by shaders and transfers only.
    GpuOnly,
    /// Host-visible, written by the CPU and read by the GPU (parameters, staging uploads).
    Upload,
    /// Host-visible and cached, written by the GPU and read by the CPU (readback).
    Readback,
}

/// What a buffer is used for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BufferUsage(vk::BufferUsageFlags);

impl BufferUsage {
    pub const STORAGE: Self = Self(vk::BufferUsageFlags::STORAGE_BUFFER);
    pub const TRANSFER_SRC: Self = Self(vk::BufferUsageFlags::TRANSFER_SRC);
    pub const TRANSFER_DST: Self = Self(vk::BufferUsageFlags::TRANSFER_DST);
    pub const VERTEX: Self = Self(vk::BufferUsageFlags::VERTEX_BUFFER);
    pub const INDEX: Self = Self(vk::BufferUsageFlags::INDEX_BUFFER);
    pub const UNIFORM: Self = Self(vk::BufferUsageFlags::UNIFORM_BUFFER);
    pub const INDIRECT: Self = Self(vk::BufferUsageFlags::INDIRECT_BUFFER);
}

impl std::ops::BitOr for BufferUsage {
    type Output = Self;
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

pub struct Buffer {
    pub(crate) raw: vk::Buffer,
    allocation: Allocation,
    size: u64,
    name: String,
}

impl Buffer {
    /// Creates a buffer of `size` bytes (at least 1) with a named allocation.
    pub fn new(
        ctx: &GpuContext,
        name: &str,
        size: u64,
        usage: BufferUsage,
        memory: MemoryKind,
    ) -> Result<Self, VkError> {
        let size = size.max(4);
        let info = vk::BufferCreateInfo::default()
            .size(size)
            .usage(usage.0)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid device and create info; the buffer is destroyed in `destroy`.
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.check("vkCreateBuffer")?;
        // SAFETY: `raw` was just created on this device.
        let requirements = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let location = match memory {
            MemoryKind::GpuOnly => MemoryLocation::GpuOnly,
            MemoryKind::Upload => MemoryLocation::CpuToGpu,
            MemoryKind::Readback => MemoryLocation::GpuToCpu,
        };
        let allocation = ctx.allocator().allocate(&AllocationCreateDesc {
            name,
            requirements,
            location,
            linear: true,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        });
        let allocation = match allocation {
            Ok(a) => a,
            Err(source) => {
                // SAFETY: the buffer has no memory bound and is unused.
                unsafe { ctx.device.destroy_buffer(raw, None) };
                return Err(match source {
                    gpu_allocator::AllocationError::OutOfMemory => VkError::OutOfMemory { what: name.into() },
                    source => VkError::Allocation { what: name.into(), source },
                });
            }
        };
        // SAFETY: the allocation satisfies the buffer's requirements and is not bound elsewhere.
        let bound = unsafe { ctx.device.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) }
            .check("vkBindBufferMemory");
        if let Err(e) = bound {
            let _ = ctx.allocator().free(allocation);
            // SAFETY: unused buffer.
            unsafe { ctx.device.destroy_buffer(raw, None) };
            return Err(e);
        }
        ctx.set_name(raw, name);
        Ok(Self { raw, allocation, size, name: name.to_string() })
    }

    pub fn size(&self) -> u64 {
        self.size
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// Copies `data` into a host-visible buffer at byte `offset`. The caller makes sure the GPU
    /// is not reading the range (written before submit, or after the last use's fence).
    pub fn write<T: bytemuck::Pod>(&mut self, offset: u64, data: &[T]) -> Result<(), VkError> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let name = self.name.clone();
        let mapped = self.allocation.mapped_slice_mut().ok_or_else(|| VkError::Allocation {
            what: name.clone(),
            source: gpu_allocator::AllocationError::FailedToMap("buffer is not host-visible".into()),
        })?;
        let start = offset as usize;
        let end = start + bytes.len();
        if end > mapped.len() {
            return Err(VkError::Allocation {
                what: name,
                source: gpu_allocator::AllocationError::Internal(format!(
                    "write of {end} bytes past the end"
                )),
            });
        }
        mapped[start..end].copy_from_slice(bytes);
        Ok(())
    }

    /// Reads `count` values of `T` from a host-visible buffer (after the writing GPU work's fence).
    pub fn read<T: bytemuck::Pod>(&self, count: usize) -> Result<Vec<T>, VkError> {
        let mapped = self.allocation.mapped_slice().ok_or_else(|| VkError::Allocation {
            what: self.name.clone(),
            source: gpu_allocator::AllocationError::FailedToMap("buffer is not host-visible".into()),
        })?;
        let bytes = count * std::mem::size_of::<T>();
        if bytes > mapped.len() {
            return Err(VkError::Allocation {
                what: self.name.clone(),
                source: gpu_allocator::AllocationError::Internal(format!(
                    "read of {bytes} bytes past the end"
                )),
            });
        }
        Ok(bytemuck::pod_collect_to_vec(&mapped[..bytes]))
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        if let Err(e) = ctx.allocator().free(self.allocation) {
            log::error!("freeing {}: {e}", self.name);
        }
        // SAFETY: the caller guarantees the GPU no longer uses the buffer (after a fence wait or
        // wait_idle); its memory was just freed.
        unsafe { ctx.device.destroy_buffer(self.raw, None) };
    }
}
