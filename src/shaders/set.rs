//! Where shaders come from: the SPIR-V embedded at build time, or a directory of GLSL that is
//! compiled with the same function as build.rs and watched for changes (hot reload).
//!
//! A compile that fails, or whose struct layouts disagree with the host's, is refused: the
//! caller keeps its running pipeline, and the error stays listed until a later compile of that
//! shader succeeds.

use super::compile::{compile_glsl, CompileError};
use super::layout_check;
use notify::{RecursiveMode, Watcher};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

/// Quiet time after the last file event before recompiling (editors write in several steps).
const DEBOUNCE: Duration = Duration::from_millis(60);

struct Watch {
    dir: PathBuf,
    _watcher: notify::RecommendedWatcher,
    events: Receiver<notify::Result<notify::Event>>,
    /// Changed files not yet handed out, and when the first and latest of them arrived.
    pending: Vec<PathBuf>,
    first: Option<Instant>,
    latest: Option<Instant>,
}

/// Shaders that changed on disk, and when the first change was seen.
#[derive(Debug, Clone, Default)]
pub struct Changes {
    pub shaders: Vec<String>,
    pub since: Option<Instant>,
}

pub struct ShaderSet {
    watch: Option<Watch>,
    /// Files each shader was compiled from (itself and its includes).
    dependencies: HashMap<String, Vec<PathBuf>>,
    /// The current error of each shader whose last compile failed.
    errors: BTreeMap<String, String>,
    /// A shader of the directory that does not compile is replaced by the embedded one (the
    /// app starts and shows the error) instead of failing.
    fallback: bool,
}

impl ShaderSet {
    /// The embedded SPIR-V only; reload is off.
    pub fn embedded() -> Self {
        Self { watch: None, dependencies: HashMap::new(), errors: BTreeMap::new(), fallback: false }
    }

    /// GLSL from `dir` (with `dir/include` for headers), watched for changes.
    pub fn directory(dir: &Path) -> anyhow::Result<Self> {
        let dir = dir
            .canonicalize()
            .map_err(|e| crate::error::UserError(format!("--shaders {}: {e}", dir.display())))?;
        // A folder of shaders holds the physics stage at its top (anything else, `/` say, would
        // be watched through and through).
        if !dir.join("physics.comp").is_file() {
            return Err(crate::error::UserError(format!(
                "--shaders {}: not a shader folder (a copy of glsl/, with physics.comp at its top)",
                dir.display()
            ))
            .into());
        }
        let (tx, events) = channel();
        let mut watcher = notify::recommended_watcher(move |event| {
            let _ = tx.send(event);
        })?;
        watcher.watch(&dir, RecursiveMode::Recursive)?;
        Ok(Self {
            watch: Some(Watch {
                dir,
                _watcher: watcher,
                events,
                pending: Vec::new(),
                first: None,
                latest: None,
            }),
            dependencies: HashMap::new(),
            errors: BTreeMap::new(),
            fallback: true,
        })
    }

    /// A shader of the directory that does not compile fails `load_or_embedded` (a measurement
    /// of edited shaders must not measure the embedded ones instead).
    pub fn without_fallback(mut self) -> Self {
        self.fallback = false;
        self
    }

    /// The source tree's `glsl/` when it exists (a build from a checkout), else embedded.
    pub fn default_for_build() -> Self {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("glsl");
        if dir.join("include").is_dir() {
            match Self::directory(&dir) {
                Ok(set) => return set,
                Err(e) => log::warn!("hot reload off: cannot watch {}: {e:#}", dir.display()),
            }
        }
        Self::embedded()
    }

    /// One line for the UI: where shaders come from and whether reload is on.
    pub fn status(&self) -> String {
        match &self.watch {
            Some(w) => format!("hot reload on: editing {} recompiles on save", w.dir.display()),
            None => "hot reload off: using the shaders built into the binary (use --shaders DIR)".into(),
        }
    }

