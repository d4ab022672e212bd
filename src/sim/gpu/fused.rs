//! Which objects run every substep of a frame in one workgroup (`glsl/fused.comp`), and the
//! shared memory layout that kernel is specialized with; and the features a scene compiles in.
//!
//! The fused kernel keeps each particle's state in the registers of the thread that owns it
//! and what its neighbours read in shared memory: positions (12 bytes a particle), pin bits,
//! and a scratch area that holds the velocities the spring dashpots read during physics (in
//! passes when they do not all fit) and the self-collision hash during the constraints. An
//! object takes that path when the layout fits the device's shared memory per workgroup (48 KiB
//! on NVIDIA: a 50 x 50 cloth with dashpots and the hash fits; 32 KiB on lavapipe); others run
//! a dispatch per stage. The iterative integrators also keep their displacements there (in the
//! scratch area, 12 bytes a particle, between the physics and the constraints); VBD, where
//! those do not fit, keeps the iterates p in place of the bases and the displacements in half
//! precision, 8 bytes a particle, none without dashpots (`FusedShape::compact`).

use super::object::GpuObject;
use crate::sim::gpu_types::{
    FEATURE_BENDING, FEATURE_DAMPING, FEATURE_SELF, FEATURE_SHEAR, FEATURE_STRETCH, FEATURE_STRUCTURAL,
    FEATURE_WIND,
};
use crate::sim::integrator::{Scheme, Sweep};
use crate::sim::model::{Integrator, ObjectModel, SelfCollisionMethod, SimModel};

/// Particles one thread of the fused kernel owns at most (`MAX_SLOTS` in the shader).
pub const FUSED_SLOTS: u32 = 4;
/// Particles per thread the fused path takes by default. Measured on an H100
/// (docs/PERFORMANCE.md, "Fused substeps"): with one particle per thread ropes of 256 to
/// 1,024 nodes run 2 to 3 times faster fused than per stage and cloths of 256 to 1,024
/// particles within -10% to +15%; with two or three per thread one workgroup's latency chain
/// is longer than the per-stage dispatches (a 50 x 50 cloth: 0.236 vs 0.176 ms per frame).
pub const FUSED_DEFAULT_SLOTS: u32 = 1;
/// ... and for an object that self-collides through the hash: there the shared hash and the
/// contact lists beat the per-stage hash at every size that fits (the curtain: 0.410 against
/// 0.670 ms per frame; a 45 x 45 cloth with self-collision 0.276 against 0.506).
pub const FUSED_HASHED_SLOTS: u32 = FUSED_SLOTS;

/// Particles per thread the fused path takes by default for an object that an iterative method
/// sweeps as `sweep` (without the hash). Per stage, each pass of an iteration is a dispatch:
/// XPBD's 12 spring classes, VBD's 5 colours and the implicit method's CG passes run fused
/// wherever they fit (the H200, 10 substeps x 10 iterations, ms a frame per stage against fused
/// at two particles a thread: a 40 x 40 cloth XPBD 4.41 against 1.56, VBD 3.10 against 1.41,
/// the implicit method 1.41 against 1.20; docs/records/bench/h200/newton-rows/). XPBD by Jacobi makes
/// one pass over all particles an iteration, which one SM issues more slowly than the
/// per-stage dispatches spread over many (0.71 against 0.86): it takes the default.
fn solver_slots(sweep: Sweep) -> u32 {
    match sweep {
        Sweep::SpringClasses | Sweep::VertexColours | Sweep::NewtonCg => FUSED_SLOTS,
        Sweep::Jacobi => FUSED_DEFAULT_SLOTS,
    }
}

/// What the fused layouts are planned for: shared memory per workgroup [bytes] and particles
/// per thread at most (for objects that self-collide through the hash: `hashed_slots`; that an
/// iterative method solves: `solver_slots`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FusedLimits {
    pub shared_bytes: u32,
    pub slots: u32,
    pub hashed_slots: u32,
    /// ... for objects an iterative method solves without the hash (`None`: the method's own,
    /// `solver_slots`).
    pub solver_slots: Option<u32>,
    /// Substeps one dispatch of the fused kernel runs at most; a frame takes as many
    /// dispatches as it needs (u32::MAX: one).
    pub substeps_per_dispatch: u32,
}

