//! The simulation behind the app: the scene being edited, its model and the GPU simulation.
//! Edits are applied by kind: parameter changes rewrite the GPU parameters in place (the state
//! is kept); a new substep count, integrator or self-collision method rebuilds the simulation
//! and carries the state and the simulated time over; anything
//! that changes the particles' layout (sizes, positions, pins, objects, the colliders' number, types and motions) rebuilds
//! and starts from the new initial state.

use crate::render::SceneRenderer;
use crate::scene::{self, Scene};
use crate::shaders::ShaderSet;
use crate::sim::gpu::{self, GpuSim};
use crate::sim::gpu_types::Particle;
use crate::sim::model::SimModel;
use crate::vk::GpuContext;
use anyhow::Result;

/// What applying an edit did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Applied {
    Nothing,
    /// Parameters rewritten in place; the state is kept.
    Parameters,
    /// Rebuilt with the state carried over (substeps, integrator or self-collision method changed).
    RebuiltKeepingState,
    /// Rebuilt from the scene's initial state.
    Rebuilt,
}

pub struct SimHost {
    scene: Scene,
    model: SimModel,
    sim: GpuSim,
    /// Where particles pinned by Ctrl + click were pinned (object, index), for their markers;
    /// the others are pinned where the model places them.
    pinned_at: std::collections::HashMap<(usize, u32), [f32; 3]>,
    /// What `integrator = "auto"` picked for the running simulation (None for a named method).
    auto_picked: Option<String>,
    /// The scene asks for `integrator = "auto"` and has not been calibrated yet: the
    /// simulation runs the provisional model (`scene::to_model`) until `calibrate`.
    calibration_pending: bool,
}

/// The model of a scene, calibrated first when it asks for `integrator = "auto"`, and then
/// what it picked (also logged).
fn model_for(ctx: &GpuContext, scene: &Scene) -> Result<(SimModel, Option<String>)> {
    let (model, picked) = crate::study::integrator_choice::model_for(ctx, scene)?;
    if let Some(p) = &picked {
        log::info!("{p}");
    }
    Ok((model, picked))
}

/// What `integrator = "auto"` calibrates again for when it changes: the scene but for the light,
/// the colours and where the colliders and the wind's cone are (what the view's handles drag, a
/// frame at a time: calibrating for each frame of a drag stalled the window for seconds).
fn calibrated_part(s: &Scene) -> Scene {
    let mut s = s.clone();
    s.light = Default::default();
    s.cloths.iter_mut().for_each(|c| (c.color, c.back_color) = ([0.0; 3], [0.0; 3]));
    s.ropes.iter_mut().for_each(|r| r.color = [0.0; 3]);
    s.mesh_cloths.iter_mut().for_each(|c| (c.color, c.back_color) = ([0.0; 3], [0.0; 3]));
    s.spheres.iter_mut().for_each(|c| c.center = [0.0; 3]);
    s.boxes.iter_mut().for_each(|c| c.center = [0.0; 3]);
    for c in &mut s.capsules {
        (c.start, c.end) = ([0.0; 3], std::array::from_fn(|k| c.end[k] - c.start[k]));
    }
    s.wind.origin = [0.0; 3];
    s
}

/// The parts of a scene that fix the particles' layout and the buffers' sizes.
fn layout_key(s: &Scene) -> String {
    let cloths: Vec<_> = s
        .cloths
        .iter()
        .map(|c| {
            format!(
                "{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
                c.resolution,
                c.size,
                c.origin,
                c.orientation,
                c.pin,
                c.pinned,
                c.pin_box,
                c.pin_motion,
                c.pin_groups
            )
        })
        .collect();
    let ropes: Vec<_> = s
        .ropes
        .iter()
        .map(|r| {
            format!(
                "{}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
                r.nodes, r.start, r.end, r.pin, r.pinned, r.pin_box, r.pin_motion, r.pin_groups
            )
        })
        .collect();
    // A collider's motion (and pins') is a function of the time since the start: changing it
    // restarts (a pin motion's pivot is where the pins have been carried since).
    let kinds: Vec<_> =
        crate::scene::colliders(s).into_iter().map(|c| (c.shape.kind(), c.motion, c.turn)).collect();
    // A mesh collider's triangles are uploaded with the simulation and the renderer's meshes.
    let meshes: Vec<_> = s.meshes.iter().map(|m| (&m.file, m.scale, m.reach)).collect();
    // A mesh cloth's particles and topology come from its file as placed and welded.
    let mesh_cloths: Vec<_> = s
        .mesh_cloths
        .iter()
        .map(|c| {
            format!(
                "{}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
                c.file,
                c.center,
                c.rotation,
                c.scale,
                c.weld,
                c.sew,
                c.seams,
                c.pinned,
                c.pin_box,
                c.pin_motion,
                c.pin_groups
            )
        })
        .collect();
    format!("{cloths:?}{ropes:?}{kinds:?}{meshes:?}{mesh_cloths:?}")
}

