//! The integrators, each declared once: its variant of `Integrator` and its row of `METHODS`
//! (name, order, how the GPU runs it, its CPU twin, its chart colour). Everything else (scene
//! parsing, the editor's list, the CPU reference, the GPU pipelines and buffers, the chart, the
//! stability map, `auto`) looks a method up here, so a new method is its shader, its CPU twin
//! (`sim::cpu::integrators`) and one row. The runtime choice among them (`integrator =
//! "auto"`, a calibration on the GPU) is `study::integrator_choice`.
//!
//! Every method advances the spring network of one substep and is followed by the same
//! constraint stage (stretch limit, self-collision, spheres).

use super::cpu::integrators as cpu;
use glam::DVec3;

/// How a substep advances the spring network (`sim.integrator`).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize, clap::ValueEnum,
)]
#[serde(rename_all = "snake_case")]
#[value(rename_all = "snake_case")]
pub enum Integrator {
    /// The paper's: v += a(x, v) dt, then x += v dt. First order, explicit.
    #[default]
    SymplecticEuler,
    /// Position Verlet (drift-kick-drift): half a step of drift, forces at the midpoint, the
    /// other half. Second order for conservative forces, explicit, one force pass per substep.
    Verlet,
    /// Extended position-based dynamics (Macklin et al. 2016, 2019): one distance constraint per
    /// spring with compliance 1/k and the spring's damping, Gauss-Seidel over spring classes,
    /// on BDF2 (`BDF2_STEP`). One iteration with small substeps is a consistent second-order
    /// method; many iterations converge to BDF2. A held object settles at any stiffness and
    /// dashpot, soft at few iterations (docs/ACCURACY.md, "Large steps").
    Xpbd,
    /// BDF2 (`BDF2_STEP`) by Newton's method with preconditioned conjugate gradients (Baraff
    /// and Witkin 1998): `iterations` CG iterations a substep, linearised again every
    /// `NEWTON_CG_ITERATIONS`, each step searched along where the springs are stiff against
    /// the step (`sim::cpu::implicit_searches`); dashpots implicit; starts adaptively as VBD.
    Implicit,
    /// Vertex Block Descent (Chen et al. 2024): BDF2 (`BDF2_STEP`) by a 3x3 Newton step per
    /// vertex on inertia + spring energy (dashpots implicit), vertex-coloured Gauss-Seidel.
    Vbd,
    /// XPBD's constraints by Jacobi on BDF2: every spring updated at once from the iterate
    /// before, each particle's move bounded so that no sweep overshoots (plain Jacobi where
    /// the springs are soft against the substep, their mean where they are stiff). One pass an
    /// iteration (the spring classes take twelve); consistent like XPBD as the substep
    /// shrinks, softer at few iterations and large substeps. Settles at any stiffness, as
    /// XPBD (slowly at one iteration with heavy dashpots).
    XpbdJacobi,
}

/// How the GPU runs a method (`sim::gpu`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// One force pass per substep (`physics.comp`; `verlet`: position Verlet's half drifts);
    /// small objects run every substep fused in one workgroup.
    Explicit { verlet: bool },
    /// The inertial prediction (`predict.comp`), then `iterations` passes of the solver.
    Iterative(Solver),
}

/// An iterative method's GPU solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Solver {
    /// The iteration shader.
    pub shader: &'static str,
    /// `predict.comp` keeps the prediction y - x in the auxiliary buffer (else it zeroes the 12
    /// multipliers a particle keeps there; a mesh cloth's, one an entry of its spring lists).
    pub keeps_prediction: bool,
    /// The iterate starts from the prediction less the part of the external pull the springs
    /// held last substep (`sim::cpu::integrators::held_fraction`), not from the prediction.
    pub adaptive_start: bool,
    /// Contact between objects is projected after every iteration, not only after the
    /// solve, and each projection moves the particle's prediction with it (`contact_rounds`).
    pub contact_rounds: bool,
    /// Vec4s per particle of iterate slices and of auxiliary data.
    pub slices: u64,
    pub aux: u64,
    /// How a solver iteration sweeps the object.
    pub sweep: Sweep,
}

