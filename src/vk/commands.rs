//! Command buffers: a reusable slot (command buffer + fence) and a `Recorder` that is the only
//! way code outside `vk` records commands.

use super::barrier::BufferBarrier;
use super::buffer::Buffer;
use super::context::GpuContext;
use super::error::{Check, VkError};
use super::pipeline::{BindingSet, ComputePipeline};
use super::query::TimestampPool;
use ash::vk;

/// A primary command buffer with its fence, re-recorded for each submission.
pub struct CommandSlot {
    cb: vk::CommandBuffer,
    fence: vk::Fence,
    pending: bool,
}

impl CommandSlot {
    pub fn new(ctx: &GpuContext, name: &str) -> Result<Self, VkError> {
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(ctx.command_pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        // SAFETY: the pool belongs to this device; the buffer is freed in `destroy`.
        let cb = unsafe { ctx.device.allocate_command_buffers(&alloc) }.check("vkAllocateCommandBuffers")?[0];
        // SAFETY: valid device.
        let fence = match unsafe { ctx.device.create_fence(&vk::FenceCreateInfo::default(), None) } {
            Ok(f) => f,
            Err(e) => {
                // SAFETY: the command buffer was never submitted.
                unsafe { ctx.device.free_command_buffers(ctx.command_pool, &[cb]) };
                return Err(VkError::from_call("vkCreateFence", e));
            }
        };
        ctx.set_name(cb, name);
        Ok(Self { cb, fence, pending: false })
    }

    /// Waits for the previous submission (if any), then starts recording.
    pub fn begin<'a>(&mut self, ctx: &'a GpuContext) -> Result<Recorder<'a>, VkError> {
        self.wait(ctx)?;
        let info = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        // SAFETY: the buffer is not pending (waited above); the pool allows individual resets.
        unsafe {
            ctx.device
                .reset_command_buffer(self.cb, vk::CommandBufferResetFlags::empty())
                .check("vkResetCommandBuffer")?;
            ctx.device.begin_command_buffer(self.cb, &info).check("vkBeginCommandBuffer")?;
        }
        Ok(Recorder { ctx, cb: self.cb })
    }

    /// Ends the recording and submits it; the slot is pending until `wait`.
    pub fn submit(&mut self, ctx: &GpuContext, recorder: Recorder<'_>) -> Result<(), VkError> {
        debug_assert_eq!(recorder.cb, self.cb);
        let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(self.cb)];
        let submit = [vk::SubmitInfo2::default().command_buffer_infos(&cbs)];
        // SAFETY: the buffer is in the recording state (from `begin`), the fence is unsignalled.
        unsafe {
            ctx.device.end_command_buffer(self.cb).check("vkEndCommandBuffer")?;
            ctx.device.reset_fences(&[self.fence]).check("vkResetFences")?;
            ctx.device.queue_submit2(ctx.queue, &submit, self.fence).check("vkQueueSubmit2")?;
        }
        self.pending = true;
        Ok(())
    }

    /// Waits for the last submission to finish.
    pub fn wait(&mut self, ctx: &GpuContext) -> Result<(), VkError> {
        if self.pending {
            // SAFETY: the fence belongs to this device and was submitted.
            unsafe { ctx.device.wait_for_fences(&[self.fence], true, u64::MAX) }.check("vkWaitForFences")?;
            self.pending = false;
        }
        Ok(())
    }

    /// Frees the slot; the caller has waited for it (or the device is idle).
    pub fn destroy(self, ctx: &GpuContext) {
        // SAFETY: not pending (callers wait first); both objects belong to this device.
        unsafe {
            ctx.device.destroy_fence(self.fence, None);
            ctx.device.free_command_buffers(ctx.command_pool, &[self.cb]);
        }
    }
}

impl GpuContext {
    /// Records and runs a command buffer once, waiting for it to finish.
    pub fn one_shot<T>(
        &self,
        name: &str,
        record: impl FnOnce(&mut Recorder<'_>) -> Result<T, VkError>,
    ) -> Result<T, VkError> {
        let mut slot = CommandSlot::new(self, name)?;
        let result = (|| {
            let mut rec = slot.begin(self)?;
            let value = record(&mut rec)?;
            slot.submit(self, rec)?;
            slot.wait(self)?;
            Ok(value)
        })();
        if result.is_err() {
            let _ = self.wait_idle();
        }
        slot.destroy(self);
        result
    }
}

/// Records commands into a command buffer between `CommandSlot::begin` and `submit`.
pub struct Recorder<'a> {
    ctx: &'a GpuContext,
    cb: vk::CommandBuffer,
}

impl Recorder<'_> {
    /// Binds a compute pipeline and its binding set and dispatches `groups` workgroups.
    pub fn dispatch(&mut self, pipeline: &ComputePipeline, set: BindingSet, groups: [u32; 3]) {
        // SAFETY: recording state; pipeline, layout and set belong to this device and outlive
        // the submission (their owners destroy them only after waiting).
        unsafe {
            let d = &self.ctx.device;
            d.cmd_bind_pipeline(self.cb, vk::PipelineBindPoint::COMPUTE, pipeline.raw);
            d.cmd_bind_descriptor_sets(
                self.cb,
                vk::PipelineBindPoint::COMPUTE,
                pipeline.layout,
                0,
                &[set.raw],
                &[],
            );
            d.cmd_dispatch(self.cb, groups[0], groups[1], groups[2]);
        }
    }

    /// One `vkCmdPipelineBarrier2` with all the given buffer barriers.
    pub fn barrier(&mut self, barriers: &[BufferBarrier<'_>]) {
        if barriers.is_empty() {
            return;
        }
        let raw: Vec<_> = barriers.iter().map(|b| b.to_vk()).collect();
        let dep = vk::DependencyInfo::default().buffer_memory_barriers(&raw);
        // SAFETY: recording state; the buffers are live.
        unsafe { self.ctx.device.cmd_pipeline_barrier2(self.cb, &dep) };
    }

    /// Copies `bytes` from `src` at `src_offset` to `dst` at `dst_offset` (both ranges in bounds).
    pub fn copy_buffer_region(
        &mut self,
        src: &Buffer,
        src_offset: u64,
        dst: &Buffer,
        dst_offset: u64,
        bytes: u64,
    ) {
        assert!(src_offset + bytes <= src.size() && dst_offset + bytes <= dst.size(), "copy out of bounds");
        if bytes == 0 {
            return;
        }
        let region = [vk::BufferCopy { src_offset, dst_offset, size: bytes }];
        // SAFETY: recording state; the ranges were checked against both buffers above.
        unsafe { self.ctx.device.cmd_copy_buffer(self.cb, src.raw, dst.raw, &region) };
    }

    /// Resets the whole timestamp pool; record before the first `timestamp`.
    pub fn reset_timestamps(&mut self, pool: &TimestampPool) {
        // SAFETY: recording state, outside a render pass.
        unsafe { self.ctx.device.cmd_reset_query_pool(self.cb, pool.raw, 0, pool.capacity()) };
    }

    /// Writes timestamp `index` once all previously recorded compute work has finished.
    pub fn timestamp(&mut self, pool: &TimestampPool, index: u32) {
        if index < pool.capacity() {
            // SAFETY: recording state; the query was reset earlier in this command buffer.
            unsafe {
                self.ctx.device.cmd_write_timestamp2(
                    self.cb,
                    vk::PipelineStageFlags2::COMPUTE_SHADER,
                    pool.raw,
                    index,
                )
            };
        }
    }
}
