//! The physical model both simulators run: the GPU one (`sim::gpu`) and the f64 CPU reference
//! (`sim::cpu`). Built from a scene preset by `scene::build`, or directly by tests.
//! Units: metres, seconds, kilograms, newtons.

pub use super::integrator::Integrator;
use glam::DVec3;

/// Lanes a rope's node searches with (`SimModel::contact_lanes`; docs/records/bench/h100/rope-capsules-lanes).
pub const CONTACT_LANES: u32 = 64;

/// Lanes a cloth's particle searches with where cloths keep their edges apart
/// (`SimModel::contact_lanes`; docs/PERFORMANCE.md, "Contact lists between objects").
pub const CLOTH_EDGE_LANES: u32 = 16;

/// How far a cloth's grid diagonals may stretch with every self-contact still found
/// (`TRIANGLE_STRETCH` in glsl/include/lists.glsl).
pub const TRIANGLE_STRETCH: f64 = 1.5;

/// How far from a particle, in contact hash cells, its 2 x 2 x 2 block of cells surely reaches
/// (half a cell, less a margin for rounding): the cell is sized so that this covers every
/// contact's reach plus its corner reach.
pub const CONTACT_BLOCK_REACH: f64 = 0.49;

/// The skin of the contact lists between objects, in the smallest reach (two contact radii):
/// a list holds what is within the reach plus the skin and lasts until some particle has moved
/// half the skin (`glsl/include/contact_common.glsl`). A larger skin rebuilds less often but
/// lists more: a thick rope between two cloths then overflows its list (docs/PERFORMANCE.md,
/// "Contact lists between objects").
pub const CONTACT_SKIN: f64 = 0.5;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ObjectKind {
    Cloth = 0,
    Rope = 1,
}

impl ObjectKind {
    pub fn label(self) -> &'static str {
        match self {
            ObjectKind::Cloth => "cloth",
            ObjectKind::Rope => "rope",
        }
    }
}

/// What an object's size is, without its particles: enough to check it fits a device.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectShape {
    pub kind: ObjectKind,
    pub name: String,
    pub dims: [u32; 2],
    /// A mesh cloth's topology (its triangles drawn).
    pub mesh: Option<std::sync::Arc<crate::sim::cloth_mesh::ClothMesh>>,
}

impl ObjectShape {
    /// Whether it is a cloth made from a mesh.
    pub fn is_mesh(&self) -> bool {
        self.mesh.is_some()
    }

    pub fn particle_count(&self) -> u64 {
        self.dims[0] as u64 * self.dims[1] as u64
    }

    /// Number of drawable surface vertices: one per cloth particle, a ring per rope node.
    pub fn surface_count(&self) -> u64 {
        match self.kind {
            ObjectKind::Cloth => self.particle_count(),
            ObjectKind::Rope => self.particle_count() * crate::sim::gpu_types::ROPE_RING as u64,
        }
    }
}

