//! Physical device choice: discrete > integrated > virtual > CPU, overridable by a selector (an
//! index into the device list or a case-insensitive part of the device name).

use super::error::{Check, VkError};
use ash::vk;

/// The kind of a physical device, in order of preference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum DeviceKind {
    Discrete,
    Integrated,
    Virtual,
    Cpu,
    Other,
}

impl DeviceKind {
    fn from_vk(t: vk::PhysicalDeviceType) -> Self {
        match t {
            vk::PhysicalDeviceType::DISCRETE_GPU => Self::Discrete,
            vk::PhysicalDeviceType::INTEGRATED_GPU => Self::Integrated,
            vk::PhysicalDeviceType::VIRTUAL_GPU => Self::Virtual,
            vk::PhysicalDeviceType::CPU => Self::Cpu,
            _ => Self::Other,
        }
    }
}

/// What the rest of the program needs to know about the chosen device.
#[derive(Debug, Clone)]
pub struct DeviceInfo {
    pub name: String,
    pub kind: DeviceKind,
    pub driver: String,
    pub api_version: String,
    /// Nanoseconds per timestamp tick; `None` when the queue has no timestamps.
    pub timestamp_period_ns: Option<f64>,
    /// Largest single storage buffer binding, in bytes.
    pub max_storage_buffer_range: u64,
    /// Largest workgroup count per dispatch dimension.
    pub max_workgroup_count: [u32; 3],
    /// Size of the largest device-local memory heap, in bytes.
    pub device_local_bytes: u64,
    /// Shared memory a compute workgroup may use, in bytes.
    pub max_shared_memory: u32,
    /// Invocations per subgroup (a warp: 32 on NVIDIA; lavapipe: its SIMD width).
    pub subgroup_size: u32,
    /// Compute shaders may use the clustered subgroup reductions (`subgroupClusteredAdd`).
    pub subgroup_clustered: bool,
    /// Loop iterations an invocation may run in all, its loops together, before the driver
    /// ends every loop early: lavapipe (Mesa's llvmpipe) stops a shader's loops after 65,535
    /// (`LP_MAX_TGSI_LOOP_ITERATIONS` in gallivm, one counter shared by all its loops and never
    /// reset), silently. `None`: no such limit.
    pub loop_iteration_limit: Option<u32>,
    /// Storage buffer descriptors a compute stage may use (`maxPerStageDescriptorStorageBuffers`,
    /// within `maxDescriptorSetStorageBuffers` and `maxPerStageResources`).
    pub max_stage_storage_buffers: u32,
}

impl std::fmt::Display for DeviceInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({:?}, {}, Vulkan {})", self.name, self.kind, self.driver, self.api_version)
    }
}

pub(crate) struct Candidate {
    pub physical: vk::PhysicalDevice,
    pub queue_family: u32,
    pub info: DeviceInfo,
}

