//! The app's frame without a window, for `bench --end-to-end`: each frame records the
//! simulation (all substeps and the surface stage), then the app's scene renderer draws the
//! scene (the ground grid where it has a ground) into an offscreen colour + depth target (1920 x 1080 by
//! default), with `FRAME_SLOTS` frames in flight as in the window. What it leaves out of the
//! app's frame is the swapchain (acquire and present) and ImGui.
//!
//! The host waits for a slot's fence before it rewrites that slot's camera uniform and reads
//! its timestamps; the colour and depth targets are shared by the frames in flight, so each
//! frame starts with a barrier that orders the previous frame's attachment writes before its
//! own (discarding the contents: both are cleared).

use crate::bench::{EndToEnd, Spread};
use crate::render::camera::OrbitCamera;
use crate::render::view::{self, SKY};
use crate::render::SceneRenderer;
use crate::scene::{self, Scene};
use crate::shaders::ShaderSet;
use crate::sim::gpu::{FusedLimits, GpuSim, FRAME_SLOTS};
use crate::vk::{
    Access, Buffer, BufferBarrier, BufferUsage, CommandSlot, Format, GpuContext, Image, ImageBarrier,
    MemoryKind, TimestampPool,
};
use anyhow::{Context as _, Result};
use std::time::Instant;

/// How to run an end-to-end measurement.
#[derive(Debug, Clone, Copy)]
pub struct Options {
    /// The offscreen target's size in pixels.
    pub extent: [u32; 2],
    pub warmup: usize,
    pub frames: usize,
    /// As `bench::measure`'s: `Some(0)` runs every object per stage.
    pub fused_slots: Option<u32>,
    /// Read the last frame's pixels back (RGBA8).
    pub capture: bool,
}

/// Everything a run creates, freed in one place whatever fails.
struct Target {
    color: Image,
    depth: Image,
    slots: Vec<CommandSlot>,
    pools: Vec<TimestampPool>,
    readback: Option<Buffer>,
}

impl Target {
    fn new(ctx: &GpuContext, extent: [u32; 2], capture: bool) -> Result<Self> {
        let color = Image::color(ctx, "offscreen colour", extent, Format::Rgba8Unorm)?;
        let depth = match Image::depth(ctx, "offscreen depth", extent) {
            Ok(d) => d,
            Err(e) => {
                color.destroy(ctx);
                return Err(e.into());
            }
        };
        let mut target = Self { color, depth, slots: Vec::new(), pools: Vec::new(), readback: None };
        if let Err(e) = target.fill(ctx, extent, capture) {
            target.destroy(ctx);
            return Err(e);
        }
        Ok(target)
    }

    fn fill(&mut self, ctx: &GpuContext, extent: [u32; 2], capture: bool) -> Result<()> {
        for slot in 0..FRAME_SLOTS {
            self.slots.push(CommandSlot::new(ctx, &format!("offscreen frame[{slot}]"))?);
            if let Some(pool) = TimestampPool::new(ctx, 2)? {
                self.pools.push(pool);
            }
        }
        if capture {
            let bytes = extent[0] as u64 * extent[1] as u64 * 4;
            self.readback = Some(Buffer::new(
                ctx,
                "offscreen readback",
                bytes,
                BufferUsage::TRANSFER_DST,
                MemoryKind::Readback,
            )?);
        }
        Ok(())
    }

    fn destroy(self, ctx: &GpuContext) {
        let _ = ctx.wait_idle();
        for s in self.slots {
            s.destroy(ctx);
        }
        for p in self.pools {
            p.destroy(ctx);
        }
        if let Some(b) = self.readback {
            b.destroy(ctx);
        }
        self.color.destroy(ctx);
        self.depth.destroy(ctx);
    }
}

/// Runs `scene` as the app does, drawing offscreen, for `options.warmup` frames, then measures
/// `options.frames` frames by the wall clock and by timestamps, with shaders from `shaders`.
pub fn measure(
    ctx: &GpuContext,
    scene: &Scene,
    options: Options,
    shaders: &mut ShaderSet,
) -> Result<EndToEnd> {
    // Timed whatever the scene stretches to, as `bench` does: the plausibility check is off.
    let mut model = scene::to_model(scene);
    model.plausibility_off();
    let limits = FusedLimits::for_device(ctx.info()).with_slots(options.fused_slots);
    let mut sim = GpuSim::with_fused_limits(ctx, &model, limits, shaders)?;
    sim.set_stage_timing(false);
    let renderer = SceneRenderer::new(ctx, Format::Rgba8Unorm, Format::Depth32, shaders).and_then(|mut r| {
        match r.set_objects(ctx, &scene::shapes(scene), &scene::colliders(scene)) {
            Ok(()) => Ok(r),
            Err(e) => {
                r.destroy(ctx);
                Err(e)
            }
        }
    });
    let mut renderer = match renderer {
        Ok(r) => r,
        Err(e) => {
            sim.destroy(ctx);
            return Err(e);
        }
    };
    let result = Target::new(ctx, options.extent, options.capture).and_then(|mut target| {
        let result = run(ctx, scene, &model, &mut sim, &mut renderer, &mut target, options);
        target.destroy(ctx);
        result
    });
    renderer.destroy(ctx);
    sim.destroy(ctx);
    result
}

