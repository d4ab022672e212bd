//! Thin, safe-ish wrappers over raw Vulkan (ash). All `unsafe` in the crate but the signal handler
//! of `temporary` lives in this module.
//!
//! Invariants:
//! - [`GpuContext`] is the one owner of destruction order: entry -> instance -> debug messenger ->
//!   device -> allocator are created in that order and destroyed in reverse after `device_wait_idle`.
//!   Every other object is freed through a consuming `destroy(self, &GpuContext)`; a resource that
//!   is dropped without it shows up in the allocator's leak report. A device that is stuck (a
//!   submission outlived `ContextOptions::gpu_timeout`) keeps everything instead.
//! - Every allocation is named; the allocator logs leaks on shutdown and
//!   [`GpuContext::live_allocations`] exposes the same report to tests.
//! - Barriers go through [`barrier`]: call sites name accesses ([`Access`]), and one place maps them
//!   to synchronization2 stage/access masks. No ALL_COMMANDS barriers.
//! - Validation (with synchronization validation) is opt-in per context; the debug messenger counts
//!   validation warnings and errors in a [`ValidationCanary`] that tests assert to be zero.

mod barrier;
mod buffer;
mod commands;
mod context;
mod debug;
mod device;
mod error;
mod graphics;
mod image;
mod pipeline;
mod pipeline_cache;
mod query;
mod retire;
mod swapchain;
mod sync;
mod ui;

pub use barrier::{Access, BufferBarrier, ImageBarrier};
pub use buffer::{Buffer, BufferUsage, MemoryKind};
pub use commands::{CommandSlot, Recorder};
pub use context::{
    any_device_stuck, exit_without_teardown, ContextOptions, GpuContext, WindowHandles, DEFAULT_GPU_TIMEOUT,
};
pub use debug::ValidationCanary;
pub use device::{DeviceInfo, DeviceKind};
pub use error::VkError;
pub use graphics::{Blend, GraphicsDesc, GraphicsPipeline, Topology, VertexFormat, VertexLayout};
pub use image::{Format, Image, ImageRef, ViewRef};
pub use pipeline::{BindingKind, BindingSet, BindingSetLayout, ComputePipeline, DescriptorArena};
pub use query::TimestampPool;
pub use retire::{RetireQueue, Retired};
pub use swapchain::{Acquired, Swapchain};
pub use sync::Semaphore;
pub use ui::UiRenderer;
