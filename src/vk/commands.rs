//! Command buffers: a reusable slot (command buffer + fence) and a `Recorder` that is the only
//! way code outside `vk` records commands.

use super::barrier::{BufferBarrier, ImageBarrier};
use super::buffer::Buffer;
use super::context::GpuContext;
use super::error::{Check, VkError};
use super::graphics::GraphicsPipeline;
use super::image::{ImageRef, ViewRef};
use super::pipeline::{BindingSet, ComputePipeline};
use super::query::TimestampPool;
use super::sync::Semaphore;
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
        self.submit_with(ctx, recorder, None, None)
    }

    /// Like `submit`, but the commands that write colour attachments wait for `wait` (an
    /// acquired swapchain image) and `signal` is signalled when all commands are done.
    pub fn submit_with(
        &mut self,
        ctx: &GpuContext,
        recorder: Recorder<'_>,
        wait: Option<&Semaphore>,
        signal: Option<&Semaphore>,
    ) -> Result<(), VkError> {
        debug_assert_eq!(recorder.cb, self.cb);
        let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(self.cb)];
        let waits: Vec<_> = wait
            .map(|s| {
                vk::SemaphoreSubmitInfo::default()
                    .semaphore(s.raw)
                    .stage_mask(vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT)
            })
            .into_iter()
            .collect();
        let signals: Vec<_> = signal
            .map(|s| {
                vk::SemaphoreSubmitInfo::default()
                    .semaphore(s.raw)
                    .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            })
            .into_iter()
            .collect();
        let submit = [vk::SubmitInfo2::default()
            .command_buffer_infos(&cbs)
            .wait_semaphore_infos(&waits)
            .signal_semaphore_infos(&signals)];
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
            ctx.wait_fence(self.fence)?;
            self.pending = false;
        }
        Ok(())
    }

    /// Frees the slot; the caller has waited for it (or the device is idle).
    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
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

