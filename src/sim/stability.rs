//! Stability: the predicted explicit limit of each object and the runtime guard's report.
//!
//! Prediction: for symplectic Euler a mode of angular frequency w is stable while w dt <= 2.
//! The stiffness matrix of a spring network satisfies (Gershgorin) lambda_max <= max over
//! particles of 2 * sum of the stiffnesses of its springs, so w_max <= sqrt(2 sum k / m); for a
//! chain this is the exact highest mode (sqrt(4k/m)). Drag and damping are left out.

use super::model::{Integrator, ObjectKind, SimModel};

/// The predicted explicit limit of one object.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    pub name: String,
    pub kind: ObjectKind,
    /// A mesh cloth's: the advice names only the methods for large steps it runs with
    /// (`sim::cloth_mesh::METHODS`).
    pub mesh: bool,
    /// Upper bound of the highest angular frequency [rad/s].
    pub omega_max: f64,
    /// Largest stable substep, 2 / omega_max [s].
    pub dt_max: f64,
}

impl Prediction {
    /// An object's prediction from its highest angular frequency.
    fn of(name: &str, kind: ObjectKind, mesh: bool, omega_max: f64) -> Prediction {
        let dt_max = if omega_max > 0.0 { 2.0 / omega_max } else { f64::INFINITY };
        Prediction { name: name.to_string(), kind, mesh, omega_max, dt_max }
    }

    /// Fewest substeps per frame that keep `frame_dt / substeps` within the limit (may exceed
    /// `MAX_SUBSTEPS`; it saturates at u32::MAX).
    pub fn min_substeps(&self, frame_dt: f64) -> u32 {
        (frame_dt / self.dt_max).ceil().max(1.0) as u32
    }

    /// What to set for an explicit method to be within the limit: the substep count, or, past
    /// `MAX_SUBSTEPS`, that none will do; then the methods for large steps (the iterative ones).
    pub fn substep_advice(&self, frame_dt: f64) -> String {
        let n = self.min_substeps(frame_dt);
        let stable = stable_integrators(self.mesh);
        if n <= MAX_SUBSTEPS {
            format!(
                "use at least {n} substeps per frame, or sim.integrator = {stable} (the methods for large steps)"
            )
        } else {
            format!(
                "no substep count up to {MAX_SUBSTEPS} is within it (it needs {:.1e}): use sim.integrator = {stable} \
                 (the methods for large steps)",
                frame_dt / self.dt_max
            )
        }
    }
}

/// The most substeps per frame a scene may ask for (`sim.substeps`).
pub const MAX_SUBSTEPS: u32 = 4096;

/// Advice for shorter substeps: more of them, or at `MAX_SUBSTEPS` a shorter frame.
fn more_substeps(model: &SimModel) -> String {
    if model.substeps >= MAX_SUBSTEPS {
        format!(
            "a shorter sim.frame_dt (now {} s; sim.substeps is at its maximum, {MAX_SUBSTEPS})",
            model.frame_dt
        )
    } else {
        format!("more substeps (sim.substeps, now {})", model.substeps)
    }
}

/// The methods for large steps (the iterative ones: a stiff held cloth settles at one 1/60 s
/// substep with each, `tests/suite/large_steps.rs`), for advice: `"xpbd", "implicit" or "vbd"`;
/// where `mesh`, those a mesh cloth runs with.
pub fn stable_integrators(mesh: bool) -> String {
    let runs = |m: &&Integrator| m.iterative() && (!mesh || crate::sim::cloth_mesh::METHODS.contains(m));
    Integrator::named(Integrator::ALL.iter().filter(runs).copied())
}

/// Sum of the spring stiffnesses of the best-connected particle of an object of `dims` particles (a rope: [nodes, 1]) with springs of `stiffness`
/// (structural, shear, bending).
fn stiffness_sum(dims: [u32; 2], stiffness: [f64; 3]) -> f64 {
    let [cols, rows] = dims;
    let count = |span: u32, reach: u32| {
        if span > 2 * reach {
            2.0
        } else if span > reach {
            1.0
        } else {
            0.0
        }
    };
    let (x1, y1, x2, y2) = (count(cols, 1), count(rows, 1), count(cols, 2), count(rows, 2));
    let shear = if cols > 1 && rows > 1 { 4.0f64.min(x1 * y1 * 2.0) } else { 0.0 };
    stiffness[0] * (x1 + y1) + stiffness[1] * shear + stiffness[2] * (x2 + y2)
}

