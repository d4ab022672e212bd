//! The swapchain of the context's window surface, with one depth buffer and one "rendering
//! finished" semaphore per image. Recreated on resize or when presentation reports it out of
//! date; zero-sized windows (minimised) are never given a swapchain.

use super::context::GpuContext;
use super::error::{Check, VkError};
use super::image::{create_view, Format, Image, ImageRef, ViewRef};
use super::sync::Semaphore;
use ash::vk;

pub struct Swapchain {
    raw: vk::SwapchainKHR,
    format: Format,
    extent: [u32; 2],
    images: Vec<vk::Image>,
    views: Vec<vk::ImageView>,
    /// Signalled by the frame's submission, waited on by presentation; one per image.
    finished: Vec<Semaphore>,
    depth: Image,
}

/// What acquiring an image gave.
pub enum Acquired {
    Image(u32),
    /// The surface changed: recreate the swapchain and try again next frame.
    OutOfDate,
}

impl Swapchain {
    /// A swapchain for `extent` (the window's inner size), replacing `old` when given.
    pub fn new(
        ctx: &GpuContext,
        extent: [u32; 2],
        vsync: bool,
        old: Option<Swapchain>,
    ) -> Result<Self, VkError> {
        let surface =
            ctx.surface.as_ref().ok_or_else(|| VkError::NoDevice("the context has no window".into()))?;
        // SAFETY: the surface belongs to this instance and the physical device supports it.
        let (caps, formats, modes) = unsafe {
            (
                surface.loader.get_physical_device_surface_capabilities(ctx.physical, surface.raw),
                surface.loader.get_physical_device_surface_formats(ctx.physical, surface.raw),
                surface.loader.get_physical_device_surface_present_modes(ctx.physical, surface.raw),
            )
        };
        let caps = caps.check("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")?;
        let formats = formats.check("vkGetPhysicalDeviceSurfaceFormatsKHR")?;
        let modes = modes.check("vkGetPhysicalDeviceSurfacePresentModesKHR")?;
        // UNORM: the fragment shaders write display-ready (gamma-encoded) colours, as ImGui does.
        let chosen = formats
            .iter()
            .find(|f| Format::from_vk(f.format).is_some_and(|f| f != Format::Depth32))
            .copied()
            .ok_or(VkError::Call {
                call: "choosing a surface format (need BGRA8 or RGBA8 UNORM)",
                result: vk::Result::ERROR_FORMAT_NOT_SUPPORTED,
            })?;
        let format = Format::from_vk(chosen.format).unwrap_or(Format::Bgra8Unorm);
        let extent = if caps.current_extent.width != u32::MAX {
            [caps.current_extent.width, caps.current_extent.height]
        } else {
            [
                extent[0].clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                extent[1].clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            ]
        };
        let mode = if vsync {
            vk::PresentModeKHR::FIFO
        } else {
            [vk::PresentModeKHR::MAILBOX, vk::PresentModeKHR::IMMEDIATE]
                .into_iter()
                .find(|m| modes.contains(m))
                .unwrap_or(vk::PresentModeKHR::FIFO)
        };
        let mut count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            count = count.min(caps.max_image_count);
        }
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(surface.raw)
            .min_image_count(count)
            .image_format(chosen.format)
            .image_color_space(chosen.color_space)
            .image_extent(vk::Extent2D { width: extent[0], height: extent[1] })
            .image_array_layers(1)
            .image_usage(vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(vk::CompositeAlphaFlagsKHR::OPAQUE)
            .present_mode(mode)
            .clipped(true)
            .old_swapchain(old.as_ref().map(|o| o.raw).unwrap_or_default());
        // SAFETY: valid surface and device; `old` (if any) is retired by this call and destroyed
        // right after, once the device is idle.
        let created = unsafe { surface.swapchain_loader.create_swapchain(&info, None) };
        if let Some(old) = old {
            let _ = ctx.wait_idle();
            old.destroy(ctx);
        }
        let raw = created.check("vkCreateSwapchainKHR")?;
        let mut this = Self {
            raw,
            format,
            extent,
            images: Vec::new(),
            views: Vec::new(),
            finished: Vec::new(),
            depth: Image::depth(ctx, "depth", extent).inspect_err(|_| {
                // SAFETY: the swapchain is unused.
                unsafe { surface.swapchain_loader.destroy_swapchain(raw, None) };
            })?,
        };
        let rest = (|| -> Result<(), VkError> {
            // SAFETY: `raw` is a live swapchain of this device.
            this.images = unsafe { surface.swapchain_loader.get_swapchain_images(raw) }
                .check("vkGetSwapchainImagesKHR")?;
            for &image in &this.images {
                this.views.push(create_view(ctx, image, chosen.format, vk::ImageAspectFlags::COLOR)?);
                this.finished.push(Semaphore::new(ctx)?);
            }
            Ok(())
        })();
        match rest {
            Ok(()) => Ok(this),
            Err(e) => {
                this.destroy(ctx);
                Err(e)
            }
        }
    }

    pub fn extent(&self) -> [u32; 2] {
        self.extent
    }

    pub fn format(&self) -> Format {
        self.format
    }

    pub fn depth(&self) -> &Image {
        &self.depth
    }

    pub fn image(&self, index: u32) -> ImageRef {
        ImageRef { raw: self.images[index as usize], aspect: vk::ImageAspectFlags::COLOR }
    }

    pub fn view(&self, index: u32) -> ViewRef {
        ViewRef { raw: self.views[index as usize] }
    }

    pub fn finished(&self, index: u32) -> &Semaphore {
        &self.finished[index as usize]
    }

    /// Acquires the next image, signalling `available` when it can be written.
    pub fn acquire(&self, ctx: &GpuContext, available: &Semaphore) -> Result<Acquired, VkError> {
        let surface = ctx.surface.as_ref().expect("a swapchain exists only with a surface");
        // SAFETY: live swapchain; the semaphore is unsignalled (the previous use was waited on).
        match unsafe {
            // No timeout here: a hidden window can hold its images for any time, and a stuck
            // frame is found by its fence first.
            surface.swapchain_loader.acquire_next_image(self.raw, u64::MAX, available.raw, vk::Fence::null())
        } {
            Ok((index, _suboptimal)) => Ok(Acquired::Image(index)),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(Acquired::OutOfDate),
            Err(e) => Err(VkError::from_call("vkAcquireNextImageKHR", e)),
        }
    }

    /// Presents image `index` after its `finished` semaphore; false when the swapchain should
    /// be recreated (out of date or suboptimal).
    pub fn present(&self, ctx: &GpuContext, index: u32) -> Result<bool, VkError> {
        let surface = ctx.surface.as_ref().expect("a swapchain exists only with a surface");
        let waits = [self.finished[index as usize].raw];
        let swapchains = [self.raw];
        let indices = [index];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: the image was acquired and its rendering submitted with `finished` signalled.
        match unsafe { surface.swapchain_loader.queue_present(ctx.queue, &info) } {
            Ok(suboptimal) => Ok(!suboptimal),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(false),
            Err(e) => Err(VkError::from_call("vkQueuePresentKHR", e)),
        }
    }

    /// Frees the swapchain; the device must be idle.
    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        let Some(surface) = ctx.surface.as_ref() else { return };
        // SAFETY: the device is idle (callers wait), so no image, view or semaphore is in use.
        unsafe {
            for v in self.views {
                ctx.device.destroy_image_view(v, None);
            }
            surface.swapchain_loader.destroy_swapchain(self.raw, None);
        }
        for s in self.finished {
            s.destroy(ctx);
        }
        self.depth.destroy(ctx);
    }
}
