//! The collider types, declared once: each is a row of `KINDS` (its name, the feature bit that
//! compiles it in, its id in `glsl/include/colliders.glsl`), a variant of `Shape` with its
//! signed distance (the CPU twin of the GLSL `collider_distance`), and its GPU record. The
//! contact response is shared by every type: a particle closer than its object's margin to a
//! collider's surface is moved out along the surface normal to the margin, its approaching
//! normal velocity is removed, and Coulomb friction (`ColliderModel::respond`) bounds its
//! tangential impulse by mu times the normal one, sticking within the cone.

use super::collider_mesh::ColliderMesh;
use super::gpu_types::{
    FEATURE_BOX, FEATURE_CAPSULE, FEATURE_GROUND, FEATURE_MESH, FEATURE_SPHERES, FEATURE_TURNING,
};
use super::model::ObjectModel;
use super::turn::Turn;
use glam::{DQuat, DVec3};

/// A collider type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ColliderKind {
    Sphere,
    Ground,
    Box,
    Capsule,
    Mesh,
}

/// What the rest of the code looks up about a collider type.
pub struct KindRow {
    pub kind: ColliderKind,
    /// The preset's table name (`[[sphere]]`, `[ground]`, ...).
    pub label: &'static str,
    /// The `FEATURES` specialization bit that compiles its test in (`F_*` in features.glsl).
    pub feature: u32,
    /// `COLLIDER_*` in colliders.glsl (checked by tests/suite/layout.rs).
    pub glsl_id: u32,
}

pub const KINDS: [KindRow; 5] = [
    KindRow { kind: ColliderKind::Sphere, label: "sphere", feature: FEATURE_SPHERES, glsl_id: 0 },
    KindRow { kind: ColliderKind::Ground, label: "ground", feature: FEATURE_GROUND, glsl_id: 1 },
    KindRow { kind: ColliderKind::Box, label: "box", feature: FEATURE_BOX, glsl_id: 2 },
    KindRow { kind: ColliderKind::Capsule, label: "capsule", feature: FEATURE_CAPSULE, glsl_id: 3 },
    KindRow { kind: ColliderKind::Mesh, label: "mesh", feature: FEATURE_MESH, glsl_id: 4 },
];

impl ColliderKind {
    pub fn row(self) -> &'static KindRow {
        KINDS.iter().find(|r| r.kind == self).expect("every kind has a row")
    }

    pub fn label(self) -> &'static str {
        self.row().label
    }
}

/// A collider's shape in world space.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Sphere {
        center: DVec3,
        radius: f64,
    },
    /// The half-space below y = height.
    Ground {
        height: f64,
    },
    /// An oriented box: `rotation` turns its local axes into the world's.
    Box {
        center: DVec3,
        half_extents: DVec3,
        rotation: DQuat,
    },
    /// The points within `radius` of the segment from `a` to `b`.
    Capsule {
        a: DVec3,
        b: DVec3,
        radius: f64,
    },
    /// A triangle mesh (`ColliderMesh`, in its own frame) placed at `center` and turned by
    /// `rotation`, its surface offset outwards by `thickness`.
    Mesh {
        center: DVec3,
        rotation: DQuat,
        thickness: f64,
        mesh: std::sync::Arc<ColliderMesh>,
    },
}

/// A collider of the model: its shape (where it is at t = 0), where it has its own its
/// friction (else each object's applies), how it moves, and how it turns (steady or keyed)
/// about its reference point (`Shape::reference_point`, which the motion carries; the ground
/// does not turn).
#[derive(Debug, Clone, PartialEq)]
pub struct ColliderModel {
    pub shape: Shape,
    pub friction: Option<f64>,
    pub motion: Motion,
    pub turn: Turn,
}

/// A collider's GPU record (`ColliderModel::gpu`): five vec4s.
pub type ColliderRecord = [[f32; 4]; 5];

/// Where a collider is at one moment and how its surface moves there: offset by `shift` from
/// its placement and turned by `turn` about its reference point (carried by the shift), moving
/// at `velocity` and turning at `spin` [rad/s].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub shift: DVec3,
    pub velocity: DVec3,
    pub turn: DQuat,
    pub spin: DVec3,
}

impl Pose {
    /// Offset by `shift`, moving at `velocity`, not turned.
    pub fn moving(shift: DVec3, velocity: DVec3) -> Self {
        Self { shift, velocity, turn: DQuat::IDENTITY, spin: DVec3::ZERO }
    }
}

/// How a collider moves: a kinematic body, positioned by time; contacts use its velocity.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Motion {
    #[default]
    Fixed,
    /// A constant velocity [m/s].
    Velocity(DVec3),
    /// Offsets from the shape's placement at times t (increasing): linear in between, held
    /// before the first and after the last.
    Keyframes(Vec<(f64, DVec3)>),
    /// The same keys, smooth in between (`smooth_offset`).
    Smooth(Vec<(f64, DVec3)>),
}

