//! Applying an edited scene to the running simulation, and what the app says about it.

use super::Viewer;
use crate::app::sim_host::Applied;
use crate::scene::Scene;

impl Viewer {
    /// Applies an edited scene, reporting refusals in the editor; false when refused.
    pub(super) fn apply(&mut self, edited: Scene) -> bool {
        let (Some(host), Some(renderer)) = (self.host.as_mut(), self.renderer.as_mut()) else { return false };
        let applied = host.apply(&self.ctx, renderer, &mut self.shaders, edited);
        let rebuilt = matches!(applied, Ok(Applied::Rebuilt | Applied::RebuiltKeepingState));
        if rebuilt {
            // The new simulation's timestamp pools were never written: waiting on them would hang.
            self.frames.iter_mut().for_each(|f| f.simulated = false);
        }
        match applied {
            Ok(Applied::Rebuilt) => self.message("scene rebuilt from its initial state", false),
            Ok(Applied::RebuiltKeepingState) => self.message("simulation rebuilt; state kept", false),
            Ok(_) => {}
            Err(e) => {
                self.message(format!("not applied: {e:#}"), true);
                return false;
            }
        }
        if rebuilt {
            self.show_auto_pick();
        }
        true
    }

    /// Says what `integrator = "auto"` picked (a notice, and a line under the integrator).
    pub(super) fn show_auto_pick(&mut self) {
        self.editor.auto_picked = self.host.as_ref().and_then(|h| h.auto_picked()).map(str::to_string);
        if let Some(picked) = self.editor.auto_picked.clone() {
            self.message(picked, false);
        }
    }
}
