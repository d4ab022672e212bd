//! Deferred release: objects replaced while frames that use them may still be running (old
//! pipelines after a hot reload) wait here until those frames are known to have completed.

use super::context::GpuContext;
use super::graphics::GraphicsPipeline;
use super::pipeline::ComputePipeline;

/// Something to destroy later.
pub enum Retired {
    Compute(ComputePipeline),
    Graphics(GraphicsPipeline),
}

impl Retired {
    fn destroy(self, ctx: &GpuContext) {
        match self {
            Retired::Compute(p) => p.destroy(ctx),
            Retired::Graphics(p) => p.destroy(ctx),
        }
    }
}

/// Objects tagged with the index of the first frame that no longer uses them.
#[derive(Default)]
pub struct RetireQueue {
    items: Vec<(u64, Retired)>,
}

impl RetireQueue {
    /// Queues `items`, used by frames before `first_unused`.
    pub fn push(&mut self, first_unused: u64, items: impl IntoIterator<Item = Retired>) {
        self.items.extend(items.into_iter().map(|i| (first_unused, i)));
    }

    /// Destroys everything whose frames have all completed: frames `0..completed` are done.
    pub fn release(&mut self, ctx: &GpuContext, completed: u64) {
        let (done, keep): (Vec<_>, Vec<_>) =
            std::mem::take(&mut self.items).into_iter().partition(|(f, _)| *f <= completed);
        self.items = keep;
        for (_, item) in done {
            item.destroy(ctx);
        }
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Destroys everything; the device must be idle.
    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        for (_, item) in self.items {
            item.destroy(ctx);
        }
    }
}