impl SimHost {
    /// The simulation of `scene`. One that asks for `integrator = "auto"` starts uncalibrated
    /// (`calibration_pending`), so that the window can say that it will wait before
    /// `calibrate` holds it (seconds; minutes on a CPU driver).
    pub fn new(
        ctx: &GpuContext,
        scene: Scene,
        renderer: &mut SceneRenderer,
        shaders: &mut ShaderSet,
    ) -> Result<Self> {
        gpu::check_fits(ctx.info(), &scene::shapes(&scene))?;
        let model = scene::to_model(&scene);
        let sim = GpuSim::with_shaders(ctx, &model, shaders)?;
        if let Err(e) = renderer.set_objects(ctx, &scene::shapes(&scene), &scene::colliders(&scene)) {
            sim.destroy(ctx);
            return Err(e);
        }
        let calibration_pending = scene.sim.integrator.method().is_none();
        Ok(Self { scene, model, sim, pinned_at: Default::default(), auto_picked: None, calibration_pending })
    }

    /// Whether the scene waits for `calibrate` (see `new`).
    pub fn calibration_pending(&self) -> bool {
        self.calibration_pending
    }

    /// Calibrates `integrator = "auto"` for a scene that waits for it (`calibration_pending`)
    /// and rebuilds the simulation with the pick, from the state it has (the window does not
    /// simulate while it waits). On an error the provisional model stays, and so does the
    /// state.
    pub fn calibrate(&mut self, ctx: &GpuContext, shaders: &mut ShaderSet) -> Result<()> {
        if !std::mem::take(&mut self.calibration_pending) {
            return Ok(());
        }
        ctx.wait_idle()?;
        let (model, auto_picked) = model_for(ctx, &self.scene)?;
        let sim = self.new_sim(ctx, &model, shaders, true)?;
        std::mem::replace(&mut self.sim, sim).destroy(ctx);
        self.model = model;
        self.auto_picked = auto_picked;
        Ok(())
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// What `integrator = "auto"` picked for the running simulation (None for a named method).
    pub fn auto_picked(&self) -> Option<&str> {
        self.auto_picked.as_deref()
    }

    pub fn model(&self) -> &SimModel {
        &self.model
    }

    pub fn sim(&self) -> &GpuSim {
        &self.sim
    }

    pub fn sim_mut(&mut self) -> &mut GpuSim {
        &mut self.sim
    }

    /// The model of `edited` as the running simulation would take it in place: its own with a
    /// fixed method; with `integrator = "auto"`, the running pick, when the edit changed only
    /// what the calibration does not depend on (`calibrated_part`), else none (it calibrates
    /// again).
    fn model_keeping_pick(&self, edited: &Scene) -> Option<SimModel> {
        if self.calibrates_for(edited) {
            return None;
        }
        let mut model = scene::to_model(edited);
        if edited.sim.integrator.method().is_none() {
            (model.integrator, model.substeps, model.iterations) =
                (self.model.integrator, self.model.substeps, self.model.iterations);
        }
        Some(model)
    }

    /// The model with which `edited` applies in place (its parameters rewritten, the state
    /// kept), or none when it needs a new simulation: another layout of particles, other
    /// pipelines, a calibration, or parameters the running one cannot take.
    fn in_place_model(&self, edited: &Scene) -> Option<SimModel> {
        let (old, new) = (&self.scene.sim, &edited.sim);
        let same_pipelines = (old.substeps, old.integrator, old.self_collision, old.tolerance)
            == (new.substeps, new.integrator, new.self_collision, new.tolerance);
        (same_pipelines && layout_key(edited) == layout_key(&self.scene))
            .then(|| self.model_keeping_pick(edited))
            .flatten()
            .filter(|model| self.sim.takes_params(model))
    }

    /// Whether applying `edited` builds a new simulation (its pipelines compiled: milliseconds
    /// on a GPU, seconds on a CPU driver); not for a scene that would be refused.
    pub fn rebuilds_for(&self, edited: &Scene) -> bool {
        *edited != self.scene && scene::validate(edited).is_ok() && self.in_place_model(edited).is_none()
    }

    /// Whether applying `edited` calibrates `integrator = "auto"` (seconds; minutes on a CPU
    /// driver).
    pub fn calibrates_for(&self, edited: &Scene) -> bool {
        edited.sim.integrator.method().is_none() && calibrated_part(edited) != calibrated_part(&self.scene)
    }

    /// Applies an edited scene. An invalid or too large scene is refused with the reason and
    /// the running simulation is left as it was.
    pub fn apply(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut SceneRenderer,
        shaders: &mut ShaderSet,
        edited: Scene,
    ) -> Result<Applied> {
        if edited == self.scene {
            return Ok(Applied::Nothing);
        }
        scene::validate(&edited).map_err(crate::error::UserError)?;
        let same_layout = layout_key(&edited) == layout_key(&self.scene);
        if let Some(model) = self.in_place_model(&edited) {
            ctx.wait_idle()?;
            self.sim.update_params(&model)?;
            self.model = model;
            self.scene = edited;
            return Ok(Applied::Parameters);
        }
        gpu::check_fits(ctx.info(), &scene::shapes(&edited))?;
        ctx.wait_idle()?;
        let (model, auto_picked) = model_for(ctx, &edited)?;
        let sim = self.new_sim(ctx, &model, shaders, same_layout)?;
        if let Err(e) = renderer.set_objects(ctx, &scene::shapes(&edited), &scene::colliders(&edited)) {
            sim.destroy(ctx);
            // The renderer's index buffers are gone: restore them for the old scene.
            renderer.set_objects(ctx, &scene::shapes(&self.scene), &scene::colliders(&self.scene))?;
            return Err(e);
        }
        std::mem::replace(&mut self.sim, sim).destroy(ctx);
        self.model = model;
        self.scene = edited;
        self.auto_picked = auto_picked;
        if !same_layout {
            self.pinned_at.clear();
        }
        Ok(if same_layout { Applied::RebuiltKeepingState } else { Applied::Rebuilt })
    }

    /// A new simulation of `model`; with `carry`, it goes on from the running one's state and
    /// time (and so do the colliders' motions). The running one is left as it is.
    fn new_sim(
        &mut self,
        ctx: &GpuContext,
        model: &SimModel,
        shaders: &mut ShaderSet,
        carry: bool,
    ) -> Result<GpuSim> {
        let carried = if carry { Some(self.sim.read_states(ctx)?) } else { None };
        let mut sim = GpuSim::with_shaders(ctx, model, shaders)?;
        if let Some(states) = &carried {
            sim.continue_at(self.sim.time());
            let particles: Vec<_> = states.iter().map(|s| s.particles.clone()).collect();
            if let Err(e) = sim.upload_states(ctx, &particles) {
                sim.destroy(ctx);
                return Err(e);
            }
        }
        Ok(sim)
    }

    /// Pins or unpins particle `index` of object `object` at `at` (where it is: Ctrl + click): in the
    /// running simulation at the next frame, in the model (a reset keeps it) and in the scene's
    /// `pinned` list (saving keeps it). A particle pinned by the object's `pin` rule cannot be
    /// unpinned this way: the error says which rule to change. The first pin of an object or the
    /// removal of its last rewrites its parameters (the adaptive methods start a held object's
    /// particles otherwise: `OBJ_ANCHORED`), after the frames in flight.
    pub fn set_pinned(
        &mut self,
        ctx: &GpuContext,
        object: usize,
        index: u32,
        pin: bool,
        at: [f32; 3],
    ) -> Result<(), String> {
        let n_cloths = self.scene.cloths.len();
        let o = self.model.objects.get_mut(object).ok_or("no such object")?;
        let i = index as usize;
        if i >= o.pinned.len() {
            return Err("no such particle".into());
        }
        let cols = o.dims[0];
        let (col, row) = (index % cols, index / cols);
        let group = o.group_of(i);
        let n_grids = n_cloths + self.scene.ropes.len();
        if object >= n_grids {
            // A mesh cloth's particles by vertex index.
            let (rest, held) = (o.positions[i], o.pinned[i] && group > 0);
            let c = self.scene.mesh_cloths.get_mut(object - n_grids).ok_or("no such object")?;
            if held {
                return Err(format!(
                    "mesh cloth '{}' vertex {index} is held by its pin_group[{}]: take it out of that group to free it",
                    c.name,
                    group - 1
                ));
            }
            let boxed = c.pin_box.is_some_and(|b| b.contains(rest));
            if (!pin && boxed) || !set_listed(&mut c.pinned, index, pin) {
                return Err(format!(
                    "mesh cloth '{}' vertex {index} is pinned by its pin_box: change the pin_box to free it",
                    c.name
                ));
            }
            if !c.has_pins() {
                c.pin_motion = None;
            }
        } else if o.pinned[i] && group > 0 {
            let (kind, name, which) = match object < n_cloths {
                true => ("cloth", &self.scene.cloths[object].name, format!("particle [{col}, {row}]")),
                false => ("rope", &self.scene.ropes[object - n_cloths].name, format!("node {index}")),
            };
            return Err(format!(
                "{kind} '{name}' {which} is held by its pin_group[{}]: take it out of that group to free it",
                group - 1
            ));
        }
        if object >= n_grids {
            // (done above)
        } else if object < n_cloths {
            let cloth = &mut self.scene.cloths[object];
            let by_rule = cloth.pinned_by_rule()[i];
            if (!pin && by_rule) || !set_listed(&mut cloth.pinned, [col, row], pin) {
                let also = if cloth.pin_box.is_some() { " or pin_box" } else { "" };
                return Err(format!(
                    "cloth '{}' particle [{col}, {row}] is pinned by pin = {:?}{also}: change the cloth's pin{also} to free it",
                    cloth.name, cloth.pin
                ));
            }
            if !cloth.has_pins() {
                cloth.pin_motion = None; // (nothing left for it to move: a preset with it is refused)
            }
        } else {
            let rope = &mut self.scene.ropes[object - n_cloths];
            let by_rule = rope.pinned_by_rule()[i];
            if (!pin && by_rule) || !set_listed(&mut rope.pinned, index, pin) {
                let also = if rope.pin_box.is_some() { " or pin_box" } else { "" };
                return Err(format!(
                    "rope '{}' node {index} is pinned by pin = {:?}{also}: change the rope's pin{also} to free it",
                    rope.name, rope.pin
                ));
            }
            if !rope.has_pins() {
                rope.pin_motion = None;
            }
        }
        let anchored = o.anchored();
        o.pinned[i] = pin;
        let anchoring = o.anchored() != anchored;
        if pin {
            self.pinned_at.insert((object, index), at);
        } else {
            self.pinned_at.remove(&(object, index));
        }
        let particle = Particle { pos: [at[0], at[1], at[2], pin as u32 as f32], vel: [0.0; 4] };
        self.sim.set_particle(object, index, particle);
        if anchoring {
            let mut rewrite = || -> Result<()> {
                ctx.wait_idle()?;
                self.sim.update_params(&self.model)
            };
            rewrite().map_err(|e| format!("pinning: the object's parameters: {e:#}"))?;
        }
        Ok(())
    }

    /// Puts every object back to the scene's initial state.
    pub fn reset(&mut self, ctx: &GpuContext) -> Result<()> {
        ctx.wait_idle()?;
        let initial: Vec<_> =
            self.model.objects.iter().map(|o| gpu::particles(o, self.model.frame_dt)).collect();
        self.sim.upload_states(ctx, &initial)?;
        self.sim.reset_time();
        self.pinned_at.clear();
        Ok(())
    }

    /// Where every pinned particle is held (its marker in the view): where it was placed,
    /// carried by its pins' motion to now (`PinMotion::carried`).
    pub fn pin_markers(&self) -> Vec<glam::Vec3> {
        let mut out = Vec::new();
        let now = self.sim.time();
        for (k, o) in self.model.objects.iter().enumerate() {
            for (i, _) in o.pinned.iter().enumerate().filter(|(_, &p)| p) {
                out.push(match self.pinned_at.get(&(k, i as u32)) {
                    Some(&at) => glam::Vec3::from(at),
                    None => o.pin_carried(i, o.positions[i], now).as_vec3(),
                });
            }
        }
        out
    }

    pub fn destroy(self, ctx: &GpuContext) {
        self.sim.destroy(ctx);
    }
}

/// Adds `item` to `list` (`pin`) or removes it; false when asked to remove an item the list
/// does not hold (a particle pinned by a rule, not by the list).
fn set_listed<T: PartialEq>(list: &mut Vec<T>, item: T, pin: bool) -> bool {
    match (pin, list.iter().position(|p| *p == item)) {
        (true, None) => list.push(item),
        (false, Some(k)) => drop(list.remove(k)),
        (false, None) => return false,
        (true, Some(_)) => {}
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mesh cloth placed, welded or pinned otherwise, or another one added, is a new layout
    /// (its particles come anew from its file; the running state is not carried into it); its
    /// material is not.
    #[test]
    fn a_mesh_cloths_placement_is_part_of_the_layout() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/skirt.toml");
        let base = scene::load(&path, &[]).unwrap();
        let same = |edit: fn(&mut Scene)| {
            let mut s = base.clone();
            edit(&mut s);
            layout_key(&s) == layout_key(&base)
        };
        assert!(same(|s| s.mesh_cloths[0].stiffness.structural *= 2.0));
        assert!(same(|s| s.mesh_cloths[0].self_collision = false));
        assert!(!same(|s| s.mesh_cloths[0].center[1] += 0.1));
        assert!(!same(|s| s.mesh_cloths[0].rotation[1] = 90.0));
        assert!(!same(|s| s.mesh_cloths[0].weld = 0.01));
        assert!(!same(|s| s.mesh_cloths[0].pinned.push(3)));
        assert!(!same(|s| s.mesh_cloths.push(s.mesh_cloths[0].clone())));
    }

    /// `auto` keeps its pick for the light, colours and what the handles drag (a sphere, a
    /// capsule moved whole, the wind's cone), and calibrates again for a material, a
    /// collider's size or the simulation settings.
    #[test]
    fn auto_calibrates_again_only_for_what_it_measured() {
        let mut base =
            scene::parse(include_str!("../../presets/playground.toml"), "playground.toml", &[]).unwrap();
        let capsule =
            scene::Capsule { start: [0.0, 0.2, 0.0], end: [0.5, 0.2, 0.0], radius: 0.05, motion: None };
        base.capsules.push(capsule);
        let same = |edit: fn(&mut Scene)| {
            let mut s = base.clone();
            edit(&mut s);
            calibrated_part(&s) == calibrated_part(&base)
        };
        assert!(same(|s| s.light.position[1] += 1.0));
        assert!(same(|s| s.cloths[0].color = [1.0, 0.0, 0.0]));
        assert!(same(|s| s.spheres[0].center[0] += 0.3));
        assert!(same(|s| s.wind.origin[2] -= 0.5));
        assert!(same(|s| s
            .capsules
            .iter_mut()
            .for_each(|c| (c.start[1], c.end[1]) = (c.start[1] + 0.2, c.end[1] + 0.2))));
        assert!(!same(|s| s.cloths[0].stiffness.structural *= 2.0));
        assert!(!same(|s| s.spheres[0].radius *= 1.5));
        assert!(!same(|s| s.sim.substeps += 1));
        assert!(!same(|s| s.capsules.iter_mut().for_each(|c| c.end[0] += 0.2)), "a capsule stretched");
    }
}
