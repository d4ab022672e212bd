//! Scenes: the TOML preset format (these types), loading with `--set` overrides (`load`), range
//! checks (`validate`) and the conversion to the simulation model (`build`).
//!
//! Every table rejects unknown keys. Units are SI: metres, seconds, kilograms, newtons.

mod build;
mod load;
pub mod mesh_file;
pub mod place;
mod validate;

pub use build::{colliders, shapes, to_model, turbulence_of};
pub use load::{apply_override, load, load_meshes, load_runnable, parse, save};
pub use validate::{check as validate, MAX_FRICTION};

use serde::{Deserialize, Serialize};

/// A whole scene: settings, wind, colliders (ground, spheres, boxes, capsules), cloths and ropes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    #[serde(default)]
    pub sim: SimSettings,
    #[serde(default)]
    pub wind: Wind,
    #[serde(default)]
    pub light: Light,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<Ground>,
    #[serde(default, rename = "sphere", skip_serializing_if = "Vec::is_empty")]
    pub spheres: Vec<Sphere>,
    #[serde(default, rename = "box", skip_serializing_if = "Vec::is_empty")]
    pub boxes: Vec<BoxCollider>,
    #[serde(default, rename = "capsule", skip_serializing_if = "Vec::is_empty")]
    pub capsules: Vec<Capsule>,
    #[serde(default, rename = "mesh", skip_serializing_if = "Vec::is_empty")]
    pub meshes: Vec<MeshCollider>,
    #[serde(default, rename = "cloth", skip_serializing_if = "Vec::is_empty")]
    pub cloths: Vec<Cloth>,
    #[serde(default, rename = "rope", skip_serializing_if = "Vec::is_empty")]
    pub ropes: Vec<Rope>,
    #[serde(default, rename = "mesh_cloth", skip_serializing_if = "Vec::is_empty")]
    pub mesh_cloths: Vec<MeshCloth>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimSettings {
    /// Substeps per frame.
    #[serde(default = "defaults::substeps")]
    pub substeps: u32,
    /// Simulated time per frame [s].
    #[serde(default = "defaults::frame_dt")]
    pub frame_dt: f64,
    /// Gravitational acceleration [m/s^2].
    #[serde(default = "defaults::gravity")]
    pub gravity: [f64; 3],
    /// How self-collision finds candidate pairs: "hash" (spatial hash, O(N)) or "brute_force"
    /// (every pair, O(N^2), the reference).
    #[serde(default)]
    pub self_collision: crate::sim::model::SelfCollisionMethod,
    /// The runtime guard stops the simulation when a particle moves faster than this [m/s].
    #[serde(default = "defaults::max_speed")]
    pub max_speed: f64,
    /// ... or when a structural spring stretches past this strain (1: twice its rest length;
    /// 0: no check).
    #[serde(default = "defaults::max_strain")]
    pub max_strain: f64,
    /// ... or when its total energy grows, with nothing supplying any (no wind, no moving
    /// collider), by more than this fraction of its scale (weight times size; 0: no check).
    #[serde(default = "defaults::max_energy_gain")]
    pub max_energy_gain: f64,
    /// "symplectic_euler" (the paper's), "verlet", "xpbd", "implicit", or "auto": the cheapest
    /// method and substep count that meets `tolerance`, from a short calibration.
    #[serde(default)]
    pub integrator: IntegratorChoice,
    /// Solver iterations per substep (the iterative methods: xpbd, implicit, vbd).
    #[serde(default = "defaults::iterations")]
    pub iterations: u32,
    /// XPBD (`xpbd`, the spring classes): over-relaxation of each Gauss-Seidel correction,
    /// between 0 and 2.
    #[serde(default = "defaults::one")]
    pub relaxation: f64,
    /// With integrator = "auto": the largest acceptable position error, as a fraction of the
    /// object's size (RMS over particles, after the calibration time).
    #[serde(default = "defaults::tolerance")]
    pub tolerance: f64,
    /// Whether objects touch each other (cloth-cloth, cloth-rope, rope-rope), each pair kept
    /// the sum of their contact radii apart (a cloth's collision_margin, a rope's radius). Only
    /// scenes with more than one object pay for it.
    #[serde(default = "defaults::yes")]
    pub inter_object: bool,
    /// Whether two cloths touching each other also keep their edges (rows, columns, diagonals)
    /// apart, so that no edge of one passes through the other where no vertex touches. Off,
    /// only where one of them keeps its own edges apart (self_contact "triangles_and_edges").
    #[serde(default = "defaults::yes")]
    pub inter_object_edges: bool,
    /// Passes over a cloth's contacts with its own triangles each substep (self_contact =
    /// "triangles"): a layer landing on several others is stopped within the substep only
    /// with several.
    #[serde(default = "defaults::contact_iterations")]
    pub contact_iterations: u32,
}