/// Lists the devices that support what the simulator needs (Vulkan 1.3 with synchronization2,
/// maintenance4 (workgroup sizes from specialization constants) and
/// a queue family with graphics and compute), with the reasons others were skipped.
pub(crate) fn candidates(
    instance: &ash::Instance,
    presents: &dyn Fn(vk::PhysicalDevice, u32) -> bool,
) -> Result<(Vec<Candidate>, Vec<String>), VkError> {
    // SAFETY: `instance` is a live instance; the returned handles live as long as it does.
    let physicals = unsafe { instance.enumerate_physical_devices() }.check("vkEnumeratePhysicalDevices")?;
    let mut found = Vec::new();
    let mut skipped = Vec::new();
    for physical in physicals {
        let mut v11 = vk::PhysicalDeviceVulkan11Properties::default();
        let mut v12 = vk::PhysicalDeviceVulkan12Properties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut v12).push_next(&mut v11);
        let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
        let mut features2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f13);
        // SAFETY: valid physical device from this instance; the chained structs outlive the calls.
        let (families, memory) = unsafe {
            instance.get_physical_device_properties2(physical, &mut props2);
            instance.get_physical_device_features2(physical, &mut features2);
            (
                instance.get_physical_device_queue_family_properties(physical),
                instance.get_physical_device_memory_properties(physical),
            )
        };
        let props = props2.properties;
        let dynamic_indexing = features2.features.shader_storage_buffer_array_dynamic_indexing == vk::TRUE;
        let sync2 = f13.synchronization2 == vk::TRUE
            && f13.maintenance4 == vk::TRUE
            && f13.dynamic_rendering == vk::TRUE
            && dynamic_indexing;
        let name = props
            .device_name_as_c_str()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|_| "unnamed device".into());
        let driver = format!(
            "{} {}",
            v12.driver_name_as_c_str().map(|s| s.to_string_lossy()).unwrap_or_default(),
            v12.driver_info_as_c_str().map(|s| s.to_string_lossy()).unwrap_or_default()
        )
        .trim()
        .to_string();
        let api = props.api_version;
        if api < vk::API_VERSION_1_3 || !sync2 {
            skipped.push(format!(
                "{name}: needs Vulkan 1.3 with synchronization2, maintenance4, dynamic rendering and dynamic indexing of storage buffer arrays"
            ));
            continue;
        }
        // The step shaders vote across a subgroup (the contact lists' rebuild flag); the hash
        // scan and the implicit method's dot products add across one, the latter keeping a
        // subgroup's sum for every four invocations (glsl/include/reduce.glsl).
        let vote = vk::SubgroupFeatureFlags::BASIC
            | vk::SubgroupFeatureFlags::VOTE
            | vk::SubgroupFeatureFlags::ARITHMETIC;
        if !v11.subgroup_supported_stages.contains(vk::ShaderStageFlags::COMPUTE)
            || !v11.subgroup_supported_operations.contains(vote)
        {
            skipped.push(format!("{name}: needs subgroup vote and arithmetic operations in compute shaders"));
            continue;
        }
        if v11.subgroup_size < 4 {
            skipped.push(format!(
                "{name}: needs subgroups of at least 4 invocations (has {})",
                v11.subgroup_size
            ));
            continue;
        }
        let wanted = vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE;
        let Some(queue_family) = (0..families.len())
            .find(|&i| families[i].queue_flags.contains(wanted) && presents(physical, i as u32))
        else {
            skipped.push(format!(
                "{name}: no queue family with graphics, compute and presentation to the window"
            ));
            continue;
        };
        let valid_bits = families[queue_family].timestamp_valid_bits;
        let device_local_bytes = memory
            .memory_heaps_as_slice()
            .iter()
            .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
            .map(|h| h.size)
            .max()
            .unwrap_or(0);
        found.push(Candidate {
            physical,
            queue_family: queue_family as u32,
            info: DeviceInfo {
                name,
                kind: DeviceKind::from_vk(props.device_type),
                driver,
                api_version: format!(
                    "{}.{}.{}",
                    vk::api_version_major(api),
                    vk::api_version_minor(api),
                    vk::api_version_patch(api)
                ),
                timestamp_period_ns: (valid_bits > 0 && props.limits.timestamp_period > 0.0)
                    .then_some(props.limits.timestamp_period as f64),
                max_storage_buffer_range: props.limits.max_storage_buffer_range as u64,
                max_workgroup_count: props.limits.max_compute_work_group_count,
                device_local_bytes,
                max_shared_memory: props.limits.max_compute_shared_memory_size,
                subgroup_size: v11.subgroup_size,
                subgroup_clustered: v11.subgroup_supported_stages.contains(vk::ShaderStageFlags::COMPUTE)
                    && v11.subgroup_supported_operations.contains(vk::SubgroupFeatureFlags::CLUSTERED),
                loop_iteration_limit: (v12.driver_id == vk::DriverId::MESA_LLVMPIPE).then_some(65_535),
                max_stage_storage_buffers: props
                    .limits
                    .max_per_stage_descriptor_storage_buffers
                    .min(props.limits.max_descriptor_set_storage_buffers)
                    .min(props.limits.max_per_stage_resources),
            },
        });
    }
    Ok((found, skipped))
}

/// Picks a device: by `selector` (index or name part) when given, else the most preferred kind.
pub(crate) fn choose(
    mut list: Vec<Candidate>,
    skipped: &[String],
    selector: Option<&str>,
) -> Result<Candidate, VkError> {
    let names = || {
        list.iter().enumerate().map(|(i, c)| format!("[{i}] {}", c.info.name)).collect::<Vec<_>>().join(", ")
    };
    if list.is_empty() {
        let why = if skipped.is_empty() {
            "the Vulkan loader found no device; install a driver (Debian: mesa-vulkan-drivers provides lavapipe)".to_string()
        } else {
            format!("no device qualifies ({})", skipped.join("; "))
        };
        return Err(VkError::NoDevice(why));
    }
    let index = match selector.map(str::trim).filter(|s| !s.is_empty()) {
        Some(sel) => match sel.parse::<usize>() {
            Ok(i) if i < list.len() => i,
            Ok(i) => {
                return Err(VkError::DeviceSelector(format!(
                    "device index {i} is out of range; devices: {}",
                    names()
                )))
            }
            Err(_) => {
                let lower = sel.to_lowercase();
                list.iter().position(|c| c.info.name.to_lowercase().contains(&lower)).ok_or_else(|| {
                    VkError::DeviceSelector(format!("no device matches \"{sel}\"; devices: {}", names()))
                })?
            }
        },
        None => (0..list.len()).min_by_key(|&i| list[i].info.kind).unwrap_or(0),
    };
    Ok(list.swap_remove(index))
}