impl<'a> Recorder<'a> {
    /// The context the commands are recorded on.
    pub fn context(&self) -> &'a GpuContext {
        self.ctx
    }

    /// Binds a compute pipeline and its binding set and dispatches `groups` workgroups.
    pub fn dispatch(&mut self, pipeline: &ComputePipeline, set: BindingSet, groups: [u32; 3]) {
        self.dispatch_with(pipeline, set, groups, &[]);
    }

    /// `dispatch` with push constants (`push` words from offset 0, at most
    /// `COMPUTE_PUSH_BYTES`; more are dropped).
    pub fn dispatch_with(
        &mut self,
        pipeline: &ComputePipeline,
        set: BindingSet,
        groups: [u32; 3],
        push: &[u32],
    ) {
        self.bind_compute(pipeline, set, push);
        // SAFETY: recording state; bound above.
        unsafe { self.ctx.device.cmd_dispatch(self.cb, groups[0], groups[1], groups[2]) };
    }

    /// `dispatch_with`, its workgroup counts read when it runs from `args` at byte `offset`
    /// (three u32s, a multiple of 4; a buffer made with `BufferUsage::INDIRECT`).
    pub fn dispatch_indirect(
        &mut self,
        pipeline: &ComputePipeline,
        set: BindingSet,
        args: &Buffer,
        offset: u64,
        push: &[u32],
    ) {
        assert!(offset % 4 == 0 && offset + 12 <= args.size(), "indirect dispatch out of bounds");
        self.bind_compute(pipeline, set, push);
        // SAFETY: recording state; bound above; the range was checked.
        unsafe { self.ctx.device.cmd_dispatch_indirect(self.cb, args.raw, offset) };
    }

    fn bind_compute(&mut self, pipeline: &ComputePipeline, set: BindingSet, push: &[u32]) {
        let push = &push[..push.len().min(super::pipeline::COMPUTE_PUSH_BYTES as usize / 4)];
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
            if !push.is_empty() {
                d.cmd_push_constants(
                    self.cb,
                    pipeline.layout,
                    vk::ShaderStageFlags::COMPUTE,
                    0,
                    bytemuck::cast_slice(push),
                );
            }
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

    /// Fills the whole of `buffer` with the 32-bit `value`.
    pub fn fill_buffer(&mut self, buffer: &Buffer, value: u32) {
        // SAFETY: recording state, outside rendering; the buffer is live.
        unsafe { self.ctx.device.cmd_fill_buffer(self.cb, buffer.raw, 0, vk::WHOLE_SIZE, value) };
    }

    /// Fills `bytes` of `buffer` from `offset` (both multiples of 4, in bounds) with `value`.
    pub fn fill_range(&mut self, buffer: &Buffer, offset: u64, bytes: u64, value: u32) {
        assert!(offset % 4 == 0 && bytes % 4 == 0 && offset + bytes <= buffer.size(), "fill out of bounds");
        // SAFETY: recording state, outside rendering; the range was checked above.
        unsafe { self.ctx.device.cmd_fill_buffer(self.cb, buffer.raw, offset, bytes, value) };
    }

    /// Writes `data` (at most 65536 bytes, a multiple of 4) into `buffer` at `offset`, inline in
    /// the command buffer.
    pub fn update_buffer(&mut self, buffer: &Buffer, offset: u64, data: &[u8]) {
        assert!(data.len() % 4 == 0 && data.len() <= 65536 && offset + data.len() as u64 <= buffer.size());
        // SAFETY: recording state, outside rendering; the range was checked above.
        unsafe { self.ctx.device.cmd_update_buffer(self.cb, buffer.raw, offset, data) };
    }

    /// One `vkCmdPipelineBarrier2` with all the given image barriers (layout transitions).
    pub fn image_barrier(&mut self, barriers: &[ImageBarrier]) {
        if barriers.is_empty() {
            return;
        }
        let raw: Vec<_> = barriers.iter().map(|b| b.to_vk()).collect();
        let dep = vk::DependencyInfo::default().image_memory_barriers(&raw);
        // SAFETY: recording state; the images are live.
        unsafe { self.ctx.device.cmd_pipeline_barrier2(self.cb, &dep) };
    }

    /// Starts dynamic rendering into `color` (cleared to `clear`) and `depth` (cleared to 1),
    /// with the viewport and scissor covering `extent`.
    pub fn begin_rendering(&mut self, color: ViewRef, depth: ViewRef, extent: [u32; 2], clear: [f32; 4]) {
        let color_attachments = [vk::RenderingAttachmentInfo::default()
            .image_view(color.raw)
            .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::CLEAR)
            .store_op(vk::AttachmentStoreOp::STORE)
            .clear_value(vk::ClearValue { color: vk::ClearColorValue { float32: clear } })];
        let depth_attachment = vk::RenderingAttachmentInfo::default()
            .image_view(depth.raw)
            .image_layout(vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::CLEAR)
            .store_op(vk::AttachmentStoreOp::DONT_CARE)
            .clear_value(vk::ClearValue {
                depth_stencil: vk::ClearDepthStencilValue { depth: 1.0, stencil: 0 },
            });
        let area = vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent: vk::Extent2D { width: extent[0], height: extent[1] },
        };
        let info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(1)
            .color_attachments(&color_attachments)
            .depth_attachment(&depth_attachment);
        let viewport = vk::Viewport {
            x: 0.0,
            y: 0.0,
            width: extent[0] as f32,
            height: extent[1] as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        };
        // SAFETY: recording state; the views are live and in the attachment layouts (callers
        // transition them first).
        unsafe {
            self.ctx.device.cmd_begin_rendering(self.cb, &info);
            self.ctx.device.cmd_set_viewport(self.cb, 0, &[viewport]);
            self.ctx.device.cmd_set_scissor(self.cb, 0, &[area]);
        }
    }

    pub fn end_rendering(&mut self) {
        // SAFETY: recording state, inside a rendering started by `begin_rendering`.
        unsafe { self.ctx.device.cmd_end_rendering(self.cb) };
    }

    /// Binds a graphics pipeline with its binding set.
    pub fn bind_graphics(&mut self, pipeline: &GraphicsPipeline, set: BindingSet) {
        // SAFETY: recording state; the pipeline and set are live and compatible.
        unsafe {
            self.ctx.device.cmd_bind_pipeline(self.cb, vk::PipelineBindPoint::GRAPHICS, pipeline.raw);
            self.ctx.device.cmd_bind_descriptor_sets(
                self.cb,
                vk::PipelineBindPoint::GRAPHICS,
                pipeline.layout,
                0,
                &[set.raw],
                &[],
            );
        }
    }

    /// Sets the push constants of the bound graphics pipeline (both stages).
    pub fn push_constants(&mut self, pipeline: &GraphicsPipeline, data: &[u8]) {
        // SAFETY: recording state; `data` fits the pipeline's push constant range (checked by
        // validation when on).
        unsafe {
            self.ctx.device.cmd_push_constants(
                self.cb,
                pipeline.layout,
                vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT,
                0,
                data,
            )
        };
    }

    /// Draws `count` indices (u32) of `indices` over `vertices`, `instances` times.
    pub fn draw_indexed(&mut self, vertices: &Buffer, indices: &Buffer, count: u32, instances: u32) {
        // SAFETY: recording state inside rendering; the buffers are live.
        unsafe {
            self.ctx.device.cmd_bind_vertex_buffers(self.cb, 0, &[vertices.raw], &[0]);
            self.ctx.device.cmd_bind_index_buffer(self.cb, indices.raw, 0, vk::IndexType::UINT32);
            self.ctx.device.cmd_draw_indexed(self.cb, count, instances, 0, 0, 0);
        }
    }

    /// Draws `count` vertices of `vertices`.
    pub fn draw(&mut self, vertices: &Buffer, count: u32) {
        // SAFETY: recording state inside rendering; the buffer is live.
        unsafe {
            self.ctx.device.cmd_bind_vertex_buffers(self.cb, 0, &[vertices.raw], &[0]);
            self.ctx.device.cmd_draw(self.cb, count, 1, 0, 0);
        }
    }

    /// Copies a colour image (in the transfer-source layout) into a tightly packed buffer.
    pub fn copy_image_to_buffer(&mut self, image: ImageRef, extent: [u32; 2], buffer: &Buffer) {
        let region = vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers::default().aspect_mask(image.aspect).layer_count(1))
            .image_extent(vk::Extent3D { width: extent[0], height: extent[1], depth: 1 });
        // SAFETY: recording state; the image is in TRANSFER_SRC_OPTIMAL (callers transition it)
        // and the buffer holds width * height * 4 bytes.
        unsafe {
            self.ctx.device.cmd_copy_image_to_buffer(
                self.cb,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                buffer.raw,
                &[region],
            )
        };
    }

    /// The raw command buffer, for recording by the UI renderer wrapper.
    pub(crate) fn raw(&self) -> vk::CommandBuffer {
        self.cb
    }

    /// Resets the whole timestamp pool; record before the first `timestamp`.
    pub fn reset_timestamps(&mut self, pool: &TimestampPool) {
        // SAFETY: recording state, outside a render pass.
        unsafe { self.ctx.device.cmd_reset_query_pool(self.cb, pool.raw, 0, pool.capacity()) };
    }

    /// Writes timestamp `index` once all previously recorded compute work has finished.
    pub fn timestamp(&mut self, pool: &TimestampPool, index: u32) {
        self.timestamp_at(pool, index, vk::PipelineStageFlags2::COMPUTE_SHADER);
    }

    /// Writes timestamp `index` once all previously recorded drawing has finished.
    pub fn timestamp_after_drawing(&mut self, pool: &TimestampPool, index: u32) {
        self.timestamp_at(pool, index, vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT);
    }

    fn timestamp_at(&mut self, pool: &TimestampPool, index: u32, stage: vk::PipelineStageFlags2) {
        if index < pool.capacity() {
            // SAFETY: recording state; the query was reset earlier in this command buffer.
            unsafe { self.ctx.device.cmd_write_timestamp2(self.cb, stage, pool.raw, index) };
        }
    }
}
