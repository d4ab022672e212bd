//! The one GLSL -> SPIR-V compile function, shared by `build.rs` (through `#[path]`) and the
//! runtime (hot reload). It depends on `std` and `shaderc` only, so the build script can include
//! this file as it is.
//!
//! `#include "name"` resolves relative to the including file first, then to `glsl/include/`
//! (the `include_dir` argument), and only to files inside the shader's folder or the include
//! folder (so everything read is watched); includes nest at most `MAX_INCLUDE_DEPTH` deep (a
//! header that includes itself without a guard is an error, not an endless expansion). Every
//! file read is reported in `CompiledShader::dependencies`, so callers know what to watch.

use std::cell::RefCell;
use std::fmt;
use std::path::{Path, PathBuf};

/// SPIR-V and the files that went into it.
pub struct CompiledShader {
    pub spirv: Vec<u32>,
    /// The source itself followed by every file it included (each once).
    pub dependencies: Vec<PathBuf>,
    /// Compiler warnings, empty when there were none.
    pub warnings: String,
}

/// A compile failure with the compiler's own message (file:line: error).
#[derive(Debug, Clone)]
pub struct CompileError {
    pub path: PathBuf,
    pub message: String,
    /// Files read before the failure, so a watcher can still track a broken include.
    pub dependencies: Vec<PathBuf>,
}

impl fmt::Display for CompileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message.trim_end())
    }
}

impl std::error::Error for CompileError {}

/// How deep includes may nest (the shipped shaders nest 4 deep).
pub const MAX_INCLUDE_DEPTH: usize = 32;

/// Shader stage from the file extension (`.comp`, `.vert`, `.frag`).
pub fn shader_kind(path: &Path) -> Option<shaderc::ShaderKind> {
    match path.extension()?.to_str()? {
        "comp" => Some(shaderc::ShaderKind::Compute),
        "vert" => Some(shaderc::ShaderKind::Vertex),
        "frag" => Some(shaderc::ShaderKind::Fragment),
        _ => None,
    }
}

/// Compiles one GLSL file to SPIR-V for Vulkan 1.3.
pub fn compile_glsl(path: &Path, include_dir: &Path) -> Result<CompiledShader, CompileError> {
    let fail = |message: String, dependencies: Vec<PathBuf>| CompileError {
        path: path.to_path_buf(),
        message,
        dependencies,
    };
    let kind = shader_kind(path)
        .ok_or_else(|| fail("unknown shader stage: expected a .comp, .vert or .frag file".into(), vec![]))?;
    let source = std::fs::read_to_string(path)
        .map_err(|e| fail(format!("cannot read: {e}"), vec![path.to_path_buf()]))?;

    let dependencies = RefCell::new(vec![path.to_path_buf()]);
    // The folders includes may come from.
    let roots: Vec<PathBuf> = [path.parent().unwrap_or(Path::new(".")), include_dir]
        .iter()
        .filter_map(|p| p.canonicalize().ok())
        .collect();
    let compiler = shaderc::Compiler::new().map_err(|e| fail(format!("shaderc: {e}"), vec![]))?;
    let mut options = shaderc::CompileOptions::new().map_err(|e| fail(format!("shaderc: {e}"), vec![]))?;
    options.set_target_env(shaderc::TargetEnv::Vulkan, shaderc::EnvVersion::Vulkan1_3 as u32);
    // No spirv-opt: it strips the struct and member names that `reflect` uses to check layouts
    // against the Rust mirrors, and the Vulkan drivers optimise SPIR-V themselves.
    options.set_optimization_level(shaderc::OptimizationLevel::Zero);
    options.set_include_callback(|requested, _kind, requesting, depth| {
        if depth > MAX_INCLUDE_DEPTH {
            return Err(format!(
                "includes nest deeper than {MAX_INCLUDE_DEPTH} at \"{requested}\" from {requesting}: an #include cycle (a header without an include guard that includes itself or an includer)?"
            ));
        }
        let from = Path::new(requesting).parent().unwrap_or(Path::new("."));
        let candidates = [from.join(requested), include_dir.join(requested)];
        let found = candidates.iter().find(|p| p.is_file()).ok_or_else(|| {
            format!(
                "cannot find include \"{requested}\" (looked in {} and {})",
                from.display(),
                include_dir.display()
            )
        })?;
        let inside = found.canonicalize().is_ok_and(|c| roots.iter().any(|r| c.starts_with(r)));
        if !inside {
            return Err(format!(
                "include \"{requested}\" is outside the shader folder and its include folder ({})",
                found.display()
            ));
        }
        let content =
            std::fs::read_to_string(found).map_err(|e| format!("cannot read {}: {e}", found.display()))?;
        let mut deps = dependencies.borrow_mut();
        if !deps.contains(found) {
            deps.push(found.clone());
        }
        Ok(shaderc::ResolvedInclude { resolved_name: found.display().to_string(), content })
    });

    let name = path.display().to_string();
    let result = compiler.compile_into_spirv(&source, kind, &name, "main", Some(&options));
    drop(options);
    let dependencies = dependencies.into_inner();
    match result {
        Ok(artifact) => Ok(CompiledShader {
            spirv: artifact.as_binary().to_vec(),
            warnings: artifact.get_warning_messages(),
            dependencies,
        }),
        Err(e) => Err(fail(e.to_string(), dependencies)),
    }
}