/// `sim.integrator`: a method (by its label in `sim::integrator`'s table), or "auto".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum IntegratorChoice {
    Method(crate::sim::model::Integrator),
    Auto,
}

impl Default for IntegratorChoice {
    fn default() -> Self {
        IntegratorChoice::Method(Default::default())
    }
}

impl IntegratorChoice {
    /// Every choice: the methods in the table's order, then "auto".
    pub fn all() -> Vec<IntegratorChoice> {
        let methods = crate::sim::model::Integrator::ALL.map(IntegratorChoice::Method);
        methods.into_iter().chain([IntegratorChoice::Auto]).collect()
    }

    /// The method, or None for "auto".
    pub fn method(self) -> Option<crate::sim::model::Integrator> {
        match self {
            IntegratorChoice::Method(m) => Some(m),
            IntegratorChoice::Auto => None,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            IntegratorChoice::Method(m) => m.label(),
            IntegratorChoice::Auto => "auto",
        }
    }
}

impl TryFrom<String> for IntegratorChoice {
    type Error = String;

    fn try_from(name: String) -> Result<Self, String> {
        if name == "auto" {
            return Ok(IntegratorChoice::Auto);
        }
        crate::sim::model::Integrator::from_label(&name).map(IntegratorChoice::Method).ok_or_else(|| {
            let names: Vec<&str> = Self::all().into_iter().map(Self::label).collect();
            format!("unknown integrator \"{name}\": expected one of {}", names.join(", "))
        })
    }
}

impl From<IntegratorChoice> for String {
    fn from(c: IntegratorChoice) -> String {
        c.label().to_string()
    }
}

impl Default for SimSettings {
    fn default() -> Self {
        Self {
            substeps: defaults::substeps(),
            frame_dt: defaults::frame_dt(),
            gravity: defaults::gravity(),
            self_collision: Default::default(),
            max_speed: defaults::max_speed(),
            max_strain: defaults::max_strain(),
            max_energy_gain: defaults::max_energy_gain(),
            integrator: Default::default(),
            iterations: defaults::iterations(),
            relaxation: 1.0,
            tolerance: defaults::tolerance(),
            inter_object: true,
            inter_object_edges: true,
            contact_iterations: defaults::contact_iterations(),
        }
    }
}

/// The wind: a cone from `origin` along `direction`. At `reference_distance` along the axis it
/// is full within `full_force_radius` of the axis and falls to zero over a further
/// `attenuation_radius`. As the paper has it (`model = "paper"`), a force on every particle
/// whatever the cloth's orientation and speed; aerodynamic (the default), air flowing at
/// `speed` along the axis, with `turbulence` (`sim::turbulence`) added, that pushes on the
/// cloth's area, by the air's velocity relative to the cloth: normal drag 1/2 density
/// normal_drag |u_n| u_n per unit area, tangential drag likewise with `tangential_drag`, and on
/// a cloth lift 1/2 density lift sin(2 alpha) |u|^2 per unit area across the air (alpha the
/// angle of attack).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wind {
    #[serde(default)]
    pub enabled: bool,
    #[serde(default)]
    pub model: WindKind,
    /// Air speed at full strength [m/s] (aerodynamic).
    #[serde(default = "defaults::wind_speed")]
    pub speed: f64,
    /// Air density [kg/m^3] (aerodynamic).
    #[serde(default = "defaults::air_density")]
    pub density: f64,
    /// Drag coefficient across the cloth (a flat plate's, about 1.2) (aerodynamic).
    #[serde(default = "defaults::normal_drag")]
    pub normal_drag: f64,
    /// Drag coefficient along the cloth (skin friction, a few hundredths) (aerodynamic).
    #[serde(default = "defaults::tangential_drag")]
    pub tangential_drag: f64,
    /// Lift coefficient of a cloth at 45 degrees to the air (0: drag only) (aerodynamic).
    #[serde(default)]
    pub lift: f64,
    /// Root-mean-square speed of the air's turbulence [m/s] (0: a steady wind) (aerodynamic).
    #[serde(default)]
    pub turbulence: f64,
    /// Size of the turbulence's eddies [m] (aerodynamic).
    #[serde(default = "defaults::turbulence_scale")]
    pub turbulence_scale: f64,
    /// How fast the eddies change as the wind carries them [Hz] (aerodynamic).
    #[serde(default = "defaults::turbulence_frequency")]
    pub turbulence_frequency: f64,
    /// Picks the turbulence's eddies: the same seed, the same wind.
    #[serde(default = "defaults::seed")]
    pub seed: u32,
    /// Apex of the cone [m].
    #[serde(default)]
    pub origin: [f64; 3],
    /// Axis of the cone (normalised on load).
    #[serde(default = "defaults::wind_direction")]
    pub direction: [f64; 3],
    /// Force on each particle at full strength [N].
    #[serde(default)]
    pub force: f64,
    /// [m]
    #[serde(default = "defaults::one")]
    pub full_force_radius: f64,
    /// [m]
    #[serde(default = "defaults::one")]
    pub attenuation_radius: f64,
    /// [m]
    #[serde(default = "defaults::one")]
    pub reference_distance: f64,
}

