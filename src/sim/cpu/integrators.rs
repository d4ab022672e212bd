//! The integrators of the CPU reference: each advances one object by one substep, before the
//! constraint stage. `sim::integrator`'s table names them (a method's `cpu` field); the GPU
//! runs the same iterations (Jacobi, colour or spring-class order, the same Newton steps), so
//! the two agree to rounding.

use super::{air_force, rest_lengths, springs, wind_at, Spring, SpringType, SPRING_GROUPS};
use crate::sim::collider::Pose;
use crate::sim::integrator::{
    newton_steps, spring_class_parity, vertex_colour, vertex_colours, xpbd_class_order, BDF2_STEP,
    RIGID_REGULARISER, SPRING_CLASSES, STIFF_START,
};
use crate::sim::model::{Integrator, ObjectModel, SimModel};
use crate::sim::pins::PinStep;
use glam::{DMat3, DVec3};

type State = (Vec<DVec3>, Vec<DVec3>);

/// A particle's BDF2 history for the position-based methods (`sim::integrator::BDF2_STEP`),
/// or `None` where there is none: the first substep, or a state written from outside. The GPU
/// keeps the same per particle (`history` in glsl/include/bindings.glsl).
pub type History = Option<Past>;

/// What a particle's last substep left: its increments x_n - x_{n-1} and v_n - v_{n-1} as the
/// solve made them (the constraint stage's corrections after the solve are not in them, so a
/// contact shifts the remembered motion with the particle instead of kicking it back), and the
/// fraction of gravity its springs held (`held_fraction`; methods without an adaptive start
/// leave it 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Past {
    pub dx: DVec3,
    pub dv: DVec3,
    pub held: f64,
}

/// What one substep of an object starts from: the model, the object, the substep's length
/// [s] and the object's positions and velocities.
#[derive(Clone, Copy)]
pub struct Substep<'a> {
    pub model: &'a SimModel,
    pub object: &'a ObjectModel,
    pub dt: f64,
    pub x: &'a [DVec3],
    pub v: &'a [DVec3],
    /// When the substep starts [s] (the wind's turbulence).
    pub time: f64,
    /// How the pinned particles of each pin group move over the substep (`sim::pins`,
    /// `ObjectModel::pin_steps`); they keep the velocity of that move.
    pub pins: &'a [PinStep],
}

impl Substep<'_> {
    /// How particle i's pin group moves over the substep (a free particle's: group 0's, which
    /// carries it in `toward_rest`).
    pub fn pins_of(&self, i: usize) -> &PinStep {
        &self.pins[self.object.group_of(i)]
    }
}

/// One substep with the model's integrator; the position-based methods read and update each
/// particle's history.
pub(super) fn advance(s: &Substep<'_>, history: &mut [History]) -> State {
    (s.model.integrator.method().cpu)(s, history)
}

pub(crate) fn symplectic_euler(s: &Substep<'_>, _: &mut [History]) -> State {
    explicit(s, false)
}

pub(crate) fn verlet(s: &Substep<'_>, _: &mut [History]) -> State {
    explicit(s, true)
}

fn grid(o: &ObjectModel, i: usize) -> (i64, i64) {
    let cols = o.dims[0] as usize;
    ((i % cols) as i64, (i / cols) as i64)
}

/// The springs of particle i that have a stiffness, with it (the solvers' constraints).
fn elastic_springs(o: &ObjectModel, i: usize) -> impl Iterator<Item = (Spring, f64)> + '_ {
    springs(o, i).into_iter().filter_map(move |s| {
        let k = o.stiffness_of(s.kind as usize);
        (k != 0.0).then_some((s, k))
    })
}

/// Gravity, wind and drag on particle i at x[i] with velocity v [N] (x: every particle's
/// position, for the aerodynamic wind's area and orientation). The paper's wind and Stokes drag
/// are per particle, a mesh cloth's by its share of the area (`external_force` in
/// glsl/include/forces.glsl).
fn external(m: &SimModel, o: &ObjectModel, i: usize, x: &[DVec3], v: DVec3, time: f64) -> DVec3 {
    let share = o.share_of(i);
    m.gravity * o.mass_of(i) + wind_at(&m.wind, x[i]) * share + air_force(m, o, i, x, v, time)
        - v * o.drag * share
}

/// The springs' force on particle i: elastic and dashpot parts [N].
fn spring_force(o: &ObjectModel, i: usize, x: &[DVec3], v: &[DVec3]) -> DVec3 {
    let mut force = DVec3::ZERO;
    for s in springs(o, i) {
        let k = o.stiffness_of(s.kind as usize);
        if k == 0.0 && o.damping == 0.0 {
            continue;
        }
        let delta = x[s.other] - x[i];
        let d = delta.length();
        if d <= 0.0 {
            continue;
        }
        let u = delta / d;
        force += u * (k * (d - s.rest) + o.damping * (v[s.other] - v[i]).dot(u));
    }
    force
}

/// Symplectic Euler, or position Verlet (`verlet`): forces at the half-drifted positions
/// x + v dt / 2, the kick, then the second half of the drift with the new velocity.
fn explicit(s: &Substep<'_>, verlet: bool) -> State {
    let Substep { model: m, object: o, dt, x, v, time, .. } = *s;
    let drift = if verlet { 0.5 * dt } else { 0.0 };
    let at: Vec<DVec3> = x.iter().zip(v).map(|(x, v)| *x + *v * drift).collect();
    let mut nx = x.to_vec();
    let mut nv = vec![DVec3::ZERO; x.len()];
    for i in 0..x.len() {
        if o.pinned[i] {
            let pins = s.pins_of(i);
            let d = pins.move_of(x[i]);
            nx[i] = x[i] + d;
            nv[i] = pins.velocity_of(d);
            continue;
        }
        // (at the half-drifted state's time too: the wind's turbulence)
        let force = external(m, o, i, &at, v[i], time + drift) + spring_force(o, i, &at, v);
        nv[i] = v[i] + force / o.mass_of(i) * dt;
        nx[i] = at[i] + nv[i] * (dt - drift);
    }
    (nx, nv)
}

