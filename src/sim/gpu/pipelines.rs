//! The compute pipelines of a simulation, created for what its model uses: a scene without
//! self-collision builds no spatial hash pipelines, an explicit integrator no solver pipelines.

use super::{CLOTH_GROUP, FUSED_MAX, ROPE_GROUP};
use crate::shaders::ShaderSet;
use crate::sim::model::{Integrator, ObjectKind, SelfCollisionMethod, SimModel};
use crate::vk::{BindingSetLayout, ComputePipeline, GpuContext, Retired};
use anyhow::{Context as _, Result};
use std::collections::HashMap;

/// One compute pipeline: a shader with its specialization constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Stage {
    /// Forces and the explicit step (`verlet`: position Verlet, else symplectic Euler).
    Physics(ObjectKind, bool),
    /// The inertial prediction of the iterative integrators (`implicit`, else XPBD).
    Predict(ObjectKind, bool),
    XpbdIterate(ObjectKind),
    ImplicitIterate(ObjectKind),
    Constraints(ObjectKind),
    /// Cloth normals or rope tube vertices (and the runtime guard).
    Surface(ObjectKind),
    HashScan(u32),
    HashScatter,
    /// Every substep of a small object in one workgroup (`verlet` as for `Physics`).
    Fused(bool),
}

fn group(kind: ObjectKind) -> Vec<u32> {
    match kind {
        ObjectKind::Cloth => CLOTH_GROUP.to_vec(),
        ObjectKind::Rope => vec![ROPE_GROUP, 1],
    }
}

impl Stage {
    pub(super) fn shader(self) -> &'static str {
        match self {
            Stage::Physics(..) => "physics.comp",
            Stage::Predict(..) => "predict.comp",
            Stage::XpbdIterate(_) => "xpbd_iterate.comp",
            Stage::ImplicitIterate(_) => "implicit_iterate.comp",
            Stage::Constraints(_) => "constraints.comp",
            Stage::Surface(ObjectKind::Cloth) => "cloth_normals.comp",
            Stage::Surface(ObjectKind::Rope) => "rope_vertices.comp",
            Stage::HashScan(_) => "hash_scan.comp",
            Stage::HashScatter => "hash_scatter.comp",
            Stage::Fused(_) => "fused.comp",
        }
    }

    /// Constant `i` has id `i`: the step shaders take their workgroup shape (ids 0, 1) and a
    /// variant flag (id 2); the scan takes its phase.
    fn specialization(self) -> Vec<u32> {
        match self {
            Stage::Physics(kind, flag) | Stage::Predict(kind, flag) => {
                [group(kind), vec![flag as u32]].concat()
            }
            Stage::XpbdIterate(kind) | Stage::ImplicitIterate(kind) | Stage::Constraints(kind) => group(kind),
            Stage::Surface(_) | Stage::HashScatter => Vec::new(),
            Stage::HashScan(phase) => vec![phase],
            Stage::Fused(verlet) => vec![0, 0, verlet as u32],
        }
    }

    /// The pipelines `model` needs.
    pub(super) fn needed(model: &SimModel) -> Vec<Stage> {
        let mut kinds: Vec<ObjectKind> = model.objects.iter().map(|o| o.kind).collect();
        kinds.sort_by_key(|k| *k as u32);
        kinds.dedup();
        let verlet = model.integrator == Integrator::Verlet;
        let mut stages = Vec::new();
        for &kind in &kinds {
            match model.integrator {
                Integrator::SymplecticEuler | Integrator::Verlet => stages.push(Stage::Physics(kind, verlet)),
                Integrator::Xpbd => stages.extend([Stage::Predict(kind, false), Stage::XpbdIterate(kind)]),
                Integrator::Implicit => {
                    stages.extend([Stage::Predict(kind, true), Stage::ImplicitIterate(kind)])
                }
            }
            stages.extend([Stage::Constraints(kind), Stage::Surface(kind)]);
        }
        if model.self_collision == SelfCollisionMethod::Hash
            && model.objects.iter().any(|o| o.self_distance.is_some())
        {
            stages.extend([Stage::HashScan(0), Stage::HashScan(1), Stage::HashScan(2), Stage::HashScatter]);
        }
        if !model.integrator.iterative()
            && model.objects.iter().any(|o| o.particle_count() as u32 <= FUSED_MAX)
        {
            stages.push(Stage::Fused(verlet));
        }
        stages
    }
}

pub(super) struct Pipelines {
    map: HashMap<Stage, ComputePipeline>,
}

impl Pipelines {
    /// Creates the pipelines of `stages`, each shader compiled (or loaded) once.
    pub(super) fn new(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        shaders: &mut ShaderSet,
        stages: &[Stage],
    ) -> Result<Self> {
        let mut map = HashMap::new();
        let mut compiled: HashMap<&str, Vec<u32>> = HashMap::new();
        for &stage in stages {
            let name = stage.shader();
            let words = match compiled.get(name) {
                Some(w) => Ok(w.clone()),
                None => shaders.load_or_embedded(name),
            };
            let pipeline = words.and_then(|words| {
                let p = Self::create(ctx, layout, stage, &words);
                compiled.insert(name, words);
                p
            });
            match pipeline {
                Ok(p) => {
                    map.insert(stage, p);
                }
                Err(e) => {
                    Self { map }.destroy(ctx);
                    return Err(e);
                }
            }
        }
        Ok(Self { map })
    }

    fn create(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        stage: Stage,
        words: &[u32],
    ) -> Result<ComputePipeline> {
        let name = stage.shader();
        ComputePipeline::new(ctx, name, words, layout, &stage.specialization())
            .with_context(|| format!("creating pipeline {name} ({stage:?})"))
    }

    /// Rebuilds the pipelines of the `changed` shaders that compile; returns the names
    /// reloaded and the replaced pipelines (still possibly in use by frames in flight).
    pub(super) fn reload(
        &mut self,
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        shaders: &mut ShaderSet,
        changed: &[String],
    ) -> (Vec<String>, Vec<Retired>) {
        let mut reloaded = Vec::new();
        let mut retired = Vec::new();
        for name in changed {
            let mut stages: Vec<Stage> = self.map.keys().copied().filter(|s| s.shader() == name).collect();
            if stages.is_empty() {
                continue;
            }
            stages.sort_by_key(|s| format!("{s:?}"));
            let Ok(words) = shaders.load(name) else { continue }; // error recorded in `shaders`
            let mut fresh = Vec::new();
            for &stage in &stages {
                match Self::create(ctx, layout, stage, &words) {
                    Ok(p) => fresh.push((stage, p)),
                    Err(e) => log::error!("shader {name}: {e:#}"),
                }
            }
            if fresh.len() == stages.len() {
                for (stage, p) in fresh {
                    if let Some(old) = self.map.insert(stage, p) {
                        retired.push(Retired::Compute(old));
                    }
                }
                reloaded.push(name.clone());
            } else {
                fresh.into_iter().for_each(|(_, p)| p.destroy(ctx));
            }
        }
        (reloaded, retired)
    }

    /// The pipeline of `stage`, which `Stage::needed` listed for the simulation's model.
    pub(super) fn get(&self, stage: Stage) -> &ComputePipeline {
        match self.map.get(&stage) {
            Some(p) => p,
            None => unreachable!("pipeline {stage:?} was not created for this model"),
        }
    }

    pub(super) fn destroy(self, ctx: &GpuContext) {
        for (_, p) in self.map {
            p.destroy(ctx);
        }
    }
}
