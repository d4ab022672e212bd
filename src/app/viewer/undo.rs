//! Undo and redo in the app: the history (`app::history`) sees the scene after every frame's
//! edits, and an undone or redone scene is applied as an edit is; and what is unsaved, which
//! makes closing the window ask first; what Esc closes before it asks to quit.

use super::super::history::History;
use super::super::input::KeyAction;
use super::Viewer;

impl Viewer {
    /// Commits this frame's edits to the history, unless one is still in progress (a field,
    /// a handle or a particle being dragged: its edits become one step when it ends).
    pub(super) fn observe_edits(&mut self) {
        let busy = self.editor.ui_active || self.handle.is_some() || self.input.grab.is_some();
        let Some(host) = self.host.as_ref() else { return };
        let history = self.history.get_or_insert_with(|| History::new(host.scene()));
        history.observe(host.scene(), busy || self.pending_scene.is_some());
        self.editor.undo_depth = history.depth();
        self.editor.unsaved = history.unsaved(host.scene());
    }

    /// Esc closes what is open before it asks to quit, in this order: a handle being dragged
    /// (let go where it is), the controls, the log (both only where the UI is drawn), the Save's
    /// Replace question. True when it closed something.
    pub(super) fn dismiss(&mut self) -> bool {
        if self.handle.take().is_some() {
            return true;
        }
        let editor = &mut self.editor;
        if !editor.hide_ui {
            for open in [&mut editor.show_help, &mut editor.notices.show_log] {
                if std::mem::take(open) {
                    return true;
                }
            }
        }
        editor.replace.take().is_some()
    }

    /// The scene was just loaded or saved: no unsaved edits.
    pub(super) fn mark_saved(&mut self) {
        if let (Some(history), Some(host)) = (self.history.as_mut(), self.host.as_ref()) {
            history.mark_saved(host.scene());
            self.editor.unsaved = false;
        }
    }

    /// When the app must stop on a failure of the GPU (stuck or lost) with unsaved edits: saves
    /// the scene as `msdsim-rescued-<seconds since 1970>.toml` in the current folder and says
    /// where; `None` when there was nothing to save or it could not be saved.
    pub fn rescue_unsaved(&mut self) -> Option<String> {
        self.observe_edits();
        if !self.editor.unsaved {
            return None;
        }
        let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default();
        let path = std::path::PathBuf::from(format!("msdsim-rescued-{}.toml", now.as_secs()));
        let saved = crate::scene::save(self.host.as_ref()?.scene(), &path);
        Some(match saved {
            Ok(()) => {
                let said = format!("the unsaved scene was saved to {}", path.display());
                self.rescued = Some(path);
                said
            }
            Err(e) => format!("the unsaved scene could not be saved ({e:#})"),
        })
    }

    /// When the user quits (Esc twice, or the close button) with unsaved edits: they are not
    /// lost, but saved as a failure's are (`rescue_unsaved`), and the terminal says where.
    pub(super) fn keep_unsaved_on_quit(&mut self) {
        if let Some(said) = self.rescue_unsaved() {
            eprintln!("msdsim: {said}");
        }
    }

    /// The window's close button: quits at once without unsaved edits; with them, only when
    /// pressed again within QUIT_CONFIRM seconds (as Esc), saying so, and keeping them.
    pub(super) fn close_requested(&mut self) -> bool {
        self.observe_edits();
        if !self.editor.unsaved {
            return true;
        }
        if self.input.escape(std::time::Instant::now()) == KeyAction::Quit {
            self.keep_unsaved_on_quit();
            return true;
        }
        self.message(
            format!(
                "the scene has unsaved edits: close again within {} s to quit (they are saved to msdsim-rescued-*.toml in the current folder)",
                super::super::input::QUIT_CONFIRM
            ),
            false,
        );
        false
    }

    /// Applies the scene before the last edit (`redo`: after the last undone one); says so,
    /// or why not.
    pub(super) fn undo(&mut self, redo: bool) {
        self.observe_edits();
        let Some(history) = self.history.as_mut() else { return };
        let Some(scene) = (if redo { history.redo() } else { history.undo() }) else {
            self.message(if redo { "nothing to redo" } else { "nothing to undo" }, false);
            return;
        };
        let what = if redo { "redone" } else { "undone" };
        if self.host.as_ref().is_some_and(|h| h.calibrates_for(&scene)) {
            // Applied once the calibration's notice has been drawn (edits_wait).
            self.pending_scene = Some(scene);
            self.message(format!("edit {what}"), false);
        } else if self.apply(scene) {
            self.message(format!("edit {what}"), false);
        } else if let Some(history) = self.history.as_mut() {
            if redo {
                history.refuse_redo();
            } else {
                history.refuse_undo();
            }
        }
        self.observe_edits();
    }
}
