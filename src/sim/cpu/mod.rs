//! CPU reference of the model in `sim::model`, in f64 and plain Rust, used by the tests to check
//! the GPU simulation. It follows the model's definition (below), not the shader code.
//!
//! One substep of each object:
//! 1. The integrator (`integrators.rs`, a row of `sim::integrator`'s table) advances the spring network:
//!    forces F = m g + wind(x) - c v + sum over its springs of [k (d - L) + b ((v_j - v_i) . u)] u,
//!    with u the unit vector to the neighbour, d the distance and L the rest length. Pinned
//!    particles keep their position and have zero velocity.
//! 2. Constraints, Jacobi on the physics result: each free particle sums (a) for every structural
//!    and shear spring stretched past (1 + limit) L, half the excess towards the neighbour times
//!    the mean of the two ends' shares, one over each one's count of such springs (equal and
//!    opposite; all of it over its own count when the neighbour is pinned), and (b) in a rope,
//!    for every particle nearer than the self-collision distance s (except pairs nearer than s
//!    at rest), half the overlap away from it (all of it when that one is pinned). Where (b)
//!    finds any, the correction is the mean of (b) and of (a) weighted by its count (Jacobi
//!    averaging), plus in a cloth its moves from contacts with its own triangles (particle
//!    against triangle, equal and opposite, `self_contact`), plus (c) for
//!    every particle of another object nearer than the two contact radii, its share of the
//!    overlap by inverse mass over the larger of the two particles' contact counts (equal and
//!    opposite momenta for both ends); x += correction, v += correction / dt. Then, collider
//!    by collider (`sim::collider`): a particle nearer than its margin to the surface is moved
//!    out along the surface normal to the margin, its approaching normal velocity is removed,
//!    and Coulomb friction bounds the tangential impulse by mu times the normal one
//!    (`ColliderModel::respond`); where the colliders are thin or sharp, its edges first
//!    (`collide_edges`).
//!
//! After the frame's last substep, cloth normals (angle-weighted over the four structural edges)
//! and rope tube vertices are computed from the final positions.
//!
//! Inputs are rounded to f32 once at construction, so the reference simulates exactly the scene
//! the GPU receives; everything after that is f64.

pub(crate) mod integrators;
mod inter_object;
pub mod self_contact;

pub use integrators::{energy, implicit_searches, max_strain, rigid_starts, History};

use super::collider::Pose;
use super::gpu_types::ROPE_RING;
use super::model::{ObjectKind, ObjectModel, SimModel, WindModel};
use glam::{DQuat, DVec3};

/// State of one object in the reference.
#[derive(Debug, Clone)]
pub struct CpuObject {
    pub x: Vec<DVec3>,
    pub v: Vec<DVec3>,
    /// Surface vertex positions and normals (cloth: per particle; rope: ROPE_RING per node),
    /// valid after `step_frame`.
    pub surface: Vec<(DVec3, DVec3)>,
    /// Each particle's BDF2 history (the position-based methods).
    pub history: Vec<History>,
}

pub struct CpuSim {
    model: SimModel,
    dt: f64,
    objects: Vec<CpuObject>,
    /// Substeps run so far (where moving colliders are).
    substeps_done: u64,
}

fn r32(x: f64) -> f64 {
    x as f32 as f64
}

fn r32v(v: DVec3) -> DVec3 {
    DVec3::new(r32(v.x), r32(v.y), r32(v.z))
}