    pub fn reloading(&self) -> bool {
        self.watch.is_some()
    }

    /// SPIR-V for `name` (e.g. "physics.comp"): compiled from the directory when watching, else
    /// embedded. A failure (compile error or layout mismatch) is recorded and returned.
    pub fn load(&mut self, name: &str) -> Result<Vec<u32>, String> {
        let Some(watch) = &self.watch else {
            return super::embedded(name).map_err(|e| e.to_string());
        };
        let path = watch.dir.join(name);
        let result = compile_glsl(&path, &watch.dir.join("include"));
        let result = match result {
            Ok(compiled) => {
                self.dependencies.insert(name.to_string(), compiled.dependencies.clone());
                if !compiled.warnings.is_empty() {
                    log::warn!("{}", compiled.warnings.trim());
                }
                layout_check::check(&compiled.spirv).map(|_| compiled.spirv).map_err(|e| {
                    format!("{}: refused, it would break the host's struct layout: {e}", path.display())
                })
            }
            Err(CompileError { message, dependencies, .. }) => {
                if !dependencies.is_empty() {
                    self.dependencies.insert(name.to_string(), dependencies);
                }
                Err(format!("{}: {}", path.display(), message.trim()))
            }
        };
        match &result {
            Ok(_) => {
                self.errors.remove(name);
            }
            Err(e) => {
                if self.fallback {
                    log::error!("shader {e}"); // else the caller fails with it
                }
                self.errors.insert(name.to_string(), e.clone());
            }
        }
        result
    }

    /// Like `load`, but falls back to the embedded SPIR-V when the directory's version fails
    /// (so the app starts even with a broken shader on disk; the error stays listed).
    pub fn load_or_embedded(&mut self, name: &str) -> anyhow::Result<Vec<u32>> {
        match self.load(name) {
            Ok(words) => Ok(words),
            Err(_) if self.fallback => super::embedded(name),
            Err(e) if self.watch.is_some() => Err(crate::error::UserError(e).into()),
            Err(e) => Err(anyhow::anyhow!(e)),
        }
    }

    /// Current errors, by shader name.
    pub fn errors(&self) -> impl Iterator<Item = (&String, &String)> {
        self.errors.iter()
    }

    /// The shaders affected by file changes, once the files have been quiet for a moment.
    pub fn changes(&mut self) -> Changes {
        let Some(watch) = self.watch.as_mut() else { return Changes::default() };
        while let Ok(event) = watch.events.try_recv() {
            let Ok(event) = event else { continue };
            if matches!(event.kind, notify::EventKind::Access(_)) {
                continue;
            }
            let now = Instant::now();
            watch.first.get_or_insert(now);
            watch.latest = Some(now);
            watch.pending.extend(event.paths);
        }
        let quiet = watch.latest.is_some_and(|t| t.elapsed() >= DEBOUNCE);
        if !quiet {
            return Changes::default();
        }
        let files: Vec<PathBuf> =
            std::mem::take(&mut watch.pending).into_iter().map(|p| p.canonicalize().unwrap_or(p)).collect();
        let since = watch.first.take();
        watch.latest = None;
        let mut shaders: Vec<String> = self
            .dependencies
            .iter()
            .filter(|(_, deps)| deps.iter().any(|d| files.iter().any(|f| same_file(f, d))))
            .map(|(name, _)| name.clone())
            .collect();
        // A shader that failed before it could report its includes: retry it when it changes.
        for f in &files {
            if let Some(name) = f.file_name().and_then(|n| n.to_str()) {
                if self.errors.contains_key(name) && !shaders.iter().any(|s| s == name) {
                    shaders.push(name.to_string());
                }
            }
        }
        shaders.sort();
        Changes { shaders, since }
    }
}

fn same_file(a: &Path, b: &Path) -> bool {
    a == b || b.canonicalize().is_ok_and(|b| a == b)
}