/// Substeps a fused dispatch runs at most on a device that ends an invocation's loops after a
/// number of iterations (`DeviceInfo::loop_iteration_limit`: lavapipe, after which the
/// dispatch's writes are lost, silently): 8 stay well within the limit for the presets' scenes
/// and cost nothing measurable, where a dispatch a substep does (docs/design/fused.md, "Devices
/// with a loop limit", has the figures).
const LIMITED_SUBSTEPS_PER_DISPATCH: u32 = 8;
/// ... for an object whose contact search runs long loops: one. Edge-edge self-contact (its
/// edge pairs' search runs two loops of six a candidate, glsl/include/self_contact.glsl, and
/// reaches the limit within a few substeps of a dense fold) and a mesh cloth's self-collision
/// (each candidate triangle walks its corners' spring lists, `mesh_linked`).
const LIMITED_LONG_LOOP_SUBSTEPS_PER_DISPATCH: u32 = 1;

impl FusedLimits {
    /// `slots` particles per thread at most for every object.
    pub fn new(shared_bytes: u32, slots: u32) -> Self {
        Self {
            shared_bytes,
            slots,
            hashed_slots: slots,
            solver_slots: Some(slots),
            substeps_per_dispatch: u32::MAX,
        }
    }

    /// The device's shared memory, `FUSED_DEFAULT_SLOTS` and `FUSED_HASHED_SLOTS`; each
    /// iterative method's `solver_slots` except on a CPU driver, where one workgroup runs on
    /// one core (lavapipe, two cores: VBD on a 40 x 40 cloth, 10 iterations, 180 ms a frame
    /// per stage against 218 fused at two particles a thread).
    pub fn for_device(info: &crate::vk::DeviceInfo) -> Self {
        let cpu = info.kind == crate::vk::DeviceKind::Cpu;
        Self {
            shared_bytes: info.max_shared_memory,
            slots: FUSED_DEFAULT_SLOTS,
            hashed_slots: FUSED_HASHED_SLOTS,
            solver_slots: cpu.then_some(FUSED_DEFAULT_SLOTS),
            substeps_per_dispatch: u32::MAX,
        }
        .within(info)
    }

    /// These limits with `slots` particles per thread at most for every object (`None`: as
    /// they are).
    pub fn with_slots(self, slots: Option<u32>) -> Self {
        slots.map_or(self, |s| Self { slots: s, hashed_slots: s, solver_slots: Some(s), ..self })
    }

    /// These limits within the device's shared memory, its loop limit and the kernel's
    /// `FUSED_SLOTS`.
    pub fn within(self, info: &crate::vk::DeviceInfo) -> Self {
        let device_substeps = info.loop_iteration_limit.map_or(u32::MAX, |_| LIMITED_SUBSTEPS_PER_DISPATCH);
        Self {
            shared_bytes: self.shared_bytes.min(info.max_shared_memory),
            slots: self.slots.min(FUSED_SLOTS),
            hashed_slots: self.hashed_slots.min(FUSED_SLOTS),
            solver_slots: self.solver_slots.map(|s| s.min(FUSED_SLOTS)),
            substeps_per_dispatch: self.substeps_per_dispatch.min(device_substeps).max(1),
        }
    }

    /// Substeps one dispatch runs for fused objects whose `FEATURES` are `features`, in a frame
    /// of `substeps`: `substeps_per_dispatch`, one on a device with a loop limit where a
    /// cloth keeps edges from edges (a rope's segment pairs search two edges a candidate, not
    /// six) or a mesh cloth keeps particles from its triangles (each candidate triangle walks
    /// its corners' spring lists, `mesh_linked`; the limit counts a loop's iterations over the
    /// whole invocation).
    pub fn chunk(&self, mut features: impl Iterator<Item = u32>, substeps: u32) -> u32 {
        let limited = self.substeps_per_dispatch != u32::MAX;
        let long_loops = |f: u32| {
            use crate::sim::gpu_types::{has_cloth_edge_pairs, FEATURE_CLOTH_MESH, FEATURE_TRIANGLES};
            has_cloth_edge_pairs(f)
                || f & (FEATURE_CLOTH_MESH | FEATURE_TRIANGLES) == FEATURE_CLOTH_MESH | FEATURE_TRIANGLES
        };
        let most = if limited && features.any(long_loops) {
            self.substeps_per_dispatch.min(LIMITED_LONG_LOOP_SUBSTEPS_PER_DISPATCH)
        } else {
            self.substeps_per_dispatch
        };
        most.clamp(1, substeps.max(1))
    }
}

