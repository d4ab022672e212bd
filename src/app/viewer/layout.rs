//! Where the windows are: the part of the view the panels leave free, which the camera's fit
//! frames the scene in, and the file that keeps the panels' places between sessions.

use super::Viewer;
use crate::app::AppArgs;
use crate::render::{camera, view};
use crate::ui;

/// Where ImGui keeps the windows' places, sizes and collapsed state between sessions:
/// `$XDG_CONFIG_HOME/msdsim/imgui.ini` (else `~/.config/msdsim/imgui.ini`) for an interactive
/// session; none for a scripted one (`--frames`, the exercises), whose pictures must not depend
/// on what a user did before, or where the folder cannot be made.
pub(super) fn panels_file(args: &AppArgs) -> Option<std::path::PathBuf> {
    if args.frames.is_some() || args.exercise_window || args.exercise_editor {
        return None;
    }
    let config = std::env::var_os("XDG_CONFIG_HOME")
        .filter(|v| !v.is_empty())
        .map(std::path::PathBuf::from)
        .or_else(|| {
            std::env::var_os("HOME")
                .filter(|v| !v.is_empty())
                .map(|h| std::path::PathBuf::from(h).join(".config"))
        })?;
    let dir = config.join("msdsim");
    match std::fs::create_dir_all(&dir) {
        Ok(()) => Some(dir.join("imgui.ini")),
        Err(e) => {
            log::info!("window places are not kept: cannot make {}: {e}", dir.display());
            None
        }
    }
}

impl Viewer {
    /// Fits the camera to the scene (the wind cone too) in the largest part of the window the
    /// panels leave free (render::camera::free_rect).
    pub(super) fn fit_camera(&mut self) {
        let Some(host) = &self.host else { return };
        let size = self.window.inner_size();
        let [w, h] = [size.width as f32, size.height as f32];
        let scale = self.imgui.io().display_framebuffer_scale[0].max(1e-3);
        let covered: Vec<[f32; 4]> =
            ui::covered(&self.editor, [w / scale, h / scale]).iter().map(|r| r.map(|v| v * scale)).collect();
        let free = camera::free_rect([w, h], &covered);
        view::fit_camera_in(&mut self.camera, host.model(), free, [w, h]);
    }
}
