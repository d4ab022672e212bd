//! Recording the physics stage of one substep for the objects not fused, state A -> B, as the
//! model's integrator runs it (`sim::integrator`'s table):
//! - explicit methods: one pass of `physics.comp`;
//! - iterative methods: the prediction (`predict.comp`: y into the iterates and auxiliary
//!   buffers; on the free objects of the methods that start adaptively, three passes of
//!   `rigid_start.comp` more), then `iterations` iterations of the solver, each one pass over every particle
//!   (Jacobi), one pass per vertex colour or spring class (Gauss-Seidel), or for the implicit
//!   method's conjugate gradients two passes and one more for each Newton step (and on an
//!   object that searches along its steps two more: the search's sums and the move; with a
//!   total pass after the sums on large objects). Every pass is ordered after the one
//!   before by a barrier on the iterates and auxiliary data, and on what the last iteration
//!   writes: the result into B and whether the contact lists hold (`hash.rs`).

use super::batch::Pass;
use super::object::GpuObject;
use super::pipelines::Stage;
use super::GpuSim;
use crate::sim::integrator::{newton_steps, Scheme, Sweep};
use crate::vk::{Access, BufferBarrier, Recorder};

impl GpuSim {
    /// `substep`: which of the frame's substeps (the pass that writes the new positions notes
    /// whether the contact lists hold for it, `hash.rs`).
    pub(super) fn record_physics(&self, rec: &mut Recorder<'_>, substep: u32) {
        let stepped: Vec<(usize, &GpuObject)> =
            self.objects.iter().enumerate().filter(|(_, o)| !self.is_fused(o)).collect();
        let batches = &self.batches;
        let method = self.model.integrator;
        let solver = match method.method().scheme {
            Scheme::Explicit { verlet } => {
                let mut physics = Pass::new();
                for &(k, o) in &stepped {
                    let stage = Stage::Physics(o.kind, verlet, o.plan.features);
                    let push = [substep, self.lists_on(o) as u32];
                    physics.add(k, self.pipelines.get(stage), o.step_groups, &push);
                }
                physics.record(rec, batches, 0);
                return;
            }
            Scheme::Iterative(solver) => solver,
        };
        let mut predict = Pass::new();
        for &(k, o) in &stepped {
            let stage = Stage::Predict(o.kind, method, o.plan.features);
            predict.add(k, self.pipelines.get(stage), o.step_groups, &[substep]);
        }
        predict.record(rec, batches, 0);
        let between_passes: Vec<BufferBarrier<'_>> = stepped
            .iter()
            .flat_map(|&(_, o)| {
                let rw = |b| BufferBarrier::new(b, Access::ComputeReadWrite, Access::ComputeReadWrite);
                // The last iteration's passes count into the hash (lists off), one colour each.
                let hash = o.hash.iter().flat_map(|h| [&h.counts, &h.cell_rank]).map(rw);
                o.scratch_barriers().into_iter().chain([rw(&o.state[1])]).chain(hash)
            })
            .collect();
        // Free objects of the methods that start adaptively: the rigid start's sums, their
        // totals and the moved iterates (glsl/rigid_start.comp).
        let rigid: Vec<(usize, &GpuObject)> =
            stepped.iter().copied().filter(|(_, o)| o.rigid_start).collect();
        if !rigid.is_empty() {
            for phase in [RIGID_PARTIAL, RIGID_TOTAL, RIGID_APPLY] {
                rec.barrier(&between_passes);
                let mut pass = Pass::new();
                for &(k, o) in &rigid {
                    let groups = if phase == RIGID_TOTAL { [1, 1, 1] } else { o.step_groups };
                    let pipeline = self.pipelines.get(Stage::RigidStart(o.kind, o.plan.features));
                    pass.add(k, pipeline, groups, &[phase]);
                }
                pass.record(rec, batches, 0);
            }
        }
        // Passes of one iteration of the methods that sweep (not the implicit method).
        let passes = match solver.sweep {
            Sweep::Jacobi | Sweep::NewtonCg => 1,
            Sweep::VertexColours => stepped.iter().map(|(_, o)| o.colours).max().unwrap_or(1),
            Sweep::SpringClasses => stepped.iter().map(|(_, o)| o.classes).max().unwrap_or(1),
        };
        let rounds = self.model.contact_rounds();
        // One pass: each object's workgroups and pass word (SKIP: it takes no part).
        let iterate = |rec: &mut Recorder<'_>, k: u32, each: &PassOf| {
            rec.barrier(&between_passes);
            let mut pass = Pass::new();
            for &(i, o) in &stepped {
                let (groups, word) = each(i, o);
                if word == SKIP {
                    continue;
                }
                let pipeline = self.pipelines.get(Stage::Iterate(o.kind, method, o.mesh));
                let flags = self.lists_on(o) as u32 | if rounds > 1 { CONTACT_ROUNDS } else { 0 };
                pass.add(i, pipeline, groups, &[k, word, substep, flags]);
            }
            pass.record(rec, batches, 0);
        };
        if solver.sweep == Sweep::NewtonCg {
            // Objects of many workgroups have their partial sums totalled by a pass of one.
            let totals = |o: &GpuObject| o.step_groups.iter().product::<u32>() > self.cg_totals_above;
            // Objects that search along their Newton steps (their parameters' OBJ_LINE_SEARCH).
            let searched = |i: usize| self.objects[i].searches;
            let word_of = |i: usize, o: &GpuObject, word: u32| {
                let word = if totals(o) { word | CG_TOTALS } else { word };
                if searched(i) {
                    word | CG_SEARCHED
                } else {
                    word
                }
            };
            // `search`: the pass is the search's, which the other objects skip.
            let pass = |rec: &mut Recorder<'_>, k: u32, word: u32, search: bool| {
                let takes_part = |i: usize| !search || searched(i);
                iterate(rec, k, &|i, o| match takes_part(i) {
                    true => (o.step_groups, word_of(i, o, word)),
                    false => ([0; 3], SKIP),
                });
                // A Newton step's last update is followed by a linearisation or the search,
                // which read no totals, and the move by a linearisation.
                let phase = word & CG_PHASES;
                let read_next = !(phase == CG_UPDATE && word & LAST_CG != 0) && phase != CG_MOVE;
                if read_next && stepped.iter().any(|&(i, o)| totals(o) && takes_part(i)) {
                    let total =
                        (word & !CG_PHASES) | if phase == CG_SEARCH { CG_SEARCH_TOTAL } else { CG_TOTAL };
                    iterate(rec, k, &|i, o| match totals(o) && takes_part(i) {
                        true => ([1, 1, 1], word_of(i, o, total)),
                        false => ([0; 3], SKIP),
                    });
                }
            };
            let any_search = stepped.iter().any(|&(i, _)| searched(i));
            let mut k = 0;
            for cg in newton_steps(self.model.iterations) {
                pass(rec, k, cg_pass(CG_LINEARISE, 0, cg), false);
                for c in 0..cg {
                    pass(rec, k + c, cg_pass(CG_PRODUCT, c, cg), false);
                    pass(rec, k + c, cg_pass(CG_UPDATE, c, cg), false);
                }
                if any_search {
                    pass(rec, k + cg - 1, cg_pass(CG_SEARCH, cg - 1, cg), true);
                    pass(rec, k + cg - 1, cg_pass(CG_MOVE, cg - 1, cg), true);
                }
                k += cg;
            }
            return;
        }
        let swept = |pass: u32| {
            move |_: usize, o: &GpuObject| match solver.sweep {
                Sweep::VertexColours if pass >= o.colours => ([0; 3], SKIP),
                Sweep::VertexColours => (o.colour_groups, pass),
                Sweep::SpringClasses if pass == XPBD_FINISH => (o.step_groups, pass),
                Sweep::SpringClasses if pass >= o.classes => ([0; 3], SKIP),
                Sweep::SpringClasses => (o.class_groups, pass),
                _ => (o.step_groups, pass),
            }
        };
        for k in 0..self.model.iterations {
            for pass in 0..passes {
                iterate(rec, k, &swept(pass));
            }
            // Contact between objects from the iterates every iteration but the last (whose
            // result takes the substep's own round after the physics): the next iteration
            // adds each particle's sum to its iterate and its prediction.
            if let Some(contact) = self.contact.as_ref().filter(|_| k + 1 < rounds) {
                rec.barrier(&between_passes);
                contact.record(rec, &self.pipelines, &self.objects, substep * rounds + k);
            }
        }
        if solver.sweep == Sweep::SpringClasses {
            // Every particle finished once all classes of the last iteration are done.
            iterate(rec, self.model.iterations - 1, &swept(XPBD_FINISH));
        }
    }
}