/// The offset at time `t` along `keys` (times increasing) by a monotone cubic (Fritsch and
/// Carlson 1980), component by component: through every key, its velocity continuous, at rest
/// at the first and last key and wherever a component turns back at a key, and never beyond
/// the keys on either side within a segment (no overshoot, as Blender's auto-clamped handles).
/// Held before the first key and after the last.
pub fn smooth_offset(keys: &[(f64, DVec3)], t: f64) -> DVec3 {
    let (k, u) = match segment(keys, t) {
        Ok(at) => at,
        Err(held) => return held,
    };
    let ((ta, a), (tb, b)) = (keys[k], keys[k + 1]);
    let span = tb - ta;
    let (ma, mb) = (key_slope(keys, k), key_slope(keys, k + 1));
    let (u2, u3) = (u * u, u * u * u);
    a * (2.0 * u3 - 3.0 * u2 + 1.0)
        + ma * (span * (u3 - 2.0 * u2 + u))
        + b * (-2.0 * u3 + 3.0 * u2)
        + mb * (span * (u3 - u2))
}

/// Where time `t` falls along `keys` (times increasing): in segment k (keys k and k + 1) at
/// the fraction u of it, or held (`Err`) at the first key before it, at the last after it, at
/// zero without keys. Linear and smooth keys share it.
fn segment(keys: &[(f64, DVec3)], t: f64) -> Result<(usize, f64), DVec3> {
    let Some(&(t0, first)) = keys.first() else { return Err(DVec3::ZERO) };
    if t <= t0 {
        return Err(first);
    }
    match keys.windows(2).position(|w| t <= w[1].0) {
        Some(k) => Ok((k, (t - keys[k].0) / (keys[k + 1].0 - keys[k].0))),
        None => Err(keys[keys.len() - 1].1),
    }
}

/// The velocity at key `k` of `smooth_offset`: per component the mean of the two segments'
/// slopes, zero at the ends and where they differ in sign (a turn or a hold), and at most three
/// times the smaller of them (Fritsch and Carlson's bound, which keeps each segment monotone).
fn key_slope(keys: &[(f64, DVec3)], k: usize) -> DVec3 {
    if k == 0 || k + 1 >= keys.len() {
        return DVec3::ZERO;
    }
    let slope = |i: usize| (keys[i + 1].1 - keys[i].1) / (keys[i + 1].0 - keys[i].0);
    let (before, after) = (slope(k - 1), slope(k));
    let one = |l: f64, r: f64| {
        if l * r <= 0.0 {
            return 0.0;
        }
        let mean = 0.5 * (l + r);
        mean.signum() * mean.abs().min(3.0 * l.abs().min(r.abs()))
    };
    DVec3::new(one(before.x, after.x), one(before.y, after.y), one(before.z, after.z))
}

/// The fastest `smooth_offset` moves along `keys` [m/s]: an upper bound, each component's
/// fastest on each segment (its velocity is a quadratic in time: at a key or at the vertex).
pub fn smooth_top_speed(keys: &[(f64, DVec3)]) -> f64 {
    let mut top = 0.0f64;
    for k in 0..keys.len().saturating_sub(1) {
        let span = keys[k + 1].0 - keys[k].0;
        let (a, b) = (keys[k].1, keys[k + 1].1);
        let (ma, mb) = (key_slope(keys, k), key_slope(keys, k + 1));
        let mut peak = DVec3::ZERO;
        for c in 0..3 {
            // d/du of the Hermite form, over the span: q(u) = c0 + c1 u + c2 u^2.
            let c0 = ma[c] * span;
            let c1 = 6.0 * (b[c] - a[c]) - 4.0 * ma[c] * span - 2.0 * mb[c] * span;
            let c2 = -6.0 * (b[c] - a[c]) + 3.0 * (ma[c] + mb[c]) * span;
            let q = |u: f64| (c0 + c1 * u + c2 * u * u).abs();
            let mut m = q(0.0).max(q(1.0));
            if c2 != 0.0 {
                let v = -c1 / (2.0 * c2);
                if (0.0..=1.0).contains(&v) {
                    m = m.max(q(v));
                }
            }
            peak[c] = m / span;
        }
        top = top.max(peak.length());
    }
    top
}

impl Motion {
    /// The displacement from the shape's placement at time `t`.
    pub fn offset(&self, t: f64) -> DVec3 {
        match self {
            Motion::Fixed => DVec3::ZERO,
            Motion::Velocity(v) => *v * t,
            Motion::Keyframes(keys) => match segment(keys, t) {
                Ok((k, u)) => keys[k].1.lerp(keys[k + 1].1, u),
                Err(held) => held,
            },
            Motion::Smooth(keys) => smooth_offset(keys, t),
        }
    }

    pub fn is_moving(&self) -> bool {
        *self != Motion::Fixed
    }
}

impl ColliderModel {
    pub fn sphere(center: DVec3, radius: f64) -> Self {
        Self {
            shape: Shape::Sphere { center, radius },
            friction: None,
            motion: Motion::Fixed,
            turn: Turn::default(),
        }
    }

    /// Whether it moves or turns.
    pub fn is_moving(&self) -> bool {
        self.motion.is_moving() || self.turns()
    }

    /// Whether it turns (the ground never does, whatever its `turn`).
    pub fn turns(&self) -> bool {
        self.turn.turns() && !matches!(self.shape, Shape::Ground { .. })
    }