/// The passes of one iteration of an iterative method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sweep {
    /// One pass over every particle.
    Jacobi,
    /// Gauss-Seidel over the vertex colours (`vertex_colours`): one pass per colour, each
    /// seeing the colours before it.
    VertexColours,
    /// Newton steps of conjugate gradients (`newton_steps`): a pass that linearises, then two
    /// passes a CG iteration (the Hessian's product with the direction; the update), each
    /// summing the dot products the next one needs.
    NewtonCg,
    /// Gauss-Seidel over the spring classes (`SPRING_CLASSES`): one pass per class, a spring's
    /// update moving both its ends; then, after the last iteration, a pass that finishes every
    /// particle.
    SpringClasses,
}

/// One substep of an object from (x, v) on the CPU reference: the new positions and velocities
/// (the position-based methods also read and update each particle's BDF2 history).
pub type CpuStep = fn(&cpu::Substep<'_>, &mut [cpu::History]) -> (Vec<DVec3>, Vec<DVec3>);

/// The iterative (position-based) methods integrate with BDF2, the second-order backward
/// differentiation formula: each substep's solve is implicit over h = BDF2_STEP dt from a base
/// and a prediction that carry the particle's last substep (`sim::cpu::integrators::inertial`
/// has the formulas). It is L-stable like implicit Euler, which they used before, but damps a
/// mode of frequency w by O((w dt)^4) a substep, not (w dt)^2 / 2, which on stiff, lightly
/// damped cloth was the whole error of implicit Euler (docs/design/integrators.md, "BDF2").
pub const BDF2_STEP: f64 = 2.0 / 3.0;

/// How far the adaptive methods (VBD, the implicit method) start each particle's iterate from
/// their guess towards where it is: a particle whose springs' stiffness ratio is kappa (h^2
/// sum k + h sum b over its mass) keeps STIFF_START / (STIFF_START + kappa) of the guess
/// (`sim::cpu::integrators::toward_rest` says why). At 10 the presets' cloths at their substeps
/// (kappa about 0.1) start within 1% of the guess and keep their convergence rates; at 1 the
/// implicit method at 4 iterations fell to first order.
pub const STIFF_START: f64 = 10.0;

/// The turn of a free object's rigid move (`sim::cpu::integrators::RigidMove`) solves (I + e
/// tr(S)) w = L with this e (S = sum r r^T, I = tr(S) - S): a straight rope's inertia tensor has no part about its axis, and
/// there the turn is left at (nearly) zero, which moves no particle of it. Above the f32
/// rounding of the GPU's sums (about log2(n) f32 epsilons of sum q q^T), so that a nearly
/// straight rope's turn stays finite there; small enough that a cloth spinning in its plane
/// keeps its spin (a share e of the turn a substep).
pub const RIGID_REGULARISER: f64 = 1e-5;

/// Conjugate-gradient iterations of one Newton step of the implicit method (`sim::cpu::integrators::implicit`): every
/// `NEWTON_CG_ITERATIONS` iterations it linearises again at the iterate they reached. At one
/// 1/60 s substep on a stiff cloth (docs/log.md, "The implicit method by Newton's method and
/// conjugate gradients") two Newton steps of five settle to the static sag and come to rest,
/// one of ten hangs 126% too low and rings, and steps of two or three converge more slowly.
pub const NEWTON_CG_ITERATIONS: u32 = 5;

/// The Newton steps of `iterations` conjugate-gradient iterations: the counts of each
/// (`NEWTON_CG_ITERATIONS`, the last one the rest).
pub fn newton_steps(iterations: u32) -> impl Iterator<Item = u32> {
    (0..iterations.div_ceil(NEWTON_CG_ITERATIONS))
        .map(move |q| (iterations - q * NEWTON_CG_ITERATIONS).min(NEWTON_CG_ITERATIONS))
}

/// One integrator's row.
pub struct Method {
    pub integrator: Integrator,
    /// Its name in presets, on the command line and in reports.
    pub label: &'static str,
    /// Global order of accuracy in the positions as the substep shrinks (iterative methods:
    /// with their iterations converged, or at a fixed count as the substep shrinks).
    pub order: f64,
    pub scheme: Scheme,
    /// The CPU reference (`sim::cpu::integrators`).
    pub cpu: CpuStep,
    /// Colour of its curves in the accuracy chart (RGB).
    pub colour: (u8, u8, u8),
    /// The iterations a substep it is meant to run at (iterative methods; 1 for the others):
    /// the count the tests' convergence rates and the cost targets (docs/PERFORMANCE.md) use.
    pub few_iterations: u32,
    /// `sim.relaxation` applies (scales each constraint update).
    pub relaxed: bool,
    /// Its springs are constraints with a compliance, each pulling with its multiplier: a
    /// solve cut short leaves the multiplier below k times the stretch, so the springs pull
    /// less than their stiffness says and the cloth hangs longer than its springs' energy
    /// assumes. The energy it integrates then lies between the motion's and gravity's alone
    /// and the total with the springs' energy at their stiffness (`sim::gpu::energy`).
    pub compliant: bool,
}

const fn solver(
    shader: &'static str,
    (keeps_y, adaptive, rounds): (bool, bool, bool),
    slices: u64,
    aux: u64,
    sweep: Sweep,
) -> Scheme {
    Scheme::Iterative(Solver {
        shader,
        keeps_prediction: keeps_y,
        adaptive_start: adaptive,
        contact_rounds: rounds,
        slices,
        aux,
        sweep,
    })
}

/// The table, in the order of `Integrator`'s variants.
const METHODS: [Method; 6] = [
    Method {
        integrator: Integrator::SymplecticEuler,
        label: "symplectic_euler",
        order: 1.0,
        scheme: Scheme::Explicit { verlet: false },
        cpu: cpu::symplectic_euler,
        colour: (31, 119, 180),
        few_iterations: 1,
        relaxed: false,
        compliant: false,
    },
    Method {
        integrator: Integrator::Verlet,
        label: "verlet",
        order: 2.0,
        scheme: Scheme::Explicit { verlet: true },
        cpu: cpu::verlet,
        colour: (44, 160, 44),
        few_iterations: 1,
        relaxed: false,
        compliant: false,
    },
    Method {
        integrator: Integrator::Xpbd,
        label: "xpbd",
        order: 2.0,
        // In place (one slice); aux: the multipliers of the particle's 6 forward springs.
        scheme: solver("xpbd_iterate.comp", (false, false, false), 1, 3, Sweep::SpringClasses),
        cpu: cpu::xpbd,
        colour: (255, 127, 14),
        few_iterations: 1,
        relaxed: true,
        compliant: true,
    },
    Method {
        integrator: Integrator::Implicit,
        label: "implicit",
        order: 2.0,
        // Slices: the iterate, CG's move, residual, preconditioned residual, two directions,
        // the Hessian's product and the preconditioner (two); aux: the prediction, then the
        // workgroups' partial dot products and their partial sums of the line search.
        scheme: solver("implicit_iterate.comp", (true, true, false), 9, 3, Sweep::NewtonCg),
        cpu: cpu::implicit,
        colour: (214, 39, 40),
        few_iterations: 4,
        relaxed: false,
        compliant: false,
    },
    Method {
        integrator: Integrator::Vbd,
        label: "vbd",
        order: 2.0,
        // In place (one slice); aux: the prediction (and with contact rounds the colliders'
        // moves within the solve: `sim::gpu::object::SolverBuffers`).
        scheme: solver("vbd_iterate.comp", (true, true, true), 1, 1, Sweep::VertexColours),
        cpu: cpu::vbd,
        colour: (148, 103, 189),
        few_iterations: 4,
        relaxed: false,
        compliant: false,
    },
    Method {
        integrator: Integrator::XpbdJacobi,
        label: "xpbd_jacobi",
        order: 2.0,
        // Two alternating slices; aux: the multipliers of the particle's 12 springs (a mesh
        // cloth's: one an entry of its lists, `SolverBuffers::new`).
        scheme: solver("xpbd_jacobi_iterate.comp", (false, false, false), 2, 3, Sweep::Jacobi),
        cpu: cpu::xpbd_jacobi,
        colour: (140, 86, 75),
        few_iterations: 1,
        // Its step bound picks the step (a relaxation would cancel out where it acts).
        relaxed: false,
        compliant: true,
    },
];

impl Integrator {
    /// Every method, in the table's order.
    pub const ALL: [Integrator; 6] = [
        Integrator::SymplecticEuler,
        Integrator::Verlet,
        Integrator::Xpbd,
        Integrator::Implicit,
        Integrator::Vbd,
        Integrator::XpbdJacobi,
    ];

    /// Its row of the table.
    pub fn method(self) -> &'static Method {
        let m = &METHODS[self as usize];
        debug_assert_eq!(m.integrator, self, "METHODS is in the order of Integrator");
        m
    }

    pub fn label(self) -> &'static str {
        self.method().label
    }

    /// `methods` as a user writes them in a preset: `"a", "b" or "c"`.
    pub fn named(methods: impl IntoIterator<Item = Integrator>) -> String {
        let names: Vec<String> = methods.into_iter().map(|m| format!("\"{}\"", m.label())).collect();
        match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => names.concat(),
        }
    }

    /// The method whose label is `name`.
    pub fn from_label(name: &str) -> Option<Integrator> {
        Self::ALL.into_iter().find(|m| m.label() == name)
    }

    /// Whether the method iterates a solver (`SimModel::iterations` applies).
    pub fn iterative(self) -> bool {
        self.solver().is_some()
    }

    /// Its GPU solver, for an iterative method.
    pub fn solver(self) -> Option<Solver> {
        match self.method().scheme {
            Scheme::Iterative(s) => Some(s),
            Scheme::Explicit { .. } => None,
        }
    }

    pub fn order(self) -> f64 {
        self.method().order
    }

    /// The iterations a substep it is meant to run at (`Method::few_iterations`).
    pub fn few_iterations(self) -> u32 {
        self.method().few_iterations
    }
}

