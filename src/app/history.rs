//! Undo and redo of scene edits (Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y): every edit that reaches the
//! scene, from the panels, the translate handles, Ctrl+click pins, add, remove and load. The
//! simulation state is not part of it: an undone edit is applied as any edit is (parameters in
//! place, layout changes from the initial state).
//!
//! It also keeps the scene as last loaded or saved, so the app knows whether there are
//! unsaved edits (Save is marked, and quitting asks first).
//!
//! The history keeps the scene as last committed and, before it, what it replaced. An edit is
//! committed once nothing is being dragged (a drag of a field or a handle is one step, however
//! many frames it runs), so `observe` is given the scene every frame with whether an edit is
//! still in progress.

use crate::scene::Scene;

/// Steps kept back (each a copy of the scene, a few kilobytes).
const DEPTH: usize = 200;

pub struct History {
    past: Vec<Scene>,
    future: Vec<Scene>,
    committed: Scene,
    saved: Scene,
}

impl History {
    pub fn new(scene: &Scene) -> Self {
        Self { past: Vec::new(), future: Vec::new(), committed: scene.clone(), saved: scene.clone() }
    }

    /// `scene` was just loaded or saved.
    pub fn mark_saved(&mut self, scene: &Scene) {
        self.saved = scene.clone();
    }

    /// Whether `now` differs from the scene as last loaded or saved.
    pub fn unsaved(&self, now: &Scene) -> bool {
        *now != self.saved
    }

    /// The scene as it is now; `busy` while an edit is in progress (a field, handle or particle
    /// dragged). A scene that differs from the last committed one is a new step (and forgets
    /// what was undone).
    pub fn observe(&mut self, now: &Scene, busy: bool) {
        if busy || *now == self.committed {
            return;
        }
        self.past.push(std::mem::replace(&mut self.committed, now.clone()));
        if self.past.len() > DEPTH {
            self.past.remove(0);
        }
        self.future.clear();
    }

    /// The scene before the last step, to apply; `None` with nothing to undo.
    pub fn undo(&mut self) -> Option<Scene> {
        let before = self.past.pop()?;
        self.future.push(std::mem::replace(&mut self.committed, before.clone()));
        Some(before)
    }

    /// The scene of the last undone step, to apply; `None` with nothing to redo.
    pub fn redo(&mut self) -> Option<Scene> {
        let after = self.future.pop()?;
        self.past.push(std::mem::replace(&mut self.committed, after.clone()));
        Some(after)
    }

    /// Takes back the last undo, whose scene could not be applied (a redo of it).
    pub fn refuse_undo(&mut self) {
        self.redo();
    }

    /// Takes back the last redo, whose scene could not be applied.
    pub fn refuse_redo(&mut self) {
        self.undo();
    }

    /// Steps that can be undone and redone.
    pub fn depth(&self) -> (usize, usize) {
        (self.past.len(), self.future.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_with_gravity(g: f64) -> Scene {
        let mut s =
            crate::scene::parse(crate::app::DEFAULT_PRESET, "playground", &[]).expect("the default preset");
        s.sim.gravity[1] = g;
        s
    }

    /// A drag over many frames is one step; undo and redo walk the steps both ways; a new
    /// edit after an undo forgets what was undone; a refused undo leaves the history as it was.
    #[test]
    fn steps_undo_redo_and_branch() {
        let a = scene_with_gravity(-9.81);
        let mut h = History::new(&a);
        h.observe(&a, false);
        assert_eq!(h.depth(), (0, 0), "nothing changed");
        for g in [-9.0, -8.0, -7.0] {
            h.observe(&scene_with_gravity(g), true); // dragging
        }
        let b = scene_with_gravity(-7.0);
        h.observe(&b, false);
        assert_eq!(h.depth(), (1, 0), "a drag is one step");
        let c = scene_with_gravity(-1.0);
        h.observe(&c, false);
        assert_eq!(h.depth(), (2, 0));

        assert_eq!(h.undo().as_ref(), Some(&b));
        h.observe(&b, false); // the app applied it
        assert_eq!(h.undo().as_ref(), Some(&a));
        h.observe(&a, false);
        assert_eq!(h.undo(), None, "nothing before the first scene");
        assert_eq!(h.depth(), (0, 2));
        assert_eq!(h.redo().as_ref(), Some(&b));
        h.observe(&b, false);
        assert_eq!(h.depth(), (1, 1));

        // An undo whose scene is refused (the app could not apply it) is taken back.
        assert_eq!(h.undo().as_ref(), Some(&a));
        h.refuse_undo();
        h.observe(&b, false);
        assert_eq!(h.depth(), (1, 1), "as before the refused undo");

        // A new edit forgets the undone steps.
        let d = scene_with_gravity(-3.0);
        h.observe(&d, false);
        assert_eq!(h.depth(), (2, 0));
        assert_eq!(h.redo(), None);
        assert_eq!(h.undo().as_ref(), Some(&b));
        assert_eq!(h.redo().as_ref(), Some(&d));
        h.refuse_redo();
        assert_eq!(h.depth(), (1, 1), "a refused redo is taken back");

        // Unsaved edits: against the scene as last loaded or saved, whatever the steps.
        assert!(h.unsaved(&b) && !h.unsaved(&a), "the first scene is the saved one");
        h.mark_saved(&b);
        assert!(!h.unsaved(&b) && h.unsaved(&a), "saved");
    }
}