    /// Its turn from t = 0 to `t`.
    pub fn turn_at(&self, t: f64) -> DQuat {
        if self.turns() {
            self.turn.orientation(t)
        } else {
            DQuat::IDENTITY
        }
    }

    /// Its angular velocity over the frame that starts at `t0` (`Turn::frame_spin`; zero where
    /// it does not turn).
    pub fn frame_spin(&self, t0: f64, frame_dt: f64) -> DVec3 {
        if self.turns() {
            self.turn.frame_spin(t0, frame_dt)
        } else {
            DVec3::ZERO
        }
    }

    /// Its shape where it is at time `t`: turned about its reference point, then moved.
    pub fn shape_at(&self, t: f64) -> Shape {
        self.shape.turned(self.turn_at(t)).translated(self.motion.offset(t))
    }

    /// Where it is `since` after the start of the frame that starts at `t0` and lasts
    /// `frame_dt` (`frame_motion`: moved at the frame's chord velocity; turned at the frame's
    /// steady rate from where it is at the frame's start, `frame_spin`). The CPU reference's;
    /// the GPU takes the same from the frame's record (`gpu`, `collider_pose` in
    /// colliders.glsl).
    pub fn pose(&self, t0: f64, frame_dt: f64, since: f64) -> Pose {
        let (start, velocity) = self.frame_motion(t0, frame_dt);
        let spin = self.frame_spin(t0, frame_dt);
        let turn = DQuat::from_scaled_axis(spin * since) * self.turn_at(t0);
        Pose { shift: start + velocity * since, velocity, turn, spin }
    }

    /// Signed distance from `x` to its surface at `pose` and the outward normal there
    /// (`collider_distance_at` in colliders.glsl).
    pub fn distance_at(&self, pose: &Pose, x: DVec3) -> (f64, DVec3) {
        if pose.spin == DVec3::ZERO && pose.turn == DQuat::IDENTITY {
            return self.shape.distance(x - pose.shift);
        }
        let centre = self.shape.reference_point();
        let (d, n) = self.shape.distance(centre + pose.turn.inverse() * (x - pose.shift - centre));
        (d, pose.turn * n)
    }

    /// The velocity of its surface at `x` at `pose`: its own plus its spin's about its
    /// reference point.
    pub fn surface_velocity(&self, pose: &Pose, x: DVec3) -> DVec3 {
        pose.velocity + pose.spin.cross(x - pose.shift - self.shape.reference_point())
    }

    /// How the collider moves during the frame that starts at `t0` and lasts `frame_dt`: its
    /// offset at the start and its (chord) velocity over the frame. Within the frame it moves
    /// at that velocity: at the end of substep s (0-based) it is offset by
    /// start + velocity (s + 1) dt. The GPU records and the CPU reference both use this.
    pub fn frame_motion(&self, t0: f64, frame_dt: f64) -> (DVec3, DVec3) {
        let start = self.motion.offset(t0);
        (start, (self.motion.offset(t0 + frame_dt) - start) / frame_dt)
    }

    /// The GPU record (`Collider` in colliders.glsl) for the frame that starts at `t0`: `a`
    /// xyz centre, point a or unused, w the type id; `b` xyz half extents or point b, w radius;
    /// `rotation` a unit quaternion (xyzw); `extra` x the friction (negative: the object's),
    /// yzw the velocity over the frame; `spin` xyz the angular velocity over the frame.
    /// Positions and the rotation are where the collider is at the frame's start.
    pub fn gpu(&self, t0: f64, frame_dt: f64) -> ColliderRecord {
        self.gpu_dragged(t0, frame_dt, DVec3::ZERO)
    }

    /// `gpu` for a collider the user moved by `drag` since the last frame (the app's editor):
    /// it starts the frame where it was and covers the distance during the frame, so what it
    /// touches is pushed and dragged (by friction) as by a moving collider.
    pub fn gpu_dragged(&self, t0: f64, frame_dt: f64, drag: DVec3) -> ColliderRecord {
        let (start, velocity) = self.frame_motion(t0, frame_dt);
        let (start, velocity) = (start - drag, velocity + drag / frame_dt);
        let v = |p: DVec3, w: f32| [p.x as f32, p.y as f32, p.z as f32, w];
        let id = f32::from_bits(self.shape.kind().row().glsl_id);
        let friction = self.friction.map(|f| f as f32).unwrap_or(-1.0);
        let (a, b, q) = match self.shape.turned(self.turn_at(t0)).translated(start) {
            Shape::Sphere { center, radius } => {
                (v(center, id), v(DVec3::ZERO, radius as f32), DQuat::IDENTITY)
            }
            Shape::Ground { height } => (v(DVec3::new(0.0, height, 0.0), id), [0.0; 4], DQuat::IDENTITY),
            Shape::Box { center, half_extents, rotation } => (v(center, id), v(half_extents, 0.0), rotation),
            Shape::Capsule { a, b, radius } => (v(a, id), v(b, radius as f32), DQuat::IDENTITY),
            Shape::Mesh { center, rotation, thickness, ref mesh } => {
                // (offsets as float values, exact below 2^24 vec4s: `collider_mesh::MAX_WORDS`,
                // which the GPU's check_meshes holds a scene to)
                let [_, items, triangles] = mesh.layout();
                (v(center, id), [0.0, items as f32, triangles as f32, thickness as f32], rotation)
            }
        };
        let (w, s) = (velocity.as_vec3(), self.frame_spin(t0, frame_dt).as_vec3());
        [
            a,
            b,
            [q.x as f32, q.y as f32, q.z as f32, q.w as f32],
            [friction, w.x, w.y, w.z],
            [s.x, s.y, s.z, 0.0],
        ]
    }