impl Default for Wind {
    fn default() -> Self {
        Self {
            enabled: false,
            model: WindKind::Aerodynamic,
            speed: defaults::wind_speed(),
            density: defaults::air_density(),
            normal_drag: defaults::normal_drag(),
            tangential_drag: defaults::tangential_drag(),
            lift: 0.0,
            turbulence: 0.0,
            turbulence_scale: defaults::turbulence_scale(),
            turbulence_frequency: defaults::turbulence_frequency(),
            seed: defaults::seed(),
            origin: [0.0; 3],
            direction: defaults::wind_direction(),
            force: 0.0,
            full_force_radius: 1.0,
            attenuation_radius: 1.0,
            reference_distance: 1.0,
        }
    }
}

/// What a cloth's self-collision keeps apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SelfContact {
    /// Particles from particles, closer than the self-collision distance (the paper's: layers
    /// pass through each other between particles).
    Particles,
    /// Particles from triangles, equal and opposite: the distance is a thickness.
    #[default]
    Triangles,
    /// As `Triangles`, and the grid's edges from its edges (layers crossing edge over edge,
    /// which no particle touches: a strip piling on its own sharp folds), at several times the
    /// cost (docs/PERFORMANCE.md, "Edge-edge self-contact").
    TrianglesAndEdges,
}

impl SelfContact {
    fn is_triangles(&self) -> bool {
        *self == SelfContact::Triangles
    }

    /// Every choice, in the editor's order.
    pub const ALL: [SelfContact; 3] =
        [SelfContact::Particles, SelfContact::Triangles, SelfContact::TrianglesAndEdges];

    /// Whether it keeps particles from triangles.
    pub fn triangles(self) -> bool {
        self != SelfContact::Particles
    }
}

/// How the wind acts on the cloth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WindKind {
    /// The paper's: `force` newtons on every particle in the cone.
    Paper,
    /// Drag from the air's velocity relative to the cloth, on its area and orientation.
    #[default]
    Aerodynamic,
}

/// The scene light (drawing only).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    /// [m]
    #[serde(default = "defaults::light_position")]
    pub position: [f64; 3],
    /// Linear RGB, 0..1.
    #[serde(default = "defaults::white")]
    pub color: [f64; 3],
    /// Ambient fraction of the material colour, 0..1.
    #[serde(default = "defaults::ambient")]
    pub ambient: f64,
}

impl Default for Light {
    fn default() -> Self {
        Self { position: defaults::light_position(), color: defaults::white(), ambient: defaults::ambient() }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sphere {
    /// [m]
    pub center: [f64; 3],
    /// [m]
    pub radius: f64,
    /// How it moves (absent: it stays put).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Motion>,
}

/// How a collider moves: a kinematic body, whose surface's velocity its contacts' friction
/// follows. At most one of `velocity` and `keyframes`, and a steady turn about its centre
/// (`angular_velocity`), with either or alone. As an object's `pin_motion`, how its pinned
/// particles move, all together: a velocity, or keyframes of their displacement [t, dx, dy,
/// dz] (only its change counts: the pins start where they are placed), a turn about `pivot`
/// (pins only: steady, `angular_velocity`, or keyed, `rotation_keyframes`), or a turn with
/// either.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Motion {
    /// A constant velocity [m/s].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<[f64; 3]>,
    /// Where its centre (a capsule's midpoint) is over time: rows of [t (s), x, y, z (m)], t
    /// increasing; joined by `interpolation`, held before the first and after the last.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keyframes: Vec<[f64; 4]>,
    /// How the keyframes are joined: `Interpolation`.
    #[serde(default, skip_serializing_if = "Interpolation::is_linear")]
    pub interpolation: Interpolation,
    /// A steady turn about the vector's direction at its length [degrees/s]: a collider's
    /// about its centre (a capsule's midpoint; with or without a velocity or keyframes, which
    /// carry the centre), pins' about `pivot`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity: Option<[f64; 3]>,
    /// Pins only: their turn over time about `pivot`, rows of [t (s), rx, ry, rz (degrees)]:
    /// the turn from the start about x, then y, then z (as a box's `rotation`), t increasing;
    /// each angle joined by `interpolation`, held before the first row and after the last.
    /// Not with `angular_velocity`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rotation_keyframes: Vec<[f64; 4]>,
    /// Pins only: what they turn about where it is at the start [m] (default: the pinned
    /// particles' centre); the translation carries it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pivot: Option<[f64; 3]>,
}

/// How a motion's keyframes are joined: "linear" (the default: straight at a constant speed
/// from key to key) or "smooth" (a monotone cubic: its velocity continuous, at rest at the first
/// and last key and where it turns back, never past a key; `sim::collider::smooth_offset`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Interpolation {
    #[default]
    Linear,
    Smooth,
}