fn run(
    ctx: &GpuContext,
    scene: &Scene,
    model: &crate::sim::model::SimModel,
    sim: &mut GpuSim,
    renderer: &mut SceneRenderer,
    target: &mut Target,
    options: Options,
) -> Result<EndToEnd> {
    let extent = options.extent;
    let mut camera = OrbitCamera::default();
    view::fit_camera(&mut camera, model);
    let uniform = view::camera_uniform(&camera, extent, scene);
    let path = if (0..model.objects.len()).all(|i| sim.runs_fused(i)) { "fused" } else { "per stage" };
    let total = options.warmup + options.frames;
    let mut sim_ms = Vec::with_capacity(options.frames);
    let mut render_ms = Vec::with_capacity(options.frames);
    let mut record_ms = Vec::with_capacity(options.frames);
    let mut submitted = Vec::with_capacity(options.frames + 1);
    let mut start = Instant::now();
    let mut used = [false; FRAME_SLOTS];
    for frame in 0..total {
        let slot = frame % FRAME_SLOTS;
        let measured = frame >= options.warmup;
        if frame == options.warmup {
            // Measure from an empty queue: the warm-up's frames are done.
            for s in &mut target.slots {
                s.wait(ctx)?;
            }
            start = Instant::now();
            submitted.push(start);
        }
        target.slots[slot].wait(ctx)?;
        if std::mem::take(&mut used[slot]) {
            // The frame this slot ran before: its guard and, when it was measured, its timings.
            if let Some(trip) = sim.check_guard()? {
                return Err(trip.into());
            }
            if frame >= options.warmup + FRAME_SLOTS {
                if let Some(t) = sim.read_timing(ctx, slot)? {
                    sim_ms.push(t.total_ms);
                }
                if let Some(pool) = target.pools.get(slot) {
                    let t = pool.read_ns(ctx, 2)?;
                    render_ms.push((t[1] - t[0]).max(0.0) * 1e-6);
                }
            }
        }
        let began = Instant::now();
        renderer.set_camera(slot, &uniform)?;
        let last = frame + 1 == total;
        let mut rec = target.slots[slot].begin(ctx)?;
        sim.record_frame(&mut rec, Access::VertexInput, slot)?;
        let pool = target.pools.get(slot);
        if let Some(pool) = pool {
            rec.reset_timestamps(pool);
            rec.timestamp_after_drawing(pool, 0);
        }
        rec.image_barrier(&[
            ImageBarrier::discarding(target.color.image(), Access::ColorAttachment, Access::ColorAttachment),
            ImageBarrier::discarding(target.depth.image(), Access::DepthAttachment, Access::DepthAttachment),
        ]);
        rec.begin_rendering(target.color.view(), target.depth.view(), extent, SKY);
        let items = view::scene_items(scene, sim.time(), None);
        renderer.record(&mut rec, slot, sim, &items, view::ground(scene));
        rec.end_rendering();
        if let Some(pool) = pool {
            rec.timestamp_after_drawing(pool, 1);
        }
        if let (true, Some(buffer)) = (last, &target.readback) {
            rec.image_barrier(&[ImageBarrier::new(
                target.color.image(),
                Access::ColorAttachment,
                Access::TransferRead,
            )]);
            rec.copy_image_to_buffer(target.color.image(), extent, buffer);
            rec.image_barrier(&[ImageBarrier::new(
                target.color.image(),
                Access::TransferRead,
                Access::ColorAttachment,
            )]);
            rec.barrier(&[BufferBarrier::new(buffer, Access::TransferWrite, Access::HostRead)]);
        }
        target.slots[slot].submit(ctx, rec)?;
        used[slot] = true;
        if measured {
            let now = Instant::now();
            record_ms.push((now - began).as_secs_f64() * 1e3);
            submitted.push(now);
        }
    }
    for s in &mut target.slots {
        s.wait(ctx)?;
    }
    let elapsed = start.elapsed().as_secs_f64() * 1e3;
    if let Some(trip) = sim.check_guard()? {
        return Err(trip.into());
    }
    // The last frames' timings (their slots were not revisited).
    for i in 0..FRAME_SLOTS.min(options.frames) {
        let slot = (total - 1 - i) % FRAME_SLOTS;
        if let Some(t) = sim.read_timing(ctx, slot)? {
            sim_ms.push(t.total_ms);
        }
        if let Some(pool) = target.pools.get(slot) {
            let t = pool.read_ns(ctx, 2)?;
            render_ms.push((t[1] - t[0]).max(0.0) * 1e-6);
        }
    }
    let intervals: Vec<f64> = submitted.windows(2).map(|w| (w[1] - w[0]).as_secs_f64() * 1e3).collect();
    let pixels = match &target.readback {
        Some(b) => {
            Some(b.read::<u8>((extent[0] * extent[1] * 4) as usize).context("reading the last frame")?)
        }
        None => None,
    };
    let spread = |v: &[f64]| (!v.is_empty()).then(|| Spread::of(v));
    Ok(EndToEnd {
        case: String::new(),
        particles: model.objects.iter().map(|o| o.particle_count() as u64).sum(),
        frames: options.frames,
        wall_ms: elapsed / options.frames.max(1) as f64,
        interval: Spread::of(&intervals),
        record: Spread::of(&record_ms),
        sim_gpu: spread(&sim_ms),
        render_gpu: spread(&render_ms),
        path,
        pixels,
    })
}