/// The model as the GPU receives it: every parameter and initial value rounded to f32.
fn rounded(model: &SimModel) -> SimModel {
    let mut m = model.clone();
    m.gravity = r32v(m.gravity);
    m.wind = m.wind.map(|w| WindModel {
        origin: r32v(w.origin),
        direction: r32v(w.direction),
        force: r32(w.force),
        cos_full: r32(w.cos_full),
        cos_att: r32(w.cos_att),
        air: w.air.map(|a| crate::sim::model::AirModel {
            speed: r32(a.speed),
            normal: r32(a.normal),
            tangent: r32(a.tangent),
            lift: r32(a.lift),
            turbulence: a.turbulence.map(|t| crate::sim::turbulence::Turbulence {
                modes: t.modes.map(|m| crate::sim::turbulence::Mode {
                    k: r32v(m.k),
                    a: r32v(m.a),
                    rate: r32(m.rate),
                    ..m
                }),
            }),
        }),
    });
    m.colliders = m.colliders.iter().map(|c| c.rounded_to_f32()).collect();
    for o in &mut m.objects {
        o.spacing = o.spacing.map(r32);
        o.stiffness = o.stiffness.map(r32);
        o.rest_scale = o.rest_scale.map(r32);
        o.seam = r32(o.seam);
        for v in
            [&mut o.damping, &mut o.mass, &mut o.drag, &mut o.friction, &mut o.margin, &mut o.rope_radius]
        {
            *v = r32(*v);
        }
        o.stretch_limit = o.stretch_limit.map(r32);
        o.self_distance = o.self_distance.map(r32);
        o.ring_weights = o.ring_weights.map(|w| w.map(r32));
        o.positions.iter_mut().for_each(|p| *p = r32v(*p));
        o.velocities.iter_mut().for_each(|p| *p = r32v(*p));
    }
    m
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum SpringType {
    Structural = 0,
    Shear = 1,
    Bending = 2,
    /// A mesh cloth's seam (`sim::cloth_mesh::SEAM`).
    Seam = 3,
}

/// A spring from one particle: the neighbour's index, the type, its rest length, its slot in
/// a grid particle's full list of 12 (the order of `glsl/include/springs.glsl`; 0 in a mesh
/// cloth) and whether this end counts it where each spring is counted once.
struct Spring {
    other: usize,
    kind: SpringType,
    rest: f64,
    slot: usize,
    once: bool,
}

/// The 12 springs of a grid particle by type, as grid offsets to the other end, in slot order
/// (slot 4 g + k; `SPRINGS` in glsl/include/springs.glsl is the same table).
const SPRING_GROUPS: [(SpringType, [(i64, i64); 4]); 3] = [
    (SpringType::Structural, [(1, 0), (-1, 0), (0, 1), (0, -1)]),
    (SpringType::Shear, [(1, 1), (-1, -1), (1, -1), (-1, 1)]),
    (SpringType::Bending, [(2, 0), (-2, 0), (0, 2), (0, -2)]),
];

/// The springs of particle i. In a grid: structural to the 4 direct neighbours, shear to the 4
/// diagonal ones, bending to the 4 at distance two, only those inside the grid, each counted
/// once from its even slot (the forward direction). In a mesh cloth: its list
/// (`sim::cloth_mesh`), each counted once from its lower end, its slot its place in the list.
fn springs(o: &ObjectModel, i: usize) -> Vec<Spring> {
    const KINDS: [SpringType; 4] =
        [SpringType::Structural, SpringType::Shear, SpringType::Bending, SpringType::Seam];
    if let Some(mesh) = &o.mesh {
        return (mesh.springs_of(i).iter().enumerate())
            .map(|(slot, s)| Spring {
                other: s.other as usize,
                kind: KINDS[s.kind as usize],
                rest: s.scaled_rest(o.rest_scale),
                slot,
                once: (s.other as usize) > i,
            })
            .collect();
    }
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    let (c, r) = ((i as i64) % cols, (i as i64) / cols);
    let mut out = Vec::with_capacity(12);
    for (g, (kind, offsets)) in SPRING_GROUPS.into_iter().enumerate() {
        for (k, (dc, dr)) in offsets.into_iter().enumerate() {
            let (nc, nr) = (c + dc, r + dr);
            if nc >= 0 && nr >= 0 && nc < cols && nr < rows {
                out.push(Spring {
                    other: (nc + nr * cols) as usize,
                    kind,
                    rest: offset_rest_length(o, kind, (dc, dr)),
                    slot: 4 * g + k,
                    once: k % 2 == 0,
                });
            }
        }
    }
    out
}

/// The structural and shear springs of particle i stretched past (1 + limit) L: the other end
/// and the excess.
fn overstretched<'a>(
    o: &'a ObjectModel,
    x: &'a [DVec3],
    i: usize,
    limit: f64,
) -> impl Iterator<Item = (usize, f64)> + 'a {
    springs(o, i).into_iter().filter_map(move |s| {
        let limited = matches!(s.kind, SpringType::Structural | SpringType::Shear);
        if !limited || o.stiffness_of(s.kind as usize) == 0.0 {
            return None;
        }
        let excess = (x[s.other] - x[i]).length() - s.rest * (1.0 + limit);
        (excess > 0.0).then_some((s.other, excess))
    })
}