impl Interpolation {
    fn is_linear(&self) -> bool {
        *self == Interpolation::Linear
    }
}

/// The ground: everything below y = height is solid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Ground {
    /// [m]
    #[serde(default)]
    pub height: f64,
    /// Coulomb friction coefficient mu on contact (default: each object's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
}

/// An oriented box collider.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxCollider {
    /// [m]
    pub center: [f64; 3],
    /// Half the box's size along its own axes [m].
    pub half_extents: [f64; 3],
    /// Rotation about x, then y, then z [degrees].
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub rotation: [f64; 3],
    /// How it moves (absent: it stays put).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Motion>,
}

/// A capsule collider: the points within `radius` of the segment from `start` to `end`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Capsule {
    /// [m]
    pub start: [f64; 3],
    /// [m]
    pub end: [f64; 3],
    /// [m]
    pub radius: f64,
    /// How it moves (absent: it stays put).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Motion>,
}

/// A triangle mesh collider from a file (Wavefront OBJ, glTF 2.0 `.gltf` or `.glb`): its
/// triangles (quads and polygons split into fans) placed by `center` and `rotation`, kept
/// outside by the winding of its triangles (counter-clockwise seen from outside) where it is
/// closed, on their front where it is open.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshCollider {
    /// The file; a relative path is the preset's folder's (made absolute when loaded).
    pub file: String,
    /// Where the file's origin goes [m].
    #[serde(default)]
    pub center: [f64; 3],
    /// Rotation about x, then y, then z [degrees], about its origin.
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub rotation: [f64; 3],
    /// The file's units in metres (0.01 for a file in centimetres).
    #[serde(default = "defaults::one", skip_serializing_if = "is_one")]
    pub scale: f64,
    /// Its surface offset outwards from the triangles [m].
    #[serde(default, skip_serializing_if = "is_zero")]
    pub thickness: f64,
    /// How far from its triangles particles are found [m]: a particle more than this inside
    /// a closed mesh is not pushed out. More than every object's margin.
    #[serde(default = "defaults::mesh_reach")]
    pub reach: f64,
    /// How it moves (absent: it stays put).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Motion>,
    /// The file's triangles, read when the preset loads.
    #[serde(skip)]
    pub loaded: Option<std::sync::Arc<mesh_file::MeshFile>>,
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn is_zero3(v: &[f64; 3]) -> bool {
    *v == [0.0; 3]
}

impl Scene {
    /// The widest margin any object keeps from colliders: a cloth's `collision_margin`, a
    /// rope's `radius` (0 without objects).
    pub fn widest_margin(&self) -> f64 {
        let margins =
            self.cloths.iter().map(|c| c.collision_margin).chain(self.ropes.iter().map(|r| r.radius));
        margins.fold(0.0, f64::max)
    }

    /// Removes every collider: the ground, spheres, boxes and capsules.
    pub fn clear_colliders(&mut self) {
        self.ground = None;
        self.spheres.clear();
        self.boxes.clear();
        self.capsules.clear();
        self.meshes.clear();
    }
}

/// One value per spring type.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerSpring {
    pub structural: f64,
    pub shear: f64,
    pub bending: f64,
}

impl PerSpring {
    pub fn to_array(self) -> [f64; 3] {
        [self.structural, self.shear, self.bending]
    }
}

/// How a cloth grid is laid out at the start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Orientation {
    /// Columns along +x, rows along -y (a hanging curtain or flag).
    #[default]
    Vertical,
    /// Columns along +x, rows along +z (a towel lying flat).
    Horizontal,
}

/// Which cloth particles are pinned, besides any listed in `pinned`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum ClothPins {
    #[default]
    None,
    TopRow,
    TopCorners,
    LeftColumn,
    Corners,
}

