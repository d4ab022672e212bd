//! The compute pipelines of a simulation, created for what its model uses: a scene without
//! self-collision builds no spatial hash pipelines, an explicit integrator no solver pipelines,
//! and the step shaders are specialized with the features each object uses (`FEATURES`,
//! `glsl/include/features.glsl`), so what a scene does not use is compiled out.

use super::fused::{FusedShape, ObjectPlan};
use super::{CLOTH_GROUP, ROPE_GROUP};
use crate::shaders::ShaderSet;
use crate::sim::integrator::{Scheme, Solver};
use crate::sim::model::{Integrator, ObjectKind, SimModel};
use crate::vk::{BindingSetLayout, ComputePipeline, GpuContext, Retired};
use anyhow::{Context as _, Result};
use std::collections::HashMap;

/// A pass of a cloth's contact with its own triangles (`self_pairs.comp`'s PASS, in its order).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum SelfPass {
    /// Each particle's contacts found, kept and counted.
    Find,
    /// Each contact's moves summed into its particles.
    Apply,
    /// The physics output moved by the sums (between passes, `sim.contact_iterations` > 1).
    Move,
    /// The kept contacts applied again from the moved positions.
    Reapply,
    /// After the constraint stage, with a cloth's edge pairs (and the spatial hash built again
    /// from where the particles began the substep: `Stage::TruncationHash`): each particle's pairs near where they began the substep noted in their particles'
    /// truncations.
    Note,
    /// Each particle's move over the substep truncated as noted.
    Truncate,
}

/// One compute pipeline: a shader with its specialization constants. `u32` fields are the
/// `FEATURES` bits (`ObjectPlan::features`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Stage {
    /// Forces and the explicit step (`verlet`: position Verlet, else symplectic Euler).
    Physics(ObjectKind, bool, u32),
    /// The inertial prediction of an iterative integrator.
    Predict(ObjectKind, Integrator, u32),
    /// A free object's rigid start (`rigid_start.comp`): the methods that start adaptively.
    RigidStart(ObjectKind, u32),
    /// One iteration (or one colour of one) of an iterative integrator's solver.
    /// (`bool`: a mesh cloth's, which reads its lists.)
    Iterate(ObjectKind, Integrator, bool),
    /// The constraints (`lists`: with the self-collision contact lists on, `hash.rs`).
    Constraints(ObjectKind, u32, bool),
    /// The stretch limit's counts, before the constraints (objects with a stretch limit).
    StretchCount(ObjectKind, u32),
    /// A cloth's contact with its own triangles: one of its passes (`lists`: with the contact
    /// lists on, which only the find and apply passes read; `self_pairs.comp`).
    SelfPairs(u32, bool, SelfPass),
    /// Cloth normals or rope tube vertices and the runtime guard (`drawn`), or the guard alone.
    Surface(ObjectKind, bool, bool),
    HashCount,
    HashScan,
    /// The hash's scatter (`creases`: a cloth with edge-edge contact also notes how creased
    /// each particle's ring edges are, glsl/include/creases.glsl).
    HashScatter(bool),
    /// The hash built again from where the particles began the substep, for a cloth's
    /// truncation (`truncation_hash.comp`): the count, or (`true`) the scatter.
    TruncationHash(bool),
    /// Contact between objects (`contact.rs`): one object's entries, the scene hash's count
    /// and scatter, and its query.
    ContactBegin,
    ContactHash,
    /// `segments`: the ropes' work items, with their segments' tests compiled in (contact.comp's
    /// SEGMENTS); without, the cloths' items and each object's sums.
    /// `cloth_edges`: cloths' edges kept from each other's compiled in (CLOTH_EDGES,
    /// `SimModel::has_cloth_edges_between`).
    Contact {
        segments: bool,
        cloth_edges: bool,
        /// Entries of a particle's list (contact.comp's PAIR_MAX, `contact::pair_max`).
        pair_max: u32,
    },
    /// Every substep of an object in one workgroup, with the model's integrator.
    Fused(Integrator, u32, FusedShape),
}

/// The solver of an iterative method (the stages that take one are created only for those).
fn solver(method: Integrator) -> Solver {
    match method.solver() {
        Some(s) => s,
        None => unreachable!("{method:?} has no solver stages"),
    }
}

/// Whether an object of `features` has a cloth's edge-edge self-contact, whose hash scatter
/// notes each particle's ring creases in self_pairs (`Stage::HashScatter`).
pub(super) fn has_creases(features: u32) -> bool {
    crate::sim::gpu_types::has_cloth_edge_pairs(features)
}