/// One cloth grid or rope (a rope is a grid of `nodes x 1`).
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectModel {
    pub kind: ObjectKind,
    pub name: String,
    /// Columns and rows of the particle grid; particle (c, r) has index c + r * columns.
    pub dims: [u32; 2],
    /// Rest distance between grid neighbours along columns and rows [m].
    pub spacing: [f64; 2],
    /// Spring stiffness for structural, shear and bending springs [N/m].
    pub stiffness: [f64; 3],
    /// Rest length of each spring type as a multiple of its grid distance.
    pub rest_scale: [f64; 3],
    /// A mesh cloth's seam springs' stiffness [N/m] (rest length zero; 0 without seams).
    pub seam: f64,
    /// Dashpot along every spring [N s/m].
    pub damping: f64,
    /// Mass of each particle [kg]; a mesh cloth's mean particle's (`mass_of`).
    pub mass: f64,
    /// Stokes drag coefficient: force -drag * v [N s/m] (a mesh cloth's particle, times its
    /// share of the area: `share_of`).
    pub drag: f64,
    /// Coulomb's friction coefficient mu: against colliders (unless a collider sets its own),
    /// other objects (the mean of the two objects') and, with triangle self-contact, itself.
    pub friction: f64,
    /// Distance kept from sphere surfaces [m].
    pub margin: f64,
    /// Maximum elongation of structural and shear springs as a fraction of rest length.
    pub stretch_limit: Option<f64>,
    /// Self-collision distance [m].
    pub self_distance: Option<f64>,
    /// A cloth's self-collision keeps its particles from its triangles (equal and opposite
    /// impulses, `sim::cpu::self_contact`) instead of from its other particles; a rope's
    /// keeps its segments from its segments (`has_segment_pairs`) instead of its nodes.
    pub triangle_contact: bool,
    /// ... and a cloth's edges from its edges too (with `triangle_contact`; a rope's segment
    /// pairs follow from `triangle_contact` alone, `has_edge_pairs`).
    pub edge_contact: bool,
    /// Rope tube radius [m] (rope only).
    pub rope_radius: f64,
    /// Rope tube vertex offsets in (side, up) units of the radius (rope only).
    pub ring_weights: [[f64; 2]; crate::sim::gpu_types::ROPE_RING],
    /// Initial state, one entry per particle.
    pub positions: Vec<DVec3>,
    pub velocities: Vec<DVec3>,
    pub pinned: Vec<bool>,
    /// How the pinned particles of group 0 move, all together (`sim::pins`).
    pub pin_motion: crate::sim::pins::PinMotion,
    /// How those of each further pin group move: group g >= 1 is `pin_groups[g - 1]`
    /// (`PIN_GROUPS` in all).
    pub pin_groups: Vec<crate::sim::pins::PinMotion>,
    /// The pin group of each particle (empty: all 0; a free particle's is 0).
    pub pin_group: Vec<u8>,
    /// A cloth made from a mesh (`dims` [particles, 1]): its springs, triangles and colouring
    /// instead of the grid's (`sim::cloth_mesh`); none for a grid or a rope.
    pub mesh: Option<std::sync::Arc<crate::sim::cloth_mesh::ClothMesh>>,
}

/// Pin groups an object may have: its own pins (group 0) and up to 7 `pin_group` entries
/// (`PIN_GROUPS` in glsl/include/layout.glsl).
pub const PIN_GROUPS: usize = 8;

impl ObjectModel {
    pub fn shape(&self) -> ObjectShape {
        ObjectShape { kind: self.kind, name: self.name.clone(), dims: self.dims, mesh: self.mesh.clone() }
    }

    pub fn particle_count(&self) -> usize {
        self.shape().particle_count() as usize
    }

    /// Particle i's mass [kg]: `mass`, times a mesh cloth particle's share of its area
    /// (`ClothMesh::mass_share`; `particle_mass` in glsl/include/mesh_springs.glsl).
    pub fn mass_of(&self, i: usize) -> f64 {
        self.mass * self.share_of(i)
    }

    /// Particle i's share of its object's area over the mean particle's: 1 but on a mesh cloth
    /// (`ClothMesh::mass_share`).
    pub fn share_of(&self, i: usize) -> f64 {
        self.mesh.as_ref().map_or(1.0, |m| m.mass_share[i])
    }

    /// Particle i's pin group (`pin_group`).
    pub fn group_of(&self, i: usize) -> usize {
        self.pin_group.get(i).map_or(0, |&g| g as usize)
    }

    /// How the pins of group g move.
    pub fn pin_motion_of(&self, g: usize) -> &crate::sim::pins::PinMotion {
        if g == 0 {
            &self.pin_motion
        } else {
            &self.pin_groups[g - 1]
        }
    }

    /// Every group's motion, group 0 first.
    pub fn pin_motions(&self) -> impl Iterator<Item = &crate::sim::pins::PinMotion> {
        std::iter::once(&self.pin_motion).chain(&self.pin_groups)
    }