fn offset_rest_length(o: &ObjectModel, kind: SpringType, (dc, dr): (i64, i64)) -> f64 {
    let dx = dc as f64 * o.spacing[0];
    let dy = dr as f64 * o.spacing[1];
    o.rest_scale[kind as usize] * (dx * dx + dy * dy).sqrt()
}

/// The rest length of each of the 12 springs of a particle, by slot (`SPRING_GROUPS`) [m].
pub fn rest_lengths(o: &ObjectModel) -> [[f64; 4]; 3] {
    SPRING_GROUPS.map(|(kind, offsets)| offsets.map(|offset| offset_rest_length(o, kind, offset)))
}

/// The cone's strength at x: 1 inside the full-force half-angle, falling linearly in the
/// cosine to 0 at the attenuation half-angle.
fn wind_strength(w: &WindModel, x: DVec3) -> f64 {
    let to_x = x - w.origin;
    let d = to_x.length();
    if d <= 0.0 {
        return 0.0;
    }
    let cosine = w.direction.dot(to_x / d);
    if cosine >= w.cos_full {
        1.0
    } else if cosine <= w.cos_att {
        0.0
    } else {
        (cosine - w.cos_att) / (w.cos_full - w.cos_att)
    }
}

/// The paper's wind force on a particle at x (none with the aerodynamic wind).
fn wind_at(wind: &Option<WindModel>, x: DVec3) -> DVec3 {
    match wind {
        Some(w) if w.air.is_none() => w.direction * w.force * wind_strength(w, x),
        _ => DVec3::ZERO,
    }
}

/// The aerodynamic wind's force on particle i of `o` (positions x, its velocity v), the twin
/// of `air_force` in glsl/include/air.glsl. The air's velocity relative to the particle is u
/// = speed strength(x) axis - v. A cloth particle's share of the area is a = (x_right -
/// x_left) x (x_down - x_up) / 4 (a missing neighbour replaced by the particle itself: half the
/// share on an edge, a quarter at a corner), its normal n = a / |a|; the force is |a| (normal
/// |u.n| (u.n) n + tangent |u_t| u_t). A rope node's is the diameter times half its two
/// segments, drag across the rope (normal) and along it (tangent). A mesh cloth particle's
/// area is a third of each of its triangles' area vectors.
pub(crate) fn air_force(m: &SimModel, o: &ObjectModel, i: usize, x: &[DVec3], v: DVec3, time: f64) -> DVec3 {
    let Some(w) = &m.wind else { return DVec3::ZERO };
    let Some(air) = w.air else { return DVec3::ZERO };
    let gust = air.turbulence.map_or(DVec3::ZERO, |t| t.velocity(x[i], time));
    let u = (w.direction * air.speed + gust) * wind_strength(w, x[i]) - v;
    let cols = o.dims[0] as usize;
    let (c, r) = (i % cols, i / cols);
    let at = |ok: bool, j: usize| if ok { x[j] } else { x[i] };
    if o.dims[1] > 1 || o.mesh.is_some() {
        let area = match &o.mesh {
            // (a mesh cloth's: a third of each of its triangles' area vectors)
            Some(mesh) => (mesh.ring_of(i))
                .map(|t| {
                    let [a, b, c] = t.map(|k| x[k as usize]);
                    (b - a).cross(c - a) / 6.0
                })
                .sum(),
            None => {
                let rows = o.dims[1] as usize;
                let (left, right) = (at(c > 0, i.wrapping_sub(1)), at(c + 1 < cols, i + 1));
                let (up, down) = (at(r > 0, i.wrapping_sub(cols)), at(r + 1 < rows, i + cols));
                (right - left).cross(down - up) * 0.25
            }
        };
        let a = area.length();
        if a <= 0.0 {
            return DVec3::ZERO;
        }
        let n = area / a;
        let un = u.dot(n);
        let ut = u - n * un;
        let speed = u.length();
        // Lift: across u in the plane of u and n, |u|^2 sin(2 alpha) / 2 (cos alpha = |u_t| /
        // |u|); none face-on or edge-on.
        let lift = if speed > 0.0 { (n * speed - u * (un / speed)) * (air.lift * un) } else { DVec3::ZERO };
        (n * (air.normal * un.abs() * un) + ut * (air.tangent * ut.length()) + lift) * a
    } else {
        let axis = at(c + 1 < cols, i + 1) - at(c > 0, i.wrapping_sub(1));
        let len = axis.length();
        if len <= 0.0 {
            return DVec3::ZERO;
        }
        let t = axis / len;
        let along = u.dot(t);
        let across = u - t * along;
        (across * (air.normal * across.length()) + t * (air.tangent * along.abs() * along))
            * (o.rope_radius * len)
    }
}

