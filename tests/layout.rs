//! The Rust mirrors in `sim::gpu_types` against the std430/std140 layouts the shaders were
//! compiled with: every member offset of every shared struct, in every embedded shader that
//! uses it, and the array stride of arrays of it (the same check hot reload applies).

mod common;

use msdsim::shaders::{self, layout_check};

#[test]
fn rust_mirrors_match_the_shader_layouts() {
    let mut found = Vec::new();
    for name in shaders::embedded_names() {
        let words = shaders::embedded(name).expect("embedded SPIR-V");
        found.extend(layout_check::check(&words).unwrap_or_else(|e| panic!("{name}: {e}")));
    }
    for host in layout_check::host_layouts() {
        assert!(found.contains(&host.name), "no shader declares {}: the check would be vacuous", host.name);
    }
}

/// The check sees a changed offset (so it can fail).
#[test]
fn a_shifted_member_is_refused() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl");
    let tmp = tempfile::tempdir().unwrap();
    common::copy_dir(&dir, tmp.path());
    let header = tmp.path().join("include/layout.glsl");
    let text = std::fs::read_to_string(&header).unwrap();
    std::fs::write(&header, text.replace("    float mass; ", "    float extra; float mass; ")).unwrap();
    let compiled =
        shaders::compile::compile_glsl(&tmp.path().join("physics.comp"), &tmp.path().join("include"))
            .unwrap();
    let err = layout_check::check(&compiled.spirv).unwrap_err();
    assert!(err.contains("ObjectParams"), "{err}");
}