    /// Some of its pins move.
    pub fn pins_move(&self) -> bool {
        self.pin_motions().any(|m| m.is_moving())
    }

    /// The pinned particles' motion over substep `s` of `dt` in the frame at `t0`, group by group.
    pub fn pin_steps(&self, t0: f64, frame_dt: f64, s: u32, dt: f64) -> Vec<crate::sim::pins::PinStep> {
        self.pin_motions().map(|m| m.step(t0, frame_dt, s, dt)).collect()
    }

    /// Where particle i (pinned) placed at `x` is at time `t` (`PinMotion::carried`).
    pub fn pin_carried(&self, i: usize, x: DVec3, t: f64) -> DVec3 {
        self.pin_motion_of(self.group_of(i)).carried(x, t)
    }

    /// Particle i's velocity at t = 0: its pins' where it is pinned.
    pub fn initial_velocity(&self, i: usize, frame_dt: f64) -> DVec3 {
        match self.pinned[i] {
            true => self.pin_motion_of(self.group_of(i)).initial_velocity(self.positions[i], frame_dt),
            false => self.velocities[i],
        }
    }

    /// The stiffness of a spring of `kind` (0 structural, 1 shear, 2 bending, 3 a mesh cloth's
    /// seam) [N/m].
    pub fn stiffness_of(&self, kind: usize) -> f64 {
        self.stiffness.get(kind).copied().unwrap_or(self.seam)
    }

    pub fn surface_count(&self) -> usize {
        self.shape().surface_count() as usize
    }

    /// Whether a particle is pinned: the object cannot move as a whole
    /// (`sim::cpu::integrators::toward_rest`).
    pub fn anchored(&self) -> bool {
        self.pinned.iter().any(|&p| p)
    }

    /// Whether self-contact is between the pieces of the surface, equal and opposite
    /// (`sim::cpu::self_contact`; the GPU's F_TRIANGLES): a cloth's particles against its
    /// triangles, asked for, on a grid of at least 2 x 2 or a mesh; a rope's segments against its
    /// segments, as capsules (`has_segment_pairs`). Else particle against particle.
    pub fn has_triangles(&self) -> bool {
        let surface = self.dims[1] > 1 || self.kind == ObjectKind::Rope || self.mesh.is_some();
        self.triangle_contact && self.dims[0] > 1 && surface
    }

    /// Whether self-contact keeps the grid's edges from its edges too: with triangles, or a
    /// rope's segments (its only edges).
    pub fn has_edge_pairs(&self) -> bool {
        (self.edge_contact || self.kind == ObjectKind::Rope) && self.has_triangles()
    }

    /// Whether self-contact is a rope's segments against its segments (capsules of the
    /// self-collision distance's thickness, one row of edges with no triangles; the GPU's
    /// F_SEGMENT_PAIRS): an edge pair then counts wherever its nearest points lie, at an end
    /// too, since no triangle holds a node against a segment.
    pub fn has_segment_pairs(&self) -> bool {
        self.kind == ObjectKind::Rope && self.has_triangles()
    }

    /// Whether self-contact keeps a cloth's edges from its edges (`has_edge_pairs` but not a
    /// rope's segments): its pairs need an edge creased, judged from each particle's ring (the
    /// twin from feature bits: `gpu_types::has_cloth_edge_pairs`).
    pub fn has_cloth_edge_pairs(&self) -> bool {
        self.has_edge_pairs() && !self.has_segment_pairs()
    }

    /// How far from a particle self-contact candidates are searched (`self_reach` in
    /// glsl/include/lists.glsl): the self-collision distance h, plus for a cloth half a grid
    /// cell's diagonal stretched by `TRIANGLE_STRETCH` (a triangle within h has its nearest
    /// vertex that near).
    pub fn self_reach(&self) -> Option<f64> {
        let diagonal = self.spacing[0].hypot(self.spacing[1]);
        let more = if self.has_triangles() { 0.5 * TRIANGLE_STRETCH * diagonal } else { 0.0 };
        self.self_distance.map(|h| h + more)
    }