/// Where a position-based substep starts (BDF2, `sim::integrator::BDF2_STEP`): the solve
/// minimises |p - y|^2_M / (2 h^2) + E(p) with h = 2 dt / 3 from the base x~ = x_n + (x_n -
/// x_{n-1}) / 3, towards the prediction y = x~ + 2/3 dt v_n + 2/9 dt (v_n - v_{n-1}) + h^2 F / m,
/// and the velocity that reaches p is (p - x~) / h. F: the external forces (every method
/// treats the springs' dashpots in its solve). A particle without history (`restart`) takes the last substep to have been
/// one Jacobi step of implicit Euler: v_n - v_{n-1} = dt a and x_n - x_{n-1} = dt (v_n + dt a)
/// with a = (F + F_s) / (m + dt^2 S), F_s its springs' elastic force and S their stiffness
/// sum. A particle at rest in equilibrium (F + F_s = 0) stays there, and a free one (S = 0)
/// starts as implicit Euler's step; the denominator keeps it stable at any stiffness. (With
/// F / m alone, the springs act through the solve only, with weight h^2 = 4/9 dt^2 where
/// implicit Euler gives them dt^2: a chain hanging still started to move at about g dt / 3,
/// 7.9e-4 m/s at 64 substeps.)
///
/// A free object whose solve starts from its rigid move (`rigid_starts`: its springs stiff
/// against the step) takes implicit Euler's step instead: h = dt from the base x~ = x_n towards
/// y = x_n + dt v_n + dt^2 F / m, velocity (p - x_n) / dt. Its few iterations leave part of
/// each solve undone, and BDF2's two-step history fed what they left back into the motion:
/// with the implicit method's one Newton step of 3 to 5 CG iterations a free stiff cloth
/// settled, then moved again and sped up as a whole, and BDF2's extrapolation of a rigid turn
/// gained spin every substep. Implicit Euler lowers its incremental potential from where the
/// object is, so whatever the solve leaves can only take energy out
/// (docs/design/integrators.md, "Where the solve starts").
struct Inertial {
    /// The solve's step h.
    h: f64,
    /// x~ (x + d / 3 for a pinned particle that its pins move by d over the substep).
    base: Vec<DVec3>,
    /// y (x + d for a pinned particle: where it is at the substep's end).
    y: Vec<DVec3>,
    /// Where the solve's iterate starts: y, or with `adaptive` y less the part of the external
    /// acceleration's pull h^2 F / m that the springs held last substep (`held_fraction`),
    /// moved by `toward_rest`.
    start: Vec<DVec3>,
}

fn inertial(s: &Substep<'_>, history: &[History]) -> Inertial {
    let Substep { model: m, object: o, dt, x, v, time, .. } = *s;
    let rigid = rigid_starts(m, o);
    let h = if rigid { dt } else { BDF2_STEP * dt };
    let adaptive = adaptive_start(m);
    let anchored = adaptive && o.anchored();
    let mut start = Vec::with_capacity(x.len());
    let (base, y) = (0..x.len())
        .map(|i| {
            if o.pinned[i] {
                // Moving pins: a base x~ of their steady motion (x_n - x_{n-1} = d, the move
                // over the substep), so that the solve's displacement y - x~ = 2 d / 3 is
                // their velocity over h, as its neighbours' are.
                // (implicit Euler's base is x_n: displacement d over h = dt)
                let d = s.pins_of(i).move_of(x[i]);
                start.push(x[i] + d);
                return (x[i] + d * (1.0 - h / dt), x[i] + d);
            }
            let force = external(m, o, i, x, v[i], time);
            let pull = force / o.mass_of(i) * (h * h);
            let (base, y, held) = if rigid {
                (x[i], x[i] + v[i] * dt + pull, history[i].map_or(0.0, |p| p.held))
            } else {
                let past = history[i].unwrap_or_else(|| restart(o, i, x, v[i], force, dt));
                let base = x[i] + past.dx / 3.0;
                (base, base + v[i] * (2.0 / 3.0 * dt) + past.dv * (2.0 / 9.0 * dt) + pull, past.held)
            };
            let guess = y - pull * held;
            start.push(match adaptive {
                true if anchored => toward_rest(o, i, h, x[i] + s.pins_of(i).move_of(x[i]), guess),
                true => guess,
                false => y,
            });
            (base, y)
        })
        .unzip();
    if rigid {
        let rigid = RigidMove::fit(x, &start);
        for (i, guess) in start.iter_mut().enumerate() {
            *guess = toward_rest(o, i, h, rigid.of(x[i]), *guess);
        }
    }
    Inertial { h, base, y, start }
}

/// The rigid move that fits a free object's guessed displacements d_i = guess_i - x_i best in
/// least squares, linearised: a translation t (their mean) and a turn w about the centre c
/// (I w = sum r_i x (d_i - t), r_i = x_i - c, I the inertia tensor of unit masses), and the
/// exact turn it stands for: implicit Euler's guesses y - x = dt v_n of an object that turned
/// by an angle a over the last substep move its particles by sin a across their radius (and
/// 1 - cos a inwards, which the fit does not see), so |w| = sin a, and the move turns x_i by
/// asin |w| about w: x_i + t + w x r_i + w x (w x r_i) / (1 + cos a) (`toward_rest` starts a
/// stiff free object there). The linearised move w x r_i alone stretched every spring across
/// the turn by its share of a^2 / 2, which the few iterations of a stiff solve left partly in
/// place as velocity: a free stiff cloth gained energy; without the asin, a turn shrank by
/// sin a / a each substep. A turn past a quarter a substep is taken as a quarter. The sums
/// are taken about the object's first particle, as the GPU takes them
/// (glsl/include/rigid_start.glsl).
struct RigidMove {
    centre: DVec3,
    t: DVec3,
    w: DVec3,
}

impl RigidMove {
    fn fit(x: &[DVec3], guess: &[DVec3]) -> Self {
        let origin = x[0];
        let n = x.len() as f64;
        let (mut sq, mut sd, mut sqd, mut sqq) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DMat3::ZERO);
        for (x, g) in x.iter().zip(guess) {
            let (q, d) = (*x - origin, *g - *x);
            sq += q;
            sd += d;
            sqd += q.cross(d);
            sqq += outer(q, q);
        }
        let (centre, t) = (sq / n, sd / n);
        let moment = sqd - centre.cross(t) * n;
        let spread = sqq - outer(centre, centre) * n;
        let trace = spread.x_axis.x + spread.y_axis.y + spread.z_axis.z;
        // I = tr(S) E - S for S = sum r r^T, regularised (RIGID_REGULARISER)
        let inertia = DMat3::from_diagonal(DVec3::splat(trace * (1.0 + RIGID_REGULARISER))) - spread;
        let w = if trace > 0.0 { inertia.inverse() * moment } else { DVec3::ZERO };
        Self { centre: centre + origin, t, w }
    }

    /// Where the move takes a particle at x.
    fn of(&self, x: DVec3) -> DVec3 {
        let w = self.w / self.w.length().max(1.0);
        let across = w.cross(x - self.centre);
        let cos = (1.0 - w.length_squared()).max(0.0).sqrt();
        x + self.t + across + w.cross(across) / (1.0 + cos)
    }
}

