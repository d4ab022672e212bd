//! Checks compiled SPIR-V against the host's struct layouts (`sim::gpu_types`): every struct
//! a buffer, uniform or push constant holds must be one the host shares, by name, and agree
//! with it in every member's name and offset, every scalar's offset and type (float, uint,
//! int), and the stride of arrays of it. So a renamed struct (`#define Particle Prt`) or a
//! member of another type (`uint mass`) is refused as a moved one is. Used by the tests and by
//! hot reload, which refuses a header change that would break the host layout.

use super::reflect::{reflect, Reflection, Scalar};
use crate::sim::gpu_types::{
    Camera, Collider, Draw, Globals, GpuLayout, GpuScalar, ObjectParams, Particle, SurfaceVertex,
};

/// A struct the host shares with the shaders.
pub struct HostLayout {
    pub name: &'static str,
    pub size: usize,
    /// (member name, byte offset) in declaration order.
    pub offsets: Vec<(&'static str, usize)>,
    /// Every scalar, (byte offset, kind).
    pub scalars: Vec<(usize, GpuScalar)>,
}

/// Every struct shared with the shaders.
pub fn host_layouts() -> Vec<HostLayout> {
    fn one<T: GpuLayout>() -> HostLayout {
        HostLayout { name: T::NAME, size: T::SIZE, offsets: T::offsets(), scalars: T::scalars() }
    }
    vec![
        one::<Particle>(),
        one::<Collider>(),
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
    let Reflection { layouts, bound } = reflect(words);
    for (place, name) in bound {
        if !host.iter().any(|h| h.name == name) {
            let shared: Vec<&str> = host.iter().map(|h| h.name).collect();
            return Err(format!(
                "{place} holds struct `{name}`, which is not one the host shares ({}): a renamed struct's layout cannot be checked",
                shared.join(", ")
            ));
        }
        if !layouts.iter().any(|l| l.name == name) {
            return Err(format!(
                "{place} holds struct `{name}`, whose layout cannot be read from the SPIR-V (an array length set by a specialization constant?)"
            ));
        }
    }
    let mut found = Vec::new();
    for layout in layouts {
        let Some(HostLayout { name, size, offsets, scalars }) = host.iter().find(|h| h.name == layout.name)
        else {
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
        let host_scalars: Vec<(u32, Scalar)> = scalars.iter().map(|&(o, s)| (o as u32, Some(s))).collect();
        if layout.scalars != host_scalars {
            let at = layout.scalars.iter().zip(&host_scalars).position(|(a, b)| a != b);
            let word = |v: &[(u32, Scalar)], k: Option<usize>| {
                k.and_then(|k| v.get(k)).map_or("nothing".to_string(), |(o, s)| {
                    let glsl = match s {
                        Some(GpuScalar::F32) => "a float",
                        Some(GpuScalar::U32) => "a uint",
                        Some(GpuScalar::I32) => "an int",
                        None => "a scalar the host has no type for",
                    };
                    format!("{glsl} at byte {o}")
                })
            };
            let k = at.or(Some(layout.scalars.len().min(host_scalars.len())));
            return Err(format!(
                "struct {name}: the shader has {}, the host (src/sim/gpu_types.rs) has {} ({} and {} scalars)",
                word(&layout.scalars, k),
                word(&host_scalars, k),
                layout.scalars.len(),
                host_scalars.len()
            ));
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