/// The workgroup shape of a step stage: a grid cloth's cells in squares, a rope's nodes and a
/// mesh cloth's particles (features `f`) in a row.
fn group(kind: ObjectKind, f: u32) -> Vec<u32> {
    match kind {
        ObjectKind::Cloth if f & crate::sim::gpu_types::FEATURE_CLOTH_MESH == 0 => CLOTH_GROUP.to_vec(),
        _ => vec![ROPE_GROUP, 1],
    }
}

impl Stage {
    pub(super) fn shader(self) -> &'static str {
        match self {
            Stage::Physics(..) => "physics.comp",
            Stage::Predict(..) => "predict.comp",
            Stage::RigidStart(..) => "rigid_start.comp",
            Stage::Iterate(_, method, _) => solver(method).shader,
            Stage::Constraints(..) => "constraints.comp",
            Stage::StretchCount(..) => "stretch_count.comp",
            Stage::SelfPairs(..) => "self_pairs.comp",
            Stage::Surface(ObjectKind::Cloth, ..) => "cloth_normals.comp",
            Stage::Surface(ObjectKind::Rope, ..) => "rope_vertices.comp",
            Stage::HashCount => "hash_count.comp",
            Stage::HashScan => "hash_scan.comp",
            Stage::HashScatter(_) => "hash_scatter.comp",
            Stage::TruncationHash(_) => "truncation_hash.comp",
            Stage::ContactBegin => "contact_begin.comp",
            Stage::ContactHash => "contact_hash.comp",
            Stage::Contact { .. } => "contact.comp",
            Stage::Fused(..) => "fused.comp",
        }
    }

    /// Whether its shader runs a chunk of objects a dispatch (defines BATCHED,
    /// glsl/include/batch.glsl; `batch.rs`).
    pub(super) fn batched(self) -> bool {
        matches!(
            self,
            Stage::Physics(..)
                | Stage::Predict(..)
                | Stage::RigidStart(..)
                | Stage::Iterate(..)
                | Stage::Constraints(..)
                | Stage::StretchCount(..)
                | Stage::ContactBegin
                | Stage::Contact { .. }
        )
    }

    /// Constant `i` has id `i`: the step shaders take their workgroup shape (ids 0, 1), a
    /// variant flag (id 2; the prediction has none) and the features (id 3), the prediction also
    /// whether it keeps y (id 4) and starts adaptively (id 5); the fused kernel
    /// its layout (`FusedShape::specialization`).
    fn specialization(self) -> Vec<u32> {
        match self {
            Stage::Physics(kind, verlet, f) => [group(kind, f), vec![verlet as u32, f]].concat(),
            Stage::Predict(kind, method, f) => {
                let s = solver(method);
                [group(kind, f), vec![0, f, s.keeps_prediction as u32, s.adaptive_start as u32]].concat()
            }
            Stage::Constraints(kind, f, lists) => [group(kind, f), vec![lists as u32, f]].concat(),
            Stage::StretchCount(kind, f) | Stage::RigidStart(kind, f) => {
                [group(kind, f), vec![0, f]].concat()
            }
            Stage::SelfPairs(f, lists, pass) => {
                // (dispatched over the object's step groups, a rope's when its segments pair;
                // with a cloth's edge pairs the searches' lanes times as wide: `lanes_of`)
                let rope = f & crate::sim::gpu_types::FEATURE_SEGMENT_PAIRS != 0;
                let kind = if rope { ObjectKind::Rope } else { ObjectKind::Cloth };
                [group(kind, f), vec![lists as u32, f, pass as u32]].concat()
            }
            // (compiled for every feature but a rope's segment pairs, as the shader's default;
            // a mesh cloth's with its lists)
            Stage::Iterate(_, _, true) => {
                let f = crate::sim::gpu_types::FEATURES_DEFAULT | crate::sim::gpu_types::FEATURE_CLOTH_MESH;
                [group(ObjectKind::Cloth, f), vec![0, f]].concat()
            }
            Stage::Iterate(kind, _, false) => group(kind, 0),
            // (a mesh cloth's with its lists: FEATURES, id 3)
            Stage::Surface(_, drawn, true) => {
                let f = crate::sim::gpu_types::FEATURES_DEFAULT | crate::sim::gpu_types::FEATURE_CLOTH_MESH;
                vec![drawn as u32, 0, 0, f]
            }
            Stage::Surface(_, drawn, false) => vec![drawn as u32],
            Stage::HashScatter(creases) => vec![creases as u32],
            Stage::TruncationHash(scatter) => vec![scatter as u32],
            Stage::Contact { segments, cloth_edges, pair_max } => {
                vec![segments as u32, cloth_edges as u32, pair_max]
            }
            Stage::HashCount | Stage::HashScan | Stage::ContactBegin | Stage::ContactHash => Vec::new(),
            Stage::Fused(method, f, shape) => shape.specialization(method, f),
        }
    }

    /// The step stages of an object of `kind` with `plan` (physics or the solver, constraints,
    /// the surface variants, the fused kernel when it has a layout), specialized for the
    /// features it uses.
    pub(super) fn of_object(kind: ObjectKind, model: &SimModel, plan: ObjectPlan) -> Vec<Stage> {
        let f = plan.features;
        let mesh = f & crate::sim::gpu_types::FEATURE_CLOTH_MESH != 0;
        let method = model.integrator;
        let mut stages = match method.method().scheme {
            Scheme::Explicit { verlet } => vec![Stage::Physics(kind, verlet, f)],
            Scheme::Iterative(_) => {
                vec![Stage::Predict(kind, method, f), Stage::Iterate(kind, method, mesh)]
            }
        };
        // (for every object: pins may be taken off in the app)
        if method.solver().is_some_and(|s| s.adaptive_start) {
            stages.push(Stage::RigidStart(kind, f));
        }
        stages.extend([
            Stage::Constraints(kind, f, false),
            Stage::Surface(kind, true, mesh),
            Stage::Surface(kind, false, mesh),
        ]);
        if f & crate::sim::gpu_types::FEATURE_STRETCH != 0 {
            stages.push(Stage::StretchCount(kind, f));
        }

        stages.extend(plan.fused.map(|shape| Stage::Fused(method, f, shape)));
        stages
    }

    /// Whether the pipeline of this stage, which `model` needs, is created only once a frame
    /// runs it (`GpuSim::ensure_pipelines`): an object's step runs fused or per stage, and a
    /// scene often runs one path only (on lavapipe each compile of the larger kernels takes
    /// 0.2 to 0.5 s). The surface and contact between objects always run.
    pub(super) fn deferred(self, model: &SimModel) -> bool {
        match self {
            Stage::Physics(..)
            | Stage::Predict(..)
            | Stage::RigidStart(..)
            | Stage::Iterate(..)
            | Stage::Constraints(..)
            | Stage::StretchCount(..)
            | Stage::SelfPairs(..)
            | Stage::HashScatter(_)
            | Stage::TruncationHash(_)
            | Stage::HashCount
            | Stage::Fused(..) => true,
            Stage::HashScan => !model.inter_object_contact(),
            Stage::Surface(..) | Stage::ContactBegin | Stage::ContactHash | Stage::Contact { .. } => false,
        }
    }

    /// The pipelines `model` needs, its objects planned as `plans` (one per object).
    pub(super) fn needed(model: &SimModel, plans: &[ObjectPlan]) -> Vec<Stage> {
        let mut stages: Vec<Stage> = model
            .objects
            .iter()
            .zip(plans)
            .flat_map(|(o, &plan)| Stage::of_object(o.kind, model, plan))
            .collect();
        for (o, plan) in model.objects.iter().zip(plans) {
            if super::object::builds_hash(o, model) {
                stages.push(Stage::Constraints(o.kind, plan.features, true));
                stages.push(Stage::HashScatter(has_creases(plan.features)));
            }
            if super::object::has_self_pairs(o) {
                let f = plan.features;
                stages.extend([
                    Stage::SelfPairs(f, false, SelfPass::Find),
                    Stage::SelfPairs(f, false, SelfPass::Apply),
                ]);
                if super::object::builds_hash(o, model) {
                    stages.extend([
                        Stage::SelfPairs(f, true, SelfPass::Find),
                        Stage::SelfPairs(f, true, SelfPass::Apply),
                    ]);
                }
                if model.contact_iterations > 1 {
                    stages.extend([SelfPass::Move, SelfPass::Reapply].map(|p| Stage::SelfPairs(f, false, p)));
                }
                if o.has_cloth_edge_pairs() {
                    stages
                        .extend([SelfPass::Note, SelfPass::Truncate].map(|p| Stage::SelfPairs(f, false, p)));
                    if super::object::builds_hash(o, model) {
                        stages.extend([Stage::TruncationHash(false), Stage::TruncationHash(true)]);
                    }
                }
            }
        }
        if model.objects.iter().any(|o| super::object::builds_hash(o, model)) {
            stages.extend([Stage::HashCount, Stage::HashScan]);
        }
        if model.inter_object_contact() {
            let pair_max = super::contact::pair_max(model) as u32;
            stages.extend([
                Stage::HashScan,
                Stage::ContactBegin,
                Stage::ContactHash,
                Stage::Contact { segments: false, cloth_edges: model.has_cloth_edges_between(), pair_max },
            ]);
            if model.objects.iter().any(|o| !o.contact_triangles()) {
                stages.push(Stage::Contact { segments: true, cloth_edges: false, pair_max });
            }
        }
        let mut seen = std::collections::HashSet::new();
        stages.retain(|s| seen.insert(*s));
        stages
    }
}

