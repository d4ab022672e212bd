//! The GPU context: entry, instance, optional validation, optional window surface, device, queue,
//! allocator and a command pool. It is the single owner of their destruction order (see the
//! module docs of `vk`).

use super::debug::{messenger_callback, ValidationCanary};
use super::device::{self, DeviceInfo, DeviceKind};
use super::error::{Check, VkError};
use super::pipeline_cache::PipelineCache;
use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};
use std::ffi::{c_char, CStr};
use std::mem::ManuallyDrop;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// How to create a context.
#[derive(Debug, Clone, Default)]
pub struct ContextOptions {
    /// Enable VK_LAYER_KHRONOS_validation with synchronization validation.
    pub validation: bool,
    /// Device index or part of its name; `None` picks the most capable kind.
    pub device: Option<String>,
    /// How long to wait for a submission before the device is taken to be stuck (a shader
    /// that never ends); `None`: `DEFAULT_GPU_TIMEOUT`, times `CPU_TIMEOUT_SCALE` on a CPU
    /// device.
    pub gpu_timeout: Option<std::time::Duration>,
}

/// The default of `ContextOptions::gpu_timeout`: far above any one submission msdsim makes
/// (a frame's substeps), also on lavapipe.
pub const DEFAULT_GPU_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(60);
/// A CPU device (lavapipe) runs the same work one to two orders of magnitude slower, so a
/// legitimate heavy frame there outlasts the GPU's default.
pub const CPU_TIMEOUT_SCALE: u32 = 10;

/// A window to present to: its platform handles.
#[derive(Debug, Clone, Copy)]
pub struct WindowHandles {
    pub display: RawDisplayHandle,
    pub window: RawWindowHandle,
}

pub(crate) struct Surface {
    pub loader: ash::khr::surface::Instance,
    pub raw: vk::SurfaceKHR,
    pub swapchain_loader: ash::khr::swapchain::Device,
}

pub struct GpuContext {
    // Field order is not relied on: Drop tears down explicitly in reverse creation order.
    _entry: ash::Entry,
    pub(crate) instance: ash::Instance,
    debug: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    pub(crate) debug_device: Option<ash::ext::debug_utils::Device>,
    canary: Arc<ValidationCanary>,
    pub(crate) physical: vk::PhysicalDevice,
    pub(crate) device: ash::Device,
    pub(crate) queue: vk::Queue,
    pub(crate) command_pool: vk::CommandPool,
    pub(crate) surface: Option<Surface>,
    allocator: ManuallyDrop<Arc<Mutex<Allocator>>>,
    info: DeviceInfo,
    timeout: std::time::Duration,
    /// A submission outlived `timeout`: the GPU may still be running it, so nothing it could
    /// use is freed or waited for again (see `stuck`).
    stuck: AtomicBool,
    /// The compute pipelines created on the device, for reuse (`vk::pipeline_cache`).
    pipelines: Mutex<PipelineCache>,
}

impl GpuContext {
    /// A headless context.
    pub fn new(options: &ContextOptions) -> Result<Self, VkError> {
        Self::create(options, None)
    }

    /// A context that can present to `window` (the device chosen must support it).
    pub fn with_window(options: &ContextOptions, window: WindowHandles) -> Result<Self, VkError> {
        Self::create(options, Some(window))
    }

