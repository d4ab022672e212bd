//! Bandwidth probe: a buffer-to-buffer copy in a compute shader, timed with timestamps. Its
//! bytes per second (read + write) are the roofline the simulation stages are compared with.

use crate::shaders;
use crate::vk::{
    BindingSetLayout, Buffer, BufferUsage, CommandSlot, ComputePipeline, DescriptorArena, GpuContext,
    MemoryKind, TimestampPool,
};
use anyhow::{Context as _, Result};

/// Bytes copied per second (counting the read and the write), median of `runs`, and the size.
pub fn measure(ctx: &GpuContext, max_bytes: u64, runs: usize) -> Result<(f64, u64)> {
    let bytes =
        max_bytes.min(ctx.info().max_storage_buffer_range).min(ctx.info().device_local_bytes / 4) / 16 * 16;
    let layout = BindingSetLayout::storage_buffers(ctx, 2)?;
    let mut arena = DescriptorArena::new(ctx, 1, 2)?;
    let spirv = shaders::embedded("bench_copy.comp")?;
    let pipeline = ComputePipeline::new(ctx, "bench copy", &spirv, &layout, &[])?;
    let src = Buffer::new(
        ctx,
        "bench src",
        bytes,
        BufferUsage::STORAGE | BufferUsage::TRANSFER_DST,
        MemoryKind::GpuOnly,
    )?;
    let dst = Buffer::new(ctx, "bench dst", bytes, BufferUsage::STORAGE, MemoryKind::GpuOnly)?;
    let pool = TimestampPool::new(ctx, 2)?;
    let mut slot = CommandSlot::new(ctx, "bench copy")?;
    let result = (|| -> Result<f64> {
        let pool = pool.as_ref().context("the device has no timestamps")?;
        let set = arena.allocate(ctx, &layout, &[&src, &dst])?;
        let groups = (bytes / 16).div_ceil(256) as u32;
        let (x, y) = (groups.min(1024), groups.div_ceil(1024));
        let mut times = Vec::new();
        for _ in 0..runs {
            let mut rec = slot.begin(ctx)?;
            rec.reset_timestamps(pool);
            rec.timestamp(pool, 0);
            rec.dispatch(&pipeline, set, [x, y, 1]);
            rec.timestamp(pool, 1);
            slot.submit(ctx, rec)?;
            slot.wait(ctx)?;
            let t = pool.read_ns(ctx, 2)?;
            times.push((t[1] - t[0]) * 1e-9);
        }
        times.sort_by(f64::total_cmp);
        Ok(2.0 * bytes as f64 / times[times.len() / 2])
    })();
    let _ = ctx.wait_idle();
    slot.destroy(ctx);
    if let Some(p) = pool {
        p.destroy(ctx);
    }
    src.destroy(ctx);
    dst.destroy(ctx);
    pipeline.destroy(ctx);
    arena.destroy(ctx);
    layout.destroy(ctx);
    Ok((result?, bytes))
}