/// a b^T.
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// How stiff a particle's springs are against its inertia over the solve's step h:
/// (h^2 sum k + h sum b) / m over its springs that have a stiffness (`elastic_springs`).
fn stiffness_ratio(o: &ObjectModel, i: usize, h: f64) -> f64 {
    elastic_springs(o, i).map(|(_, k)| h * h * k + h * o.damping).sum::<f64>() / o.mass_of(i)
}

/// Where the adaptive methods start particle i: `guess` (the prediction less the pull its
/// springs held), moved towards `x` by the share kappa / (kappa + STIFF_START) of the way,
/// kappa its `stiffness_ratio`. On an anchored object (a particle pinned) x is where the
/// particle is, carried on by its pins' move over the substep (at rest with its pins, so that
/// a carried cloth starts as a held one does); on a free object, where the rigid move that
/// fits the guesses takes it (`RigidMove`). Where the springs are soft against the step a few
/// iterations converge from the guess, which keeps the motion (second order); where they are
/// stiff the sweeps cannot carry a correction across the object, and what they leave of the
/// guess's distance from the solution becomes velocity: from the guess a stiff cloth held at
/// its corners at one large substep never came to rest and gained energy, and a free one
/// thrown stretched gained energy many times over; from x, what the solve leaves is
/// deformation not taken, which damps. A free object keeps its rigid move: started from where
/// it is, a stiff cloth in free fall did not fall (its sweeps cannot move it as a whole
/// either), and without the turn a spinning one stopped (docs/design/integrators.md, "Where
/// the solve starts").
fn toward_rest(o: &ObjectModel, i: usize, h: f64, x: DVec3, guess: DVec3) -> DVec3 {
    let kappa = stiffness_ratio(o, i, h);
    x + (guess - x) * (STIFF_START / (STIFF_START + kappa))
}

/// The model's method starts its iterate adaptively (its row's `adaptive_start`).
fn adaptive_start(m: &SimModel) -> bool {
    m.integrator.solver().is_some_and(|s| s.adaptive_start)
}

/// The fraction of gravity's pull h^2 g that the solve took back from particle i's prediction
/// (0 in free fall, 1 hanging at rest; clamped to [0, 1]): VBD's adaptive initialisation (Chen
/// et al. 2024, section 3.6) with the solve's own correction p - y in place of the last
/// acceleration, which near rest is mostly noise. The next substep starts its iterate at y less
/// that fraction of the external pull, so a cloth at rest starts at rest and a falling one
/// starts falling: at few iterations and large steps a method from y hangs too low, since its
/// springs take back only part of each substep's pull (measured in docs/log.md).
pub fn held_fraction(m: &SimModel, h: f64, correction: DVec3) -> f64 {
    let g2 = m.gravity.length_squared();
    if g2 == 0.0 {
        return 0.0;
    }
    (-correction.dot(m.gravity) / (g2 * h * h)).clamp(0.0, 1.0)
}

/// The history of a particle without one (`inertial`): (x_n - x_{n-1}, v_n - v_{n-1}) of one
/// Jacobi step of implicit Euler from (x, v) under `force` and the springs' elastic force.
fn restart(o: &ObjectModel, i: usize, x: &[DVec3], v: DVec3, force: DVec3, dt: f64) -> Past {
    let (mut elastic, mut stiffness) = (DVec3::ZERO, 0.0);
    for (s, k) in elastic_springs(o, i) {
        let delta = x[s.other] - x[i];
        let d = delta.length();
        if d <= 0.0 {
            continue;
        }
        elastic += delta / d * (k * (d - s.rest));
        stiffness += k;
    }
    let a = (force + elastic) / (o.mass_of(i) + dt * dt * stiffness);
    Past { dx: (v + a * dt) * dt, dv: a * dt, held: 0.0 }
}

/// Positions after the solve, with the velocity that reaches them, v = (p - x~) / h, and each
/// particle's new history (with `adaptive`, the fraction of gravity it held).
fn finish(s: &Substep<'_>, start: &Inertial, p: Vec<DVec3>, history: &mut [History]) -> State {
    let v: Vec<DVec3> = p.iter().zip(&start.base).map(|(p, b)| (*p - *b) / start.h).collect();
    finish_moved(s, start, (p, v), None, history)
}

/// The end of a substep at positions `p` with velocities `v`, each particle's history from
/// the solve's own positions `solved` (`p` where `None`): VBD's contact rounds (`VbdSolve`)
/// move particles out of the colliders within the solve, and the history leaves those moves
/// out as it leaves out the constraint stage's corrections (`VbdSolve::sweep` says why).
fn finish_moved(
    s: &Substep<'_>,
    start: &Inertial,
    (p, v): (Vec<DVec3>, Vec<DVec3>),
    solved: Option<&[DVec3]>,
    history: &mut [History],
) -> State {
    let (o, x, v0) = (s.object, s.x, s.v);
    let adaptive = adaptive_start(s.model);
    let nv = (0..x.len())
        .map(|i| {
            if o.pinned[i] {
                history[i] = None;
                let pins = s.pins_of(i);
                return pins.velocity_of(pins.move_of(x[i]));
            }
            let held = if adaptive { held_fraction(s.model, start.h, p[i] - start.y[i]) } else { 0.0 };
            let solved = solved.map_or(p[i], |q| q[i]);
            let solved_v = (solved - start.base[i]) / start.h;
            history[i] = Some(Past { dx: solved - x[i], dv: solved_v - v0[i], held });
            v[i]
        })
        .collect();
    (p, nv)
}