/// Which rope nodes are pinned, besides any listed in `pinned`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RopePins {
    #[default]
    None,
    First,
    Last,
    Both,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cloth {
    pub name: String,
    /// Particles along a row and along a column: [columns, rows].
    pub resolution: [u32; 2],
    /// Width and height of the grid [m].
    pub size: [f64; 2],
    /// Position of the particle at column 0, row 0 [m].
    pub origin: [f64; 3],
    #[serde(default)]
    pub orientation: Orientation,
    /// Mass of each particle [kg].
    pub mass: f64,
    /// Spring stiffness per type [N/m].
    pub stiffness: PerSpring,
    /// Rest length per type as a multiple of the grid distance (1 = the initial layout).
    #[serde(default = "defaults::rest_scale")]
    pub rest_scale: PerSpring,
    /// Dashpot along every spring [N s/m].
    #[serde(default)]
    pub damping: f64,
    /// Stokes drag coefficient [N s/m].
    #[serde(default)]
    pub drag: f64,
    /// Maximum elongation of structural and shear springs, as a fraction of rest length.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stretch_limit: Option<f64>,
    /// Coulomb friction coefficient mu against colliders (0: ice; a cloth on wood about 0.4).
    #[serde(default)]
    pub friction: f64,
    /// Distance kept from sphere surfaces [m].
    #[serde(default = "defaults::margin")]
    pub collision_margin: f64,
    #[serde(default)]
    pub self_collision: bool,
    /// Self-collision distance [m]; default half the smaller grid spacing.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_collision_distance: Option<f64>,
    /// What self-collision keeps apart: "triangles" (the default: the cloth's particles from
    /// its triangles, the distance a thickness, no layer passing through another where a few
    /// layers meet), "triangles_and_edges" (and its edges from its edges: piles of sharp folds
    /// too, at several times the cost) or "particles" (the paper's: particles from particles,
    /// at a fraction of the cost, but layers pass between them).
    #[serde(default, skip_serializing_if = "SelfContact::is_triangles")]
    pub self_contact: SelfContact,
    #[serde(default)]
    pub pin: ClothPins,
    /// Further pinned particles as [column, row].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pinned: Vec<[u32; 2]>,
    /// Further pinned particles: those placed inside this box.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_box: Option<PinBox>,
    /// How the pinned particles move together (absent: they stay put): `PinMotion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_motion: Option<Motion>,
    /// Further groups of pinned particles, each with a motion of its own (`[[cloth.pin_group]]`).
    #[serde(default, rename = "pin_group", skip_serializing_if = "Vec::is_empty")]
    pub pin_groups: Vec<PinGroup<[u32; 2]>>,
    /// Linear RGB of the side the normals point to, 0..1 (drawing only).
    #[serde(default = "defaults::cloth_color")]
    pub color: [f64; 3],
    /// Linear RGB of the other side, 0..1 (drawing only).
    #[serde(default = "defaults::cloth_back_color")]
    pub back_color: [f64; 3],
}