/// Threads of a fused workgroup at most (the Vulkan minimum of maxComputeWorkGroupInvocations
/// is 128; lavapipe and NVIDIA allow 1024).
const MAX_THREADS: u32 = 1024;
/// Shared memory left to the compiler's own use [bytes].
const SHARED_MARGIN: u32 = 256;
/// Fewest hash buckets worth a shared hash.
const MIN_BUCKETS: u32 = 32;
/// Entries of a particle's self-collision contact list (`LIST_ENTRIES` in glsl/include/lists.glsl,
/// the fused kernel's `LIST_MAX`): what is within the self-collision distance plus the skin
/// (`list_skin()`: that distance for particles, 0.75 of it for a cloth's triangles) and not left
/// out as a rest-state neighbour. A fuller
/// list is built again the next substep (as without lists).
pub const SELF_LIST_ENTRIES: u32 = 32;

/// The features object `o` uses in `model` (the `FEATURES` specialization constant): spring
/// types with stiffness or dashpots, dashpots, wind, the stretch limit, self-collision, each
/// collider type, colliders against edges (`sim::collider::edges_needed`).
pub fn features(o: &ObjectModel, model: &SimModel) -> u32 {
    let mut f = 0;
    for (bit, k) in [FEATURE_STRUCTURAL, FEATURE_SHEAR, FEATURE_BENDING].into_iter().zip(o.stiffness) {
        if k != 0.0 || o.damping != 0.0 {
            f |= bit;
        }
    }
    let uses = [
        (FEATURE_DAMPING, o.damping != 0.0),
        (FEATURE_WIND, model.wind.is_some()),
        (FEATURE_STRETCH, o.stretch_limit.is_some()),
        (FEATURE_SELF, o.self_distance.is_some()),
        (crate::sim::gpu_types::FEATURE_TRIANGLES, o.self_distance.is_some() && o.has_triangles()),
        (crate::sim::gpu_types::FEATURE_EDGE_PAIRS, o.self_distance.is_some() && o.has_edge_pairs()),
        (crate::sim::gpu_types::FEATURE_SEGMENT_PAIRS, o.self_distance.is_some() && o.has_segment_pairs()),
    ];
    let f = uses.into_iter().filter(|(_, on)| *on).fold(f, |f, (bit, _)| f | bit);
    let f = if model.inter_object_contact() { f | crate::sim::gpu_types::FEATURE_CONTACT } else { f };
    let f = if crate::sim::collider::edges_needed(o, &model.colliders) {
        f | crate::sim::gpu_types::FEATURE_EDGES
    } else {
        f
    };
    let f = if o.mesh.is_some() { f | crate::sim::gpu_types::FEATURE_CLOTH_MESH } else { f };
    f | crate::sim::collider::features(&model.colliders)
}

/// How one object's steps are compiled: the features it uses and its fused layout. Computed
/// once per object (`ObjectPlan::of`): the pipelines are created for it and the frame records
/// with it, so the two cannot disagree.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjectPlan {
    /// The `FEATURES` bits (`features`).
    pub features: u32,
    /// Its layout on the fused path, when it fits the limits (`FusedShape::plan`).
    pub fused: Option<FusedShape>,
}

impl ObjectPlan {
    pub fn of(o: &ObjectModel, model: &SimModel, limits: FusedLimits) -> Self {
        Self { features: features(o, model), fused: FusedShape::plan(o, model, limits) }
    }
}

/// The specialization of `fused.comp` for one object (`specialization`: ids 0, 4..=8, 10 to 12
/// from the layout; 1, 2, 3 and 9 from the integrator, its iterations and the features).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FusedShape {
    /// Workgroup size: a multiple of 32, at most 1024.
    pub threads: u32,
    pub particles: u32,
    /// Words of scratch: the largest of the velocity window, the hash, an iterative method's
    /// displacements (3 per particle; 2 when `compact`, 0 without dashpots) and what a free
    /// object's rigid start needs beyond the positions.
    pub scratch: u32,
    /// Shared hash buckets (a power of two; 1 without the hash).
    pub buckets: u32,
    /// Slots per physics pass (the velocity window covers `threads * pass_slots` particles).
    pub pass_slots: u32,
    /// Largest index distance from a particle to a spring neighbour (0 for a mesh cloth, whose
    /// one pass's window holds every particle).
    pub halo: u32,
    /// An iterative method at one iteration: the loop and XPBD's multipliers compiled out
    /// (`ONE_ITERATION`; another iteration count is another pipeline).
    pub one_iteration: bool,
    /// Entries of each particle's self-collision contact list (with the shared hash; else 0).
    pub list: u32,
    /// Words of the implicit method's dot products (`workgroup_sum`: two sets of a slot for
    /// every four threads; 2 for the other methods, their placeholder) and of a free object's
    /// rigid start's totals (`RIGID_SUMS` for the methods that start adaptively; else 1).
    pub reduce: u32,
    /// VBD's compact solve (`COMPACT` in the kernel), taken only where the displacements do
    /// not fit beside the bases: shared memory holds the iterates p (the neighbours' springs
    /// read p_i - p_j from them, as the explicit methods read positions) and the displacements
    /// as half floats of dx / h (2 words a particle; none without dashpots), which only the
    /// dashpots read (b/h n.(dx_i - dx_j): the neighbour's displacement rounded to 2^-11 of
    /// itself); each thread's own displacements stay f32 in registers, so a particle's velocity (dx / h) carries no
    /// rounding of its position. The other methods move a neighbour's displacement (XPBD's
    /// classes), read it at full precision in their springs (XPBD by Jacobi) or keep their
    /// directions there (the implicit method): they run per stage instead.
    pub compact: bool,
    /// Where the stretch limit's counts live in scratch (`STRETCH_AT`; four bits a
    /// particle): 0 without the limit, `STRETCH_PACKED` from its start, or `STRETCH_IN_LINKS`.
    /// No array of their own (scratch grows to n / 8 words where it was smaller), so the
    /// paper's curtain keeps its 2,048 buckets in 48 KiB.
    pub stretch_counts: u32,
}