impl CpuSim {
    pub fn new(model: &SimModel) -> Self {
        let model = rounded(model);
        let dt = r32(model.dt());
        let objects = model
            .objects
            .iter()
            .map(|o| CpuObject {
                x: o.positions.clone(),
                // (a pinned particle: its pins' velocity at the start, as the GPU's `particles`)
                v: (0..o.positions.len()).map(|i| o.initial_velocity(i, model.frame_dt)).collect(),
                surface: vec![(DVec3::ZERO, DVec3::ZERO); o.surface_count()],
                history: vec![None; o.particle_count()],
            })
            .collect();
        Self { model, dt, objects, substeps_done: 0 }
    }

    pub fn objects(&self) -> &[CpuObject] {
        &self.objects
    }

    /// Replaces the state of object `index` (positions and velocities, one per particle) with
    /// the same motion as computed elsewhere (the GPU's, read back): the BDF2 histories stay.
    pub fn set_state(&mut self, index: usize, x: Vec<DVec3>, v: Vec<DVec3>) {
        let o = &mut self.objects[index];
        assert!(x.len() == o.x.len() && v.len() == o.v.len(), "state size must match the object");
        o.x = x;
        o.v = v;
    }

    /// Writes one particle from outside the simulation (as `GpuSim::set_particle` does: a drag,
    /// an edit): it loses its BDF2 history.
    pub fn set_particle(&mut self, object: usize, index: usize, x: DVec3, v: DVec3) {
        let o = &mut self.objects[object];
        o.x[index] = x;
        o.v[index] = v;
        o.history[index] = None;
    }

    /// One frame: `substeps` substeps, then the surface (normals, rope vertices).
    pub fn step_frame(&mut self) {
        for _ in 0..self.model.substeps {
            self.substep();
        }
        for (o, state) in self.model.objects.iter().zip(&mut self.objects) {
            state.surface = match o.kind {
                ObjectKind::Cloth => cloth_surface(o, &state.x),
                ObjectKind::Rope => rope_surface(o, &state.x),
            };
        }
    }

    pub fn substep(&mut self) {
        let m = &self.model;
        // Where each collider is at the end of this substep and how fast it moves: as the GPU
        // has it (sim::collider::ColliderModel::frame_motion).
        let substeps = m.substeps as u64;
        let frame_start = (self.substeps_done / substeps) as f64 * m.frame_dt;
        let since = ((self.substeps_done % substeps) + 1) as f64 * self.dt;
        // (the substep's start, as the GPU has it: the frame's start and whole substeps since)
        let time = frame_start + (self.substeps_done % substeps) as f64 * self.dt;
        let step = (self.substeps_done % substeps) as u32;
        let motions: Vec<Pose> = m.colliders.iter().map(|c| c.pose(frame_start, m.frame_dt, since)).collect();
        self.substeps_done += 1;
        // Every object's physics first: the constraints of one read the others' new positions
        // (inter-object contact), as the GPU's constraint stage follows all physics.
        let advanced: Vec<(Vec<DVec3>, Vec<DVec3>)> = if m.contact_rounds() > 1 {
            solve_with_contact_rounds(m, &mut self.objects, (self.dt, time, frame_start, step), &motions)
        } else {
            m.objects
                .iter()
                .zip(&mut self.objects)
                .map(|(o, state)| {
                    let pins = o.pin_steps(frame_start, m.frame_dt, step, self.dt);
                    let s = integrators::Substep {
                        model: m,
                        object: o,
                        dt: self.dt,
                        x: &state.x,
                        v: &state.v,
                        time,
                        pins: &pins,
                    };
                    integrators::advance(&s, &mut state.history)
                })
                .collect()
        };
        let positions: Vec<&[DVec3]> = advanced.iter().map(|(x, _)| x.as_slice()).collect();
        let contact = if m.inter_object_contact() {
            let starts: Vec<&[DVec3]> = self.objects.iter().map(|o| o.x.as_slice()).collect();
            inter_object::inter_object(m, &positions, &starts)
        } else {
            positions.iter().map(|x| vec![DVec3::ZERO; x.len()]).collect()
        };
        for (a, (o, state)) in m.objects.iter().zip(&mut self.objects).enumerate() {
            let (px, pv) = &advanced[a];
            let (cx, cv) = constraints(m, o, self.dt, &motions, &contact[a], &state.x, (px, pv));
            state.x = cx;
            state.v = cv;
        }
    }
}