/// The particles of each vertex colour (`sim::integrator::vertex_colours`), colour by colour:
/// the order the Gauss-Seidel methods sweep (within a colour no two particles share a spring,
/// so the order inside it does not matter).
fn colour_order(o: &ObjectModel) -> Vec<usize> {
    // (a mesh cloth: its colouring's order, as the GPU's passes take it)
    if let Some(mesh) = &o.mesh {
        return mesh.colour_order.iter().map(|&i| i as usize).collect();
    }
    let colours = vertex_colours(o.dims);
    let cols = o.dims[0];
    let mut order: Vec<usize> = (0..o.particle_count()).collect();
    order.sort_by_key(|&i| vertex_colour(i as u32 % cols, i as u32 / cols, colours));
    order
}

/// XPBD with Gauss-Seidel over spring classes, from the BDF2 start (`inertial`: dt below is
/// its step h = 2 dt / 3 and dp the displacement from its base x~). Each spring of stiffness
/// k > 0 is a distance constraint C = |p_i - p_j| - L with compliance 1/k (alpha~ = 1 / (k
/// dt^2)), damping gamma = b / (k dt) and one multiplier lambda. An iteration visits the classes in turn
/// (`sim::integrator::xpbd_class_order`, the structural last: within a class no two springs
/// share a particle, so the order inside it does not matter); each spring takes the XPBD update
/// dlambda = relaxation (-C - alpha~ lambda - gamma n.(dp_i - dp_j)) / ((1 + gamma)(w_i + w_j) + alpha~),
/// p_i += w_i n dlambda, p_j -= w_j n dlambda, lambda += dlambda (w = 0 for a pinned end). At
/// convergence the result is BDF2; with one iteration and a small substep (alpha~ >> w) a
/// correction is the spring's impulse h^2 F / m at the positions the classes before left, a
/// consistent step whose error falls with the substep's square (measured in ACCURACY.md; on
/// implicit Euler's start it was first order and damped: 41 times symplectic Euler's error at
/// 256 substeps).
/// (Two earlier versions: a Jacobi sweep that divided each particle's summed corrections by its
/// spring count made a cloth up to 12 times too soft whatever the substep; vertex-coloured
/// Gauss-Seidel, where a particle applies its own share of each spring while its neighbours are
/// held, was right but converged slowly: after 1 s of a 24 x 24 cloth at 16 substeps and one
/// iteration it stood 106 mm from the converged solve, against 4.6 mm for the spring classes.)
pub(crate) fn xpbd(s: &Substep<'_>, history: &mut [History]) -> State {
    let Substep { model: m, object: o, x: x0, .. } = *s;
    let n = x0.len();
    let start = inertial(s, history);
    let (dt, x) = (start.h, &start.base[..]);
    let mut p = start.y.clone();
    if let Some(mesh) = &o.mesh {
        xpbd_mesh(m, o, mesh, (dt, x), &mut p);
        return finish(s, &start, p, history);
    }
    let mut lambda = vec![[0.0f64; 6]; n];
    let w = 1.0 / o.mass;
    let rest = super::rest_lengths(o);
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    for _ in 0..m.iterations {
        for (dir, parity) in xpbd_class_order() {
            let ((dc, dr), slot) = SPRING_CLASSES[dir];
            let k = o.stiffness[slot / 4];
            if k == 0.0 {
                continue;
            }
            let (alpha, gamma) = (1.0 / (k * dt * dt), o.damping / (k * dt));
            for r in 0..rows {
                for c in 0..cols {
                    let (nc, nr) = (c + dc, r + dr);
                    if nc < 0
                        || nr < 0
                        || nc >= cols
                        || nr >= rows
                        || spring_class_parity(dir, c, r) != parity
                    {
                        continue;
                    }
                    let (i, j) = ((c + r * cols) as usize, (nc + nr * cols) as usize);
                    let (w_i, w_j) = (if o.pinned[i] { 0.0 } else { w }, if o.pinned[j] { 0.0 } else { w });
                    let spring = XpbdSpring { rest: rest[slot / 4][slot % 4], alpha, gamma };
                    spring.update(m.relaxation, (&mut p, x), (i, j), (w_i, w_j), &mut lambda[i][dir]);
                }
            }
        }
    }
    finish(s, &start, p, history)
}

/// One spring of `xpbd`: its rest length, alpha~ = 1 / (k dt^2) and gamma = b / (k dt).
struct XpbdSpring {
    rest: f64,
    alpha: f64,
    gamma: f64,
}

impl XpbdSpring {
    /// The spring from particle i to j of the iterate `p` (x the base) takes XPBD's update with
    /// inverse masses w_i, w_j and multiplier `lambda` (none where both ends are pinned or they
    /// coincide).
    fn update(
        &self,
        relaxation: f64,
        (p, x): (&mut [DVec3], &[DVec3]),
        (i, j): (usize, usize),
        (w_i, w_j): (f64, f64),
        lambda: &mut f64,
    ) {
        let delta = p[i] - p[j];
        let d = delta.length();
        if w_i + w_j == 0.0 || d <= 0.0 {
            return;
        }
        let normal = delta / d;
        let moved = normal.dot((p[i] - x[i]) - (p[j] - x[j]));
        let cons = d - self.rest;
        let dl = relaxation * (-cons - self.alpha * *lambda - self.gamma * moved)
            / ((1.0 + self.gamma) * (w_i + w_j) + self.alpha);
        p[i] += normal * (w_i * dl);
        p[j] -= normal * (w_j * dl);
        *lambda += dl;
    }
}

/// `xpbd` on a mesh cloth (`o`'s `mesh`) from the iterate `p` (x the BDF2 base, dt its step):
/// its spring classes in their order (`sim::cloth_mesh::spring_classes`), each spring the
/// update of `xpbd` with both ends' masses (lumped by area) and its own stiffness, its
/// multiplier kept at its entry in its lower end's list (as the GPU's MESH_LAMBDA).
fn xpbd_mesh(
    m: &SimModel,
    o: &ObjectModel,
    mesh: &crate::sim::cloth_mesh::ClothMesh,
    (dt, x): (f64, &[DVec3]),
    p: &mut [DVec3],
) {
    let mut lambda = vec![0.0f64; mesh.springs.len()];
    let w = |i: usize| if o.pinned[i] { 0.0 } else { 1.0 / o.mass_of(i) };
    for _ in 0..m.iterations {
        for c in 0..mesh.class_count() {
            for &[a, e] in mesh.class(c) {
                let (a, e) = (a as usize, e as usize);
                let s = &mesh.springs[e];
                let (j, k) = (s.other as usize, o.stiffness_of(s.kind as usize));
                if k == 0.0 {
                    continue;
                }
                let (alpha, gamma) = (1.0 / (k * dt * dt), o.damping / (k * dt));
                let spring = XpbdSpring { rest: s.scaled_rest(o.rest_scale), alpha, gamma };
                spring.update(m.relaxation, (p, x), (a, j), (w(a), w(j)), &mut lambda[e]);
            }
        }
    }
}