/// The sums of a free object's rigid start (glsl/include/rigid_start.glsl's rigid_terms).
const RIGID_SUMS: u32 = 16;

/// The stretch limit's counts packed eight a word from scratch's start (fused.comp's
/// STRETCH_PACKED).
const STRETCH_PACKED: u32 = 1;
/// The most a stretch count's four bits hold (`stretched` in glsl/fused.comp).
const STRETCH_COUNT_MOST: usize = 15;
/// ... in the top bits of the hash's links, where a particle self-collision reads the hash
/// during the constraints (STRETCH_IN_LINKS).
const STRETCH_IN_LINKS: u32 = 2;

impl FusedShape {
    /// The layout of object `o` in `model` within `limits`, or `None` when the object does not
    /// fit: it then runs per stage.
    pub fn plan(o: &ObjectModel, model: &SimModel, limits: FusedLimits) -> Option<Self> {
        let solver = model.integrator.solver();
        let n = o.particle_count() as u32;
        let hashed = o.self_distance.is_some() && model.self_collision == SelfCollisionMethod::Hash;
        let most = match solver {
            _ if hashed => limits.hashed_slots,
            Some(s) => limits.solver_slots.unwrap_or(solver_slots(s.sweep)),
            None => limits.slots,
        };
        // Objects that touch each other meet every substep: they run per stage. So does a
        // mesh with a stretch limit and a particle of more limited springs than a count's four
        // bits hold (STRETCH_PACKED; a grid's particle has eight), and a mesh with XPBD, by
        // spring classes or by Jacobi (its multipliers, one an entry of its lists, live in the
        // solver's buffer).
        let counted = o.stretch_limit.is_none()
            || o.mesh.as_ref().is_none_or(|m| m.most_limited_springs() <= STRETCH_COUNT_MOST);
        let listed =
            o.mesh.is_none() || !matches!(model.integrator, Integrator::XpbdJacobi | Integrator::Xpbd);
        let alone = !model.inter_object_contact();
        if n == 0 || n > most.min(FUSED_SLOTS) * MAX_THREADS || !alone || !counted || !listed {
            return None;
        }
        let slots = n.div_ceil(MAX_THREADS);
        let threads = n.div_ceil(slots).next_multiple_of(32);
        // A mesh's spring may join any two particles: its velocity window (the dashpots')
        // must hold them all, in one pass.
        let mesh = o.mesh.is_some();
        let halo = if mesh {
            0
        } else if o.dims[1] > 1 {
            2 * o.dims[0]
        } else {
            2
        };
        let budget = limits.shared_bytes.saturating_sub(SHARED_MARGIN);
        let adaptive = solver.is_some_and(|s| s.adaptive_start);
        let reduce = if model.integrator == Integrator::Implicit { 2 * threads.div_ceil(4) } else { 2 }
            + if adaptive { RIGID_SUMS } else { 1 };
        // (a cloth's triangles and a rope's segments are searched before the constraints)
        let stretch_counts = match o.stretch_limit {
            None => 0,
            Some(_) if hashed && !o.has_triangles() => STRETCH_IN_LINKS,
            Some(_) => STRETCH_PACKED,
        };
        let fixed = 12 * n + 4 * n.div_ceil(32) + 4 * reduce;
        let words = budget.checked_sub(fixed)? / 4;
        // The physics reads the neighbours' velocities (the dashpots; the iterative methods
        // treat them in their solve).
        let damped = o.damping != 0.0 && solver.is_none();
        // VBD's compact layout keeps its displacements for the dashpots alone (as half floats):
        // none without dashpots.
        let halves = if o.damping != 0.0 { 2 * n } else { 0 };
        let (displacements, compact) = match solver {
            None => (0, false),
            Some(_) if 3 * n <= words => (3 * n, false),
            Some(_) if model.integrator == Integrator::Vbd && halves <= words => (halves, true),
            Some(_) => return None,
        };
        let window = |q: u32| 3 * (threads * q + 2 * halo);
        let pass_slots = if damped { (1..=slots).rev().find(|&q| window(q) <= words)? } else { slots };
        if mesh && pass_slots < slots {
            return None;
        }
        let buckets = if hashed {
            let most = words.checked_sub(n)?;
            let b = (2 * n).next_power_of_two().min(1 << most.max(1).ilog2());
            (b >= MIN_BUCKETS).then_some(b)?
        } else {
            1
        };
        // A free object's rigid start passes its sums through the positions and scratch
        // (fused.comp's rigid_word): at least one of each subgroup (of 4 lanes or more).
        let rigid = if adaptive { threads.div_ceil(4).saturating_sub(3 * n) } else { 0 };
        if rigid > words {
            return None;
        }
        let scratch = [
            rigid,
            if damped { window(pass_slots) } else { 0 },
            if hashed { buckets + n } else { 0 },
            displacements,
            if stretch_counts == STRETCH_PACKED { n.div_ceil(8) } else { 0 },
            1,
        ]
        .into_iter()
        .max()
        .unwrap_or(1);
        if stretch_counts == STRETCH_PACKED && n.div_ceil(8) > words {
            return None;
        }
        let one_iteration = solver.is_some() && model.iterations == 1;
        // (moving pins keep the lists off, as per stage: `GpuObject::pins_move`)
        let list = if hashed && !o.pins_move() { SELF_LIST_ENTRIES } else { 0 };
        Some(Self {
            threads,
            particles: n,
            scratch,
            buckets,
            pass_slots,
            halo,
            one_iteration,
            list,
            reduce,
            compact,
            stretch_counts,
        })
    }

