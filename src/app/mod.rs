//! The native app: a winit window with the Vulkan renderer and the ImGui scene editor over the
//! GPU simulation. `viewer` holds the per-frame work, `sim_host` applies edits, `input` maps the
//! mouse and keyboard.

mod handles;
mod history;
mod input;
pub mod offscreen;
mod recorder;
mod sim_host;
mod viewer;

pub use input::{pick, PickRay};
pub use sim_host::{Applied, SimHost};
pub use viewer::{preset_label, write_png};

use crate::atomic_file::Interrupted;
use crate::error::UserError;
use crate::scene::{self, Scene};
use crate::vk::ContextOptions;
use anyhow::Result;
use std::path::PathBuf;
use std::sync::Arc;
use viewer::{Outcome, Viewer};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// The scene the app opens without `--preset`.
pub const DEFAULT_PRESET: &str = include_str!("../../presets/playground.toml");

#[derive(Debug, Clone)]
pub struct AppArgs {
    /// Label of the preset in the editor's file field.
    pub preset_label: String,
    pub size: [u32; 2],
    pub vsync: bool,
    pub paused: bool,
    /// Render this many frames, then exit (with `screenshot`: capture the last one).
    pub frames: Option<u64>,
    pub screenshot: Option<PathBuf>,
    /// Resize, minimise and restore the window on a script, then exit (for tests).
    pub exercise_window: bool,
    /// Hide the stats window (its timings differ run to run).
    pub hide_stats: bool,
    /// Hide every UI window (`--no-ui`).
    pub hide_ui: bool,
    /// Apply edits through the editor's code paths on a script, then exit (for tests).
    pub exercise_editor: bool,
    /// Shader folder to compile and watch (`None`: the source tree's glsl/ when present).
    pub shaders: Option<PathBuf>,
    /// Write every drawn frame as a PNG into this folder (it exists).
    pub record_frames: Option<PathBuf>,
    /// The object the editor opens with selected (`--select`; checked against the scene).
    pub select: Option<Selection>,
}

pub use crate::ui::Selection;

/// `--select`'s value: `cloth:N`, `rope:N`, `mesh_cloth:N` or a collider, `sphere:N`,
/// `box:N`, `capsule:N`, `mesh:N`.
pub fn parse_selection(s: &str) -> Result<Selection, String> {
    let usage = || {
        format!("'{s}': expected cloth:N, rope:N or mesh_cloth:N, or sphere:N, box:N, capsule:N or mesh:N (N from 0), e.g. cloth:0")
    };
    let (kind, n) = s.split_once(':').ok_or_else(usage)?;
    let n: usize = n.trim().parse().map_err(|_| usage())?;
    match kind.trim() {
        "cloth" => Ok(Selection::Cloth(n)),
        "rope" => Ok(Selection::Rope(n)),
        "mesh_cloth" => Ok(Selection::MeshCloth(n)),
        "sphere" => Ok(Selection::Sphere(n)),
        "box" => Ok(Selection::Box(n)),
        "capsule" => Ok(Selection::Capsule(n)),
        "mesh" => Ok(Selection::Mesh(n)),
        _ => Err(usage()),
    }
}

/// Whether `scene` has the object `select` names (else a clear error).
pub fn check_selection(select: Selection, scene: &Scene) -> Result<(), UserError> {
    let (kind, n, count) = match select {
        Selection::Cloth(n) => ("cloth", n, scene.cloths.len()),
        Selection::Rope(n) => ("rope", n, scene.ropes.len()),
        Selection::MeshCloth(n) => ("mesh_cloth", n, scene.mesh_cloths.len()),
        Selection::Sphere(n) => ("sphere", n, scene.spheres.len()),
        Selection::Box(n) => ("box", n, scene.boxes.len()),
        Selection::Capsule(n) => ("capsule", n, scene.capsules.len()),
        Selection::Mesh(n) => ("mesh", n, scene.meshes.len()),
        _ => return Ok(()),
    };
    if n < count {
        return Ok(());
    }
    Err(UserError(format!("--select {kind}:{n}: the scene has {count} {kind}(s), numbered from 0")))
}

/// Loads the preset (or the built-in default scene) with overrides.
pub fn load_scene(preset: Option<&PathBuf>, overrides: &[String]) -> Result<Scene, UserError> {
    match preset {
        Some(path) => scene::load(path, overrides),
        None => scene::parse(DEFAULT_PRESET, "the default scene (presets/playground.toml)", overrides),
    }
}

struct Handler {
    options: ContextOptions,
    args: AppArgs,
    scene: Option<Scene>,
    viewer: Option<Viewer>,
    error: Option<anyhow::Error>,
    report: Option<(u32, Option<String>, Vec<String>)>,
}

impl Handler {
    fn stop(&mut self, event_loop: &ActiveEventLoop, error: Option<anyhow::Error>) {
        if self.error.is_none() {
            self.error = error;
        }
        if let Some(v) = self.viewer.take() {
            self.report = Some(v.finish());
        }
        event_loop.exit();
    }
}

impl Handler {
    /// `stop` for a failure that ends the run with edits unsaved: they are saved first, and
    /// the error says where.
    fn stop_rescuing(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        let e = match self.viewer.as_mut().and_then(|v| v.rescue_unsaved()) {
            Some(rescued) => e.context(rescued),
            None => e,
        };
        self.stop(event_loop, Some(e))
    }
}