/// Every object's VBD solve of a substep together, with contact between objects from the
/// iterates after every iteration but the last, which the next iteration takes into each
/// particle's iterate and prediction, and each particle's colliders after its solve in every
/// iteration (`SimModel::contact_rounds`, `VbdSolve::sweep`; the last round between objects
/// is the constraint stage's, as for the other methods). `motions`: each collider's offset
/// and velocity at the substep's end; `time`: when the substep starts, `frame_start`: its
/// frame, `step`: which of the frame's substeps it is.
fn solve_with_contact_rounds(
    m: &SimModel,
    objects: &mut [CpuObject],
    (dt, time, frame_start, step): (f64, f64, f64, u32),
    motions: &[Pose],
) -> Vec<(Vec<DVec3>, Vec<DVec3>)> {
    let mut histories: Vec<Vec<History>> = objects.iter().map(|o| o.history.clone()).collect();
    let pins: Vec<Vec<super::pins::PinStep>> =
        m.objects.iter().map(|o| o.pin_steps(frame_start, m.frame_dt, step, dt)).collect();
    let steps: Vec<integrators::Substep<'_>> = (m.objects.iter().zip(objects.iter()).zip(&pins))
        .map(|((o, state), pins)| integrators::Substep {
            model: m,
            object: o,
            dt,
            x: &state.x,
            v: &state.v,
            time,
            pins,
        })
        .collect();
    let mut solves: Vec<integrators::VbdSolve> =
        steps.iter().zip(&histories).map(|(s, history)| integrators::VbdSolve::new(s, history)).collect();
    let starts: Vec<&[DVec3]> = objects.iter().map(|o| o.x.as_slice()).collect();
    let mut moved: Option<Vec<Vec<DVec3>>> = None;
    for k in 0..m.iterations {
        for (a, solve) in solves.iter_mut().enumerate() {
            let last = k + 1 == m.iterations;
            solve.sweep(&steps[a], moved.as_ref().map(|v| v[a].as_slice()), Some(motions), last);
        }
        if k + 1 < m.iterations {
            let positions: Vec<&[DVec3]> = solves.iter().map(|s| s.positions()).collect();
            moved = Some(inter_object::inter_object(m, &positions, &starts));
        }
    }
    let advanced = (solves.into_iter().zip(&steps).zip(&mut histories))
        .map(|((solve, s), history)| solve.finish(s, history))
        .collect();
    for (state, history) in objects.iter_mut().zip(histories) {
        state.history = history;
    }
    advanced
}

