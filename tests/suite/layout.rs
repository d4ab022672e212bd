//! The Rust mirrors in `sim::gpu_types` against the std430/std140 layouts the shaders were
//! compiled with: every member offset of every shared struct, in every embedded shader that
//! uses it, and the array stride of arrays of it (the same check hot reload applies).

use crate::common;

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

/// Compiles physics.comp with the header edited by `edit`, and returns the layout check's
/// verdict.
fn check_edited(edit: impl Fn(&str) -> String) -> Result<Vec<&'static str>, String> {
    check_edited_in("include/layout.glsl", "physics.comp", edit)
}

/// Compiles `shader` with `header` edited by `edit`, and returns the layout check's verdict.
fn check_edited_in(
    header: &str,
    shader: &str,
    edit: impl Fn(&str) -> String,
) -> Result<Vec<&'static str>, String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl");
    let tmp = tempfile::tempdir().unwrap();
    common::copy_dir(&dir, tmp.path());
    let header = tmp.path().join(header);
    let text = std::fs::read_to_string(&header).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "the edit no longer applies: update the test");
    std::fs::write(&header, edited).unwrap();
    let compiled =
        shaders::compile::compile_glsl(&tmp.path().join(shader), &tmp.path().join("include")).unwrap();
    layout_check::check(&compiled.spirv)
}

/// The check does not depend on the shader's names (issue 30, item 9): a struct renamed by a
/// `#define` with its members swapped, and a member whose type changed at the same offset, are
/// refused (both ran before with the wrong layout).
#[test]
fn renamed_structs_and_changed_types_are_refused() {
    let err = check_edited(|t| {
        t.replacen("struct Particle {", "#define Particle Prt\nstruct Particle {", 1).replacen(
            "    vec4 pos;   // xyz position [m]; w = 1 pinned, 0 free\n    vec4 vel;",
            "    vec4 vel;\n    vec4 pos;",
            1,
        )
    })
    .unwrap_err();
    assert!(err.contains("`Prt`") && err.contains("binding"), "{err}");
    let err = check_edited(|t| t.replacen("    float mass; ", "    uint mass; ", 1)).unwrap_err();
    assert!(
        err.contains("ObjectParams")
            && err.contains("a uint at byte 48")
            && err.contains("a float at byte 48"),
        "{err}"
    );
    // A transposed matrix has the same scalars at other places.
    let err = check_edited_in("include/render.glsl", "mesh.vert", |t| {
        t.replacen(
            "layout(std140, set = 0, binding = 0) uniform CameraBuf",
            "layout(std140, row_major, set = 0, binding = 0) uniform CameraBuf",
            1,
        )
    })
    .unwrap_err();
    assert!(err.contains("Camera"), "{err}");
}

/// The `#define`d constants of the headers (flag bits, feature bits, the rope ring, the
/// integrator and collider type ids) equal the host's mirrors in `sim::gpu_types`,
/// `sim::integrator` and `sim::collider`.
#[test]
fn header_constants_match_the_host() {
    let method_define = |m: msdsim::sim::model::Integrator| -> &'static str {
        Box::leak(format!("METHOD_{}", m.label().to_uppercase()).into_boxed_str())
    };
    use msdsim::sim::gpu_types as t;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl/include");
    let mut defines = std::collections::HashMap::new();
    for file in ["layout.glsl", "features.glsl", "colliders.glsl"] {
        for line in std::fs::read_to_string(dir.join(file)).unwrap().lines() {
            let mut words = line.split_whitespace();
            if let (Some("#define"), Some(name), Some(value)) = (words.next(), words.next(), words.next()) {
                if let Ok(v) = value.trim_end_matches('u').parse::<u32>() {
                    defines.insert(name.to_string(), v);
                }
            }
        }
    }
    let host = [
        ("ROPE_RING", t::ROPE_RING as u32),
        ("OBJ_STRETCH_LIMIT", t::OBJ_STRETCH_LIMIT),
        ("OBJ_SELF_COLLISION", t::OBJ_SELF_COLLISION),
        ("OBJ_SELF_HASH", t::OBJ_SELF_HASH),
        ("F_CONTACT", t::FEATURE_CONTACT),
        ("F_EDGES", t::FEATURE_EDGES),
        ("GUARD_NON_FINITE", t::GUARD_NON_FINITE),
        ("GUARD_RUNAWAY", t::GUARD_RUNAWAY),
        ("GUARD_FAST", t::GUARD_FAST),
        ("F_STRUCTURAL", t::FEATURE_STRUCTURAL),
        ("F_SHEAR", t::FEATURE_SHEAR),
        ("F_BENDING", t::FEATURE_BENDING),
        ("F_DAMPING", t::FEATURE_DAMPING),
        ("F_WIND", t::FEATURE_WIND),
        ("F_SPHERES", t::FEATURE_SPHERES),
        ("F_STRETCH", t::FEATURE_STRETCH),
        ("F_SELF", t::FEATURE_SELF),
        ("F_GROUND", t::FEATURE_GROUND),
        ("F_BOX", t::FEATURE_BOX),
        ("F_CAPSULE", t::FEATURE_CAPSULE),
        ("F_SEGMENT_PAIRS", t::FEATURE_SEGMENT_PAIRS),
        ("F_TURNING", t::FEATURE_TURNING),
        ("F_MESH", t::FEATURE_MESH),
    ]
    .into_iter()
    .chain(msdsim::sim::model::Integrator::ALL.map(|m| (method_define(m), m as u32)))
    .chain(msdsim::sim::collider::KINDS.iter().map(|k| {
        let name: &'static str = Box::leak(format!("COLLIDER_{}", k.label.to_uppercase()).into_boxed_str());
        (name, k.glsl_id)
    }))
    // Each collider type's feature bit is the one its row names.
    .chain(msdsim::sim::collider::KINDS.iter().map(|k| {
        let name: &'static str = Box::leak(
            format!("F_{}", if k.label == "sphere" { "SPHERES".into() } else { k.label.to_uppercase() })
                .into_boxed_str(),
        );
        (name, k.feature)
    }));
    for (name, value) in host {
        assert_eq!(defines.get(name), Some(&value), "{name}: header and host disagree");
    }
}