    /// Whether other objects' particles touch this object's triangles (contact between
    /// objects): a cloth of at least 2 x 2 (else its segments, as a rope's: a chain of
    /// capsules in index order).
    pub fn contact_triangles(&self) -> bool {
        self.kind == ObjectKind::Cloth && self.dims[0] > 1 && self.dims[1] > 1
    }

    /// How much farther than the reach the nearest corner of a piece of this object's surface
    /// may be from another object's particle touching it: for a cloth's triangle half the cell's
    /// rest diagonal, for a rope's segment (or a one-wide cloth's) half its rest length,
    /// stretched `TRIANGLE_STRETCH` times (the piece's farthest point from its corners).
    pub fn corner_reach(&self) -> f64 {
        let span = if self.contact_triangles() {
            self.spacing[0].hypot(self.spacing[1])
        } else if self.dims[0] > 1 {
            self.spacing[0]
        } else if self.dims[1] > 1 {
            self.spacing[1]
        } else {
            0.0
        };
        0.5 * TRIANGLE_STRETCH * span
    }

    /// Half the distance kept from another object's particles (inter-object contact): a
    /// rope's tube radius, a cloth's collision margin.
    pub fn contact_radius(&self) -> f64 {
        match self.kind {
            ObjectKind::Cloth => self.margin,
            ObjectKind::Rope => self.rope_radius,
        }
    }
}

/// The paper's wind cone, resolved to cosines of its two half-angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindModel {
    pub origin: DVec3,
    /// Unit axis of the cone.
    pub direction: DVec3,
    /// Force on each particle at full strength [N].
    pub force: f64,
    /// Cosine of the half-angle inside which the force is full.
    pub cos_full: f64,
    /// Cosine of the half-angle where the force has fallen to zero.
    pub cos_att: f64,
    /// The aerodynamic wind (`None`: the paper's force on every particle).
    pub air: Option<AirModel>,
}

/// The aerodynamic wind: air flowing along the cone's axis at `speed` times the cone's
/// strength there, pushing on the cloth by the air's velocity u relative to it: `normal` |u_n|
/// u_n + `tangent` |u_t| u_t per unit area (for a rope, per unit length of its diameter) [N],
/// and on a cloth the lift `lift` |u| (u.n) (n - (u.n) u / |u|^2) per unit area, across the
/// air in the plane of the air and the normal (`sim::cpu::air_force`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirModel {
    /// [m/s]
    pub speed: f64,
    /// 1/2 density normal drag coefficient [kg/m^3].
    pub normal: f64,
    /// 1/2 density tangential drag coefficient [kg/m^3].
    pub tangent: f64,
    /// Density lift coefficient [kg/m^3]: the lift is 1/2 density lift_coefficient sin(2 alpha)
    /// |u|^2 per unit area at an angle of attack alpha.
    pub lift: f64,
    /// The air's turbulent part, added to the mean within the cone (times its strength).
    pub turbulence: Option<crate::sim::turbulence::Turbulence>,
}

/// How self-collision finds its candidate pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SelfCollisionMethod {
    /// A spatial hash rebuilt every substep: O(N).
    #[default]
    Hash,
    /// Every pair: O(N^2), the reference.
    BruteForce,
}

/// `sim.contact_iterations` unless a scene sets it.
pub const DEFAULT_CONTACT_ITERATIONS: u32 = 4;