/// The binding set layouts of the pipelines: per object, and the batched stages' (`batch.rs`).
pub(super) type Layouts<'a> = [&'a BindingSetLayout; 2];

/// The id of the batched shaders' `BATCH_CHUNK` constant (glsl/include/batch.glsl), past the
/// step shaders' own.
const BATCH_CHUNK_ID: u32 = 8;

pub(super) struct Pipelines {
    map: HashMap<Stage, ComputePipeline>,
    /// Stages created only when first asked for (`ensure`), with their shaders' SPIR-V as
    /// loaded with the others (a broken shader fails at creation all the same).
    later: Vec<Stage>,
    later_words: HashMap<&'static str, Vec<u32>>,
}

impl Pipelines {
    /// Creates the pipelines of `stages`, each shader compiled (or loaded) once; those of
    /// `later` are loaded now and created by `ensure`.
    pub(super) fn new(
        ctx: &GpuContext,
        layouts: Layouts<'_>,
        chunk: u32,
        shaders: &mut ShaderSet,
        stages: &[Stage],
        later: &[Stage],
    ) -> Result<Self> {
        let mut pipelines = Self { map: HashMap::new(), later: later.to_vec(), later_words: HashMap::new() };
        let mut compiled: HashMap<&str, Vec<u32>> = HashMap::new();
        for &stage in stages.iter().chain(later) {
            let name = stage.shader();
            let words = match compiled.get(name) {
                Some(w) => Ok(w.clone()),
                None => shaders.load_or_embedded(name),
            };
            let pipeline = words.and_then(|words| {
                let p = if later.contains(&stage) {
                    pipelines.later_words.insert(name, words.clone());
                    Ok(None)
                } else {
                    Self::create(ctx, layouts, chunk, stage, &words).map(Some)
                };
                compiled.insert(name, words);
                p
            });
            match pipeline {
                Ok(Some(p)) => {
                    pipelines.map.insert(stage, p);
                }
                Ok(None) => {}
                Err(e) => {
                    pipelines.destroy(ctx);
                    return Err(e);
                }
            }
        }
        Ok(pipelines)
    }