/// XPBD by Jacobi, from the BDF2 start (`inertial`; dt below is its step h, x its base x~):
/// the constraints and update of `xpbd`, but an iteration updates every spring at once from the
/// iterate before, and particle i moves by beta_i times the sum of its springs' moves,
/// w_i n dlambda. Each particle keeps its own copy of its springs' multipliers, advanced by
/// beta_i dlambda, so that its displacement stays w_i sum n lambda (the fixed point is
/// `xpbd`'s, the converged solve).
///
/// beta_i bounds the step so that no sweep overshoots: linearised, a sweep multiplies the
/// error by I - B W J^T G D^-1 J (G the springs' 1 + gamma, D their denominators
/// (1 + gamma)(w_i + w_j) + alpha~), whose eigenvalues lie in [0, 1] (the second term is
/// similar to a positive semi-definite matrix) when every particle's block row of the second
/// term, weighted by the inverse masses (Gershgorin's bound on diag(w)^-1 B W J^T G D^-1 J
/// diag(w)), sums to at most one: beta_i sum (1 + gamma)(w_i + w_j) / D <= 1, w_j = 0 where the
/// other end is pinned (on a grid w_i e with e = 2, or 1 pinned). So beta_i = min(1, 1 /
/// sum (1 + gamma)(w_i + w_j) / D), a constant of the particle's springs and the substep. Where the springs are soft
/// against the substep (alpha~ >> w: the sum is about 2 w h^2 sum k) beta is 1 and a sweep is
/// plain Jacobi, whose one iteration is a consistent step like `xpbd`'s; where they are stiff beta tends to
/// 1 / (springs), the mean of the springs' corrections, which is stable but converges slowly
/// (the cloth is softer there than with the spring classes). An overshooting sweep (c > 1 in a
/// mode) is what makes plain Jacobi blow up at large substeps. `sim.relaxation` does not apply:
/// the bound sets the step (scaled by it, beta would cancel it wherever it acts).
pub(crate) fn xpbd_jacobi(s: &Substep<'_>, history: &mut [History]) -> State {
    let Substep { model: m, object: o, x: x0, .. } = *s;
    let n = x0.len();
    let start = inertial(s, history);
    let (dt, x) = (start.h, &start.base[..]);
    let mut p = start.y.clone();
    // Each particle's copy of its springs' multipliers, by slot (a grid's 12, a mesh's list).
    let slots = |i: usize| o.mesh.as_ref().map_or(12, |mesh| mesh.springs_of(i).len());
    let mut lambda: Vec<Vec<f64>> = (0..n).map(|i| vec![0.0; slots(i)]).collect();
    let mut updates = Vec::new();
    for _ in 0..m.iterations {
        let mut next = p.clone();
        for i in 0..n {
            if o.pinned[i] {
                continue;
            }
            // (a mesh cloth's masses differ, so each spring's denominator takes both ends';
            // on a grid w_j is w or 0)
            let w = 1.0 / o.mass_of(i);
            let (mut load, mut moved_by) = (0.0, DVec3::ZERO);
            updates.clear();
            updates.resize(slots(i), 0.0);
            for (s, k) in elastic_springs(o, i) {
                let j = s.other;
                let (alpha, gamma) = (1.0 / (k * dt * dt), o.damping / (k * dt));
                let w_j = if o.pinned[j] { 0.0 } else { 1.0 / o.mass_of(j) };
                let scale = 1.0 / ((1.0 + gamma) * (w + w_j) + alpha);
                let ends = (w + w_j) / w; // (a grid's 2, or 1 with j pinned)
                load += (1.0 + gamma) * ends * scale;
                let delta = p[i] - p[j];
                let d = delta.length();
                if d <= 0.0 {
                    continue;
                }
                let normal = delta / d;
                let moved = normal.dot((p[i] - x[i]) - (p[j] - x[j]));
                let dl = scale * (s.rest - d - alpha * lambda[i][s.slot] - gamma * moved);
                updates[s.slot] = dl;
                moved_by += normal * (w * dl);
            }
            let beta = if w * load > 1.0 { 1.0 / (w * load) } else { 1.0 };
            next[i] += moved_by * beta;
            for (l, dl) in lambda[i].iter_mut().zip(&updates) {
                *l += beta * dl;
            }
        }
        p = next;
    }
    finish(s, &start, p, history)
}

/// Vertex Block Descent (Chen et al. 2024): from the BDF2 start (`inertial`: dt below is its
/// step h, x its base x~), the incremental potential G(p) = |p - y|^2_M / (2 dt^2) + sum k/2 (|p_i - p_j| - L)^2, plus the dashpots as a
/// quadratic damping potential (b / (2 dt)) (n.(dp_i - dp_j))^2, minimised by vertex-coloured
/// Gauss-Seidel: a particle of the current colour, its neighbours held, takes one Newton step
/// on G as a function of its own position, with the 3x3 Hessian
/// m / dt^2 I + sum k (n n^T + max(0, 1 - L / d) (I - n n^T)) + (b / dt) n n^T
/// (the spring's transverse term clamped at compression keeps it positive definite).
/// Settles at any stiffness, held or free (`toward_rest`); at convergence BDF2 with implicit
/// dashpots.
pub(crate) fn vbd(s: &Substep<'_>, history: &mut [History]) -> State {
    let mut solve = VbdSolve::new(s, history);
    for _ in 0..s.model.iterations {
        solve.sweep(s, None, None, false);
    }
    solve.finish(s, history)
}

/// One object's VBD solve of a substep, an iteration at a time (`vbd`; with contact between
/// objects after every iteration, `sim::cpu`'s scene solve: `SimModel::contact_rounds`).
pub(super) struct VbdSolve {
    start: Inertial,
    /// The iterate.
    p: Vec<DVec3>,
    /// Each particle's moves of the colliders within the solve (`finish` leaves them out of
    /// the history), and its velocity where the last iteration's colliders gave it.
    kept_colliders: Vec<DVec3>,
    end_velocity: Vec<Option<DVec3>>,
    order: Vec<usize>,
}