    /// Moves a particle at `x` with velocity `v` out of the collider at `pose` to `margin`
    /// from its surface (`respond_along` with the collider's friction, its own else
    /// `object_friction`, against its surface's velocity there). The CPU twin of `collide` in
    /// colliders.glsl.
    pub fn respond(
        &self,
        (margin, object_friction): (f64, f64),
        pose: &Pose,
        (start, dt): (DVec3, f64),
        x: &mut DVec3,
        v: &mut DVec3,
    ) {
        self.respond_within((margin, object_friction), pose, (start, dt), 0.0, x, v);
    }

    /// `respond` with a particle within `touch` past the margin counted as touching (its
    /// velocity answers the collider; its position is not moved): `collide_within` in
    /// colliders.glsl.
    pub fn respond_within(
        &self,
        (margin, object_friction): (f64, f64),
        pose: &Pose,
        (start, dt): (DVec3, f64),
        touch: f64,
        x: &mut DVec3,
        v: &mut DVec3,
    ) {
        let (d, n) = self.distance_at(pose, *x);
        if d < margin + touch {
            let mu = self.friction.unwrap_or(object_friction);
            let surface = self.surface_velocity(pose, *x);
            respond_along((n, (margin - d).max(0.0)), (mu, surface), (start, dt), x, v);
        }
    }
}

/// A few f32 steps of a position near x [m]: 5e-7 (1 + its largest coordinate), as the GPU's
/// `position_slack` in colliders.glsl.
pub fn position_slack(x: DVec3) -> f64 {
    5e-7 * (1.0 + x.abs().max_element())
}

/// The response to a collider moving at `velocity` that a particle is `depth` inside of its
/// margin along the normal `n`: moved out along n by the depth, its approaching normal velocity
/// (relative to the collider) removed, then Coulomb friction with coefficient mu: the normal
/// impulse per unit mass of the substep `dt` is jn = max(approaching speed, depth / dt), and
/// the tangential impulse at most mu jn. Static when the particle's tangential speed relative
/// to the collider is within mu jn: it goes back tangentially to where it began the substep
/// (`start`) and moves with the collider; kinetic otherwise: its tangential speed loses mu jn
/// and its slip mu jn dt. The CPU twin of `contact_response` in colliders.glsl.
pub fn respond_along(
    (n, depth): (DVec3, f64),
    (mu, velocity): (f64, DVec3),
    (start, dt): (DVec3, f64),
    x: &mut DVec3,
    v: &mut DVec3,
) {
    *x += n * depth;
    let relative = *v - velocity;
    let vn = relative.dot(n);
    // The depth past a few f32 steps of the position only; never negative (a particle leaving
    // within that slack takes no friction).
    let jn = (-vn).max((depth - position_slack(*x)) / dt).max(0.0);
    let mut vt = relative - n * vn;
    let moved = *x - start - velocity * dt;
    let slip = moved - n * moved.dot(n);
    let vt_len = vt.length();
    if vt_len <= mu * jn {
        *x -= slip;
        vt = DVec3::ZERO;
    } else {
        *x -= slip * (mu * jn * dt / slip.length().max(1e-30)).min(1.0);
        vt *= 1.0 - mu * jn / vt_len;
    }
    *v = velocity + vt + n * vn.max(0.0);
}

impl ColliderModel {
    /// The collider as the GPU receives it: every number rounded to f32.
    pub fn rounded_to_f32(&self) -> Self {
        let r = |x: f64| x as f32 as f64;
        let rv = |v: DVec3| v.as_vec3().as_dvec3();
        let shape = match self.shape {
            Shape::Sphere { center, radius } => Shape::Sphere { center: rv(center), radius: r(radius) },
            Shape::Ground { height } => Shape::Ground { height: r(height) },
            Shape::Box { center, half_extents, rotation } => Shape::Box {
                center: rv(center),
                half_extents: rv(half_extents),
                rotation: DQuat::from_xyzw(r(rotation.x), r(rotation.y), r(rotation.z), r(rotation.w)),
            },
            Shape::Capsule { a, b, radius } => Shape::Capsule { a: rv(a), b: rv(b), radius: r(radius) },
            Shape::Mesh { center, rotation, thickness, ref mesh } => Shape::Mesh {
                center: rv(center),
                rotation: DQuat::from_xyzw(r(rotation.x), r(rotation.y), r(rotation.z), r(rotation.w)),
                thickness: r(thickness),
                mesh: std::sync::Arc::new(mesh.rounded_to_f32()),
            },
        };
        let motion = |m: &Motion| match m {
            Motion::Fixed => Motion::Fixed,
            Motion::Velocity(v) => Motion::Velocity(rv(*v)),
            Motion::Keyframes(k) => Motion::Keyframes(k.iter().map(|&(t, p)| (t, rv(p))).collect()),
            Motion::Smooth(k) => Motion::Smooth(k.iter().map(|&(t, p)| (t, rv(p))).collect()),
        };
        let turn = Turn { spin: rv(self.turn.spin), rotation: motion(&self.turn.rotation) };
        Self { shape, friction: self.friction.map(r), motion: motion(&self.motion), turn }
    }
}

