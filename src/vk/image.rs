//! Images: attachments (depth buffers, offscreen colour targets; owned, with a named allocation)
//! and plain references to images owned elsewhere (swapchain images).

use super::context::GpuContext;
use super::error::{Check, VkError};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

/// An image handle with the aspect barriers and copies address; valid while its owner lives.
#[derive(Clone, Copy, Debug)]
pub struct ImageRef {
    pub(crate) raw: vk::Image,
    pub(crate) aspect: vk::ImageAspectFlags,
}

/// An image view handle, valid while its owner lives.
#[derive(Clone, Copy, Debug)]
pub struct ViewRef {
    pub(crate) raw: vk::ImageView,
}

/// Pixel formats the renderer uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Depth32,
    Bgra8Unorm,
    Rgba8Unorm,
}

impl Format {
    pub(crate) fn to_vk(self) -> vk::Format {
        match self {
            Format::Depth32 => vk::Format::D32_SFLOAT,
            Format::Bgra8Unorm => vk::Format::B8G8R8A8_UNORM,
            Format::Rgba8Unorm => vk::Format::R8G8B8A8_UNORM,
        }
    }

    pub fn is_depth(self) -> bool {
        self == Format::Depth32
    }

    pub(crate) fn aspect(self) -> vk::ImageAspectFlags {
        if self.is_depth() {
            vk::ImageAspectFlags::DEPTH
        } else {
            vk::ImageAspectFlags::COLOR
        }
    }

    pub(crate) fn from_vk(f: vk::Format) -> Option<Self> {
        match f {
            vk::Format::D32_SFLOAT => Some(Format::Depth32),
            vk::Format::B8G8R8A8_UNORM => Some(Format::Bgra8Unorm),
            vk::Format::R8G8B8A8_UNORM => Some(Format::Rgba8Unorm),
            _ => None,
        }
    }
}

/// A device-local 2-D image with one view.
pub struct Image {
    raw: vk::Image,
    view: vk::ImageView,
    allocation: Allocation,
    format: Format,
}

impl Image {
    /// A depth attachment of `extent` pixels.
    pub fn depth(ctx: &GpuContext, name: &str, extent: [u32; 2]) -> Result<Self, VkError> {
        Self::attachment(ctx, name, extent, Format::Depth32)
    }

    /// A colour attachment of `extent` pixels that copies can read (an offscreen target).
    pub fn color(ctx: &GpuContext, name: &str, extent: [u32; 2], format: Format) -> Result<Self, VkError> {
        Self::attachment(ctx, name, extent, format)
    }

    fn attachment(ctx: &GpuContext, name: &str, extent: [u32; 2], format: Format) -> Result<Self, VkError> {
        let usage = if format.is_depth() {
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT
        } else {
            vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC
        };
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format.to_vk())
            .extent(vk::Extent3D { width: extent[0].max(1), height: extent[1].max(1), depth: 1 })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid device and create info; destroyed in `destroy`.
        let raw = unsafe { ctx.device.create_image(&info, None) }.check("vkCreateImage")?;
        // SAFETY: `raw` was just created on this device.
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let allocation = ctx.allocator().allocate(&AllocationCreateDesc {
            name,
            requirements,
            location: MemoryLocation::GpuOnly,
            linear: false,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        });
        let allocation = match allocation {
            Ok(a) => a,
            Err(source) => {
                // SAFETY: unused image without memory.
                unsafe { ctx.device.destroy_image(raw, None) };
                return Err(VkError::Allocation { what: name.into(), source });
            }
        };
        let view = (|| {
            // SAFETY: the allocation satisfies the image's requirements.
            unsafe { ctx.device.bind_image_memory(raw, allocation.memory(), allocation.offset()) }
                .check("vkBindImageMemory")?;
            create_view(ctx, raw, format.to_vk(), format.aspect())
        })();
        match view {
            Ok(view) => {
                ctx.set_name(raw, name);
                Ok(Self { raw, view, allocation, format })
            }
            Err(e) => {
                let _ = ctx.allocator().free(allocation);
                // SAFETY: unused image.
                unsafe { ctx.device.destroy_image(raw, None) };
                Err(e)
            }
        }
    }

    pub fn image(&self) -> ImageRef {
        ImageRef { raw: self.raw, aspect: self.format.aspect() }
    }

    pub fn view(&self) -> ViewRef {
        ViewRef { raw: self.view }
    }

    pub fn format(&self) -> Format {
        self.format
    }

    pub fn destroy(self, ctx: &GpuContext) {
        if ctx.stuck() {
            return; // kept: the GPU may still use it
        }
        // SAFETY: the GPU no longer uses the image (callers wait first).
        unsafe {
            ctx.device.destroy_image_view(self.view, None);
            ctx.device.destroy_image(self.raw, None);
        }
        if let Err(e) = ctx.allocator().free(self.allocation) {
            log::error!("freeing an image: {e}");
        }
    }
}

pub(crate) fn create_view(
    ctx: &GpuContext,
    image: vk::Image,
    format: vk::Format,
    aspect: vk::ImageAspectFlags,
) -> Result<vk::ImageView, VkError> {
    let info = vk::ImageViewCreateInfo::default()
        .image(image)
        .view_type(vk::ImageViewType::TYPE_2D)
        .format(format)
        .subresource_range(
            vk::ImageSubresourceRange::default().aspect_mask(aspect).level_count(1).layer_count(1),
        );
    // SAFETY: `image` is a live image of this device with `format`.
    unsafe { ctx.device.create_image_view(&info, None) }.check("vkCreateImageView")
}