/// The constraint stage of object `o` on the physics result `(x, v)`; `motions` holds each
/// collider's offset and velocity, `contact` each particle's summed inter-object corrections,
/// `start` where each particle began the substep (the colliders' friction).
fn constraints(
    m: &SimModel,
    o: &ObjectModel,
    dt: f64,
    motions: &[Pose],
    contact: &[DVec3],
    start: &[DVec3],
    (x, v): (&[DVec3], &[DVec3]),
) -> (Vec<DVec3>, Vec<DVec3>) {
    let cols = o.dims[0] as usize;
    let mut nv = vec![DVec3::ZERO; x.len()];
    let share = |j: usize| if o.pinned[j] { 1.0 } else { 0.5 };
    let edges = crate::sim::collider::edges_needed(o, &m.colliders);
    // Every pass over the cloth's own contacts but the last moves the physics output (the
    // velocity following but for the position-only part); the last joins the correction below.
    let own = self_contact::self_contact(o, x, start, m.contact_iterations);
    let shifted: Vec<DVec3> = v.iter().zip(&own.shift).map(|(v, s)| *v + *s / dt).collect();
    let (x, v) = (own.moved.as_slice(), shifted.as_slice());
    let mut nx = x.to_vec();
    for i in 0..x.len() {
        if o.pinned[i] {
            nv[i] = v[i]; // (its pins' velocity)
            continue;
        }
        let (c, r) = ((i % cols) as i64, (i / cols) as i64);
        let mut correction = DVec3::ZERO;
        let mut stretched = 0u32;
        if let Some(limit) = o.stretch_limit {
            let own: Vec<(usize, f64)> = overstretched(o, x, i, limit).collect();
            stretched = own.len() as u32;
            for (j, excess) in own {
                // (a mesh cloth's ends by their inverse masses w: 2 w_i / (w_i + w_j) of the
                // move, so that their momenta stay equal and opposite; 1 on a grid)
                let (wi, wj) = (o.mass / o.mass_of(i), o.mass / o.mass_of(j));
                let split = if o.pinned[j] {
                    1.0 / stretched as f64
                } else {
                    0.5 * (1.0 / stretched as f64 + 1.0 / overstretched(o, x, j, limit).count() as f64)
                        * (2.0 * wi / (wi + wj))
                };
                correction += (x[j] - x[i]).normalize() * excess * share(j) * split;
            }
        }
        if let Some(reach) = o.self_distance.filter(|_| !o.has_triangles()) {
            let (mut pushes, mut active) = (DVec3::ZERO, 0u32);
            for j in 0..x.len() {
                let rest_c = ((j % cols) as i64 - c) as f64 * o.spacing[0];
                let rest_r = ((j / cols) as i64 - r) as f64 * o.spacing[1];
                if rest_c * rest_c + rest_r * rest_r < reach * reach {
                    continue; // itself and neighbours that are this close at rest
                }
                let delta = x[j] - x[i];
                let d = delta.length();
                if d > 0.0 && d < reach {
                    pushes += delta / d * (d - reach) * share(j);
                    active += 1;
                }
            }
            if active > 0 {
                correction = (correction * stretched as f64 + pushes) / (stretched + active) as f64;
            }
        }
        correction += own.last[i] + contact[i];
        let mut p = x[i] + correction;
        let mut vel = v[i] + (correction - own.last_rest[i]) / dt;
        if edges {
            collide_edges(m, o, (i, x), motions, (start[i], dt), (&mut p, &mut vel));
        }
        for (c, pose) in m.colliders.iter().zip(motions) {
            c.respond((o.margin, o.friction), pose, (start[i], dt), &mut p, &mut vel);
        }
        nx[i] = p;
        nv[i] = vel;
    }
    // With a cloth's edge pairs, each move over the substep truncated so that no particle
    // passes the planes between the sides of the pairs near at its start, the colliders' part
    // too, and where that moved it its colliders again (note_truncation in
    // glsl/include/self_contact.glsl).
    if o.has_cloth_edge_pairs() && o.self_distance.is_some() {
        let t = self_contact::truncation(o, start, &nx, m.max_speed * dt);
        for (i, t) in t.into_iter().enumerate() {
            if self_contact::truncate(&mut nx[i], &mut nv[i], start[i], t) {
                for (c, pose) in m.colliders.iter().zip(motions) {
                    c.respond((o.margin, o.friction), pose, (start[i], dt), &mut nx[i], &mut nv[i]);
                }
            }
        }
    }
    (nx, nv)
}

/// Colliders (but the ground, and those farther from the particle than the margin and half a
/// shear diagonal at twice its rest length) against the edges of particle `i` of `o`
/// (positions `x`, the physics output): each structural edge's and shear diagonal's midpoint
/// within the margin of a collider moves the edge's ends out along the normal there by its depth (twice that when the
/// other end is pinned); the particle, at `p` with velocity `vel`, takes the mean of its edges'
/// moves against each collider through the particle response (`respond_along`). The CPU twin
/// of `collide_edges` in glsl/include/constraints_body.glsl.
fn collide_edges(
    m: &SimModel,
    o: &ObjectModel,
    (i, x): (usize, &[DVec3]),
    motions: &[Pose],
    (start, dt): (DVec3, f64),
    (p, vel): (&mut DVec3, &mut DVec3),
) {
    // Farther than this, no midpoint of an edge up to twice its rest length is within the margin.
    let reach = o.margin + 2f64.sqrt() * o.spacing[0].max(o.spacing[1]);
    for (collider, pose) in m.colliders.iter().zip(motions) {
        if matches!(collider.shape, crate::sim::collider::Shape::Ground { .. })
            || collider.distance_at(pose, x[i]).0 >= reach
        {
            continue;
        }
        let (mut push, mut count) = (DVec3::ZERO, 0u32);
        for s in springs(o, i).iter().filter(|s| matches!(s.kind, SpringType::Structural | SpringType::Shear))
        {
            let mid = (x[i] + x[s.other]) * 0.5;
            let (d, n) = collider.distance_at(pose, mid);
            if d < o.margin {
                push += n * (o.margin - d) * if o.pinned[s.other] { 2.0 } else { 1.0 };
                count += 1;
            }
        }
        let depth = push.length();
        if depth > 0.0 {
            let mu = collider.friction.unwrap_or(o.friction);
            let along = (push / depth, depth / count as f64);
            let surface = collider.surface_velocity(pose, x[i]);
            crate::sim::collider::respond_along(along, (mu, surface), (start, dt), p, vel);
        }
    }
}