impl Shape {
    pub fn kind(&self) -> ColliderKind {
        match self {
            Shape::Sphere { .. } => ColliderKind::Sphere,
            Shape::Ground { .. } => ColliderKind::Ground,
            Shape::Box { .. } => ColliderKind::Box,
            Shape::Capsule { .. } => ColliderKind::Capsule,
            Shape::Mesh { .. } => ColliderKind::Mesh,
        }
    }

    /// Signed distance from `p` to the surface (negative inside) and the outward unit normal
    /// of the nearest surface point.
    pub fn distance(&self, p: DVec3) -> (f64, DVec3) {
        match *self {
            Shape::Sphere { center, radius } => {
                let from = p - center;
                let d = from.length();
                (d - radius, if d > 0.0 { from / d } else { DVec3::Y })
            }
            Shape::Ground { height } => (p.y - height, DVec3::Y),
            Shape::Box { center, half_extents, rotation } => {
                let local = rotation.inverse() * (p - center);
                let q = local.abs() - half_extents;
                let outside = q.max(DVec3::ZERO);
                let sign = DVec3::new(sign(local.x), sign(local.y), sign(local.z));
                if outside.length() > 0.0 {
                    (outside.length(), rotation * (sign * outside / outside.length()))
                } else {
                    // Inside: out through the nearest face.
                    let axis = if q.x >= q.y && q.x >= q.z {
                        0
                    } else if q.y >= q.z {
                        1
                    } else {
                        2
                    };
                    let mut n = DVec3::ZERO;
                    n[axis] = sign[axis];
                    (q[axis], rotation * n)
                }
            }
            Shape::Capsule { a, b, radius } => {
                let ab = b - a;
                let len2 = ab.length_squared();
                let t = if len2 > 0.0 { ((p - a).dot(ab) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let from = p - (a + ab * t);
                let d = from.length();
                let n = if d > 0.0 { from / d } else { ab.any_orthonormal_vector() };
                (d - radius, n)
            }
            Shape::Mesh { center, rotation, thickness, ref mesh } => {
                let (d, n) = mesh.distance_placed(rotation.inverse() * (p - center), center);
                (d - thickness, rotation * n)
            }
        }
    }

    /// The point keyframes place: a sphere's or box's centre, a capsule's midpoint, the
    /// ground's point above the origin.
    pub fn reference_point(&self) -> DVec3 {
        match *self {
            Shape::Sphere { center, .. } | Shape::Box { center, .. } | Shape::Mesh { center, .. } => center,
            Shape::Ground { height } => DVec3::new(0.0, height, 0.0),
            Shape::Capsule { a, b, .. } => (a + b) / 2.0,
        }
    }

    /// The shape turned by `q` about its reference point (the ground does not turn).
    pub fn turned(&self, q: DQuat) -> Shape {
        match *self {
            Shape::Sphere { .. } | Shape::Ground { .. } => self.clone(),
            Shape::Box { center, half_extents, rotation } => {
                Shape::Box { center, half_extents, rotation: (q * rotation).normalize() }
            }
            Shape::Mesh { center, rotation, thickness, ref mesh } => {
                Shape::Mesh { center, rotation: (q * rotation).normalize(), thickness, mesh: mesh.clone() }
            }
            Shape::Capsule { a, b, radius } => {
                let mid = (a + b) / 2.0;
                Shape::Capsule { a: mid + q * (a - mid), b: mid + q * (b - mid), radius }
            }
        }
    }

    /// The shape moved by `d`.
    pub fn translated(&self, d: DVec3) -> Shape {
        match *self {
            Shape::Sphere { center, radius } => Shape::Sphere { center: center + d, radius },
            Shape::Ground { height } => Shape::Ground { height: height + d.y },
            Shape::Box { center, half_extents, rotation } => {
                Shape::Box { center: center + d, half_extents, rotation }
            }
            Shape::Capsule { a, b, radius } => Shape::Capsule { a: a + d, b: b + d, radius },
            Shape::Mesh { center, rotation, thickness, ref mesh } => {
                Shape::Mesh { center: center + d, rotation, thickness, mesh: mesh.clone() }
            }
        }
    }

    /// A mesh collider's vertices where its centre and rotation place them, and its triangles
    /// (`None` for the analytic shapes).
    pub fn placed_mesh(&self) -> Option<(Vec<DVec3>, &[[u32; 3]])> {
        match *self {
            Shape::Mesh { center, rotation, ref mesh, .. } => {
                Some((mesh.vertices.iter().map(|&p| center + rotation * p).collect(), &mesh.triangles))
            }
            _ => None,
        }
    }

    /// The corners of a box around the shape (`None` for the unbounded ground).
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        match *self {
            Shape::Sphere { center, radius } => Some((center - radius, center + radius)),
            Shape::Ground { .. } => None,
            Shape::Box { center, half_extents, rotation } => {
                let m = glam::DMat3::from_quat(rotation);
                let reach = DVec3::from_array(std::array::from_fn(|i| {
                    (0..3).map(|k| (m.col(k)[i] * half_extents[k]).abs()).sum::<f64>()
                }));
                Some((center - reach, center + reach))
            }
            Shape::Capsule { a, b, radius } => Some((a.min(b) - radius, a.max(b) + radius)),
            Shape::Mesh { center, rotation, thickness, ref mesh } => {
                // The box around its vertices in its frame, placed and turned as it is.
                let (lo, hi) = mesh.bounds();
                let half_extents = (hi - lo) / 2.0;
                let placed =
                    Shape::Box { center: center + rotation * ((lo + hi) / 2.0), half_extents, rotation };
                placed.bounds().map(|(lo, hi)| (lo - thickness, hi + thickness))
            }
        }
    }
}

/// +1 or -1 (+1 at zero, as GLSL's `p >= 0.0 ? 1.0 : -1.0` in colliders.glsl).
fn sign(x: f64) -> f64 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The speed up to which discrete contact cannot be missed, and what sets it. A contact is
/// tested once per substep, at the substep's end, and resolved by projecting out to the
/// nearer side: a particle that crosses more than a collider's half-thickness plus its margin
/// in one substep (a sphere's or capsule's radius, a box's smallest half extent; the ground
/// has no far side) lands past the middle and is pushed out of the far side. Likewise within
/// an object: more than the self-collision distance per substep, relative. Between objects a
/// pair that crosses within a substep is pushed back to the side it began on (`contact.comp`'s
/// `gap_of`), so a crossing is caught while the pair ends within the reach (the two objects'
/// contact radii) of each other: from a gap of at least the reach, up to twice the reach per
/// substep, relative. Past this speed contacts can tunnel.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpeed {
    /// [m/s]
    pub speed: f64,
    /// What sets it, e.g. "capsule 0 against cloth 'towel'".
    pub what: String,
}