impl VbdSolve {
    pub fn new(s: &Substep<'_>, history: &[History]) -> Self {
        let start = inertial(s, history);
        let n = s.x.len();
        Self {
            p: start.start.clone(),
            start,
            kept_colliders: vec![DVec3::ZERO; n],
            end_velocity: vec![None; n],
            order: colour_order(s.object),
        }
    }

    /// The iterate's positions.
    pub fn positions(&self) -> &[DVec3] {
        &self.p
    }

    /// One iteration (`last`: the substep's last). `moved`: each particle's contact sum of the
    /// round after the iteration before, which it adds to its iterate and its prediction when
    /// its colour comes (as glsl/vbd_iterate.comp), so that its solve keeps the correction.
    /// `colliders`: each collider's offset and velocity at the substep's end, to take each
    /// particle out of them after its solve (the particle's response, with friction): before
    /// the last iteration its prediction moves likewise; in the last the response gives its
    /// velocity from the solve's. Contact's moves are the solve's own (in the velocity and the
    /// history: a pile's support is part of its motion); the colliders' are kept out of both,
    /// as the constraint stage keeps them: with them in the history BDF2 carried the push into
    /// the next substeps, and with them in the velocity over h the base BDF2 put below the
    /// surface came back as speed (a cloth dropped at 3.5 m/s on the ground bounced back at 1.0
    /// to 1.6 m/s either way). Contact's moves taken that way instead (out of the history, into
    /// the velocity over the substep) threw a stack of cards apart.
    pub fn sweep(
        &mut self,
        s: &Substep<'_>,
        moved: Option<&[DVec3]>,
        colliders: Option<&[Pose]>,
        last: bool,
    ) {
        let o = s.object;
        let (h, x) = (self.start.h, &self.start.base[..]);
        for &i in &self.order {
            if o.pinned[i] {
                continue;
            }
            if let Some(moved) = moved {
                self.p[i] += moved[i];
                self.start.y[i] += moved[i];
            }
            let p = &self.p;
            let inertia = o.mass_of(i) / (h * h);
            let mut force = (self.start.y[i] - p[i]) * inertia;
            let mut hessian = DMat3::from_diagonal(DVec3::splat(inertia));
            for (_, f, block) in newton_springs(o, h, p, x, i) {
                force += f;
                hessian += block;
            }
            self.p[i] += hessian.inverse() * force;
            let Some(motions) = colliders else { continue };
            let mut v = (self.p[i] - self.kept_colliders[i] - x[i]) / h;
            let mut at = self.p[i];
            // (the last: touching within a few f32 steps of the margin, where the iterations
            // before held it)
            let touch = if last { crate::sim::collider::position_slack(at) } else { 0.0 };
            for (c, pose) in s.model.colliders.iter().zip(motions) {
                c.respond_within((o.margin, o.friction), pose, (s.x[i], s.dt), touch, &mut at, &mut v);
            }
            let moved = at - self.p[i];
            self.kept_colliders[i] += moved;
            if last {
                self.end_velocity[i] = Some(v);
            } else {
                self.start.y[i] += moved;
            }
            self.p[i] = at;
        }
    }

    pub fn finish(self, s: &Substep<'_>, history: &mut [History]) -> State {
        let h = self.start.h;
        let solved: Vec<DVec3> = (0..self.p.len()).map(|i| self.p[i] - self.kept_colliders[i]).collect();
        let v = (0..self.p.len())
            .map(|i| self.end_velocity[i].unwrap_or((solved[i] - self.start.base[i]) / h))
            .collect();
        finish_moved(s, &self.start, (self.p, v), Some(&solved), history)
    }
}

/// One spring of particle i in BDF2's incremental potential at the iterate p (`vbd` and
/// `implicit`): the force on i (elastic, and the dashpot on the displacements from the base x)
/// and the spring's 3x3 block of the Hessian, (k + b / dt) n n^T + k t (I - n n^T) with the
/// transverse factor t = max(0, 1 - L / d) clamped at compression (positive semi-definite).
/// None for coincident ends.
fn spring_newton(
    o: &ObjectModel,
    s: &Spring,
    k: f64,
    dt: f64,
    p: &[DVec3],
    x: &[DVec3],
    i: usize,
) -> Option<(DVec3, DMat3)> {
    let delta = p[i] - p[s.other];
    let d = delta.length();
    if d <= 0.0 {
        return None;
    }
    let normal = delta / d;
    let nn = DMat3::from_cols(normal * normal.x, normal * normal.y, normal * normal.z);
    let rest = s.rest;
    let transverse = (1.0 - rest / d).max(0.0);
    let damp = o.damping / dt;
    let moved = normal.dot((p[i] - x[i]) - (p[s.other] - x[s.other]));
    let force = -normal * (k * (d - rest) + damp * moved);
    Some((force, nn * (k + damp) + (DMat3::IDENTITY - nn) * (k * transverse)))
}

/// Particle i's springs with a stiffness or a dashpot in BDF2's incremental potential at p
/// (`spring_newton`): each one's other end, its force on i and its block of the Hessian.
fn newton_springs<'a>(
    o: &'a ObjectModel,
    dt: f64,
    p: &'a [DVec3],
    x: &'a [DVec3],
    i: usize,
) -> impl Iterator<Item = (usize, DVec3, DMat3)> + 'a {
    springs(o, i).into_iter().filter_map(move |s| {
        let k = o.stiffness_of(s.kind as usize);
        if k == 0.0 && o.damping == 0.0 {
            return None;
        }
        spring_newton(o, &s, k, dt, p, x, i).map(|(force, block)| (s.other, force, block))
    })
}

