//! Recording the physics stage of one substep for the objects not fused, state A -> B, as the
//! model's integrator runs it (`sim::integrator`'s table):
//! - explicit methods: one pass of `physics.comp`;
//! - iterative methods: the prediction (`predict.comp`: y into the iterates and auxiliary
//!   buffers), then `iterations` iterations of the solver, each one pass over every particle
//!   (Jacobi) or one pass per vertex colour (Gauss-Seidel). Every pass is ordered after the one
//!   before by a barrier on the iterates and auxiliary data, and on what the last iteration
//!   writes: the result into B and whether the contact lists hold (`hash.rs`).

use super::object::GpuObject;
use super::pipelines::Stage;
use super::GpuSim;
use crate::sim::integrator::{Scheme, Sweep, SPRING_CLASSES};
use crate::vk::{Access, BufferBarrier, Recorder};

impl GpuSim {
    /// `substep`: which of the frame's substeps (the pass that writes the new positions notes
    /// whether the contact lists hold for it, `hash.rs`).
    pub(super) fn record_physics(&self, rec: &mut Recorder<'_>, substep: u32) {
        let stepped: Vec<&GpuObject> = self.objects.iter().filter(|o| !self.is_fused(o)).collect();
        let method = self.model.integrator;
        let solver = match method.method().scheme {
            Scheme::Explicit { verlet } => {
                for o in &stepped {
                    let stage = Stage::Physics(o.kind, verlet, o.plan.features);
                    let push = [substep, self.lists_on(o) as u32];
                    rec.dispatch_with(self.pipelines.get(stage), o.sets[0], o.step_groups, &push);
                }
                return;
            }
            Scheme::Iterative(solver) => solver,
        };
        for o in &stepped {
            rec.dispatch(
                self.pipelines.get(Stage::Predict(o.kind, method, o.plan.features)),
                o.sets[0],
                o.step_groups,
            );
        }
        let between_passes: Vec<BufferBarrier<'_>> = stepped
            .iter()
            .flat_map(|o| {
                let rw = |b| BufferBarrier::new(b, Access::ComputeReadWrite, Access::ComputeReadWrite);
                // The last iteration's passes count into the hash (lists off), one colour each.
                let hash = o.hash.iter().flat_map(|h| [&h.counts, &h.cell_rank]).map(rw);
                o.scratch_barriers().into_iter().chain([rw(&o.state[1])]).chain(hash)
            })
            .collect();
        // Passes of an iteration: (pass, whether the object takes part, its workgroups).
        let classes = 2 * SPRING_CLASSES.len() as u32;
        let passes = match solver.sweep {
            Sweep::Jacobi => 1,
            Sweep::VertexColours => stepped.iter().map(|o| o.colours).max().unwrap_or(1),
            Sweep::SpringClasses => classes,
        };
        let iterate = |rec: &mut Recorder<'_>, k: u32, pass: u32| {
            rec.barrier(&between_passes);
            for o in &stepped {
                let groups = match solver.sweep {
                    Sweep::VertexColours if pass >= o.colours => continue,
                    Sweep::VertexColours => o.colour_groups,
                    Sweep::Jacobi | Sweep::SpringClasses => o.step_groups,
                };
                let pipeline = self.pipelines.get(Stage::Iterate(o.kind, method));
                rec.dispatch_with(pipeline, o.sets[0], groups, &[k, pass, substep, self.lists_on(o) as u32]);
            }
        };
        for k in 0..self.model.iterations {
            for pass in 0..passes {
                iterate(rec, k, pass);
            }
        }
        if solver.sweep == Sweep::SpringClasses {
            // Every particle finished once all classes of the last iteration are done.
            iterate(rec, self.model.iterations - 1, classes);
        }
    }
}