/// Angle-weighted normals from the (up to) four structural edges around each particle.
fn cloth_surface(o: &ObjectModel, x: &[DVec3]) -> Vec<(DVec3, DVec3)> {
    if let Some(mesh) = &o.mesh {
        // A mesh cloth's: its triangles' normals about each particle, weighted by their areas.
        return (0..x.len())
            .map(|i| {
                let sum: DVec3 = mesh
                    .ring_of(i)
                    .map(|[a, b, c]| {
                        let [a, b, c] = [a, b, c].map(|k| x[k as usize]);
                        (b - a).cross(c - a)
                    })
                    .sum();
                (x[i], if sum.length() > 0.0 { sum.normalize() } else { DVec3::Z })
            })
            .collect();
    }
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    let around = [(1, 0), (0, -1), (-1, 0), (0, 1)];
    (0..x.len())
        .map(|i| {
            let (c, r) = (i as i64 % cols, i as i64 / cols);
            let edges: Vec<Option<DVec3>> = around
                .iter()
                .map(|(dc, dr)| {
                    let (nc, nr) = (c + dc, r + dr);
                    if nc < 0 || nr < 0 || nc >= cols || nr >= rows {
                        return None;
                    }
                    let e = x[(nc + nr * cols) as usize] - x[i];
                    (e.length() > 0.0).then(|| e.normalize())
                })
                .collect();
            let mut sum = DVec3::ZERO;
            for k in 0..4 {
                if let (Some(a), Some(b)) = (edges[k], edges[(k + 1) % 4]) {
                    let cr = a.cross(b);
                    if cr.length() > 0.0 {
                        sum += cr.normalize() * a.dot(b).clamp(-1.0, 1.0).acos();
                    }
                }
            }
            let n = if sum.length() > 0.0 { sum.normalize() } else { DVec3::Z };
            (x[i], n)
        })
        .collect()
}

/// Rope tube vertices on a rotation-minimising frame (parallel transport), as
/// `glsl/rope_vertices.comp`: node 0's frame is the paper's (side = forward x world up, up =
/// forward x side), each next node's is the one before turned by the smallest rotation taking
/// the previous forward to its own, so the tube neither pinches nor twists where the rope
/// turns vertical.
fn rope_surface(o: &ObjectModel, x: &[DVec3]) -> Vec<(DVec3, DVec3)> {
    let n = x.len();
    let unit_or = |v: DVec3, fallback: DVec3| if v.length() > 1e-12 { v.normalize() } else { fallback };
    let forward_at = |i: usize| {
        let to_next = if i + 1 < n { unit_or(x[i + 1] - x[i], DVec3::ZERO) } else { DVec3::ZERO };
        let from_prev = if i > 0 { unit_or(x[i] - x[i - 1], DVec3::ZERO) } else { DVec3::ZERO };
        unit_or(to_next + from_prev, unit_or(to_next, DVec3::X))
    };
    // The smallest rotation taking unit a to unit b (a half-turn when they are opposite).
    let turn = |a: DVec3, b: DVec3| {
        let c = a.dot(b);
        if c < -0.99999 {
            let axis = if a.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
            DQuat::from_vec4(a.cross(axis).normalize().extend(0.0))
        } else {
            let v = a.cross(b);
            DQuat::from_xyzw(v.x, v.y, v.z, 1.0 + c).normalize()
        }
    };
    let forward0 = forward_at(0);
    let side0 = forward0.cross(DVec3::Y);
    let side0 = if side0.length() > 1e-6 {
        side0.normalize()
    } else {
        DVec3::new(forward0.y, -forward0.x, 0.0).normalize()
    };
    let mut frame = DQuat::IDENTITY;
    let mut out = Vec::with_capacity(n * ROPE_RING);
    for (i, &at) in x.iter().enumerate() {
        let forward = forward_at(i);
        if i > 0 {
            frame = (turn(forward_at(i - 1), forward) * frame).normalize();
        }
        let side = frame * side0;
        let side = unit_or(side - forward * side.dot(forward), side0);
        let up = forward.cross(side).normalize();
        let to_prev = if i > 0 { x[i - 1] - at } else { DVec3::ZERO };
        let to_next = if i + 1 < n { x[i + 1] - at } else { DVec3::ZERO };
        for w in &o.ring_weights {
            let offset = side * w[0] + up * w[1];
            let o_r = offset * o.rope_radius;
            let reach = o.rope_radius * ring_reach(o_r, to_prev).min(ring_reach(o_r, to_next));
            out.push((at + offset * reach, unit_or(offset, up)));
        }
    }
    out
}