#[derive(Debug, Clone, PartialEq)]
pub struct SimModel {
    pub gravity: DVec3,
    /// Simulated time per frame [s].
    pub frame_dt: f64,
    pub substeps: u32,
    pub wind: Option<WindModel>,
    /// Spheres, the ground, boxes, capsules (`sim::collider`).
    pub colliders: Vec<crate::sim::collider::ColliderModel>,
    pub objects: Vec<ObjectModel>,
    pub self_collision: SelfCollisionMethod,
    /// The runtime guard stops a simulation whose particles move faster than this [m/s].
    pub max_speed: f64,
    /// ... or whose structural springs stretch past this strain (0: no check).
    pub max_strain: f64,
    /// ... or whose energy grows without a source by more than this fraction of its scale (0:
    /// no check; `sim::gpu::energy`).
    pub max_energy_gain: f64,
    pub integrator: Integrator,
    /// Solver iterations per substep (the iterative methods only).
    pub iterations: u32,
    /// XPBD (`xpbd`, the spring classes): the over-relaxation factor (0..2) of each Gauss-Seidel
    /// correction (`Method::relaxed`).
    pub relaxation: f64,
    /// Objects touch each other (`inter_object_contact` says whether a scene uses it).
    pub inter_object: bool,
    /// Two touching cloths keep their edges apart (else only where either keeps its own edges
    /// apart, `ObjectModel::edge_contact`).
    pub inter_object_edges: bool,
    /// Passes over a cloth's contacts with its own triangles a substep (found once, each
    /// pass applied from the positions the passes before moved; `sim::cpu::self_contact`).
    pub contact_iterations: u32,
}

impl SimModel {
    /// Whether the objects touch each other: asked for, and more than one object.
    pub fn inter_object_contact(&self) -> bool {
        self.inter_object && self.objects.len() > 1
    }

    /// Projections of contact between objects a substep: one after each iteration of a method
    /// whose iterations pull back to the prediction (`Solver::contact_rounds`: VBD), each moving
    /// the prediction with the particle, so that the next iteration keeps the correction and
    /// a pile's support carries through it; else one after the solve. With one a substep a
    /// stack of cards fell through itself at VBD 20 x 10 (docs/design/contact.md).
    pub fn contact_rounds(&self) -> u32 {
        let rounds = self.integrator.solver().is_some_and(|s| s.contact_rounds);
        if self.inter_object_contact() && rounds {
            self.iterations.max(1)
        } else {
            1
        }
    }

    /// Whether contact between objects keeps some two cloths' edges apart
    /// (`SimModel::keeps_cloth_edges_apart`).
    pub fn has_cloth_edges_between(&self) -> bool {
        let o = &self.objects;
        o.iter().enumerate().any(|(a, x)| o[a + 1..].iter().any(|y| self.keeps_cloth_edges_apart(x, y)))
    }

    /// Whether contact between objects keeps object a's edges from object b's edges (rows,
    /// columns and diagonals; `sim::cpu::inter_object`): both cloths, and the scene asks for it
    /// (`inter_object_edges`) or either keeps its own edges from its edges (`edge_contact`). A
    /// rope's segments always keep from edges.
    pub fn keeps_cloth_edges_apart(&self, a: &ObjectModel, b: &ObjectModel) -> bool {
        a.contact_triangles()
            && b.contact_triangles()
            && (self.inter_object_edges || a.edge_contact || b.edge_contact)
    }

    /// Work items (lanes) among which contact between objects splits the search of each of
    /// object q's particles (contact.comp): a rope's few nodes each search a block of cells as
    /// large as their segments, too much for one thread a node; where cloths keep their edges
    /// apart, a cloth's particle tests each candidate's edges against its own, dozens in a
    /// pile (`CLOTH_EDGE_LANES`); otherwise a cloth's particle, with a small block, searches
    /// alone.
    pub fn contact_lanes(&self, q: usize) -> u32 {
        if !self.objects[q].contact_triangles() {
            CONTACT_LANES
        } else if self.has_cloth_edges_between() {
            CLOTH_EDGE_LANES
        } else {
            1
        }
    }

