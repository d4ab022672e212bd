//! The ImGui renderer (imgui-rs-vulkan-renderer) behind a wrapper, so UI code records through a
//! `Recorder` and never touches ash. It shares the context's allocator and must be destroyed
//! before the context.

use super::commands::Recorder;
use super::context::GpuContext;
use super::image::Format;
use imgui_rs_vulkan_renderer::{DynamicRendering, Options, Renderer};

pub struct UiRenderer {
    inner: Option<Renderer>,
}

impl UiRenderer {
    pub fn new(
        ctx: &GpuContext,
        imgui: &mut imgui::Context,
        color: Format,
        depth: Format,
        frames_in_flight: usize,
    ) -> anyhow::Result<Self> {
        let renderer = Renderer::with_gpu_allocator(
            ctx.allocator_handle(),
            ctx.device.clone(),
            ctx.queue,
            ctx.command_pool,
            DynamicRendering {
                color_attachment_format: color.to_vk(),
                depth_attachment_format: Some(depth.to_vk()),
            },
            imgui,
            Some(Options { in_flight_frames: frames_in_flight, ..Default::default() }),
        )
        .map_err(|e| anyhow::anyhow!("creating the ImGui renderer: {e}"))?;
        Ok(Self { inner: Some(renderer) })
    }

    /// Records the UI draw lists into the current rendering.
    pub fn draw(&mut self, rec: &mut Recorder<'_>, data: &imgui::DrawData) -> anyhow::Result<()> {
        if let Some(r) = self.inner.as_mut() {
            r.cmd_draw(rec.raw(), data).map_err(|e| anyhow::anyhow!("drawing the UI: {e}"))?;
        }
        Ok(())
    }

    /// Frees the renderer's buffers and pipeline; the device must be idle (a stuck one keeps
    /// them, as every `destroy` does).
    pub fn destroy(mut self, ctx: &GpuContext) {
        let inner = self.inner.take();
        if ctx.stuck() {
            std::mem::forget(inner);
        }
    }
}