/// One pass of an iteration: object i's workgroups and pass word (`SKIP`: it takes no part).
type PassOf<'a> = dyn Fn(usize, &GpuObject) -> ([u32; 3], u32) + 'a;

/// The implicit method per stage: objects of more workgroups than this total their partial
/// sums in a pass of one workgroup (each pass's workgroups summing them all themselves grows
/// with the square of the count: a 1024 x 1024 cloth's 4,096 took 12.65 against 13.33 ms a
/// frame at 4 iterations with the passes, H100, docs/records/bench/h100/implicit-cg).
pub(super) const CG_TOTALS_ABOVE: u32 = 1024;

impl GpuSim {
    /// The implicit method per stage: objects of more than `groups` workgroups total their
    /// partial sums in a pass of their own (`CG_TOTALS_ABOVE` by default; tests lower it to
    /// run that path on small objects).
    pub fn set_cg_totals_above(&mut self, groups: u32) {
        self.cg_totals_above = groups;
    }
}

/// The rigid start's passes (glsl/rigid_start.comp's PHASE_*).
const RIGID_PARTIAL: u32 = 0;
const RIGID_TOTAL: u32 = 1;
const RIGID_APPLY: u32 = 2;

/// The implicit method's passes (glsl/implicit_iterate.comp's PHASE_*) and the bits of the
/// pass word that hold them.
const CG_LINEARISE: u32 = 0;
const CG_PRODUCT: u32 = 1;
const CG_UPDATE: u32 = 2;
const CG_TOTAL: u32 = 3;
const CG_SEARCH: u32 = 4;
const CG_SEARCH_TOTAL: u32 = 5;
const CG_MOVE: u32 = 6;
const CG_PHASES: u32 = 7;
/// The pass word's bit of a Newton step's last CG iteration (`cg_pass`).
const LAST_CG: u32 = 32;
/// The pass word's bit saying that PHASE_TOTAL passes total the partial sums.
const CG_TOTALS: u32 = 64;
/// The pass word's bit of an object that searches along its Newton steps: its last update
/// leaves the iterate to PHASE_MOVE.
const CG_SEARCHED: u32 = 128;
/// The iteration's flags word: contact between objects runs after each iteration
/// (`SimModel::contact_rounds`; glsl/vbd_iterate.comp's CONTACT_ROUNDS).
const CONTACT_ROUNDS: u32 = 2;
/// A pass word no pass has: the object takes no part in the pass.
const SKIP: u32 = u32::MAX;
/// XPBD's pass after its last iteration's classes, that finishes every particle
/// (glsl/include/springs.glsl's XPBD_FINISH): past any class a mesh's colouring can make.
const XPBD_FINISH: u32 = u32::MAX - 1;

/// The pass word of a Newton step's pass `phase` in its CG iteration `c` of `count`: the phase,
/// c's parity (bit 3), whether c is the first (bit 4) and the last (`LAST_CG`).
fn cg_pass(phase: u32, c: u32, count: u32) -> u32 {
    phase | (c & 1) << 3 | ((c == 0) as u32) << 4 | if c + 1 == count { LAST_CG } else { 0 }
}