/// The predicted explicit limit of an object of `dims` particles of `mass` [kg] with springs of
/// `stiffness` [N/m] (structural, shear, bending), as `predict` gives it for the built object:
/// the editor asks it of the scene without building the particles.
pub fn predict_object(
    name: &str,
    kind: ObjectKind,
    dims: [u32; 2],
    stiffness: [f64; 3],
    mass: f64,
) -> Prediction {
    let omega_max = (2.0 * stiffness_sum(dims, stiffness) / mass).sqrt();
    Prediction::of(name, kind, false, omega_max)
}

pub fn predict(model: &SimModel) -> Vec<Prediction> {
    (model.objects.iter())
        .map(|o| match &o.mesh {
            // A mesh cloth's stiffest particle against its mass, from its lists (seams among
            // them).
            Some(mesh) => {
                let sum = (0..o.particle_count())
                    .map(|i| {
                        let k: f64 = mesh.springs_of(i).iter().map(|s| o.stiffness_of(s.kind as usize)).sum();
                        k / o.mass_of(i)
                    })
                    .fold(0.0, f64::max);
                Prediction::of(&o.name, o.kind, true, (2.0 * sum).sqrt())
            }
            None => predict_object(&o.name, o.kind, o.dims, o.stiffness, o.mass),
        })
        .collect()
}

/// The runtime guard caught an object's state going non-finite or running away.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{kind} '{name}' {what} at t = {time:.3} s (particle {particle}); the simulation stopped. {advice}",
    kind = kind.label()
)]
pub struct GuardTrip {
    pub name: String,
    pub kind: ObjectKind,
    /// What tripped it.
    pub cause: GuardCause,
    /// First flagged particle (lowest index).
    pub particle: u32,
    pub what: String,
    pub time: f64,
    pub advice: String,
}

/// What tripped the runtime guard.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GuardCause {
    /// A position or velocity is not a finite number.
    NonFinite,
    /// A particle moves faster than `sim.max_speed`.
    Runaway,
    /// A structural spring is stretched past `sim.max_strain`.
    Overstretched,
    /// The energy grew without a source past `sim.max_energy_gain` (`sim::gpu::energy`).
    EnergyGain,
}