impl std::fmt::Display for ContactSpeed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "contacts are exact up to {:.2} m/s per particle (set by {})", self.speed, self.what)
    }
}

/// The lowest contact speed of a model (`None` without contacts that can tunnel).
pub fn contact_speed(model: &super::model::SimModel) -> Option<ContactSpeed> {
    let dt = model.dt();
    let mut limits: Vec<(f64, String)> = Vec::new();
    for (k, o) in model.objects.iter().enumerate() {
        let name = format!("{} '{}'", o.kind.label(), o.name);
        for (i, c) in model.colliders.iter().enumerate() {
            let half = match c.shape {
                Shape::Sphere { radius, .. } | Shape::Capsule { radius, .. } => radius,
                Shape::Box { half_extents, .. } => half_extents.min_element(),
                // Found down to its reach from its triangles.
                Shape::Mesh { thickness, ref mesh, .. } => (mesh.reach - thickness).max(0.0),
                Shape::Ground { .. } => continue,
            };
            limits.push(((half + o.margin) / dt, format!("{} {i} against {name}", c.shape.kind().label())));
        }
        if let Some(s) = o.self_distance {
            // (a cloth that keeps its edges apart holds each move to a fraction of it instead:
            // faster, its particles are slowed, not passed through)
            if o.has_cloth_edge_pairs() {
                let most = crate::sim::cpu::self_contact::TRUNCATION_MOVE;
                let why = format!(
                    "the self-collision distance of {name}, its moves held to {most} of it a substep"
                );
                limits.push((most * s / dt, why));
            } else {
                limits.push((s / dt, format!("the self-collision distance of {name}")));
            }
        }
        if model.inter_object_contact() {
            for other in &model.objects[k + 1..] {
                let reach = o.contact_radius() + other.contact_radius();
                limits.push((
                    2.0 * reach / dt,
                    format!("the contact of {name} with {} '{}'", other.kind.label(), other.name),
                ));
            }
        }
    }
    limits.into_iter().min_by(|a, b| a.0.total_cmp(&b.0)).map(|(speed, what)| ContactSpeed { speed, what })
}

/// The feature bits of the collider types `colliders` use, and whether any turns (a scene
/// whose colliders do not turn compiles the turn out).
pub fn features(colliders: &[ColliderModel]) -> u32 {
    let turning = |c: &ColliderModel| if c.turns() { FEATURE_TURNING } else { 0 };
    colliders.iter().fold(0, |f, c| f | c.shape.kind().row().feature | turning(c))
}