    fn create(options: &ContextOptions, window: Option<WindowHandles>) -> Result<Self, VkError> {
        // SAFETY: loading the system Vulkan loader; no other Vulkan state exists yet.
        let entry = unsafe { ash::Entry::load() }.map_err(|e| VkError::Loader(e.to_string()))?;
        let canary = Arc::new(ValidationCanary::default());

        let mut layers: Vec<*const c_char> = Vec::new();
        let mut extensions: Vec<*const c_char> = Vec::new();
        if let Some(w) = window {
            let required = ash_window::enumerate_required_extensions(w.display)
                .map_err(|e| VkError::from_call("vkEnumerateInstanceExtensionProperties (surface)", e))?;
            extensions.extend_from_slice(required);
        }
        if options.validation {
            // SAFETY: plain enumeration on a loaded entry.
            let available = unsafe { entry.enumerate_instance_layer_properties() }
                .check("vkEnumerateInstanceLayerProperties")?;
            if !available.iter().any(|l| l.layer_name_as_c_str() == Ok(VALIDATION_LAYER)) {
                return Err(VkError::NoValidationLayer);
            }
            layers.push(VALIDATION_LAYER.as_ptr());
            extensions.push(ash::ext::debug_utils::NAME.as_ptr());
            extensions.push(ash::ext::validation_features::NAME.as_ptr());
        }

        let app = vk::ApplicationInfo::default()
            .application_name(c"msdsim")
            .engine_name(c"msdsim")
            .api_version(vk::API_VERSION_1_3);
        let enabled = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(&enabled);
        let mut messenger_info = messenger_create_info(&canary);
        let mut create = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_layer_names(&layers)
            .enabled_extension_names(&extensions);
        if options.validation {
            create = create.push_next(&mut features).push_next(&mut messenger_info);
        }
        // SAFETY: every pointer in `create` refers to locals that outlive the call.
        let instance = unsafe { entry.create_instance(&create, None) }.map_err(|e| match e {
            vk::Result::ERROR_INCOMPATIBLE_DRIVER => VkError::NoDevice(
                "the Vulkan loader found no driver; install one (Debian: mesa-vulkan-drivers provides lavapipe), \
                 or point VK_DRIVER_FILES at the driver's ICD file"
                    .into(),
            ),
            e => VkError::from_call("vkCreateInstance", e),
        })?;

        let mut debug = None;
        let mut surface = None;
        let rest = (|| -> Result<_, VkError> {
            if options.validation {
                let loader = ash::ext::debug_utils::Instance::new(&entry, &instance);
                // SAFETY: the canary outlives the messenger: both are destroyed in Drop, messenger first.
                let m = unsafe { loader.create_debug_utils_messenger(&messenger_create_info(&canary), None) }
                    .check("vkCreateDebugUtilsMessengerEXT")?;
                debug = Some((loader, m));
            }
            if let Some(w) = window {
                // SAFETY: the handles come from a live window that outlives the context (the app
                // drops the context before the window).
                let raw = unsafe { ash_window::create_surface(&entry, &instance, w.display, w.window, None) }
                    .check("vkCreateSurfaceKHR")?;
                surface = Some((ash::khr::surface::Instance::new(&entry, &instance), raw));
            }
            Self::open_device(&instance, options, surface.as_ref())
        })();
        match rest {
            Ok((candidate, device, allocator, command_pool)) => {
                // SAFETY: the device was created with one queue in this family.
                let queue = unsafe { device.get_device_queue(candidate.queue_family, 0) };
                let debug_device =
                    debug.as_ref().map(|_| ash::ext::debug_utils::Device::new(&instance, &device));
                let surface = surface.map(|(loader, raw)| Surface {
                    loader,
                    raw,
                    swapchain_loader: ash::khr::swapchain::Device::new(&instance, &device),
                });
                log::info!("GPU device: {}", candidate.info);
                let timeout = options.gpu_timeout.unwrap_or(match candidate.info.kind {
                    DeviceKind::Cpu => DEFAULT_GPU_TIMEOUT * CPU_TIMEOUT_SCALE,
                    _ => DEFAULT_GPU_TIMEOUT,
                });
                Ok(Self {
                    _entry: entry,
                    instance,
                    debug,
                    debug_device,
                    canary,
                    physical: candidate.physical,
                    device,
                    queue,
                    command_pool,
                    surface,
                    allocator: ManuallyDrop::new(Arc::new(Mutex::new(allocator))),
                    info: candidate.info,
                    timeout,
                    stuck: AtomicBool::new(false),
                    pipelines: Mutex::new(PipelineCache::default()),
                })
            }
            Err(e) => {
                // SAFETY: tearing down what this function created, in reverse order.
                unsafe {
                    if let Some((loader, raw)) = &surface {
                        loader.destroy_surface(*raw, None);
                    }
                    if let Some((loader, m)) = &debug {
                        loader.destroy_debug_utils_messenger(*m, None);
                    }
                    instance.destroy_instance(None);
                }
                Err(e)
            }
        }
    }

