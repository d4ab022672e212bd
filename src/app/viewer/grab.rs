//! The mouse on the scene: the selection's translate handles, and grabbing, dragging and
//! pinning particles.

use super::super::handles;
use super::super::input::{pick, pick_radii, Grab, PickRay};
use super::Viewer;
use crate::sim::gpu_types::Particle;
use glam::Vec3;

impl Viewer {
    /// Takes, drags and lets go of the selection's translate handles; true while one is held
    /// (the click then picks no particle).
    fn update_handles(&mut self) -> bool {
        let size = self.window.inner_size();
        let size = [size.width as f32, size.height as f32];
        let (from, dir) = self.camera.ray(self.input.cursor, size);
        let target = self.editor.selected;
        if self.input.pick_requested {
            let at = self.host.as_ref().and_then(|h| handles::position(h.scene(), target));
            if let Some(axis) = at.and_then(|at| handles::hit(&self.camera, size, self.input.cursor, at)) {
                self.input.pick_requested = false;
                self.handle = Some(handles::Drag::begin(target, axis, at.expect("hit"), from, dir));
            }
        }
        let Some(drag) = self.handle else { return false };
        if !self.input.left_down() || drag.target != target {
            self.handle = None;
            return false;
        }
        let (Some(host), Some(to)) = (self.host.as_ref(), drag.position(from, dir)) else { return true };
        let mut edited = host.scene().clone();
        handles::set_position(&mut edited, drag.target, to);
        if edited != *host.scene() {
            self.apply(edited);
        }
        true
    }

    /// Picks, drags and releases particles (after the UI, before recording).
    pub(super) fn update_grab(&mut self) {
        // While an edit waits to be applied (edits_wait), clicks, pins and handle drags wait
        // with it: applied to the running scene now, the waiting edit would undo them.
        if self.wait_announced || self.update_handles() {
            return;
        }
        let size = self.window.inner_size();
        let (origin, dir) = self.camera.ray(self.input.cursor, [size.width as f32, size.height as f32]);
        let ray = PickRay { origin, dir, pixel: self.camera.pixel_size(size.height as f32) };
        if std::mem::take(&mut self.input.pin_requested) {
            let Some(host) = self.host.as_mut() else { return };
            let radii = pick_radii(host.model());
            let picked = host.sim_mut().read_states(&self.ctx).map(|states| {
                pick(&states, ray, &radii, f32::INFINITY)
                    .map(|hit| (hit, states[hit.0].particles[hit.1 as usize].pos))
            });
            match picked {
                Ok(Some(((object, index, _, was_pinned), p))) => {
                    let at = [p[0], p[1], p[2]];
                    if let Err(e) = self.host.as_mut().expect("host").set_pinned(
                        &self.ctx,
                        object,
                        index,
                        !was_pinned,
                        at,
                    ) {
                        self.message(e, true);
                    }
                }
                Ok(None) => {}
                Err(e) => self.message(format!("picking failed: {e:#}"), true),
            }
        }
        if std::mem::take(&mut self.input.pick_requested) {
            let Some(host) = self.host.as_mut() else { return };
            let radii = pick_radii(host.model());
            // A sphere, box or capsule in front of the particle (or with none behind it) is
            // selected instead, and the drag orbits.
            let collider = handles::pick_collider(host.scene(), host.sim().time(), origin, dir);
            let nearer = collider.map_or(f32::INFINITY, |(_, t)| t);
            match host.sim_mut().read_states(&self.ctx) {
                Ok(states) => match pick(&states, ray, &radii, nearer) {
                    Some((object, index, depth, was_pinned)) => {
                        self.input.grab =
                            Some(Grab { object, index, depth, was_pinned, target: origin + dir * depth });
                        // Clicking an object also selects it (its parameters in the panel).
                        self.editor.selected = crate::ui::Selection::of_object(object, host.scene());
                    }
                    None => {
                        if let Some((target, _)) = collider {
                            self.editor.selected = target;
                        }
                        self.input.pick_missed();
                    }
                },
                Err(e) => self.message(format!("picking failed: {e:#}"), true),
            }
        }
        // (w: 1 + its pin group where pinned, as `sim::gpu::particles` has it)
        let particle =
            |target: Vec3, w: f32| Particle { pos: [target.x, target.y, target.z, w], vel: [0.0; 4] };
        if let Some(grab) = self.input.grab.as_mut() {
            grab.target = origin + dir * grab.depth;
            let (object, index, target) = (grab.object, grab.index, grab.target);
            if let Some(host) = self.host.as_mut() {
                host.sim_mut().set_particle(object, index, particle(target, 1.0));
            }
        }
        if let Some(released) = self.input.released.take() {
            if let Some(host) = self.host.as_mut() {
                let group = host.model().objects[released.object].group_of(released.index as usize);
                let w = if released.was_pinned { 1.0 + group as f32 } else { 0.0 };
                host.sim_mut().set_particle(released.object, released.index, particle(released.target, w));
            }
        }
    }
}