/// How far a rope's ring vertex keeps the plane halfway to a neighbour: `RING_KEEP` of the
/// way at most (as `glsl/rope_vertices.comp`).
const RING_KEEP: f64 = 0.9;

/// The share of its offset `o` a ring vertex keeps so that it stays RING_KEEP of the way short
/// of the plane halfway to the neighbour at `to` (zero: none), as `ring_reach` in
/// glsl/rope_vertices.comp: on the inside of a bend sharper than the tube is thick the rings
/// would cross and turn faces inside out.
fn ring_reach(o: DVec3, to: DVec3) -> f64 {
    let toward = o.dot(to);
    let half_way = 0.5 * to.length_squared();
    if toward > RING_KEEP * half_way {
        RING_KEEP * half_way / toward
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::model::default_ring_weights;

    /// The sign of each tube face's normal against its vertices' normals (outward), the faces
    /// as the renderer and the recordings build them (two triangles for each ring side between
    /// neighbouring nodes: a, b, a + R and b, b + R, a + R).
    fn face_signs(surface: &[(DVec3, DVec3)], nodes: usize) -> Vec<f64> {
        let ring = ROPE_RING;
        let mut signs = Vec::new();
        for n in 0..nodes - 1 {
            for k in 0..ring {
                let (a, b) = (n * ring + k, n * ring + (k + 1) % ring);
                for [p, q, r] in [[a, b, a + ring], [b, b + ring, a + ring]] {
                    let normal = (surface[q].0 - surface[p].0).cross(surface[r].0 - surface[p].0);
                    signs.push(normal.dot(surface[p].1 + surface[q].1 + surface[r].1).signum());
                }
            }
        }
        signs
    }

    /// A rope's tube keeps every face facing out at sharp bends: with 2.5 cm segments and a 2 cm
    /// radius, turns of up to 130 degrees at every node. Sharper turns bend the centre line
    /// tighter than the tube is thick, where some faces still turn: not covered.
    #[test]
    fn the_rope_tube_turns_no_face_inside_out_at_sharp_bends() {
        let nodes = 12;
        let rope = |bend: f64| {
            let mut x = vec![DVec3::ZERO];
            let mut heading = 0.0f64;
            for i in 1..nodes {
                x.push(x[i - 1] + 0.025 * DVec3::new(heading.cos(), heading.sin(), 0.0));
                heading += bend.to_radians() * if i % 4 < 2 { 1.0 } else { -1.0 };
            }
            x
        };
        let mut o = ObjectModel {
            kind: ObjectKind::Rope,
            name: "rope".into(),
            dims: [nodes as u32, 1],
            spacing: [0.025, 0.025],
            stiffness: [0.0; 3],
            rest_scale: [1.0; 3],
            seam: 0.0,
            damping: 0.0,
            mass: 0.01,
            drag: 0.0,
            friction: 0.0,
            margin: 0.0,
            stretch_limit: None,
            self_distance: None,
            triangle_contact: false,
            edge_contact: false,
            rope_radius: 0.02,
            ring_weights: default_ring_weights(),
            positions: Vec::new(),
            velocities: Vec::new(),
            pinned: Vec::new(),
            pin_motion: Default::default(),
            pin_groups: Vec::new(),
            pin_group: Vec::new(),
            mesh: None,
        };
        let straight = face_signs(&rope_surface(&o, &rope(0.0)), nodes);
        assert!(straight.iter().all(|&s| s == straight[0]), "a straight tube's faces agree");
        for bend in [30.0, 60.0, 92.0, 110.0, 123.0, 130.0] {
            let x = rope(bend);
            o.positions = x.clone();
            let signs = face_signs(&rope_surface(&o, &x), nodes);
            let inside_out = signs.iter().filter(|&&s| s != straight[0]).count();
            assert_eq!(
                inside_out,
                0,
                "{bend} degree bends: {inside_out} of {} faces inside out",
                signs.len()
            );
        }
    }
}