    fn open_device(
        instance: &ash::Instance,
        options: &ContextOptions,
        surface: Option<&(ash::khr::surface::Instance, vk::SurfaceKHR)>,
    ) -> Result<(device::Candidate, ash::Device, Allocator, vk::CommandPool), VkError> {
        let presents = |physical: vk::PhysicalDevice, family: u32| match surface {
            // SAFETY: valid physical device, family index and surface of this instance.
            Some((loader, raw)) => {
                unsafe { loader.get_physical_device_surface_support(physical, family, *raw) }.unwrap_or(false)
            }
            None => true,
        };
        let (list, skipped) = device::candidates(instance, &presents)?;
        let candidate = device::choose(list, &skipped, options.device.as_deref())?;
        let priorities = [1.0f32];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(candidate.queue_family)
            .queue_priorities(&priorities)];
        let mut f13 = vk::PhysicalDeviceVulkan13Features::default()
            .synchronization2(true)
            .maintenance4(true)
            .dynamic_rendering(true);
        let extensions: Vec<*const c_char> =
            if surface.is_some() { vec![ash::khr::swapchain::NAME.as_ptr()] } else { Vec::new() };
        // The batched step shaders index their bindings' descriptor arrays by workgroup.
        let features =
            vk::PhysicalDeviceFeatures::default().shader_storage_buffer_array_dynamic_indexing(true);
        let create = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queues)
            .enabled_features(&features)
            .enabled_extension_names(&extensions)
            .push_next(&mut f13);
        // SAFETY: the physical device came from this instance; pointers outlive the call.
        let device =
            unsafe { instance.create_device(candidate.physical, &create, None) }.check("vkCreateDevice")?;
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device: candidate.physical,
            debug_settings: gpu_allocator::AllocatorDebugSettings {
                log_leaks_on_shutdown: true,
                ..Default::default()
            },
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        });
        let allocator = match allocator {
            Ok(a) => a,
            Err(source) => {
                // SAFETY: nothing was created from the device yet.
                unsafe { device.destroy_device(None) };
                return Err(VkError::Allocation { what: "the allocator".into(), source });
            }
        };
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(candidate.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: valid device; the pool is destroyed in Drop before the device.
        match unsafe { device.create_command_pool(&pool_info, None) }.check("vkCreateCommandPool") {
            Ok(pool) => Ok((candidate, device, allocator, pool)),
            Err(e) => {
                drop(allocator);
                // SAFETY: the allocator holding device memory is gone; nothing else exists.
                unsafe { device.destroy_device(None) };
                Err(e)
            }
        }
    }

    pub fn info(&self) -> &DeviceInfo {
        &self.info
    }

    /// Every device that qualifies, in the order `--device INDEX` counts them, and the reasons
    /// the others were skipped.
    pub fn devices(&self) -> Result<(Vec<DeviceInfo>, Vec<String>), VkError> {
        let (list, skipped) = device::candidates(&self.instance, &|_, _| true)?;
        Ok((list.into_iter().map(|c| c.info).collect(), skipped))
    }

    /// Validation warnings and errors counted so far (always zero without validation).
    pub fn canary(&self) -> &ValidationCanary {
        &self.canary
    }

    pub fn validation_enabled(&self) -> bool {
        self.debug.is_some()
    }

    pub(crate) fn allocator(&self) -> MutexGuard<'_, Allocator> {
        self.allocator.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The shared allocator, for the UI renderer (which must be destroyed before the context).
    pub(crate) fn allocator_handle(&self) -> Arc<Mutex<Allocator>> {
        Arc::clone(&self.allocator)
    }

    /// Names of the allocations that are still alive (the allocator's leak report).
    pub fn live_allocations(&self) -> Vec<String> {
        self.allocator().generate_report().allocations.into_iter().map(|a| a.name).collect()
    }

    /// Waits until the queue has finished all submitted work (at once an error when the device
    /// is stuck).
    pub fn wait_idle(&self) -> Result<(), VkError> {
        if self.stuck() {
            return Err(self.stuck_error());
        }
        // An empty submission's fence signals once all earlier work on the queue is done, and
        // can be waited for with the timeout (vkDeviceWaitIdle has none).
        // SAFETY: valid device; no other thread submits to this queue; the fence is destroyed
        // only after it signalled (or, stuck, never).
        unsafe {
            let fence =
                self.device.create_fence(&vk::FenceCreateInfo::default(), None).check("vkCreateFence")?;
            self.device.queue_submit2(self.queue, &[], fence).check("vkQueueSubmit2")?;
            self.wait_fence(fence)?;
            self.device.destroy_fence(fence, None);
            self.device.device_wait_idle().check("vkDeviceWaitIdle")
        }
    }

    /// Waits for a submitted `fence` with the timeout; past it, or when the device is already
    /// stuck, the device is stuck (`stuck`) and the fence must not be destroyed.
    pub(crate) fn wait_fence(&self, fence: vk::Fence) -> Result<(), VkError> {
        if self.stuck() {
            return Err(self.stuck_error());
        }
        // SAFETY: the fence belongs to this device and was submitted.
        match unsafe { self.device.wait_for_fences(&[fence], true, self.fence_timeout_ns()) } {
            Err(vk::Result::TIMEOUT) => Err(self.stuck_error()),
            result => result.check("vkWaitForFences"),
        }
    }

    /// Whether a submission outlived the timeout. The GPU may still be running it (a shader
    /// that never ends), so from then on every wait fails at once and every `destroy` keeps
    /// its object: freeing memory a running shader uses is undefined, and the driver's own
    /// teardown would wait for that work for ever. The process is expected to end
    /// (`exit_without_teardown`).
    pub fn stuck(&self) -> bool {
        self.stuck.load(Ordering::Acquire)
    }

    /// The compute pipelines this context keeps for reuse.
    pub(crate) fn pipeline_cache(&self) -> MutexGuard<'_, PipelineCache> {
        self.pipelines.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn fence_timeout_ns(&self) -> u64 {
        self.timeout.as_nanos().min(u64::MAX as u128) as u64
    }

    /// Marks the device stuck and says so.
    pub(crate) fn stuck_error(&self) -> VkError {
        self.stuck.store(true, Ordering::Release);
        ANY_STUCK.store(true, Ordering::Release);
        VkError::Stuck { seconds: self.timeout.as_secs_f64() }
    }

    /// Gives a Vulkan object a name shown in validation messages (when validation is on).
    pub(crate) fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(debug) = &self.debug_device {
            let Ok(name) = std::ffi::CString::new(name) else { return };
            let info = vk::DebugUtilsObjectNameInfoEXT::default().object_handle(handle).object_name(&name);
            // SAFETY: `handle` is a live object of this device; naming has no other effect.
            let _ = unsafe { debug.set_debug_utils_object_name(&info) };
        }
    }
}