/// BDF2 by Newton's method with preconditioned conjugate gradients (Baraff and Witkin 1998, on
/// BDF2's incremental potential; dt below is its step h, x its base x~): minimise
/// G(p) = |p - y|^2_M / (2 dt^2) + sum k/2 (|p_i - p_j| - L)^2 + the dashpots' damping
/// potential (b / (2 dt)) (n.(dp_i - dp_j))^2, as VBD does, from the adaptive start. Each
/// Newton step (`newton_steps`) linearises G at the iterate: gradient g and Hessian
/// H = M / dt^2 + the springs' blocks (`spring_newton`), then solves H dp = -g by conjugate
/// gradients from dp = 0, preconditioned by H's 3x3 diagonal blocks, pinned particles held; the
/// iterate moves by dp. CG's dot products span the object, so stiffness crosses it within an
/// iteration's reach of the whole (a Jacobi sweep moves it one neighbour an iteration). At
/// convergence BDF2 with implicit dashpots, at any stiffness. Cut short, a Newton step is not
/// always a descent of G: on an object whose springs are stiff against its inertia
/// (`implicit_searches`) the step is scaled by the best of four trial lengths
/// (`line_search`), else a very stiff cloth (1e5 N/m and more) at one 1/60 s substep gains
/// energy on the way below 10 iterations before it settles (docs/ACCURACY.md, "Large steps").
pub(crate) fn implicit(s: &Substep<'_>, history: &mut [History]) -> State {
    let Substep { model: m, object: o, x: x0, .. } = *s;
    let n = x0.len();
    let start = inertial(s, history);
    let (dt, x, y) = (start.h, &start.base[..], &start.y[..]);
    // (each particle's: a mesh cloth's masses are lumped by area)
    let inertia: Vec<f64> = (0..n).map(|i| o.mass_of(i) / (dt * dt)).collect();
    let mut p = start.start.clone();
    let free: Vec<usize> = (0..n).filter(|&i| !o.pinned[i]).collect();
    let search = implicit_searches(m, o);
    for cg in newton_steps(m.iterations) {
        // Linearise at p: r = -g, each spring's block, and the preconditioner.
        let mut r = vec![DVec3::ZERO; n];
        let mut pre = vec![DMat3::ZERO; n];
        let mut blocks: Vec<Vec<(usize, DMat3)>> = vec![Vec::new(); n];
        for &i in &free {
            let mut force = (y[i] - p[i]) * inertia[i];
            let mut diagonal = DMat3::from_diagonal(DVec3::splat(inertia[i]));
            for (j, f, block) in newton_springs(o, dt, &p, x, i) {
                force += f;
                diagonal += block;
                blocks[i].push((j, block));
            }
            r[i] = force;
            pre[i] = diagonal.inverse();
        }
        let r0 = if search { r.clone() } else { Vec::new() };
        let product = |d: &[DVec3]| -> Vec<DVec3> {
            let mut q = vec![DVec3::ZERO; n];
            for &i in &free {
                q[i] = d[i] * inertia[i] + blocks[i].iter().map(|(j, b)| *b * (d[i] - d[*j])).sum::<DVec3>();
            }
            q
        };
        let dot = |a: &[DVec3], b: &[DVec3]| free.iter().map(|&i| a[i].dot(b[i])).sum::<f64>();
        let mut z: Vec<DVec3> = (0..n).map(|i| pre[i] * r[i]).collect();
        let mut d = z.clone();
        let mut rz = dot(&r, &z);
        let mut dp = vec![DVec3::ZERO; n];
        for _ in 0..cg {
            let q = product(&d);
            let dq = dot(&d, &q);
            let alpha = if dq > 0.0 { rz / dq } else { 0.0 };
            for &i in &free {
                dp[i] += d[i] * alpha;
                r[i] -= q[i] * alpha;
                z[i] = pre[i] * r[i];
            }
            let next = dot(&r, &z);
            let beta = if rz > 0.0 { next / rz } else { 0.0 };
            for &i in &free {
                d[i] = z[i] + d[i] * beta;
            }
            rz = next;
        }
        let scale = if search { line_search(o, dt, &p, &dp, &r0) } else { 1.0 };
        for &i in &free {
            p[i] += dp[i] * scale;
        }
    }
    finish(s, &start, p, history)
}

/// The trial lengths of the implicit method's line search (glsl/include/solver_bodies.glsl's
/// `newton_descent` evaluates the same four).
pub const LINE_SEARCH_STEPS: [f64; 4] = [1.0, 0.5, 0.25, 0.125];

/// Whether the implicit method searches along its Newton steps on object `o`: where its
/// springs are stiff against the step (`stiff_against_step`). Below that the incremental
/// potential is close to its quadratic model and a Newton step close to exact, and a search
/// would cost a pass over the springs for nothing.
pub fn implicit_searches(m: &SimModel, o: &ObjectModel) -> bool {
    m.integrator == Integrator::Implicit && stiff_against_step(m, o)
}

/// Whether a free object of a method that starts adaptively starts each solve from the rigid
/// move that fits its guesses (`RigidMove`, `toward_rest`), with implicit Euler's step
/// (`Inertial`): where its springs are stiff against the step (`stiff_against_step`). A
/// softer one converges from its guess (it would move at most a tenth of the way), keeps
/// BDF2's second order and pays nothing for the sums the fit takes.
pub fn rigid_starts(m: &SimModel, o: &ObjectModel) -> bool {
    adaptive_start(m) && !o.anchored() && stiff_against_step(m, o)
}

/// Whether some particle of object `o` has springs stiffer than its inertia over the solve's
/// step (`stiffness_ratio` above 1). The GPU's per-stage path asks it as it records each frame
/// (through the parameters' flags): it tries the particles at and near the grid's corners,
/// edges and middle, which have every set of springs a particle of the grid can have, not all
/// of them (a mesh cloth's: all).
fn stiff_against_step(m: &SimModel, o: &ObjectModel) -> bool {
    let h = BDF2_STEP * m.dt();
    // (a mesh cloth's particles differ each: all of them)
    if o.mesh.is_some() {
        return (0..o.particle_count()).any(|i| stiffness_ratio(o, i, h) > 1.0);
    }
    let near = |n: u32| {
        let n = n as i64;
        let mut at: Vec<i64> =
            [0, 1, 2, n / 2, n - 3, n - 2, n - 1].into_iter().filter(|&c| c >= 0 && c < n).collect();
        at.sort_unstable();
        at.dedup();
        at
    };
    let rows = near(o.dims[1]);
    near(o.dims[0])
        .into_iter()
        .any(|c| rows.iter().any(|&r| stiffness_ratio(o, (c + r * o.dims[0] as i64) as usize, h) > 1.0))
}

