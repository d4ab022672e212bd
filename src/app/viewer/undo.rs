//! Undo and redo in the app: the history (`app::history`) sees the scene after every frame's
//! edits, and an undone or redone scene is applied as an edit is.

use super::super::history::History;
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
        if self.apply(scene) {
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
