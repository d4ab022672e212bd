//! The error type at the Vulkan boundary.

use ash::vk;

#[derive(Debug, thiserror::Error)]
pub enum VkError {
    #[error("the Vulkan loader (libvulkan.so.1) could not be loaded: {0}; install it (Debian: libvulkan1)")]
    Loader(String),
    #[error("no usable Vulkan device: {0}")]
    NoDevice(String),
    #[error("bad device selector: {0}")]
    DeviceSelector(String),
    #[error("the Vulkan validation layer VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)")]
    NoValidationLayer,
    #[error("the GPU device was lost (driver reset or crash); the simulation state on it is gone")]
    DeviceLost,
    #[error("the GPU did not finish its work within {seconds} s, so it is taken to be stuck and nothing more can run on it: the work may be too slow for this device (give it longer with --gpu-timeout SECONDS), the device may have hung, or a shader you edited (--shaders, or the app's hot reload) may loop forever")]
    Stuck { seconds: f64 },
    #[error("GPU memory exhausted while allocating {what}")]
    OutOfMemory { what: String },
    #[error("{call} failed: {result}")]
    Call { call: &'static str, result: vk::Result },
    #[error("GPU allocation of {what} failed: {source}")]
    Allocation {
        what: String,
        #[source]
        source: gpu_allocator::AllocationError,
    },
}

/// Attaches the Vulkan call name to a `vk::Result`, singling out device loss and memory exhaustion.
pub(crate) trait Check<T> {
    fn check(self, call: &'static str) -> Result<T, VkError>;
}

impl<T> Check<T> for Result<T, vk::Result> {
    fn check(self, call: &'static str) -> Result<T, VkError> {
        self.map_err(|result| VkError::from_call(call, result))
    }
}

impl VkError {
    pub(crate) fn from_call(call: &'static str, result: vk::Result) -> Self {
        match result {
            vk::Result::ERROR_DEVICE_LOST => VkError::DeviceLost,
            vk::Result::ERROR_OUT_OF_DEVICE_MEMORY | vk::Result::ERROR_OUT_OF_HOST_MEMORY => {
                VkError::OutOfMemory { what: call.to_string() }
            }
            result => VkError::Call { call, result },
        }
    }
}