/// The length a Newton step `dp` from the iterate `p` is taken at: of `LINE_SEARCH_STEPS`, the
/// one that lowers BDF2's incremental potential G the most, or none (0) where none lowers it.
/// `r0` is -g at p (the linearisation's residual). The change of G is summed by pieces
/// (`descent`), each exact from p and dp, so that its rounding is that of the change, not of
/// G.
fn line_search(o: &ObjectModel, h: f64, p: &[DVec3], dp: &[DVec3], r0: &[DVec3]) -> f64 {
    let change = descent(o, h, p, dp, r0);
    let best = (0..4).min_by(|&a, &b| change[a].total_cmp(&change[b])).unwrap_or(0);
    if change[best] < 0.0 {
        LINE_SEARCH_STEPS[best]
    } else {
        0.0
    }
}

/// G(p + a dp) - G(p) for each trial length a of `LINE_SEARCH_STEPS`, with the dashpots'
/// potential along their directions at p: -a r0.dp + a^2 / 2 dp.(M / h^2) dp, and for each
/// spring (once) k/2 ((d' - L)^2 - (d - L)^2) - a k (d - L) n.e + a^2 / 2 (b / h) (n.e)^2,
/// e = dp_i - dp_j (-a r0.dp holds the springs' first-order change, which their exact change
/// replaces; d' - d is formed from d'^2 - d^2 = a e.(2 delta + a e), exact where a e is small
/// against the spring).
fn descent(o: &ObjectModel, h: f64, p: &[DVec3], dp: &[DVec3], r0: &[DVec3]) -> [f64; 4] {
    let damp = o.damping / h;
    let mut change = [0.0; 4];
    for i in 0..p.len() {
        let first = -r0[i].dot(dp[i]);
        let second = o.mass_of(i) / (h * h) * dp[i].length_squared();
        for (t, &a) in LINE_SEARCH_STEPS.iter().enumerate() {
            change[t] += a * first + 0.5 * a * a * second;
        }
        for s in springs(o, i).iter().filter(|s| s.once) {
            let k = o.stiffness_of(s.kind as usize);
            if k == 0.0 && o.damping == 0.0 {
                continue;
            }
            let delta = p[i] - p[s.other];
            let dd = delta.length_squared();
            if dd <= 0.0 {
                continue;
            }
            let d = dd.sqrt();
            let e = dp[i] - dp[s.other];
            let ne = delta.dot(e) / d;
            let stretch = d - s.rest;
            for (t, &a) in LINE_SEARCH_STEPS.iter().enumerate() {
                let grown = a * e.dot(2.0 * delta + a * e);
                let d2 = (dd + grown).max(0.0).sqrt(); // (as the GPU's, newton_descent)
                let moved = grown / (d2 + d);
                change[t] += 0.5 * k * moved * (moved + 2.0 * stretch) - a * k * stretch * ne
                    + 0.5 * a * a * damp * ne * ne;
            }
        }
    }
    change
}

/// Total energy of an object [J]: kinetic, elastic (each spring once) and gravitational
/// (relative to height 0 along -g).
/// (Without allocating: the runtime guard sums it over whole scenes, `sim::gpu::energy`.)
pub fn energy(m: &SimModel, o: &ObjectModel, x: &[DVec3], v: &[DVec3]) -> f64 {
    let rest = rest_lengths(o);
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    let mut e = 0.0;
    for i in 0..x.len() {
        e += o.mass_of(i) * (0.5 * v[i].length_squared() - m.gravity.dot(x[i]));
        if let Some(mesh) = &o.mesh {
            // (each spring once, from its lower end)
            for s in mesh.springs_of(i).iter().filter(|s| s.other as usize > i) {
                let k = o.stiffness_of(s.kind as usize);
                let stretch = (x[s.other as usize] - x[i]).length() - s.scaled_rest(o.rest_scale);
                e += 0.5 * k * stretch * stretch;
            }
            continue;
        }
        let (c, r) = grid(o, i);
        for (g, (kind, offsets)) in SPRING_GROUPS.iter().enumerate() {
            let k = o.stiffness[*kind as usize];
            // The even slots (the forward directions): each spring once.
            for slot in [0, 2] {
                let (nc, nr) = (c + offsets[slot].0, r + offsets[slot].1);
                if k != 0.0 && nc >= 0 && nr >= 0 && nc < cols && nr < rows {
                    let stretch = (x[(nc + nr * cols) as usize] - x[i]).length() - rest[g][slot];
                    e += 0.5 * k * stretch * stretch;
                }
            }
        }
    }
    e
}

/// Largest |d / L - 1| over the structural springs.
pub fn max_strain(o: &ObjectModel, x: &[DVec3]) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..x.len() {
        for s in springs(o, i).iter().filter(|s| s.once && s.kind == SpringType::Structural) {
            worst = worst.max(((x[s.other] - x[i]).length() / s.rest - 1.0).abs());
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The energy counts every spring of the grid once: it equals the sum over each particle's
    /// springs (`springs`, both directions) halved, on a 5 x 4 cloth with particles moved
    /// about and moving.
    #[test]
    fn energy_counts_each_spring_once() {
        let toml = "[[cloth]]\nname = \"c\"\nresolution = [5, 4]\nsize = [0.4, 0.3]\norigin = [0, 1, 0]\nmass = 0.01\n\
                    stiffness = { structural = 100.0, shear = 20.0, bending = 3.0 }\n";
        let m = crate::scene::to_model(&crate::scene::parse(toml, "t", &[]).unwrap());
        let o = &m.objects[0];
        let x: Vec<DVec3> = (o.positions.iter().enumerate())
            .map(|(i, p)| *p + DVec3::new(0.003 * (i % 3) as f64, -0.002 * (i % 4) as f64, 0.001 * i as f64))
            .collect();
        let v: Vec<DVec3> = (0..x.len()).map(|i| DVec3::new(0.1 * i as f64, 0.0, -0.05)).collect();
        let mut expected = 0.0;
        for i in 0..x.len() {
            expected += 0.5 * o.mass * v[i].length_squared() - o.mass * m.gravity.dot(x[i]);
            for s in springs(o, i) {
                let stretch = (x[s.other] - x[i]).length() - s.rest;
                expected += 0.25 * o.stiffness_of(s.kind as usize) * stretch * stretch;
            }
        }
        let e = energy(&m, o, &x, &v);
        assert!((e - expected).abs() <= 1e-12 * expected.abs().max(1.0), "{e} against {expected}");
    }
}