/// Colours of the vertex colouring VBD sweeps: particle (c, r) has colour
/// (c + 2 r) mod `vertex_colours`. No spring joins two particles of one colour: the offsets of
/// the 12 springs, (+-1, 0), (0, +-1), (+-1, +-1), (+-1, -+1), (+-2, 0), (0, +-2), give
/// c + 2 r = +-1, +-2, +-3, -+1, +-2, +-4, none a multiple of 5; a rope (one row) has only
/// the offsets +-1 and +-2, none a multiple of 3. (`vertex_colours` in glsl/include/springs.glsl
/// is the same rule.)
pub fn vertex_colours(dims: [u32; 2]) -> u32 {
    if dims[1] == 1 {
        3
    } else {
        5
    }
}

/// The colour of particle (c, r) of a grid of `colours` colours.
pub fn vertex_colour(c: u32, r: u32, colours: u32) -> u32 {
    (c + 2 * r) % colours
}

/// The spring classes XPBD sweeps, in order: the six forward directions of the stencil (grid
/// offset from a spring's first node to its second, and the spring's slot in the shaders'
/// SPRINGS), each split in two by `spring_class_parity`; no two springs of a class share a
/// particle. (`class_*` in glsl/include/springs.glsl is the same rule.)
pub const SPRING_CLASSES: [((i64, i64), usize); 6] =
    [((1, 0), 0), ((0, 1), 2), ((1, 1), 4), ((-1, 1), 7), ((2, 0), 8), ((0, 2), 10)];