/// A cloth made from a mesh file (Wavefront OBJ, glTF 2.0 `.gltf` or `.glb`): a particle at
/// each vertex, springs along its edges, across its quads and across its shared edges
/// (`sim::cloth_mesh`), placed by `center`, `rotation` and `scale` as a mesh collider is. Its
/// mass is spread evenly over its vertices, as a grid's is over its particles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshCloth {
    pub name: String,
    /// The file; a relative path is the preset's folder's (made absolute when loaded).
    pub file: String,
    /// Where the file's origin goes [m].
    #[serde(default)]
    pub center: [f64; 3],
    /// Rotation about x, then y, then z [degrees], about its origin.
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub rotation: [f64; 3],
    /// The file's units in metres (0.01 for a file in centimetres).
    #[serde(default = "defaults::one", skip_serializing_if = "is_one")]
    pub scale: f64,
    /// Vertices closer than this are one particle (a file that repeats its vertices along its
    /// texture seams, as glTF does) [m]; 0: those at the same place.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub weld: f64,
    /// Areal density [kg/m^2]: the cloth's mass is this times its area.
    pub density: f64,
    /// Spring stiffness per type [N/m].
    pub stiffness: PerSpring,
    /// Rest length per type as a multiple of its length in the mesh.
    #[serde(default = "defaults::rest_scale")]
    pub rest_scale: PerSpring,
    /// Dashpot along every spring [N s/m].
    #[serde(default)]
    pub damping: f64,
    /// Stokes drag coefficient [N s/m].
    #[serde(default)]
    pub drag: f64,
    /// Maximum elongation of structural and shear springs (the mesh's edges and a quad's
    /// diagonals), as a fraction of rest length.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stretch_limit: Option<f64>,
    /// Coulomb friction coefficient mu against colliders.
    #[serde(default)]
    pub friction: f64,
    /// Distance kept from collider surfaces [m].
    #[serde(default = "defaults::margin")]
    pub collision_margin: f64,
    /// Keeps its particles from its own triangles (a grid cloth's "triangles" self-contact).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub self_collision: bool,
    /// Self-collision distance, a thickness [m]; default half the mean edge, and below every
    /// vertex's distance at rest from the triangles outside its one-ring.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_collision_distance: Option<f64>,
    /// Pinned particles by vertex index (after welding: the file's order, less the vertices
    /// merged into earlier ones).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pinned: Vec<u32>,
    /// Further pinned particles: those placed inside this box.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_box: Option<PinBox>,
    /// How the pinned particles move together (absent: they stay put).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_motion: Option<Motion>,
    /// Further groups of pinned particles, each with a motion of its own.
    #[serde(default, rename = "pin_group", skip_serializing_if = "Vec::is_empty")]
    pub pin_groups: Vec<PinGroup<u32>>,
    /// Seams (`[[mesh_cloth.seam]]`): pairs of vertex runs sewn together.
    #[serde(default, rename = "seam", skip_serializing_if = "Vec::is_empty")]
    pub seams: Vec<Seam>,
    /// Border vertices this near another part of its border are sewn to the nearest such
    /// (seams found, as `seam`s are given) [m]; 0: none. Less than its border's edges.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub sew: f64,
    /// The seams' springs' stiffness [N/m] (rest length zero): how fast they close.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub seam_stiffness: f64,
    /// Linear RGB of the side the normals point to, 0..1 (drawing only).
    #[serde(default = "defaults::cloth_color")]
    pub color: [f64; 3],
    /// Linear RGB of the other side, 0..1 (drawing only).
    #[serde(default = "defaults::cloth_back_color")]
    pub back_color: [f64; 3],
    /// The file's faces, read when the preset loads.
    #[serde(skip)]
    pub loaded: Option<std::sync::Arc<mesh_file::FaceFile>>,
}

/// A seam of a mesh cloth, as Marvelous Designer's: vertex `from[k]` is sewn to vertex `to[k]`
/// by a spring of rest length zero, so flat panels close into a garment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seam {
    /// One side's vertices (indices, in order along the seam).
    pub from: Vec<u32>,
    /// The other side's, as many, in the order they meet `from`'s.
    pub to: Vec<u32>,
}

impl MeshCloth {
    /// Its seams, each as its vertex pairs in order along it.
    pub fn seam_pairs(&self) -> Vec<Vec<[u32; 2]>> {
        self.seams.iter().map(|s| s.from.iter().zip(&s.to).map(|(&a, &b)| [a, b]).collect()).collect()
    }

    /// Whether a particle is pinned (by `pinned` or `pin_box`): what a `pin_motion` needs.
    pub fn has_pins(&self) -> bool {
        !self.pinned.is_empty() || self.pin_box.is_some()
    }

    /// Its model: the file's vertices welded and placed, its springs and triangles; the error
    /// says what is wrong with the mesh or the pins.
    pub fn build(&self) -> Result<crate::sim::model::ObjectModel, String> {
        build::mesh_cloth(self)
    }

    /// Adds a pin group holding one free particle (a small box about it; first a corner of its
    /// bounding box's, else any), as `Cloth::add_pin_group` does; false where it has all its
    /// groups or does not build.
    pub fn add_pin_group(&mut self) -> bool {
        let Ok(o) = self.build() else { return false };
        let Some(mesh) = o.mesh.as_ref() else { return false };
        // (its particles are at least its shortest edge apart, unless welded closer)
        let shortest =
            mesh.springs.iter().filter(|s| s.kind == 0).map(|s| s.rest).fold(f64::INFINITY, f64::min);
        let (lo, hi) = crate::sim::collider_mesh::bounds(&o.positions);
        let nearest = |corner: glam::DVec3| {
            (0..o.positions.len())
                .min_by(|&a, &b| o.positions[a].distance(corner).total_cmp(&o.positions[b].distance(corner)))
        };
        let corners: Vec<usize> =
            [lo, hi, glam::DVec3::new(lo.x, hi.y, lo.z), glam::DVec3::new(hi.x, lo.y, hi.z)]
                .into_iter()
                .filter_map(nearest)
                .collect();
        let Some(pin_box) = free_box(&o, &corners, shortest) else { return false };
        self.pin_groups.push(PinGroup { pinned: Vec::new(), pin_box: Some(pin_box), pin_motion: None });
        true
    }
}