impl GuardTrip {
    /// Builds the report: what happened and what to change.
    pub fn new(model: &SimModel, object: usize, particle: u32, cause: GuardCause, time: f64) -> Self {
        let o = &model.objects[object];
        let what = match cause {
            GuardCause::NonFinite => {
                "blew up (a position or velocity is no longer a finite number)".to_string()
            }
            GuardCause::Runaway => {
                format!("ran away (a particle moves faster than sim.max_speed = {} m/s)", model.max_speed)
            }
            GuardCause::Overstretched => format!(
                "is over-stretched (a structural spring at more than {:.2} times its rest length: sim.max_strain = {})",
                1.0 + model.max_strain,
                model.max_strain
            ),
            GuardCause::EnergyGain => format!(
                "gained energy without a source (past sim.max_energy_gain = {} of the scene's scale)",
                model.max_energy_gain
            ),
        };
        if cause == GuardCause::EnergyGain {
            let iterations = if model.integrator.iterative() {
                format!("more iterations (sim.iterations, now {}) or ", model.iterations)
            } else {
                String::new()
            };
            let advice = format!(
                "Nothing in the scene supplies energy (no wind, no moving collider), so a contact or the solve made it: \
                 try {iterations}{}; objects that start inside each other's contact distance, or a stack of layers, \
                 push apart; sim.max_energy_gain = 0 turns this check off.",
                more_substeps(model)
            );
            return Self { name: o.name.clone(), kind: o.kind, cause, particle, what, time, advice };
        }
        // A spring over-stretched by an explicit method past its predicted stability limit is
        // the instability: the advice below for it, not the material's.
        let p = &predict(model)[object];
        let dt = model.dt();
        let unstable = !model.integrator.iterative() && dt > p.dt_max;
        if cause == GuardCause::Overstretched && !unstable {
            let advice = if model.integrator.iterative() {
                format!(
                    "The {} solve stops short of its springs at sim.iterations = {} and sim.substeps = {}: raise \
                     sim.iterations, or try {}; or the material is too soft for its load (a stiffer structural \
                     spring, a stretch_limit). sim.max_strain = 0 turns this check off.",
                    model.integrator.label(),
                    model.iterations,
                    model.substeps,
                    more_substeps(model)
                )
            } else {
                format!(
                    "The springs do not hold the load: a stiffer structural spring or a stretch_limit, or {}; \
                     sim.max_strain = 0 turns this check off.",
                    more_substeps(model)
                )
            };
            return Self { name: o.name.clone(), kind: o.kind, cause, particle, what, time, advice };
        }
        let advice = if model.integrator.iterative() {
            format!(
                "The {} integrator is stable for any spring stiffness, so look at what it treats explicitly and at the \
                 constraints: strong spring damping, drag, contacts; try \
                 {} or more iterations (sim.iterations, now {}).",
                model.integrator.label(),
                more_substeps(model),
                model.iterations
            )
        } else if unstable {
            format!(
                "The substep ({:.3} ms, sim.substeps = {}) is past the explicit stability limit predicted for it \
                 ({:.3} ms, w_max = {:.0} rad/s): {}, or softer springs or heavier particles.",
                dt * 1e3,
                model.substeps,
                p.dt_max * 1e3,
                p.omega_max,
                p.substep_advice(model.frame_dt)
            )
        } else {
            format!(
                "The substep is within the predicted spring limit, so look at the constraints and contacts: \
                 try {}, a smaller stretch limit correction, or slower colliders.",
                more_substeps(model)
            )
        };
        Self { name: o.name.clone(), kind: o.kind, cause, particle, what, time, advice }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    /// An explicit method's over-stretched spring is the instability where the substep is past
    /// the predicted limit (the advice names the substeps and the stable integrators), and the
    /// material's load where it is within it.
    #[test]
    fn an_over_stretched_spring_past_the_limit_is_called_the_instability() {
        let rope = |stiffness: f64| {
            let text = format!(
                "[[rope]]\nname = \"r\"\nnodes = 50\nstart = [0, 0, 0]\nend = [1, 0, 0]\nmass = 0.01\nstiffness = {stiffness}\nradius = 0.01\n"
            );
            scene::to_model(&scene::parse(&text, "t", &[]).unwrap())
        };
        let advice = |m: &SimModel| GuardTrip::new(m, 0, 0, GuardCause::Overstretched, 0.1).advice;
        let (stiff, soft) = (rope(1e9), rope(100.0));
        assert!(stiff.dt() > predict(&stiff)[0].dt_max && soft.dt() <= predict(&soft)[0].dt_max);
        let past = advice(&stiff);
        assert!(past.contains("past the explicit stability limit") && past.contains("\"vbd\""), "{past}");
        assert!(advice(&soft).contains("do not hold the load"), "{}", advice(&soft));
    }

    #[test]
    fn a_chain_predicts_its_exact_highest_mode() {
        let mut s = scene::parse(
            "[[rope]]\nname = \"r\"\nnodes = 50\nstart = [0, 0, 0]\nend = [1, 0, 0]\nmass = 0.01\nstiffness = 100.0\nradius = 0.01\n",
            "t",
            &[],
        )
        .unwrap();
        s.ropes[0].bending_stiffness = 0.0;
        let p = &predict(&scene::to_model(&s))[0];
        assert!((p.omega_max - (4.0f64 * 100.0 / 0.01).sqrt()).abs() < 1e-9, "{p:?}");
    }

    /// The guard's advice never asks for more substeps than a scene may have (issue 30, item
    /// 12: "try more substeps (sim.substeps, now 4096)"): at the maximum it asks for a shorter
    /// frame, for every cause and integrator family; below it, for more substeps.
    #[test]
    fn advice_at_the_substep_maximum_asks_for_a_shorter_frame() {
        let rope = "[[rope]]\nname = \"r\"\nnodes = 5\nstart = [0, 0, 0]\nend = [1, 0, 0]\nmass = 0.01\nstiffness = 100.0\nradius = 0.01\n";
        for integrator in [Integrator::SymplecticEuler, Integrator::Vbd] {
            for substeps in [16, MAX_SUBSTEPS] {
                let mut s = scene::parse(rope, "t", &[]).unwrap();
                s.sim.substeps = substeps;
                s.sim.integrator = scene::IntegratorChoice::Method(integrator);
                let model = scene::to_model(&s);
                for cause in [GuardCause::Runaway, GuardCause::Overstretched] {
                    let advice = GuardTrip::new(&model, 0, 0, cause, 1.0).advice;
                    let at_max = substeps == MAX_SUBSTEPS;
                    let what = integrator.label();
                    assert_eq!(advice.contains("more substeps"), !at_max, "{what} at {substeps}: {advice}");
                    assert_eq!(
                        advice.contains("shorter sim.frame_dt"),
                        at_max,
                        "{what} at {substeps}: {advice}"
                    );
                }
            }
        }
    }
}