    /// The cell of the scene's contact hash (contact between objects) [m], such that a
    /// particle's block of cells reaches (`CONTACT_BLOCK_REACH` cells) the largest reach (two
    /// contact radii) and the lists' skin plus the largest corner reach
    /// (`ObjectModel::corner_reach`), or twice a rope's and another object's added, or two
    /// cloths' added where they keep their edges apart: a piece within reach has its nearest
    /// corner in sight, a rope's pair of edges their lower ends, two cloths' their nearest
    /// ends.
    pub fn contact_cell(&self) -> f64 {
        let widest = self.objects.iter().map(ObjectModel::contact_radius).fold(0.0, f64::max);
        let edge = self.objects.iter().map(ObjectModel::corner_reach).fold(0.0, f64::max);
        // A rope's segment and another object's edge are found through their lower ends: twice
        // both corner reaches; two cloths' edges through their nearest ends: both once.
        let pairs = self.objects.iter().enumerate().flat_map(|(a, o)| {
            let others = self.objects.iter().enumerate().filter(move |&(b, _)| b != a);
            others.filter_map(move |(_, p)| {
                match (o.contact_triangles(), self.keeps_cloth_edges_apart(o, p)) {
                    (false, _) => Some(2.0 * (o.corner_reach() + p.corner_reach())),
                    (true, true) => Some(o.corner_reach() + p.corner_reach()),
                    (true, false) => None,
                }
            })
        });
        let edge = pairs.fold(edge, f64::max);
        ((2.0 * widest + self.contact_skin() + edge) / CONTACT_BLOCK_REACH).max(1e-6)
    }

    /// `contact_cell` with the lists off: every substep searches for the contacts alone.
    pub fn contact_cell_without_skin(&self) -> f64 {
        (self.contact_cell() - self.contact_skin() / CONTACT_BLOCK_REACH).max(1e-6)
    }

    /// The skin of the contact lists between objects [m] (`CONTACT_SKIN`).
    pub fn contact_skin(&self) -> f64 {
        let thinnest = self.objects.iter().map(ObjectModel::contact_radius).fold(f64::INFINITY, f64::min);
        CONTACT_SKIN * 2.0 * thinnest.min(1e3)
    }

    /// Turns the guard's plausibility checks off (strain and energy gain), for runs that
    /// measure what a setting does rather than stop it: bench, the chart, the stability map.
    pub fn plausibility_off(&mut self) {
        self.max_strain = 0.0;
        self.max_energy_gain = 0.0;
    }

    /// Length of one substep [s].
    pub fn dt(&self) -> f64 {
        self.frame_dt / self.substeps as f64
    }

    /// The model without its particle arrays (initial positions, velocities, pins): what is
    /// needed to describe the simulation, at a fraction of the size.
    pub fn without_particles(&self) -> SimModel {
        SimModel {
            objects: self
                .objects
                .iter()
                .map(|o| ObjectModel {
                    kind: o.kind,
                    name: o.name.clone(),
                    dims: o.dims,
                    spacing: o.spacing,
                    stiffness: o.stiffness,
                    rest_scale: o.rest_scale,
                    seam: o.seam,
                    damping: o.damping,
                    mass: o.mass,
                    drag: o.drag,
                    friction: o.friction,
                    margin: o.margin,
                    stretch_limit: o.stretch_limit,
                    self_distance: o.self_distance,
                    triangle_contact: o.triangle_contact,
                    edge_contact: o.edge_contact,
                    rope_radius: o.rope_radius,
                    ring_weights: o.ring_weights,
                    positions: Vec::new(),
                    velocities: Vec::new(),
                    pinned: Vec::new(),
                    pin_motion: o.pin_motion.clone(),
                    pin_groups: o.pin_groups.clone(),
                    pin_group: Vec::new(),
                    mesh: o.mesh.clone(),
                })
                .collect(),
            colliders: self.colliders.clone(),
            ..*self
        }
    }
}

/// The paper's default ring: eight vertices evenly around the node.
pub fn default_ring_weights() -> [[f64; 2]; crate::sim::gpu_types::ROPE_RING] {
    std::array::from_fn(|k| {
        let a = k as f64 * std::f64::consts::TAU / crate::sim::gpu_types::ROPE_RING as f64;
        [a.cos(), a.sin()]
    })
}