fn messenger_create_info(canary: &Arc<ValidationCanary>) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
    vk::DebugUtilsMessengerCreateInfoEXT::default()
        .message_severity(
            vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
                | vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                | vk::DebugUtilsMessageSeverityFlagsEXT::INFO,
        )
        .message_type(
            vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
        )
        .pfn_user_callback(Some(messenger_callback))
        .user_data(Arc::as_ptr(canary) as *mut std::ffi::c_void)
}

/// Set once any context's device is stuck: the process must then end through
/// `exit_without_teardown`, whatever error it reports.
static ANY_STUCK: AtomicBool = AtomicBool::new(false);

/// Whether a device of this process got stuck.
pub fn any_device_stuck() -> bool {
    ANY_STUCK.load(Ordering::Acquire)
}

/// Ends the process with `code` without running exit handlers: after a stuck device, the
/// driver's handlers would wait for the work that never ends.
pub fn exit_without_teardown(code: i32) -> ! {
    // SAFETY: `_exit` ends the process; nothing after it runs.
    unsafe { libc::_exit(code) }
}

impl Drop for GpuContext {
    fn drop(&mut self) {
        if self.stuck() {
            return; // everything is kept (see `stuck`)
        }
        // SAFETY: reverse creation order after the GPU is idle; every child object has been
        // destroyed by its owner's `destroy` (leaks are reported by the allocator below).
        unsafe {
            let _ = self.device.device_wait_idle();
            for p in self.pipeline_cache().drain() {
                super::pipeline::destroy_cached(self, p);
            }
            self.device.destroy_command_pool(self.command_pool, None);
            let allocator = ManuallyDrop::take(&mut self.allocator);
            if Arc::strong_count(&allocator) > 1 {
                log::error!("the allocator is still shared at shutdown (a UI renderer was not destroyed)");
            }
            drop(allocator);
            self.device.destroy_device(None);
            if let Some(surface) = self.surface.take() {
                surface.loader.destroy_surface(surface.raw, None);
            }
            if let Some((loader, messenger)) = self.debug.take() {
                loader.destroy_debug_utils_messenger(messenger, None);
            }
            self.instance.destroy_instance(None);
        }
    }
}