    /// Shared memory the kernel declares [bytes].
    pub fn shared_bytes(&self) -> u32 {
        12 * self.particles + 4 * self.particles.div_ceil(32) + 4 * self.scratch + 4 * self.reduce
    }

    /// Words of the contact list buffer (binding 15): a header and `list` entries a particle,
    /// and one that says whether they are valid (`LIST_VALID`: the host clears it).
    pub fn list_words(&self) -> u64 {
        if self.list == 0 {
            0
        } else {
            (4 + self.list as u64) * self.particles as u64 + 1
        }
    }

    /// Specialization constants 0..=12 (index = id) for the integrator and the features.
    pub fn specialization(&self, method: Integrator, features: u32) -> Vec<u32> {
        let verlet = method.method().scheme == Scheme::Explicit { verlet: true };
        vec![
            self.threads,
            self.one_iteration as u32,
            verlet as u32,
            features,
            self.particles,
            self.scratch,
            self.buckets,
            self.pass_slots,
            self.halo,
            method as u32,
            self.list,
            self.compact as u32,
            self.stretch_counts,
        ]
    }
}

/// Which path each object takes.
impl super::GpuSim {
    /// With `false`, every object takes the per-stage path (the reference for the fused one);
    /// with `true`, every object whose layout fits runs fused, triangle self-contact too. The
    /// pipelines the next frame runs are created now.
    pub fn set_fused(&mut self, ctx: &crate::vk::GpuContext, on: bool) -> anyhow::Result<()> {
        // The two paths keep their lists in the same layout, but nothing makes them one
        // contract (the fused kernel's LIST_VALID is the per-stage path's first control word).
        let more = (self.objects.iter())
            .any(|o| o.plan.fused.is_some() && held_back(o.plan.features, self.fuse_contact) != 0);
        self.lists_stale |= on != self.fused || (on && more);
        self.fused = on;
        if on {
            self.fuse_contact = CONTACT_FEATURES;
        }
        // (what the next frame would create: a pipeline that fails to compile fails here)
        self.ensure_pipelines(ctx)
    }

    /// Whether object `object` runs its substeps fused (its layout fits and the path is on).
    pub fn runs_fused(&self, object: usize) -> bool {
        self.objects.get(object).is_some_and(|o| self.is_fused(o))
    }

