//! Compiles every shader under `glsl/` to SPIR-V in OUT_DIR and generates the table of embedded
//! shaders (`shaders.rs`). Uses the same compile function as the runtime hot reload.

#[path = "src/shaders/compile.rs"]
mod compile;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let glsl = root.join("glsl");
    let include_dir = glsl.join("include");
    println!("cargo:rerun-if-changed={}", glsl.display());
    println!("cargo:rerun-if-changed=src/shaders/compile.rs");

    let mut sources: Vec<PathBuf> = std::fs::read_dir(&glsl)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", glsl.display()))
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| compile::shader_kind(p).is_some())
        .collect();
    sources.sort();

    let mut table = String::from(
        "/// Shaders compiled by build.rs: (file name, SPIR-V bytes).\npub static EMBEDDED: &[(&str, &[u8])] = &[\n",
    );
    let mut failures = Vec::new();
    for src in &sources {
        match compile::compile_glsl(src, &include_dir) {
            Ok(shader) => {
                for dep in &shader.dependencies {
                    println!("cargo:rerun-if-changed={}", dep.display());
                }
                if !shader.warnings.is_empty() {
                    println!("cargo:warning={}", shader.warnings.trim());
                }
                let name = file_name(src);
                let spv = out.join(format!("{name}.spv"));
                let bytes: Vec<u8> = shader.spirv.iter().flat_map(|w| w.to_le_bytes()).collect();
                std::fs::write(&spv, bytes).unwrap_or_else(|e| panic!("cannot write {}: {e}", spv.display()));
                writeln!(table, "    ({name:?}, include_bytes!({:?})),", spv.display().to_string()).unwrap();
            }
            Err(e) => {
                for dep in &e.dependencies {
                    println!("cargo:rerun-if-changed={}", dep.display());
                }
                failures.push(e.to_string());
            }
        }
    }
    if !failures.is_empty() {
        eprintln!("shader compilation failed:\n{}", failures.join("\n"));
        std::process::exit(1);
    }
    table.push_str("];\n");
    std::fs::write(out.join("shaders.rs"), table).expect("cannot write shaders.rs");
}

fn file_name(p: &Path) -> String {
    p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default()
}