/// A further group of an object's pinned particles that moves by a motion of its own (as
/// Houdini Vellum's pin groups; two handles turning opposite ways twist a cloth): those listed
/// (`P`: [column, row] on a cloth, a node index on a rope) and those inside `pin_box`. A
/// particle follows one group: its object's own pins (`pin`, `pinned`, `pin_box`) or one entry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PinGroup<P> {
    #[serde(default = "Vec::new", skip_serializing_if = "Vec::is_empty")]
    pub pinned: Vec<P>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_box: Option<PinBox>,
    /// How they move (absent: they stay put), as the object's `pin_motion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_motion: Option<Motion>,
}

/// A box a quarter of `spacing` across about a particle of `o` that nothing pins: the first
/// free one of `first`, else of all; none where the object has all its pin groups
/// (`Cloth::add_pin_group`). Particles are at least `spacing` apart, so it holds that one.
fn free_box(o: &crate::sim::model::ObjectModel, first: &[usize], spacing: f64) -> Option<PinBox> {
    if o.pin_groups.len() + 1 >= crate::sim::model::PIN_GROUPS {
        return None;
    }
    let free = |i: &usize| *i < o.positions.len() && !o.pinned[*i];
    let i = first.iter().copied().find(free).or_else(|| (0..o.positions.len()).find(free))?;
    let (x, r) = (o.positions[i], 0.125 * spacing);
    Some(PinBox { min: (x - r).to_array(), max: (x + r).to_array() })
}

/// An axis-aligned box of a cloth's or rope's `pin_box`: the particles placed inside it (its
/// faces included) are pinned.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PinBox {
    /// Its lowest corner [m].
    pub min: [f64; 3],
    /// Its highest corner [m].
    pub max: [f64; 3],
}

impl PinBox {
    pub fn contains(&self, x: glam::DVec3) -> bool {
        (0..3).all(|k| self.min[k] <= x[k] && x[k] <= self.max[k])
    }
}

impl Cloth {
    /// Whether a particle is pinned (by `pin`, `pinned` or `pin_box`, which validation keeps
    /// from being empty): what a `pin_motion` needs.
    pub fn has_pins(&self) -> bool {
        self.pin != ClothPins::None || !self.pinned.is_empty() || self.pin_box.is_some()
    }

    /// Each particle: whether `pin` or `pin_box` pins it (not the `pinned` list alone).
    pub fn pinned_by_rule(&self) -> Vec<bool> {
        build::cloth(&Cloth { pinned: Vec::new(), ..self.clone() }).pinned
    }

    /// Adds a pin group (no motion yet) holding one particle that nothing pins, by a small box
    /// about it: a corner where one is free (the last first), else the first free particle.
    /// False where none is free or the object has all its groups
    /// (`sim::model::PIN_GROUPS`).
    pub fn add_pin_group(&mut self) -> bool {
        let [cols, rows] = self.resolution.map(|n| n as usize);
        let corners = [cols * rows - 1, cols - 1, cols * (rows - 1), 0];
        let [x, y] = self.spacing();
        let Some(pin_box) = free_box(&build::cloth(self), &corners, x.min(y)) else { return false };
        self.pin_groups.push(PinGroup { pinned: Vec::new(), pin_box: Some(pin_box), pin_motion: None });
        true
    }

    /// Rest distance between grid neighbours along columns and rows [m].
    pub fn spacing(&self) -> [f64; 2] {
        [self.size[0] / (self.resolution[0] - 1) as f64, self.size[1] / (self.resolution[1] - 1) as f64]
    }

