//! Semaphores (GPU-GPU ordering between acquire, submit and present).

use super::context::GpuContext;
use super::error::{Check, VkError};
use ash::vk;

pub struct Semaphore {
    pub(crate) raw: vk::Semaphore,
}

impl Semaphore {
    pub fn new(ctx: &GpuContext) -> Result<Self, VkError> {
        // SAFETY: valid device; destroyed in `destroy`.
        let raw = unsafe { ctx.device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }
            .check("vkCreateSemaphore")?;
        Ok(Self { raw })
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        // SAFETY: no pending operation waits on or signals it (callers wait idle first).
        unsafe { ctx.device.destroy_semaphore(self.raw, None) };
    }
}