    /// Creates the pipelines `new` left for later that `wanted` asks for.
    pub(super) fn ensure(
        &mut self,
        ctx: &GpuContext,
        layouts: Layouts<'_>,
        chunk: u32,
        wanted: impl Fn(&Stage) -> bool,
    ) -> Result<()> {
        let mut k = 0;
        while k < self.later.len() {
            let stage = self.later[k];
            if !wanted(&stage) {
                k += 1;
                continue;
            }
            let p = Self::create(ctx, layouts, chunk, stage, &self.later_words[stage.shader()])?;
            self.map.insert(stage, p);
            self.later.remove(k);
        }
        if self.later.is_empty() {
            self.later_words.clear();
        }
        Ok(())
    }

    /// Whether every stage's pipeline is created.
    pub(super) fn all_created(&self) -> bool {
        self.later.is_empty()
    }

    /// The pipeline of `stage` with the layout it takes (the batched stages `layouts[1]`, with
    /// `chunk` objects a dispatch as constant 8, `BATCH_CHUNK`).
    fn create(
        ctx: &GpuContext,
        layouts: Layouts<'_>,
        chunk: u32,
        stage: Stage,
        words: &[u32],
    ) -> Result<ComputePipeline> {
        let name = stage.shader();
        let mut constants: Vec<(u32, u32)> = (0..).zip(stage.specialization()).collect();
        let layout = if stage.batched() {
            constants.push((BATCH_CHUNK_ID, chunk));
            layouts[1]
        } else {
            layouts[0]
        };
        ComputePipeline::with_constants(ctx, name, words, layout, &constants)
            .with_context(|| format!("creating pipeline {name} ({stage:?})"))
    }

    /// Rebuilds the pipelines of the `changed` shaders that compile; returns the names
    /// reloaded and the replaced pipelines (still possibly in use by frames in flight).
    pub(super) fn reload(
        &mut self,
        ctx: &GpuContext,
        layouts: Layouts<'_>,
        chunk: u32,
        shaders: &mut ShaderSet,
        changed: &[String],
    ) -> (Vec<String>, Vec<Retired>) {
        let mut reloaded = Vec::new();
        let mut retired = Vec::new();
        for name in changed {
            let mut stages: Vec<Stage> = self.map.keys().copied().filter(|s| s.shader() == name).collect();
            if stages.is_empty() && !self.later_words.contains_key(name.as_str()) {
                continue;
            }
            stages.sort_by_key(|s| format!("{s:?}"));
            let Ok(words) = shaders.load(name) else { continue }; // error recorded in `shaders`
            if let Some(later) = self.later_words.get_mut(name.as_str()) {
                later.clone_from(&words);
            }
            let mut fresh = Vec::new();
            for &stage in &stages {
                match Self::create(ctx, layouts, chunk, stage, &words) {
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
