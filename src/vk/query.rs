//! GPU timestamps.

use super::context::GpuContext;
use super::error::{Check, VkError};
use ash::vk;

pub struct TimestampPool {
    pub(crate) raw: vk::QueryPool,
    capacity: u32,
    period_ns: f64,
}

impl TimestampPool {
    /// A pool of `capacity` timestamps, or `None` when the device's queue has no timestamps.
    pub fn new(ctx: &GpuContext, capacity: u32) -> Result<Option<Self>, VkError> {
        let Some(period_ns) = ctx.info().timestamp_period_ns else {
            return Ok(None);
        };
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(capacity.max(1));
        // SAFETY: valid device; destroyed in `destroy`.
        let raw = unsafe { ctx.device.create_query_pool(&info, None) }.check("vkCreateQueryPool")?;
        Ok(Some(Self { raw, capacity: capacity.max(1), period_ns }))
    }

    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Reads the first `count` timestamps in nanoseconds (after the submission's fence).
    pub fn read_ns(&self, ctx: &GpuContext, count: u32) -> Result<Vec<f64>, VkError> {
        self.read_range_ns(ctx, 0, count)
    }

    /// Reads timestamps `first..first + count` in nanoseconds. Every one of them must have been
    /// written by a completed submission: the read waits for each (forever, for one never
    /// written).
    pub fn read_range_ns(&self, ctx: &GpuContext, first: u32, count: u32) -> Result<Vec<f64>, VkError> {
        let count = count.min(self.capacity.saturating_sub(first));
        let mut ticks = vec![0u64; count as usize];
        if ticks.is_empty() {
            return Ok(Vec::new());
        }
        // SAFETY: the queries were written by a submission that has completed.
        unsafe {
            ctx.device.get_query_pool_results(
                self.raw,
                first,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .check("vkGetQueryPoolResults")?;
        Ok(ticks.iter().map(|&t| t as f64 * self.period_ns).collect())
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        // SAFETY: no pending submission uses the pool (callers wait first).
        unsafe { ctx.device.destroy_query_pool(self.raw, None) };
    }
}