    /// The self-collision distance when none is given: half the smaller grid spacing [m].
    pub fn default_self_collision_distance(&self) -> f64 {
        let [x, y] = self.spacing();
        0.5 * x.min(y)
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rope {
    pub name: String,
    /// Number of nodes.
    pub nodes: u32,
    /// First and last node at the start [m]; nodes are evenly spaced between them.
    pub start: [f64; 3],
    pub end: [f64; 3],
    /// Mass of each node [kg].
    pub mass: f64,
    /// Stiffness of the springs between neighbouring nodes [N/m].
    pub stiffness: f64,
    /// Stiffness of the springs between nodes two apart [N/m].
    #[serde(default)]
    pub bending_stiffness: f64,
    /// Rest length as a multiple of the initial node spacing.
    #[serde(default = "defaults::one")]
    pub rest_scale: f64,
    /// Dashpot along every spring [N s/m].
    #[serde(default)]
    pub damping: f64,
    /// Stokes drag coefficient [N s/m].
    #[serde(default)]
    pub drag: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stretch_limit: Option<f64>,
    /// Coulomb friction coefficient mu against colliders.
    #[serde(default)]
    pub friction: f64,
    /// Tube radius [m]; also the distance kept from sphere surfaces.
    pub radius: f64,
    /// Offsets of the 8 tube vertices around a node in (side, up) units of the radius; default a circle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring_weights: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    pub self_collision: bool,
    /// Self-collision distance [m]; default the tube diameter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_collision_distance: Option<f64>,
    #[serde(default)]
    pub pin: RopePins,
    /// Further pinned node indices.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pinned: Vec<u32>,
    /// Further pinned nodes: those placed inside this box.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_box: Option<PinBox>,
    /// How the pinned nodes move together (absent: they stay put), as a cloth's `pin_motion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_motion: Option<Motion>,
    /// Further groups of pinned nodes, each with a motion of its own (`[[rope.pin_group]]`).
    #[serde(default, rename = "pin_group", skip_serializing_if = "Vec::is_empty")]
    pub pin_groups: Vec<PinGroup<u32>>,
    /// Linear RGB, 0..1 (drawing only).
    #[serde(default = "defaults::rope_color")]
    pub color: [f64; 3],
}

impl Rope {
    /// Whether a node is pinned (by `pin`, `pinned` or `pin_box`): what a `pin_motion` needs.
    pub fn has_pins(&self) -> bool {
        self.pin != RopePins::None || !self.pinned.is_empty() || self.pin_box.is_some()
    }

    /// Each node: whether `pin` or `pin_box` pins it (not the `pinned` list alone).
    pub fn pinned_by_rule(&self) -> Vec<bool> {
        build::rope(&Rope { pinned: Vec::new(), ..self.clone() }).pinned
    }

    /// `Cloth::add_pin_group` for a rope: its last node where free, then its first, then any.
    pub fn add_pin_group(&mut self) -> bool {
        let n = self.nodes as usize;
        let spacing = glam::DVec3::from_array(self.end).distance(glam::DVec3::from_array(self.start))
            / (n - 1).max(1) as f64;
        let Some(pin_box) = free_box(&build::rope(self), &[n - 1, 0], spacing) else { return false };
        self.pin_groups.push(PinGroup { pinned: Vec::new(), pin_box: Some(pin_box), pin_motion: None });
        true
    }

    /// Its springs' stiffness as a model's [structural, shear, bending]: a rope has no shear.
    pub fn stiffness_array(&self) -> [f64; 3] {
        [self.stiffness, 0.0, self.bending_stiffness]
    }
}

mod defaults {
    pub fn substeps() -> u32 {
        16
    }
    pub fn frame_dt() -> f64 {
        1.0 / 60.0
    }
    pub fn gravity() -> [f64; 3] {
        [0.0, -9.81, 0.0]
    }
    pub fn max_speed() -> f64 {
        100.0
    }
    pub fn max_strain() -> f64 {
        1.0
    }
    pub fn max_energy_gain() -> f64 {
        0.5
    }
    pub fn iterations() -> u32 {
        10
    }
    pub fn mesh_reach() -> f64 {
        0.03
    }
    pub fn contact_iterations() -> u32 {
        crate::sim::model::DEFAULT_CONTACT_ITERATIONS
    }
    pub fn yes() -> bool {
        true
    }

    pub fn tolerance() -> f64 {
        0.01
    }
    pub fn air_density() -> f64 {
        1.2
    }
    pub fn normal_drag() -> f64 {
        1.2
    }
    pub fn tangential_drag() -> f64 {
        0.02
    }
    pub fn wind_speed() -> f64 {
        5.0
    }
    pub fn turbulence_scale() -> f64 {
        0.5
    }
    pub fn turbulence_frequency() -> f64 {
        1.0
    }
    pub fn seed() -> u32 {
        1
    }
    pub fn wind_direction() -> [f64; 3] {
        [0.0, 0.0, -1.0]
    }
    pub fn one() -> f64 {
        1.0
    }
    pub fn margin() -> f64 {
        0.01
    }
    pub fn light_position() -> [f64; 3] {
        [2.0, 4.0, 3.0]
    }
    pub fn white() -> [f64; 3] {
        [1.0, 1.0, 1.0]
    }
    pub fn ambient() -> f64 {
        0.25
    }
    pub fn cloth_color() -> [f64; 3] {
        [0.75, 0.18, 0.16]
    }
    pub fn cloth_back_color() -> [f64; 3] {
        [0.85, 0.72, 0.45]
    }
    pub fn rope_color() -> [f64; 3] {
        [0.72, 0.58, 0.36]
    }
    pub fn rest_scale() -> super::PerSpring {
        super::PerSpring { structural: 1.0, shear: 1.0, bending: 1.0 }
    }
}
