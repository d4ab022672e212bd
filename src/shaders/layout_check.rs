//! Checks compiled SPIR-V against the host's struct layouts (`sim::gpu_types`): every member
//! offset and array stride of every shared struct the module declares. Used by the tests and
//! by hot reload, which refuses a header change that would break the host layout.

use super::reflect::struct_layouts;
use crate::sim::gpu_types::{Camera, Draw, Globals, GpuLayout, ObjectParams, Particle, SurfaceVertex};

/// A struct the host shares with the shaders.
pub struct HostLayout {
    pub name: &'static str,
    pub size: usize,
    /// (member name, byte offset) in declaration order.
    pub offsets: Vec<(&'static str, usize)>,
}

/// Every struct shared with the shaders.
pub fn host_layouts() -> Vec<HostLayout> {
    fn one<T: GpuLayout>() -> HostLayout {
        HostLayout { name: T::NAME, size: T::SIZE, offsets: T::offsets() }
    }
    vec![
        one::<Particle>(),
        one::<SurfaceVertex>(),
        one::<Globals>(),
        one::<ObjectParams>(),
        one::<Camera>(),
        one::<Draw>(),
    ]
}

/// Names of the shared structs the module declares, or the first disagreement with the host.
pub fn check(words: &[u32]) -> Result<Vec<&'static str>, String> {
    let host = host_layouts();
    let mut found = Vec::new();
    for layout in struct_layouts(words) {
        let Some(HostLayout { name, size, offsets }) = host.iter().find(|h| h.name == layout.name) else {
            continue;
        };
        let spirv: Vec<(&str, usize)> =
            layout.members.iter().map(|(m, o)| (m.as_str(), *o as usize)).collect();
        if spirv.len() != offsets.len() {
            return Err(format!(
                "struct {name} has {} members in the shader but {} on the host (src/sim/gpu_types.rs)",
                spirv.len(),
                offsets.len()
            ));
        }
        for ((m, o), (hm, ho)) in spirv.iter().zip(offsets) {
            if m != hm || o != ho {
                return Err(format!(
                    "struct {name}: the shader has `{m}` at byte {o}, the host (src/sim/gpu_types.rs) has `{hm}` at byte {ho}"
                ));
            }
        }
        if let Some(stride) = layout.array_strides.iter().find(|s| **s as usize != *size) {
            return Err(format!("struct {name}: arrays of it have a stride of {stride} bytes in the shader, the host's size is {size}"));
        }
        if !found.contains(name) {
            found.push(*name);
        }
    }
    Ok(found)
}