impl ApplicationHandler for Handler {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.viewer.is_some() {
            return;
        }
        let Some(scene) = self.scene.take() else { return };
        let attributes = Window::default_attributes()
            .with_title("msdsim: mass-spring cloth and ropes")
            .with_inner_size(winit::dpi::PhysicalSize::new(self.args.size[0], self.args.size[1]));
        let window = match event_loop.create_window(attributes) {
            Ok(w) => Arc::new(w),
            Err(e) => return self.stop(event_loop, Some(anyhow::anyhow!("cannot open a window: {e}"))),
        };
        let shaders = match &self.args.shaders {
            Some(dir) => match crate::shaders::ShaderSet::directory(dir) {
                Ok(s) => s,
                Err(e) => return self.stop(event_loop, Some(e)),
            },
            None => crate::shaders::ShaderSet::default_for_build(),
        };
        match Viewer::new(window, &self.options, self.args.clone(), scene, shaders) {
            Ok(v) => {
                v.window().request_redraw();
                self.viewer = Some(v);
            }
            Err(e) => self.stop(event_loop, Some(e)),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(viewer) = self.viewer.as_mut() else { return };
        if let WindowEvent::RedrawRequested = event {
            match viewer.frame() {
                Ok(Outcome::Continue) => {}
                Ok(Outcome::Exit) => self.stop(event_loop, None),
                Err(e) => {
                    // The GPU is gone for this run (one queue: nothing drawn can pass a stuck
                    // submission), so the app stops; the edits are not lost with it.
                    let gpu_gone = e.chain().any(|c| {
                        matches!(
                            c.downcast_ref(),
                            Some(crate::vk::VkError::Stuck { .. } | crate::vk::VkError::DeviceLost)
                        )
                    });
                    if gpu_gone {
                        self.stop_rescuing(event_loop, e)
                    } else {
                        self.stop(event_loop, Some(e))
                    }
                }
            }
            return;
        }
        if viewer.handle_event(&event) {
            self.stop(event_loop, None);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        // SIGINT or SIGTERM: stop as the close button would, keeping a recording (written by
        // the teardown) and unsaved edits.
        if let Some(signal) = crate::atomic_file::stop_requested().filter(|_| self.error.is_none()) {
            return self.stop_rescuing(event_loop, Interrupted(signal).into());
        }
        if let Some(v) = &self.viewer {
            event_loop.set_control_flow(ControlFlow::Poll);
            v.window().request_redraw();
        }
    }
}

/// Opens the window and runs until it is closed (or the scripted frames are done).
pub fn run(options: &ContextOptions, args: AppArgs, scene: Scene) -> Result<()> {
    let event_loop = EventLoop::new().map_err(|e| {
        // winit's message names its own source file ("os error at .../linux/mod.rs:765: ..."):
        // the user needs the reason after it.
        let text = e.to_string();
        let reason =
            text.rsplit_once(".rs:").and_then(|(_, r)| r.split_once(": ")).map_or(text.as_str(), |(_, r)| r);
        UserError(format!(
            "no display to open a window on ({}); run headless instead: `msdsim simulate --preset FILE`, \
             or `msdsim devices`",
            reason.trim_end_matches(['.', ')'])
        ))
    })?;
    // The first SIGINT or SIGTERM asks the app to stop (`about_to_wait`), a second ends it.
    let _graceful = crate::atomic_file::Graceful::new();
    let mut handler = Handler {
        options: options.clone(),
        args,
        scene: Some(scene),
        viewer: None,
        error: None,
        report: None,
    };
    event_loop.run_app(&mut handler).map_err(|e| anyhow::anyhow!("the window's event loop failed: {e}"))?;
    if let Some(v) = handler.viewer.take() {
        handler.report = Some(v.finish());
    }
    // A signal that came during the teardown (it was let finish) is a stop too.
    if let Some(signal) = crate::atomic_file::stop_requested().filter(|_| handler.error.is_none()) {
        handler.error = Some(Interrupted(signal).into());
    }
    // A stop by a signal is reported after the teardown's checks, which it also passes.
    let interrupted = handler.error.as_ref().and_then(Interrupted::signal_of).is_some();
    if let Some(e) = handler.error.take_if(|_| !interrupted) {
        return Err(e);
    }
    if let Some((count, first, leaks)) = handler.report {
        if count > 0 {
            anyhow::bail!("{count} Vulkan validation message(s); first: {}", first.unwrap_or_default());
        }
        if !leaks.is_empty() {
            anyhow::bail!("GPU allocations leaked: {leaks:?}");
        }
    }
    handler.error.map_or(Ok(()), Err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn select_takes_a_kind_and_an_index_the_scene_has() {
        assert_eq!(parse_selection("cloth:0"), Ok(Selection::Cloth(0)));
        assert_eq!(parse_selection("rope: 2"), Ok(Selection::Rope(2)));
        assert_eq!(parse_selection("mesh:1"), Ok(Selection::Mesh(1)));
        assert_eq!(parse_selection("mesh_cloth:0"), Ok(Selection::MeshCloth(0)));
        for bad in ["cloth", "towel:0", "cloth:-1", "cloth:x", ""] {
            let e = parse_selection(bad).unwrap_err();
            assert!(e.contains("expected cloth:N, rope:N or mesh_cloth:N"), "{bad}: {e}");
        }
        let scene = load_scene(None, &[]).unwrap();
        assert!(check_selection(Selection::Cloth(0), &scene).is_ok());
        let e = check_selection(Selection::Rope(scene.ropes.len()), &scene).unwrap_err();
        assert!(e.0.contains("numbered from 0"), "{}", e.0);
        let e = check_selection(Selection::Mesh(0), &scene).unwrap_err();
        assert!(e.0.contains("mesh(s)"), "{}", e.0);
    }
}