/// Whether object `o` needs its edges tested against `colliders` as well as its particles
/// (`collide_edges` in glsl/include/constraints_body.glsl): when a collider could pass between
/// its particles or poke through a face: a box or a mesh (their edges and corners are sharp) or a sphere
/// or capsule of radius under two grid spacings. A ground never does, nor larger round shapes
/// (a face between particles 2.5 spacings apart sags into a sphere of radius 2 spacings by an
/// eighth of a spacing).
pub fn edges_needed(o: &ObjectModel, colliders: &[ColliderModel]) -> bool {
    let spacing = o.spacing[0].max(o.spacing[1]);
    colliders.iter().any(|c| match c.shape {
        Shape::Box { .. } | Shape::Mesh { .. } => true,
        Shape::Sphere { radius, .. } | Shape::Capsule { radius, .. } => radius < 2.0 * spacing,
        Shape::Ground { .. } => false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Friction only ever takes tangential speed away and never moves a particle further
    /// than its slip: over overlaps from within the position slack (where the depth gives no
    /// impulse) to deep, approaching and leaving normal speeds, and slips from tiny to large.
    /// With the normal impulse left negative for a particle leaving within the slack, the
    /// kinetic branch scaled its slip by a negative factor (up to -1e6 here) and sped it up
    /// (the curtain preset at 64 substeps: a particle at 88 m/s after one frame).
    #[test]
    fn friction_never_adds_speed_nor_moves_past_the_slip() {
        let n = DVec3::Y;
        for depth in [0.0, 1e-9, 3e-7, 1e-6, 1e-3] {
            for vn in [-1.0, -1e-3, 0.0, 1e-3, 1.0] {
                for slip in [1e-12, 1e-7, 1e-4, 1e-2] {
                    for mu in [0.0, 0.3, 1.0] {
                        let dt = 1.0 / 3840.0;
                        let start = DVec3::new(0.5, 0.0, 0.2);
                        let vt = DVec3::new(0.0, 0.0, slip / dt);
                        let mut x = start + DVec3::new(0.0, -depth, slip);
                        let mut v = vt + n * vn;
                        respond_along((n, depth), (mu, DVec3::ZERO), (start, dt), &mut x, &mut v);
                        let speed = (v - n * v.dot(n)).length();
                        assert!(
                            speed <= vt.length() * (1.0 + 1e-12),
                            "depth {depth}, vn {vn}, slip {slip}, mu {mu}: tangential speed {:e} -> {speed:e}",
                            vt.length()
                        );
                        let moved = (x - start - n * (x - start).dot(n)).length();
                        assert!(
                            moved <= slip * (1.0 + 1e-9) + 1e-15, // f64 steps of the coordinates
                            "depth {depth}, vn {vn}, slip {slip}, mu {mu}: moved {moved:e} along the surface"
                        );
                    }
                }
            }
        }
    }

    /// Each shape's distance against points whose distance is known by construction, and its
    /// normal against a finite-difference gradient.
    #[test]
    fn signed_distances_and_normals() {
        let turn = DQuat::from_rotation_y(0.5);
        let shapes = [
            Shape::Sphere { center: DVec3::new(0.1, 0.2, 0.3), radius: 0.4 },
            Shape::Ground { height: -0.2 },
            Shape::Box {
                center: DVec3::new(0.0, 0.5, 0.0),
                half_extents: DVec3::new(0.3, 0.1, 0.2),
                rotation: turn,
            },
            Shape::Capsule { a: DVec3::new(-0.5, 0.0, 0.0), b: DVec3::new(0.5, 0.2, 0.0), radius: 0.1 },
        ];
        // Known values.
        assert!((shapes[0].distance(DVec3::new(0.1, 0.2, 1.0)).0 - 0.3).abs() < 1e-12);
        assert!((shapes[1].distance(DVec3::new(5.0, 0.3, -2.0)).0 - 0.5).abs() < 1e-12);
        let above_box = DVec3::new(0.0, 0.9, 0.0);
        assert!((shapes[2].distance(above_box).0 - 0.3).abs() < 1e-12);
        let corner = turn * DVec3::new(0.3, 0.1, 0.2) + DVec3::new(0.0, 0.5, 0.0);
        let beyond = corner + turn * DVec3::new(0.03, 0.04, 0.0);
        assert!((shapes[2].distance(beyond).0 - 0.05).abs() < 1e-12);
        assert!((shapes[3].distance(DVec3::new(-0.8, 0.0, 0.0)).0 - 0.2).abs() < 1e-12);
        // Normals are the gradient of the distance, inside and outside.
        for (s, shape) in shapes.iter().enumerate() {
            for k in 0..200 {
                let t = k as f64 * 0.7;
                let p = DVec3::new(t.sin() * 0.6, 0.4 + (1.3 * t).cos() * 0.5, (0.9 * t).sin() * 0.4);
                let (d, n) = shape.distance(p);
                let h = 1e-6;
                let grad = DVec3::new(
                    shape.distance(p + DVec3::X * h).0 - shape.distance(p - DVec3::X * h).0,
                    shape.distance(p + DVec3::Y * h).0 - shape.distance(p - DVec3::Y * h).0,
                    shape.distance(p + DVec3::Z * h).0 - shape.distance(p - DVec3::Z * h).0,
                ) / (2.0 * h);
                assert!((n.length() - 1.0).abs() < 1e-9, "shape {s}: normal not unit at {p}");
                // Away from the medial ridges (where the gradient jumps) the two agree.
                if (grad.length() - 1.0).abs() < 1e-3 {
                    assert!(
                        (grad - n).length() < 1e-4,
                        "shape {s} at {p} (d {d}): normal {n} vs gradient {grad}"
                    );
                }
            }
        }
    }

    /// The response leaves the particle exactly at the margin with no approaching velocity, and
    /// its friction is Coulomb's: a tangential speed change of mu jn where it slides, none left
    /// where the cone holds it.
    #[test]
    fn response_projects_to_the_margin() {
        let c = ColliderModel {
            shape: Shape::Capsule { a: DVec3::ZERO, b: DVec3::X, radius: 0.2 },
            friction: Some(0.25),
            motion: Motion::Fixed,
            turn: Turn::default(),
        };
        let dt = 0.01;
        // Arriving at 2 m/s down and 1 m/s along: jn = 2 m/s, so friction takes 0.5 m/s.
        let mut x = DVec3::new(0.5, 0.2, 0.0);
        let start = x - DVec3::new(1.0, -2.0, 0.0) * dt;
        let mut v = DVec3::new(1.0, -2.0, 0.0);
        c.respond((0.01, 0.9), &Pose::moving(DVec3::ZERO, DVec3::ZERO), (start, dt), &mut x, &mut v);
        assert!((c.shape.distance(x).0 - 0.01).abs() < 1e-12);
        assert!(v.y.abs() < 1e-12 && (v.x - 0.5).abs() < 1e-12, "{v}");
        assert!((x.x - (start.x + 0.5 * dt)).abs() < 1e-12, "slid by the kinetic share: {x}");
        // A collider moving up at 2 m/s and along at 0.5: the particle leaves with its normal
        // velocity, and the normal impulse (4 m/s) holds it: it moves along with the collider.
        let mut x = DVec3::new(0.5, 0.2, 0.0);
        let start = x - DVec3::new(1.0, -2.0, 0.0) * dt;
        let mut v = DVec3::new(1.0, -2.0, 0.0);
        let moving = Pose::moving(DVec3::ZERO, DVec3::new(0.5, 2.0, 0.0));
        c.respond((0.01, 0.9), &moving, (start, dt), &mut x, &mut v);
        assert!((v.y - 2.0).abs() < 1e-12 && (v.x - 0.5).abs() < 1e-12, "{v}");
        assert!((x.x - (start.x + 0.5 * dt)).abs() < 1e-12, "stuck to the collider: {x}");
    }

    /// Keyframes interpolate linearly and hold at the ends; a frame's motion is its chord.
    #[test]
    fn keyframed_motion() {
        let m = Motion::Keyframes(vec![(0.5, DVec3::ZERO), (1.5, DVec3::new(1.0, 0.0, 0.0))]);
        assert_eq!(m.offset(0.0), DVec3::ZERO);
        assert!((m.offset(1.0).x - 0.5).abs() < 1e-12);
        assert_eq!(m.offset(9.0), DVec3::X);
        let c = ColliderModel { motion: m, ..ColliderModel::sphere(DVec3::ZERO, 0.1) };
        let (start, v) = c.frame_motion(1.0, 0.25);
        assert!((start.x - 0.5).abs() < 1e-12 && (v.x - 1.0).abs() < 1e-12);
    }

    /// Smooth keys: through every key, held outside them, at rest at the ends and where a
    /// component turns back, the velocity continuous at an interior key (within 1e-6 of
    /// itself from both sides: a finite difference's error), no component beyond the keys on
    /// either side of its segment, and no faster than `smooth_top_speed` says (sampled).
    #[test]
    fn smooth_keyframes() {
        let keys = vec![
            (0.0, DVec3::ZERO),
            (1.0, DVec3::new(1.0, 2.0, 0.0)),
            (1.5, DVec3::new(3.0, 2.5, -1.0)),
            (3.0, DVec3::new(3.5, 0.0, 0.0)),
        ];
        let m = Motion::Smooth(keys.clone());
        for &(t, p) in &keys {
            assert!((m.offset(t) - p).length() < 1e-12, "{t}: {}", m.offset(t));
        }
        assert_eq!(m.offset(-1.0), DVec3::ZERO);
        assert_eq!(m.offset(5.0), keys[3].1);
        let velocity = |t: f64| (m.offset(t + 1e-7) - m.offset(t - 1e-7)) / 2e-7;
        assert!(velocity(1e-6).length() < 1e-4 && velocity(3.0 - 1e-6).length() < 1e-4);
        for &(t, _) in &keys[1..3] {
            let (left, right) =
                ((m.offset(t) - m.offset(t - 1e-7)) / 1e-7, (m.offset(t + 1e-7) - m.offset(t)) / 1e-7);
            assert!((left - right).length() < 1e-5 * (1.0 + left.length()), "{t}: {left} against {right}");
        }
        // y turns back at t = 1.5: at rest there.
        assert!(velocity(1.5).y.abs() < 1e-5, "{}", velocity(1.5));
        let top = smooth_top_speed(&keys);
        let mut fastest = 0.0f64;
        for i in 1..3000 {
            let t = i as f64 * 1e-3;
            let k = keys.windows(2).position(|w| t <= w[1].0).unwrap();
            let (lo, hi) = (keys[k].1.min(keys[k + 1].1), keys[k].1.max(keys[k + 1].1));
            let p = m.offset(t);
            assert!(p.cmpge(lo - 1e-12).all() && p.cmple(hi + 1e-12).all(), "{t}: {p} beyond {lo}..{hi}");
            fastest = fastest.max(velocity(t).length());
        }
        assert!(fastest <= top * (1.0 + 1e-6) && fastest > 0.9 * top, "sampled {fastest}, bound {top}");
    }
}