/// The order XPBD sweeps its classes in, as (direction, parity): `SPRING_CLASSES` backwards,
/// the bending directions first and the structural last, parity 1 before 0 (class q = 2 dir +
/// parity from 11 down to 0; `xpbd_class` in glsl/include/springs.glsl). The structural springs
/// last: a weak spring with a heavy dashpot (its damping gamma = b / (k h) far past 1) swept
/// after them undid their work every iteration, and a stiff cloth held at its corners rang at
/// one substep; swept before them, every run of the large-step matrix comes to rest (docs/log.md,
/// "XPBD's spring classes with the structural springs last").
pub fn xpbd_class_order() -> impl Iterator<Item = (usize, u32)> {
    (0..2 * SPRING_CLASSES.len()).rev().map(|q| (q / 2, (q % 2) as u32))
}

/// The parity (0 or 1) of the spring of direction `dir` whose first node is (c, r): its
/// coordinate along the direction's line (the column for (1, 0), (1, 1), (2, 0); the row
/// otherwise), halved for the bending directions, modulo 2. Two springs of one direction that
/// share a node are one step apart along the line, so they differ in parity.
pub fn spring_class_parity(dir: usize, c: i64, r: i64) -> u32 {
    let u = if matches!(dir, 0 | 2 | 4) { c } else { r };
    (if dir >= 4 { u >> 1 } else { u } & 1) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_variant_order_and_labels_round_trip() {
        for m in Integrator::ALL {
            assert_eq!(m.method().integrator, m);
            assert_eq!(Integrator::from_label(m.label()), Some(m));
            let serde_name = toml::Value::try_from(m).unwrap();
            assert_eq!(serde_name.as_str(), Some(m.label()));
        }
    }

    /// Every spring of a grid is in exactly one class, and no two springs of a class share a
    /// particle.
    #[test]
    fn the_spring_classes_partition_the_springs_without_sharing_a_particle() {
        for dims in [[9i64, 7i64], [12, 1], [2, 2]] {
            let mut seen = std::collections::HashMap::new();
            for (dir, ((dc, dr), _)) in SPRING_CLASSES.into_iter().enumerate() {
                for r in 0..dims[1] {
                    for c in 0..dims[0] {
                        let (nc, nr) = (c + dc, r + dr);
                        if nc < 0 || nr < 0 || nc >= dims[0] || nr >= dims[1] {
                            continue;
                        }
                        let class = (dir, spring_class_parity(dir, c, r));
                        for node in [(c, r), (nc, nr)] {
                            assert!(
                                seen.insert((class, node), ()).is_none(),
                                "{dims:?}: class {class:?} meets {node:?} twice"
                            );
                        }
                    }
                }
            }
            // Each unordered neighbour pair of the 12-spring stencil once.
            let springs: usize = seen.len() / 2;
            let mut expected = 0;
            for r in 0..dims[1] {
                for c in 0..dims[0] {
                    for (dc, dr) in [(1, 0), (0, 1), (1, 1), (-1, 1), (2, 0), (0, 2)] {
                        let (nc, nr) = (c + dc, r + dr);
                        expected += (nc >= 0 && nr >= 0 && nc < dims[0] && nr < dims[1]) as usize;
                    }
                }
            }
            assert_eq!(springs, expected, "{dims:?}");
        }
    }

    /// No spring joins two particles of one colour, for every spring offset of the grid.
    #[test]
    fn the_vertex_colouring_separates_every_spring() {
        for dims in [[9u32, 7u32], [12, 1]] {
            let colours = vertex_colours(dims);
            for r in 0..dims[1] as i64 {
                for c in 0..dims[0] as i64 {
                    for (dc, dr) in [
                        (1, 0),
                        (0, 1),
                        (1, 1),
                        (1, -1),
                        (2, 0),
                        (0, 2),
                        (-1, 0),
                        (0, -1),
                        (-1, -1),
                        (-1, 1),
                        (-2, 0),
                        (0, -2),
                    ] {
                        let (nc, nr) = (c + dc, r + dr);
                        if nc < 0 || nr < 0 || nc >= dims[0] as i64 || nr >= dims[1] as i64 {
                            continue;
                        }
                        let a = vertex_colour(c as u32, r as u32, colours);
                        let b = vertex_colour(nc as u32, nr as u32, colours);
                        assert_ne!(a, b, "{dims:?}: ({c}, {r}) and ({nc}, {nr}) share colour {a}");
                    }
                }
            }
        }
    }
}