    /// Whether object `o` runs fused substeps.
    pub(super) fn is_fused(&self, o: &GpuObject) -> bool {
        self.fused && o.plan.fused.is_some() && held_back(o.plan.features, self.fuse_contact) == 0
    }
}

/// The self-contact features of an object of `features` that keep it per stage while those
/// that may run fused are `fuse_contact` (none: it may run fused). A rope's segment pairs
/// never do: a node tests two edges of a candidate, not a cloth's six, and a rope runs fused
/// wherever it fits (docs/PERFORMANCE.md, "A rope's self-collision as capsules").
pub(super) fn held_back(features: u32, fuse_contact: u32) -> u32 {
    if features & crate::sim::gpu_types::FEATURE_SEGMENT_PAIRS != 0 {
        return 0;
    }
    features & CONTACT_FEATURES & !fuse_contact
}

/// The self-contact features that decide whether an object runs fused by default.
const CONTACT_FEATURES: u32 =
    crate::sim::gpu_types::FEATURE_TRIANGLES | crate::sim::gpu_types::FEATURE_EDGE_PAIRS;

/// Which of those an object may have and run fused by default on device `info`
/// (`GpuSim::fuse_contact`): triangles except on a CPU driver, where their fused passes cost
/// twice the per-stage path (lavapipe, a 40 x 40 cloth: 138 against 69 ms a frame); edge pairs
/// on no device: a fused object's search runs in one workgroup, and a pile's edge pairs make it
/// long (the H100: the towel with edge contact 78 ms a frame fused against 13.0 per stage; the
/// curtain, which does not pile, 5.3 to 6.0 against 8.6; docs/log.md).
pub(super) fn default_fused_contact(info: &crate::vk::DeviceInfo) -> u32 {
    match info.kind {
        crate::vk::DeviceKind::Cpu => 0,
        _ => crate::sim::gpu_types::FEATURE_TRIANGLES,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kib(k: u32) -> FusedLimits {
        FusedLimits::new(k * 1024, FUSED_SLOTS)
    }

    /// Newton's hanging cloth (issue 31's rows): the curtain's cloth at 65 x 33 particles, no
    /// colliders, no self-collision.
    fn newtons_cloth() -> SimModel {
        let mut m = curtain();
        m.colliders.clear();
        m.objects[0].dims = [65, 33];
        m.objects[0].self_distance = None;
        m
    }

    fn curtain() -> SimModel {
        let s = crate::scene::parse(include_str!("../../../presets/curtain.toml"), "curtain.toml", &[])
            .expect("the curtain preset is valid");
        crate::scene::to_model(&s)
    }

    /// The paper's curtain (2,500 particles, dashpots, the hash) fits NVIDIA's 48 KiB: 864
    /// threads of three slots, the dashpots' velocities staged one slot per pass, 2,048
    /// buckets; not lavapipe's 32 KiB. Every layout stays within its limit.
    #[test]
    fn the_curtain_fits_48_kib_and_not_32() {
        let m = curtain();
        let o = &m.objects[0];
        let shape = FusedShape::plan(o, &m, kib(48)).expect("fits 48 KiB");
        assert_eq!((shape.threads, shape.particles, shape.buckets), (864, 2500, 2048), "{shape:?}");
        assert_eq!(shape.pass_slots, 1, "{shape:?}");
        assert!(shape.shared_bytes() <= 48 * 1024 - SHARED_MARGIN, "{shape:?}");
        assert_eq!(FusedShape::plan(o, &m, kib(32)), None);
        let one_slot = FusedLimits::new(48 * 1024, FUSED_DEFAULT_SLOTS);
        assert_eq!(FusedShape::plan(o, &m, one_slot), None, "2,500 particles need three slots");
        // The default limits fuse it (it self-collides through the hash), not the same cloth
        // without self-collision.
        let default = FusedLimits { hashed_slots: FUSED_HASHED_SLOTS, ..one_slot };
        assert!(FusedShape::plan(o, &m, default).is_some_and(|s| s.list > 0));
        let mut plain = m.clone();
        plain.objects[0].self_distance = None;
        assert_eq!(FusedShape::plan(&plain.objects[0], &plain, default), None);
        for limit in (16..=64).map(|k| k * 1024) {
            if let Some(s) = FusedShape::plan(o, &m, FusedLimits::new(limit, FUSED_SLOTS)) {
                assert!(s.shared_bytes() <= limit - SHARED_MARGIN, "{limit}: {s:?}");
                assert!(s.threads % 32 == 0 && s.threads * FUSED_SLOTS >= s.particles, "{s:?}");
            }
        }
    }

    /// The iterative integrators fuse when their displacements fit too (12 bytes a particle
    /// more: the curtain then needs more than 48 KiB); objects above FUSED_SLOTS x 1024
    /// particles run per stage.
    #[test]
    fn iterative_methods_fuse_where_they_fit_and_large_objects_do_not() {
        for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
            let mut m = curtain();
            m.integrator = method;
            let shape = FusedShape::plan(&m.objects[0], &m, kib(64)).expect("fits 64 KiB");
            assert!(shape.scratch >= 3 * shape.particles, "{method:?}: {shape:?}");
            assert_eq!(FusedShape::plan(&m.objects[0], &m, kib(48)), None, "{method:?}");
        }
        let mut m = curtain();
        let o = &mut m.objects[0];
        o.dims = [65, 64];
        assert_eq!(FusedShape::plan(&m.objects[0], &m, FusedLimits::new(u32::MAX, FUSED_SLOTS)), None);
    }

    /// Newton's hanging cloth (65 x 33 particles, issue 31's rows) at NVIDIA's 48 KiB: the bases
    /// and f32 displacements (24 bytes a particle) do not fit, VBD's compact solve (20) does,
    /// with the hash too (and without dashpots, 12 bytes, up to 62 x 62); the other iterative
    /// methods run it per stage. A 40 x 40 cloth takes the full layout at two particles a
    /// thread by default, except under XPBD by Jacobi, which keeps one (and so runs per stage).
    #[test]
    fn vbd_fits_newtons_cloth_compact_and_iterative_methods_take_more_slots() {
        let mut m = newtons_cloth();
        let default = FusedLimits {
            hashed_slots: FUSED_HASHED_SLOTS,
            solver_slots: None,
            ..FusedLimits::new(48 * 1024, FUSED_DEFAULT_SLOTS)
        };
        for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
            m.integrator = method;
            let shape = FusedShape::plan(&m.objects[0], &m, default);
            if method == Integrator::Vbd {
                let shape = shape.expect("VBD fits compact");
                assert!(shape.compact && shape.scratch == 2 * shape.particles, "{shape:?}");
                assert!(shape.shared_bytes() <= 48 * 1024 - SHARED_MARGIN, "{shape:?}");
            } else {
                assert_eq!(shape, None, "{method:?}");
            }
        }
        // Without dashpots the compact layout keeps no displacements: a cloth of 3,844
        // particles fits (the iterates, pins and the stretch limit's counts), not with
        // dashpots.
        m.integrator = Integrator::Vbd;
        m.objects[0].dims = [62, 62];
        m.objects[0].damping = 0.0;
        let bare = FusedShape::plan(&m.objects[0], &m, default).expect("fits without dashpots");
        assert!(bare.compact && bare.scratch == bare.particles.div_ceil(8), "{bare:?}");
        assert!(bare.shared_bytes() <= 48 * 1024 - SHARED_MARGIN, "{bare:?}");
        m.objects[0].damping = 0.1;
        assert_eq!(FusedShape::plan(&m.objects[0], &m, default), None);
        m.objects[0].dims = [65, 33];
        m.objects[0].self_distance = Some(0.05);
        let hashed = FusedShape::plan(&m.objects[0], &m, default).expect("with the hash");
        assert!(hashed.compact && hashed.buckets >= MIN_BUCKETS && hashed.list > 0, "{hashed:?}");
        assert!(hashed.shared_bytes() <= 48 * 1024 - SHARED_MARGIN, "{hashed:?}");
        m.objects[0].self_distance = None;
        m.objects[0].dims = [40, 40];
        for method in Integrator::ALL.into_iter().filter(|m| m.iterative()) {
            m.integrator = method;
            let shape = FusedShape::plan(&m.objects[0], &m, default);
            if method == Integrator::XpbdJacobi {
                assert_eq!(shape, None);
            } else {
                let shape = shape.expect("fits");
                assert!(!shape.compact && shape.threads == 800, "{method:?}: {shape:?}");
            }
        }
        let forced = FusedShape::plan(&m.objects[0], &m, default.with_slots(Some(2)));
        assert!(forced.is_some(), "--fused-slots 2 fuses XPBD by Jacobi too");
    }

    /// A GPU's limits let the iterative methods take FUSED_SLOTS particles a thread (their own
    /// choice, `solver_slots`); a CPU driver's keep one for them, where VBD ran slower fused
    /// (lavapipe, 40 x 40: 218 against 180 ms per stage), and end a dispatch's substeps at its
    /// loop limit. Both keep the device's shared memory.
    #[test]
    fn a_gpu_gives_the_iterative_methods_more_slots_and_a_cpu_driver_does_not() {
        let device = |kind, shared, loop_limit| crate::vk::DeviceInfo {
            name: String::new(),
            kind,
            driver: String::new(),
            api_version: String::new(),
            timestamp_period_ns: None,
            max_storage_buffer_range: u64::MAX,
            max_workgroup_count: [65535; 3],
            device_local_bytes: 1 << 30,
            max_shared_memory: shared,
            subgroup_size: 32,
            subgroup_clustered: true,
            loop_iteration_limit: loop_limit,
            max_stage_storage_buffers: 4096,
        };
        let gpu = FusedLimits::for_device(&device(crate::vk::DeviceKind::Discrete, 48 * 1024, None));
        assert_eq!(
            (gpu.shared_bytes, gpu.solver_slots, gpu.substeps_per_dispatch),
            (48 * 1024, None, u32::MAX)
        );
        let cpu = FusedLimits::for_device(&device(crate::vk::DeviceKind::Cpu, 32 * 1024, Some(65_535)));
        assert_eq!(cpu.shared_bytes, 32 * 1024);
        assert_eq!(cpu.solver_slots, Some(FUSED_DEFAULT_SLOTS));
        assert_eq!(cpu.substeps_per_dispatch, LIMITED_SUBSTEPS_PER_DISPATCH);
        assert_eq!((gpu.slots, gpu.hashed_slots), (cpu.slots, cpu.hashed_slots));
        // Newton's cloth under VBD: fused (compact) with a GPU's limits, and one thread a
        // particle (so per stage) under a CPU driver's.
        let mut m = newtons_cloth();
        m.integrator = Integrator::Vbd;
        assert!(FusedShape::plan(&m.objects[0], &m, gpu).is_some_and(|s| s.compact));
        assert_eq!(FusedShape::plan(&m.objects[0], &m, FusedLimits { shared_bytes: 48 * 1024, ..cpu }), None);
        // Substeps a dispatch: all of a frame's on a GPU; 8 under a loop limit, one where an
        // object's contact search runs long loops (edge pairs, a mesh cloth's triangles).
        use crate::sim::gpu_types::{FEATURE_CLOTH_MESH, FEATURE_EDGE_PAIRS, FEATURE_TRIANGLES};
        let mesh_contact = FEATURE_CLOTH_MESH | FEATURE_TRIANGLES;
        assert_eq!(gpu.chunk([mesh_contact].into_iter(), 16), 16);
        assert_eq!(cpu.chunk([FEATURE_CLOTH_MESH, FEATURE_TRIANGLES].into_iter(), 16), 8);
        assert_eq!(cpu.chunk([0, mesh_contact].into_iter(), 16), 1);
        assert_eq!(cpu.chunk([FEATURE_EDGE_PAIRS].into_iter(), 16), 1);
    }

    /// One iteration of an iterative method is a layout of its own (another pipeline; the
    /// simulation rebuilds when the count crosses it), explicit methods have none.
    #[test]
    fn one_iteration_is_its_own_layout() {
        let mut m = curtain();
        m.objects[0].dims = [16, 16];
        let plan = |m: &SimModel| FusedShape::plan(&m.objects[0], m, kib(48)).expect("fits").one_iteration;
        m.iterations = 1;
        assert!(!plan(&m), "symplectic Euler has no iterations");
        m.integrator = Integrator::Xpbd;
        assert!(plan(&m));
        m.iterations = 2;
        assert!(!plan(&m));
    }

    /// Features follow the model: a scene without wind, spheres, dashpots or self-collision
    /// compiles them out; a spring type without stiffness or dashpots is left out.
    #[test]
    fn features_follow_the_model() {
        let mut m = curtain();
        let all = features(&m.objects[0], &m);
        assert_eq!(all & FEATURE_WIND, 0, "the preset has no wind");
        assert_ne!(
            all & (crate::sim::gpu_types::FEATURE_SPHERES | FEATURE_SELF | FEATURE_DAMPING | FEATURE_STRETCH),
            0
        );
        m.colliders.clear();
        let o = &mut m.objects[0];
        o.damping = 0.0;
        o.stiffness[2] = 0.0;
        o.self_distance = None;
        let f = features(&m.objects[0], &m);
        assert_eq!(f, FEATURE_STRUCTURAL | FEATURE_SHEAR | FEATURE_STRETCH);
    }
}
