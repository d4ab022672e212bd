//! Applying an edited scene to the running simulation, and what the app says about it.

use super::Viewer;
use crate::app::sim_host::Applied;
use crate::scene::{self, Scene};
use crate::ui::Action;

/// A build of the simulation slower than this is announced a frame before the next one
/// (`Viewer::edits_wait`): on a GPU builds take milliseconds and go unannounced.
const SLOW_REBUILD: std::time::Duration = std::time::Duration::from_millis(300);

impl Viewer {
    /// Applies an edited scene, reporting refusals in the editor; false when refused.
    pub(super) fn apply(&mut self, edited: Scene) -> bool {
        let (Some(host), Some(renderer)) = (self.host.as_mut(), self.renderer.as_mut()) else { return false };
        let calibrates = host.calibrates_for(&edited);
        let started = std::time::Instant::now();
        let applied = host.apply(&self.ctx, renderer, &mut self.shaders, edited);
        let rebuilt = matches!(applied, Ok(Applied::Rebuilt | Applied::RebuiltKeepingState));
        if rebuilt && !calibrates {
            // (A build's own time: a calibration's is announced on its own.)
            self.last_rebuild = started.elapsed();
        }
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

    /// Whether the pending edits and actions wait a frame, so that the frame before says in a
    /// notice that the window will wait: they calibrate `integrator = "auto"` (seconds; minutes
    /// on a CPU driver), build a new simulation where the last build took more than
    /// `SLOW_REBUILD` (its pipelines compiled: seconds on a CPU driver), or stop a long
    /// recording that is written when it stops (`AppRecorder::long_write`). True once for them;
    /// the next frame applies them.
    pub(super) fn edits_wait(&mut self) -> bool {
        if std::mem::take(&mut self.wait_announced) {
            return false;
        }
        let Some(host) = self.host.as_ref() else { return false };
        // What applying each pending scene or action would hold the window for: (calibrates,
        // builds a new simulation slowly). A preset to load is read once.
        let slow = self.last_rebuild > SLOW_REBUILD;
        let holds = |s: &Scene| (host.calibrates_for(s), slow && host.rebuilds_for(s));
        let mut waits: Vec<(bool, bool)> = self.pending_scene.iter().map(holds).collect();
        for a in &self.pending_actions {
            match a {
                Action::Load(path) => waits.extend(scene::load(path, &[]).ok().as_ref().map(holds)),
                Action::AddClothFromPreset(_) => {
                    waits.push((host.scene().sim.integrator.method().is_none(), slow))
                }
                _ => {}
            }
        }
        let calibrates = host.calibration_pending() || waits.iter().any(|w| w.0);
        let rebuilds = !calibrates && waits.iter().any(|w| w.1);
        let stops = self.pending_actions.iter().any(|a| matches!(a, Action::ToggleRecording(_)));
        let writes = self.recorder.long_write().filter(|_| stops);
        if calibrates {
            self.message(
                "calibrating integrator = \"auto\": the window waits until it has picked a method",
                false,
            );
        } else if rebuilds {
            let took = self.last_rebuild.as_secs_f64();
            self.message(
                format!("rebuilding the simulation: the window waits (the last build took {took:.1} s)"),
                false,
            );
        } else if let Some((frames, path)) = &writes {
            self.message(format!("writing {frames} frames to {}: the window waits", path.display()), false);
        }
        self.wait_announced = calibrates || rebuilds || writes.is_some();
        self.wait_announced
    }

    /// Calibrates a scene that started with `integrator = "auto"` (`SimHost::calibration_pending`:
    /// the frame before said that the window waits); an error is reported and the provisional
    /// method runs on.
    pub(super) fn calibrate_pending(&mut self) {
        let Some(host) = self.host.as_mut().filter(|h| h.calibration_pending()) else { return };
        match host.calibrate(&self.ctx, &mut self.shaders) {
            Ok(()) => {
                // The new simulation's timestamp pools were never written: waiting on them would hang.
                self.frames.iter_mut().for_each(|f| f.simulated = false);
                self.show_auto_pick();
            }
            Err(e) => {
                let method = host.model().integrator.label();
                self.message(
                    format!("integrator = \"auto\" could not calibrate: {e:#}; running {method} meanwhile"),
                    true,
                )
            }
        }
    }

    /// Says what `integrator = "auto"` picked (a notice, and a line under the integrator).
    pub(super) fn show_auto_pick(&mut self) {
        self.editor.auto_picked = self.host.as_ref().and_then(|h| h.auto_picked()).map(str::to_string);
        if let Some(picked) = self.editor.auto_picked.clone() {
            self.message(picked, false);
        }
    }
}
