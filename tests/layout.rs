//! The Rust mirrors in `sim::gpu_types` against the std430 layouts the shaders were compiled
//! with: every member offset of every struct, in every embedded shader that uses it, and the
//! array stride of arrays of it.

use msdsim::shaders::{self, reflect};
use msdsim::sim::gpu_types::{Camera, Draw, Globals, GpuLayout, ObjectParams, Particle, SurfaceVertex};

fn check<T: GpuLayout>(found: &mut Vec<&'static str>) {
    for name in shaders::embedded_names() {
        let words = shaders::embedded(name).expect("embedded SPIR-V");
        for layout in reflect::struct_layouts(&words).into_iter().filter(|l| l.name == T::NAME) {
            let spirv: Vec<(String, usize)> =
                layout.members.iter().map(|(n, o)| (n.clone(), *o as usize)).collect();
            let rust: Vec<(String, usize)> =
                T::offsets().into_iter().map(|(n, o)| (n.to_string(), o)).collect();
            assert_eq!(spirv, rust, "{} in {name}: SPIR-V (left) vs Rust (right) member offsets", T::NAME);
            for stride in layout.array_strides {
                assert_eq!(stride as usize, T::SIZE, "{} in {name}: array stride vs Rust size", T::NAME);
            }
            found.push(T::NAME);
        }
    }
}

#[test]
fn rust_mirrors_match_the_shader_layouts() {
    let mut found = Vec::new();
    check::<Particle>(&mut found);
    check::<SurfaceVertex>(&mut found);
    check::<Globals>(&mut found);
    check::<ObjectParams>(&mut found);
    check::<Camera>(&mut found);
    check::<Draw>(&mut found);
    for name in
        [Particle::NAME, SurfaceVertex::NAME, Globals::NAME, ObjectParams::NAME, Camera::NAME, Draw::NAME]
    {
        assert!(found.contains(&name), "no shader declares {name}: the check would be vacuous");
    }
}
