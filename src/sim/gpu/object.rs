//! The GPU buffers and binding sets of one simulated object, the parameters it is given, and
//! the checks that it fits the device.

use super::fused::ObjectPlan;
use super::{BINDINGS, CLOTH_GROUP, ROPE_GROUP};
use crate::error::UserError;
use crate::sim::collider::Shape;
use crate::sim::collider_mesh::ColliderMesh;
use crate::sim::gpu_types::{
    Globals, ObjectParams, Particle, SurfaceVertex, OBJ_ANCHORED, OBJ_LINE_SEARCH, OBJ_RIGID_START,
    OBJ_SELF_COLLISION, OBJ_SELF_HASH, OBJ_SELF_TRIANGLES, OBJ_STRETCH_LIMIT,
};
use crate::sim::integrator::{vertex_colours, BDF2_STEP, SPRING_CLASSES};
use crate::sim::model::{
    Integrator, ObjectKind, ObjectModel, ObjectShape, SelfCollisionMethod, SimModel, PIN_GROUPS,
};
use crate::sim::turbulence::{Turbulence, TURBULENCE_MODES};
use crate::vk::{
    Access, BindingSet, BindingSetLayout, Buffer, BufferBarrier, BufferUsage, DescriptorArena, DeviceInfo,
    GpuContext, MemoryKind, VkError,
};
use anyhow::Result;

/// A cleared guard: no flags, no flagged particle.
pub(super) const GUARD_CLEAR: [u32; 4] = [0, u32::MAX, 0, 0];
/// Spatial hash table sizes: the scan handles 8192 buckets per block and 8192 blocks
/// (`SCAN_BLOCK` in glsl/include/layout.glsl). Its counts have a word more, the scan's
/// counter of finished blocks (glsl/hash_scan.comp).
pub(super) const SCAN_BLOCK: u64 = 8192;
const MAX_TABLE: u64 = SCAN_BLOCK * SCAN_BLOCK;

/// Buckets of the spatial hash of an object of `particles` particles: a power of two, at
/// least twice the particle count (load factor <= 1/2), within the scan's capacity.
pub(super) fn hash_table_size(particles: u64) -> u64 {
    (2 * particles).next_power_of_two().clamp(1024, MAX_TABLE)
}

/// Creates buffers `(suffix, size, usage)` named `{name}.{suffix}`, all or none.
pub(super) fn buffers<const N: usize>(
    ctx: &GpuContext,
    name: &str,
    specs: [(&str, u64, BufferUsage, MemoryKind); N],
) -> Result<[Buffer; N], VkError> {
    let mut made = Vec::with_capacity(N);
    for (suffix, size, usage, memory) in specs {
        match Buffer::new(ctx, &format!("{name}.{suffix}"), size, usage, memory) {
            Ok(b) => made.push(b),
            Err(e) => {
                made.into_iter().for_each(|b| b.destroy(ctx));
                return Err(e);
            }
        }
    }
    match <[Buffer; N]>::try_from(made) {
        Ok(all) => Ok(all),
        Err(_) => unreachable!("one buffer per spec"),
    }
}

/// The spatial hash of one object (bindings 6..=10).
pub(super) struct HashBuffers {
    pub cell_rank: Buffer,
    pub counts: Buffer,
    pub starts: Buffer,
    pub sorted: Buffer,
    pub block_sums: Buffer,
    pub buckets: u32,
}

impl HashBuffers {
    fn new(ctx: &GpuContext, name: &str, particles: u64) -> Result<Self, VkError> {
        let buckets = hash_table_size(particles);
        let (storage, gpu) = (BufferUsage::STORAGE, MemoryKind::GpuOnly);
        let [cell_rank, counts, starts, sorted, block_sums] = buffers(
            ctx,
            &format!("{name}.hash"),
            [
                ("cell_rank", 8 * particles, storage, gpu),
                ("counts", 4 * (buckets + 1), storage | BufferUsage::TRANSFER_DST, gpu),
                ("starts", 4 * (buckets + 1), storage, gpu),
                ("sorted", 16 * particles, storage, gpu),
                ("block_sums", 4 * buckets.div_ceil(SCAN_BLOCK), storage, gpu),
            ],
        )?;
        Ok(Self { cell_rank, counts, starts, sorted, block_sums, buckets: buckets as u32 })
    }

    pub(super) fn buffers(&self) -> [&Buffer; 5] {
        [&self.cell_rank, &self.counts, &self.starts, &self.sorted, &self.block_sums]
    }

    fn destroy(self, ctx: &GpuContext) {
        for b in [self.cell_rank, self.counts, self.starts, self.sorted, self.block_sums] {
            b.destroy(ctx);
        }
    }
}

/// Words of a control block of the per-stage contact lists, one per substep parity, after the
/// lists (`LIST_CONTROL_WORDS` in glsl/include/lists.glsl).
const LIST_CONTROL_WORDS: u64 = 16;

/// The per-stage contact lists' control blocks in the list buffer of an object of `particles`
/// particles (glsl/include/lists.glsl): their byte offset and size, both parities. The two
/// counters `list_counters` follow them.
pub(super) fn list_control_range(particles: u64) -> (u64, u64) {
    let lists = (4 + super::fused::SELF_LIST_ENTRIES as u64) * particles;
    (4 * lists, 4 * 2 * LIST_CONTROL_WORDS)
}

/// Bytes of the per-stage list buffer of an object of `n` particles: the lists, their control
/// blocks and the two counters.
fn self_list_bytes(n: u64) -> u64 {
    let (control, size) = list_control_range(n);
    control + size + 8
}

/// Byte offset in the list buffer of the indirect dispatch of a spatial hash pass in substep
/// `substep`: `pass` 0 the count and the scatter, 1 the scan (`LIST_DISPATCHES`
/// in glsl/include/lists.glsl).
pub(super) fn list_dispatch_offset(particles: u32, substep: u32, pass: u64) -> u64 {
    let (control, _) = list_control_range(particles as u64);
    control + 4 * (LIST_CONTROL_WORDS * (substep as u64 & 1) + 1 + 3 * pass)
}

/// Vec4s of BDF2 history a particle of an iterative method keeps (binding 16), one in each of
/// that many arrays of the particle count (`hist` in glsl/include/bindings.glsl).
const HISTORY_VEC4S: u64 = 3;

/// The iterates, auxiliary data and BDF2 history of an iterative integrator (bindings 12, 13,
/// 16).
pub(super) struct SolverBuffers {
    pub iter: Buffer,
    pub aux: Buffer,
    /// Three arrays of a vec4 a particle (`history` in glsl/include/bindings.glsl); zero is "no
    /// history".
    pub history: Buffer,
}

impl SolverBuffers {
    /// `groups`: the workgroups of a pass over every particle of `o`.
    fn new(
        ctx: &GpuContext,
        o: &ObjectModel,
        groups: u64,
        model: &SimModel,
    ) -> Result<Option<Self>, VkError> {
        let Some(solver) = model.integrator.solver() else { return Ok(None) };
        let (name, particles) = (&o.name, o.particle_count() as u64);
        // With contact rounds a slice more: the colliders' moves within the solve
        // (glsl/vbd_iterate.comp); a scene without them does not pay for it.
        let slices = solver.aux + (model.contact_rounds() > 1) as u64;
        let mut aux = slices * particles;
        if let Some(mesh) =
            o.mesh.as_ref().filter(|_| matches!(model.integrator, Integrator::XpbdJacobi | Integrator::Xpbd))
        {
            // A mesh cloth's multipliers: a float an entry of its lists (MESH_LAMBDA; XPBD's
            // a spring's at its lower end's entry).
            aux = aux.max((mesh.springs.len() as u64).div_ceil(4));
        }
        if solver.adaptive_start {
            // A free object's rigid start: four sums a workgroup and their totals after the
            // first slice (glsl/rigid_start.comp).
            aux = aux.max(particles + 4 + 4 * groups);
        }
        let slices = solver.slices;
        let (storage, gpu) = (BufferUsage::STORAGE, MemoryKind::GpuOnly);
        let cleared = storage | BufferUsage::TRANSFER_DST;
        let [iter, aux, history] = buffers(
            ctx,
            &format!("{name}.solver"),
            [
                ("iter", 16 * slices * particles, storage, gpu),
                ("aux", 16 * aux, storage, gpu),
                ("history", 16 * HISTORY_VEC4S * particles, cleared, gpu),
            ],
        )?;
        Ok(Some(Self { iter, aux, history }))
    }
}

pub(super) struct GpuObject {
    pub kind: ObjectKind,
    pub particles: u32,
    pub surface_len: u32,
    pub step_groups: [u32; 3],
    /// Vertex colours and the workgroups of a pass over one colour (`vertex_colours`).
    pub colours: u32,
    pub colour_groups: [u32; 3],
    /// XPBD's spring classes and the workgroups of a pass over one (a grid's
    /// `SPRING_CLASSES` twice, over its particles; a mesh's own, over its largest class).
    pub classes: u32,
    pub class_groups: [u32; 3],
    /// A cloth made from a mesh (`sim::cloth_mesh`).
    pub mesh: bool,
    pub surface_groups: [u32; 3],
    pub params: Buffer,
    pub state: [Buffer; 2],
    pub surface: Buffer,
    pub hash: Option<Box<HashBuffers>>,
    pub solver: Option<SolverBuffers>,
    /// 16 bytes bound at the spatial hash and solver bindings the object does not use. The
    /// shaders reach it only behind a flag but may (statically) write it, so it is ordered like
    /// the state buffers; one per object, so objects' dispatches never share it.
    pub placeholder: Buffer,
    /// The runtime guard (flags, first flagged particle), host-visible, read after each frame.
    pub guard: Buffer,
    /// Inter-object contact: per particle the corrections from other objects (binding 14).
    pub contact: Option<Buffer>,
    /// The self-collision contact lists of an object that searches the spatial hash (binding
    /// 15; glsl/include/lists.glsl): the fused kernel's (`FusedShape::list`) or the per-stage
    /// path's, with its control blocks and indirect dispatches.
    pub self_list: Option<Buffer>,
    /// A cloth's contact with its own triangles (binding 17; glsl/include/self_contact.glsl):
    /// each particle's summed moves and count, its contacts.
    pub self_pairs: Option<Buffer>,
    /// [A -> B (physics), B -> A (constraints, hash passes); surface uses set 0 (reads A)].
    pub sets: [BindingSet; 2],
    /// Whether its per-stage contact lists are on.
    pub lists: super::hash::ListPolicy,
    /// Its pins move (`ObjectModel::pin_motion`): its self-contact lists stay off, since a
    /// list's skin is measured against the free particles' moves alone (`note_position`).
    pub pins_move: bool,
    /// The implicit method searches along its Newton steps (the parameters' OBJ_LINE_SEARCH,
    /// `searches`; kept here so that recording a frame does not ask).
    pub searches: bool,
    /// It starts each substep's solve from the rigid move that fits its guesses
    /// (`rigid_start`).
    pub rigid_start: bool,
    /// The features its step pipelines compile in and its fused layout.
    pub plan: ObjectPlan,
}

impl GpuObject {
    /// Allocates the object's buffers and binding sets, all or nothing.
    pub fn new(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        arena: &mut DescriptorArena,
        shared: [&Buffer; 2],
        o: &ObjectModel,
        model: &SimModel,
        plan: ObjectPlan,
    ) -> Result<Self, VkError> {
        let n = o.particle_count() as u64;
        let state_bytes = n * std::mem::size_of::<Particle>() as u64;
        let state_usage = BufferUsage::STORAGE | BufferUsage::TRANSFER_SRC | BufferUsage::TRANSFER_DST;
        let surface_bytes = o.surface_count() as u64 * std::mem::size_of::<SurfaceVertex>() as u64;
        let parameters = object_params(o, model);
        // A mesh cloth's lists follow its parameters (glsl/include/mesh_springs.glsl): one
        // buffer, so that every stage that binds the parameters reads them.
        // (XPBD's spring classes only where it sweeps them)
        let swept = model.integrator == Integrator::Xpbd;
        let words = o.mesh.as_ref().map_or(Vec::new(), |m| m.pack(o.rest_scale, swept));
        let [mut params, a, b, surface, mut guard, placeholder] = buffers(
            ctx,
            &o.name,
            [
                (
                    "params",
                    (std::mem::size_of::<ObjectParams>() + 4 * words.len()) as u64,
                    // (how moving pins move is written each frame: `record_pin_motion`)
                    BufferUsage::STORAGE | BufferUsage::TRANSFER_DST,
                    MemoryKind::Upload,
                ),
                ("state_a", state_bytes, state_usage, MemoryKind::GpuOnly),
                ("state_b", state_bytes, state_usage, MemoryKind::GpuOnly),
                (
                    "surface",
                    surface_bytes,
                    BufferUsage::STORAGE | BufferUsage::VERTEX | BufferUsage::TRANSFER_SRC,
                    MemoryKind::GpuOnly,
                ),
                ("guard", 16, BufferUsage::STORAGE, MemoryKind::Readback),
                ("placeholder", 16, BufferUsage::STORAGE, MemoryKind::GpuOnly),
            ],
        )?;
        let mut hash = None;
        let mut solver = None;
        let mut contact = None;
        let mut self_list = None;
        let mut self_pairs = None;
        let made = (|| -> Result<(), VkError> {
            guard.write(0, &GUARD_CLEAR)?;
            params.write(0, &[parameters])?;
            if !words.is_empty() {
                params.write(std::mem::size_of::<ObjectParams>() as u64, &words)?;
            }
            if builds_hash(o, model) {
                hash = Some(Box::new(HashBuffers::new(ctx, &o.name, n)?));
            }
            if model.inter_object_contact() {
                let usage = BufferUsage::STORAGE | BufferUsage::TRANSFER_DST;
                contact = Some(Buffer::new(
                    ctx,
                    &format!("{}.contact", o.name),
                    16 * n,
                    usage,
                    MemoryKind::GpuOnly,
                )?);
            }
            let groups = step_groups(&o.shape()).iter().product::<u32>() as u64;
            solver = SolverBuffers::new(ctx, o, groups, model)?;
            if builds_hash(o, model) {
                let fused = 4 * plan.fused.map_or(0, |f| f.list_words());
                let name = format!("{}.self_list", o.name);
                let usage = BufferUsage::STORAGE | BufferUsage::TRANSFER_DST | BufferUsage::INDIRECT;
                let bytes = fused.max(self_list_bytes(n));
                self_list = Some(Buffer::new(ctx, &name, bytes, usage, MemoryKind::GpuOnly)?);
            }
            if has_self_pairs(o) {
                let usage = BufferUsage::STORAGE | BufferUsage::TRANSFER_DST | BufferUsage::INDIRECT;
                // Sums and counts (4), lengths (1), contacts, where each began the substep (3),
                // the sums' parts that move the position only (3); the further passes'
                // indirect dispatch; with edge-edge contact, the ring creases (1) and the
                // fraction of each particle's move its truncation keeps (1).
                let bytes = self_pairs_bytes(n, o.has_cloth_edge_pairs());
                let name = format!("{}.self_pairs", o.name);
                self_pairs = Some(Buffer::new(ctx, &name, bytes, usage, MemoryKind::GpuOnly)?);
            }
            Ok(())
        })();
        let mut object = Self {
            kind: o.kind,
            particles: n as u32,
            surface_len: o.surface_count() as u32,
            step_groups: step_groups(&o.shape()),
            colours: o.mesh.as_ref().map_or(vertex_colours(o.dims), |m| m.colour_count() as u32),
            colour_groups: match &o.mesh {
                Some(m) => largest_groups((0..m.colour_count()).map(|c| m.colour(c).len())),
                None => colour_groups(&o.shape()),
            },
            // (a mesh's classes made only where XPBD sweeps them; else no pass takes them)
            classes: match &o.mesh {
                Some(m) if swept => m.class_count() as u32,
                Some(_) => 0,
                None => 2 * SPRING_CLASSES.len() as u32,
            },
            class_groups: match &o.mesh {
                Some(m) if swept => largest_groups((0..m.class_count()).map(|c| m.class(c).len())),
                Some(_) => [0; 3],
                None => step_groups(&o.shape()),
            },
            mesh: o.mesh.is_some(),
            surface_groups: surface_groups(&o.shape()),
            params,
            state: [a, b],
            surface,
            hash,
            solver,
            placeholder,
            guard,
            contact,
            self_list,
            self_pairs,
            sets: [BindingSet::default(); 2],
            lists: Default::default(),
            pins_move: o.pins_move(),
            searches: searches(&parameters),
            rigid_start: rigid_start(&parameters),
            plan,
        };
        let mut set = |direction| arena.allocate(ctx, layout, &object.bindings(shared, direction));
        let sets = made.and_then(|()| Ok([set(0)?, set(1)?]));
        match sets {
            Ok(sets) => {
                object.sets = sets;
                Ok(object)
            }
            Err(e) => {
                // Descriptor sets belong to the arena; everything else is freed here.
                object.destroy(ctx);
                Err(e)
            }
        }
    }

    /// What its binding set of `direction` holds (0: A -> B), binding by binding
    /// (glsl/include/bindings.glsl); `shared`: the scene's globals and colliders.
    pub fn bindings<'a>(
        &'a self,
        shared: [&'a Buffer; 2],
        direction: usize,
    ) -> [&'a Buffer; BINDINGS as usize] {
        let [globals, colliders] = shared;
        let p = &self.placeholder;
        let [cell_rank, counts, starts, sorted, blocks] = match &self.hash {
            Some(h) => h.buffers(),
            None => [p; 5],
        };
        let [iter, aux, history] = match &self.solver {
            Some(s) => [&s.iter, &s.aux, &s.history],
            None => [p; 3],
        };
        let [from, to] = [&self.state[direction], &self.state[1 - direction]];
        [
            globals,
            &self.params,
            from,
            to,
            colliders,
            &self.surface,
            cell_rank,
            counts,
            starts,
            sorted,
            blocks,
            &self.guard,
            iter,
            aux,
            self.contact.as_ref().unwrap_or(p),
            self.self_list.as_ref().unwrap_or(p),
            history,
            self.self_pairs.as_ref().unwrap_or(p),
            p,
            p,
        ]
    }

    /// Buffers that a stage may write through the hash and solver bindings besides its state
    /// output: ordered between stages like the state buffers.
    pub fn scratch(&self) -> Vec<&Buffer> {
        let mut out = vec![&self.placeholder];
        if let Some(s) = &self.solver {
            out.extend([&s.iter, &s.aux, &s.history]);
        }
        out.extend(&self.contact);
        out.extend(&self.self_list);
        out.extend(&self.self_pairs);
        out
    }

    /// Barriers on `scratch()` between two stages that may read and write it. (The contact
    /// lists also hold the hash passes' indirect dispatches, `hash.rs` orders those reads in
    /// the two barriers that must, and self_pairs the further contact passes', which
    /// `record_self_pairs` orders. The indirect stage in every barrier cost about 6 us a
    /// substep on a 256 x 256 cloth on the H100.)
    pub fn scratch_barriers(&self) -> Vec<BufferBarrier<'_>> {
        self.scratch_barriers_with(Access::ComputeReadWrite)
    }

    /// `scratch_barriers` with `pairs` the access to self_pairs on both sides (the indirect
    /// stage where it holds the further contact passes' dispatch).
    pub fn scratch_barriers_with(&self, pairs: Access) -> Vec<BufferBarrier<'_>> {
        let rw = Access::ComputeReadWrite;
        let is_pairs = |b: &Buffer| self.self_pairs.as_ref().is_some_and(|p| std::ptr::eq(p, b));
        (self.scratch().into_iter())
            .map(|b| {
                let a = if is_pairs(b) { pairs } else { rw };
                BufferBarrier::new(b, a, a)
            })
            .collect()
    }

    pub fn destroy(self, ctx: &GpuContext) {
        let [a, b] = self.state;
        for buffer in [self.params, a, b, self.surface, self.guard, self.placeholder] {
            buffer.destroy(ctx);
        }
        if let Some(h) = self.hash {
            h.destroy(ctx);
        }
        if let Some(s) = self.solver {
            s.iter.destroy(ctx);
            s.aux.destroy(ctx);
            s.history.destroy(ctx);
        }
        if let Some(c) = self.contact {
            c.destroy(ctx);
        }
        if let Some(l) = self.self_list {
            l.destroy(ctx);
        }
        if let Some(p) = self.self_pairs {
            p.destroy(ctx);
        }
    }
}

/// Bytes of GPU memory an object needs: two state buffers, the surface, the parameters (and
/// the spatial hash, the largest solver, the contact lists, the sums of contact between
/// objects and the self-contact passes' buffer with edge pairs, counted for every object: an
/// upper bound).
fn object_bytes(o: &ObjectShape) -> u64 {
    let n = o.particle_count();
    let (slices, aux) = solver_vec4s();
    2 * n * std::mem::size_of::<Particle>() as u64
        + o.surface_count() * std::mem::size_of::<SurfaceVertex>() as u64
        + std::mem::size_of::<ObjectParams>() as u64
        + o.mesh.as_ref().map_or(0, |m| 4 * m.word_count(true))
        + 24 * n
        + 8 * hash_table_size(n)
        + 4
        + (slices + aux + HISTORY_VEC4S) * 16 * n
        + self_list_bytes(n)
        + 16 * n
        + self_pairs_bytes(n, true)
}

/// The most vec4s a particle that any iterative method keeps in its iterate slices and in its
/// auxiliary data (`sim::integrator`'s table; the implicit method's 9 and 3).
fn solver_vec4s() -> (u64, u64) {
    let solvers = Integrator::ALL.into_iter().filter_map(|m| m.solver());
    solvers.fold((0, 0), |(slices, aux), s| (slices.max(s.slices), aux.max(s.aux)))
}

fn gib(bytes: u64) -> String {
    format!("{:.2} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// Refuses objects the device cannot hold or dispatch. Needs only the shapes, so callers can
/// check before building particle arrays.
pub fn check_fits(info: &DeviceInfo, shapes: &[ObjectShape]) -> Result<(), UserError> {
    let total: u64 = shapes.iter().map(object_bytes).sum();
    if total > info.device_local_bytes {
        return Err(UserError(format!(
            "the scene is too large for the device: it needs {} of GPU memory, {} has {}",
            gib(total),
            info.name,
            gib(info.device_local_bytes)
        )));
    }
    for o in shapes {
        let what = format!("{} '{}' ({} x {})", o.kind.label(), o.name, o.dims[0], o.dims[1]);
        // The largest buffer: a state, the surface, a solver's iterate slices, the contact
        // lists or the self-contact passes' buffer.
        let n = o.particle_count();
        let state = n * std::mem::size_of::<Particle>() as u64;
        let surface = o.surface_count() * std::mem::size_of::<SurfaceVertex>() as u64;
        let contact = self_list_bytes(n).max(self_pairs_bytes(n, true));
        // (a mesh cloth's parameters carry its lists)
        let params = std::mem::size_of::<ObjectParams>() as u64
            + o.mesh.as_ref().map_or(0, |m| 4 * m.word_count(true));
        let largest = state.max(surface).max(solver_vec4s().0 * 16 * n).max(contact).max(params);
        if largest > info.max_storage_buffer_range {
            return Err(UserError(format!(
                "{what} is too large for the device: one buffer would be {}, {} binds at most {}",
                gib(largest),
                info.name,
                gib(info.max_storage_buffer_range),
            )));
        }
        if step_groups(o)
            .iter()
            .chain(&surface_groups(o))
            .zip(info.max_workgroup_count.iter().cycle())
            .any(|(g, max)| g > max)
        {
            return Err(UserError(format!(
                "{what} is too large for the device: it needs more workgroups than one dispatch allows"
            )));
        }
    }
    Ok(())
}

fn step_groups(o: &ObjectShape) -> [u32; 3] {
    match o.kind {
        ObjectKind::Cloth if o.is_mesh() => [o.dims[0].div_ceil(ROPE_GROUP), 1, 1],
        ObjectKind::Cloth => [o.dims[0].div_ceil(CLOTH_GROUP[0]), o.dims[1].div_ceil(CLOTH_GROUP[1]), 1],
        ObjectKind::Rope => [o.dims[0].div_ceil(ROPE_GROUP), 1, 1],
    }
}

/// The workgroups of a pass over the largest of a mesh's parts (a colour, a spring class),
/// an invocation an item.
fn largest_groups(sizes: impl Iterator<Item = usize>) -> [u32; 3] {
    [(sizes.max().unwrap_or(1) as u32).div_ceil(ROPE_GROUP), 1, 1]
}

/// Workgroups of a pass over one vertex colour: each row's cells of that colour, at most
/// ceil(columns / colours) (`coloured_cell` in glsl/include/solver_end.glsl).
fn colour_groups(o: &ObjectShape) -> [u32; 3] {
    let columns = o.dims[0].div_ceil(vertex_colours(o.dims));
    match o.kind {
        ObjectKind::Cloth => [columns.div_ceil(CLOTH_GROUP[0]), o.dims[1].div_ceil(CLOTH_GROUP[1]), 1],
        ObjectKind::Rope => [columns.div_ceil(ROPE_GROUP), 1, 1],
    }
}

fn surface_groups(o: &ObjectShape) -> [u32; 3] {
    match o.kind {
        // (cloth_normals.comp's workgroups are squares: a mesh cloth's row takes their first)
        ObjectKind::Cloth if o.is_mesh() => [o.dims[0].div_ceil(CLOTH_GROUP[0]), 1, 1],
        ObjectKind::Cloth => step_groups(o),
        // One workgroup walks the rope (the frames are a running product, rope_vertices.comp).
        ObjectKind::Rope => [1, 1, 1],
    }
}

fn f3(v: glam::DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

/// The globals of `model` at a frame that starts at `t` (the turbulence's phases, which each
/// frame rewrites: `GpuSim::record_wind_phases`).
pub(super) fn globals(model: &SimModel, t: f64) -> Globals {
    let wind = model.wind;
    let turbulence = turbulence(model);
    let (wind_waves, wind_gusts) = turbulence.map(|w| w.gpu(t)).unwrap_or_default();
    Globals {
        gravity: f3(model.gravity),
        dt: model.dt() as f32,
        wind_origin: wind.map(|w| f3(w.origin)).unwrap_or_default(),
        wind_force: wind.map(|w| w.force as f32).unwrap_or(0.0),
        wind_dir: wind.map(|w| f3(w.direction)).unwrap_or([0.0, 0.0, 1.0]),
        wind_cos_full: wind.map(|w| w.cos_full as f32).unwrap_or(1.0),
        wind_cos_att: wind.map(|w| w.cos_att as f32).unwrap_or(1.0),
        wind_enabled: wind.is_some() as u32,
        collider_count: model.colliders.len() as u32,
        substeps: model.substeps,
        guard_speed: model.max_speed as f32,
        iterations: model.iterations,
        relaxation: model.relaxation as f32,
        contact_speed: crate::sim::collider::contact_speed(model).map(|c| c.speed as f32).unwrap_or(0.0),
        wind_speed: wind.and_then(|w| w.air).map(|a| a.speed as f32).unwrap_or(0.0),
        wind_normal: wind.and_then(|w| w.air).map(|a| a.normal as f32).unwrap_or(0.0),
        wind_tangent: wind.and_then(|w| w.air).map(|a| a.tangent as f32).unwrap_or(0.0),
        guard_strain: model.max_strain as f32,
        wind_lift: wind.and_then(|w| w.air).map(|a| a.lift as f32).unwrap_or(0.0),
        wind_modes: turbulence.map_or(0, |_| TURBULENCE_MODES as u32),
        pad1: 0.0,
        pad2: 0.0,
        wind_waves,
        wind_gusts,
    }
}

/// The wind's turbulence in `model`, if any.
pub(super) fn turbulence(model: &SimModel) -> Option<Turbulence> {
    model.wind.and_then(|w| w.air).and_then(|a| a.turbulence)
}

/// Byte offset in an object's self_pairs buffer (`n` particles) of the indirect dispatch of
/// the further contact passes (`further_passes_word` in glsl/include/self_contact.glsl).
pub(super) fn further_passes_offset(n: u64) -> u64 {
    4 * (5 + SELF_PAIR_MAX + 6) * n
}

/// Bytes of an object's self_pairs buffer (n particles; `creases`: a cloth's edge pairs, with
/// each particle's ring creases and the fraction of its move its truncation keeps).
fn self_pairs_bytes(n: u64, creases: bool) -> u64 {
    further_passes_offset(n) + 12 + if creases { 8 * n } else { 0 }
}

/// Contacts a particle keeps in a substep (`PAIR_MAX` in glsl/include/self_contact.glsl).
pub(super) const SELF_PAIR_MAX: u64 = crate::sim::cpu::self_contact::PAIR_MAX as u64;

/// Whether object `o` has contact with its own surface through the self-contact passes (a
/// cloth's triangles, a rope's segments: `ObjectModel::has_triangles`).
pub(super) fn has_self_pairs(o: &ObjectModel) -> bool {
    o.self_distance.is_some() && o.has_triangles()
}

/// Whether object `o` builds a spatial hash of its own (its self-collision, the hash method).
pub(super) fn builds_hash(o: &ObjectModel, model: &SimModel) -> bool {
    o.self_distance.is_some() && model.self_collision == SelfCollisionMethod::Hash
}

pub(super) fn object_params(o: &ObjectModel, model: &SimModel) -> ObjectParams {
    let mut flags = 0;
    if o.stretch_limit.is_some() {
        flags |= OBJ_STRETCH_LIMIT;
    }
    if o.self_distance.is_some() {
        flags |= OBJ_SELF_COLLISION;
        if model.self_collision == SelfCollisionMethod::Hash {
            flags |= OBJ_SELF_HASH;
        }
        if o.has_triangles() {
            flags |= OBJ_SELF_TRIANGLES;
        }
    }
    if o.anchored() {
        flags |= OBJ_ANCHORED;
    }
    if crate::sim::cpu::implicit_searches(model, o) {
        flags |= OBJ_LINE_SEARCH;
    }
    if crate::sim::cpu::rigid_starts(model, o) {
        flags |= OBJ_RIGID_START;
    }
    let buckets = hash_table_size(o.particle_count() as u64) as u32;
    let cell = 2.0 * o.self_reach().unwrap_or(1.0).max(1e-6);
    let mut pins = [[0.0; 4]; 3 * PIN_GROUPS];
    for (dst, src) in pins.iter_mut().zip(pin_record(o, model, 0.0)) {
        *dst = src;
    }
    ObjectParams {
        dims: o.dims,
        spacing: o.spacing.map(|s| s as f32),
        stiffness: [o.stiffness[0] as f32, o.stiffness[1] as f32, o.stiffness[2] as f32, o.damping as f32],
        rest_scale: [o.rest_scale[0] as f32, o.rest_scale[1] as f32, o.rest_scale[2] as f32, 0.0],
        mass: o.mass as f32,
        drag: o.drag as f32,
        stretch_limit: o.stretch_limit.unwrap_or(0.0) as f32,
        friction: o.friction as f32,
        margin: o.margin as f32,
        self_distance: o.self_distance.unwrap_or(0.0) as f32,
        rope_radius: o.rope_radius as f32,
        flags,
        ring_weights: o.ring_weights.map(|w| w.map(|x| x as f32)),
        hash_mask: buckets - 1,
        cell_inv: (1.0 / cell) as f32,
        contact_iterations: model.contact_iterations,
        seam: o.seam as f32,
        rest: crate::sim::cpu::rest_lengths(o).map(|g| g.map(|l| l as f32)),
        xpbd: std::array::from_fn(|t| xpbd_constants(o.stiffness[t], o, model).map(|c| c as f32)),
        pins,
    }
}

/// Whether the per-stage recording gives an object with `params` the line search's passes:
/// its OBJ_LINE_SEARCH, which the fused kernel reads, so the two paths cannot disagree.
pub(super) fn searches(params: &ObjectParams) -> bool {
    params.flags & OBJ_LINE_SEARCH != 0
}

/// Whether the per-stage recording gives an object with `params` the rigid start's passes
/// (glsl/rigid_start.comp): its OBJ_RIGID_START, which the fused kernel reads.
pub(super) fn rigid_start(params: &ObjectParams) -> bool {
    params.flags & OBJ_RIGID_START != 0
}

/// The parameters' `pins` for the frame that starts at `t0`: each group's translation
/// velocity, pivot and turn (`sim::pins::PinMotion::step`: the substep's pivot is the frame's
/// moved on by the velocity, as glsl/include/pins.glsl has it), three vec4s a group the
/// object has (`ObjectModel::pin_motions`).
pub(super) fn pin_record(o: &ObjectModel, model: &SimModel, t0: f64) -> Vec<[f32; 4]> {
    // (the substep as the shaders have it, in f32: `Globals::dt`)
    let dt = model.dt() as f32 as f64;
    let record = |step: crate::sim::pins::PinStep| {
        let (v, c) = (step.velocity, step.pivot);
        let q = step.turn.unwrap_or(glam::DQuat::IDENTITY);
        [
            [v.x as f32, v.y as f32, v.z as f32, 0.0],
            [c.x as f32, c.y as f32, c.z as f32, step.turn.is_some() as u32 as f32],
            [q.x as f32, q.y as f32, q.z as f32, q.w as f32],
        ]
    };
    debug_assert!(
        o.pin_groups.len() < PIN_GROUPS,
        "{} pin groups: validation allows {PIN_GROUPS}",
        o.pin_groups.len() + 1
    );
    o.pin_steps(t0, model.frame_dt, 0, dt).into_iter().take(PIN_GROUPS).flat_map(record).collect()
}

/// XPBD's per-spring-type constants for the substep's solve (`obj.xpbd` in the shaders), with
/// its step dt = BDF2_STEP times the substep: alpha~ = 1 / (k dt^2), gamma = b / (k dt), and
/// the relaxation (1 for a method that takes none, `Method::relaxed`) over the denominator
/// (1 + gamma)(w_i + w_j) + alpha~ with the other end free (w_j = w_i) and pinned (w_j = 0).
/// All zero for k = 0 (the shader skips those springs).
fn xpbd_constants(k: f64, o: &ObjectModel, model: &SimModel) -> [f64; 4] {
    if k == 0.0 {
        return [0.0; 4];
    }
    let dt = BDF2_STEP * model.dt();
    let (alpha, gamma, w) = (1.0 / (k * dt * dt), o.damping / (k * dt), 1.0 / o.mass);
    let relaxation = if model.integrator.method().relaxed { model.relaxation } else { 1.0 };
    let scale = |w_sum: f64| relaxation / ((1.0 + gamma) * w_sum + alpha);
    [alpha, gamma, scale(2.0 * w), scale(w)]
}

/// The colliders' GPU records for the frame that starts at `t0` (at least one, so the buffer
/// is never empty).
pub(super) fn collider_data(model: &SimModel, t0: f64) -> Vec<crate::sim::collider::ColliderRecord> {
    let mut data: Vec<_> = model.colliders.iter().map(|c| c.gpu(t0, model.frame_dt)).collect();
    if data.is_empty() {
        data.push([[0.0; 4]; 5]);
    }
    place_meshes(model, &mut data);
    data
}

/// The mesh colliders' triangles in the collider buffer after the records: each mesh's first
/// vec4 (`mesh_distance` in colliders.glsl reads it from its record's b.x).
fn mesh_firsts(model: &SimModel) -> impl Iterator<Item = (usize, &ColliderMesh, u32)> + '_ {
    let records = model.colliders.len().max(1) as u32;
    let meshes = model.colliders.iter().enumerate().filter_map(|(i, c)| match c.shape {
        Shape::Mesh { ref mesh, .. } => Some((i, &**mesh)),
        _ => None,
    });
    meshes.scan(5 * records, |next, (i, mesh)| {
        let first = *next;
        *next = next.saturating_add(mesh.words());
        Some((i, mesh, first))
    })
}

/// Writes each mesh collider's first vec4 into its record (`collider_data`, and the records
/// of a frame whose colliders move).
pub(super) fn place_meshes(model: &SimModel, records: &mut [crate::sim::collider::ColliderRecord]) {
    for (i, _, first) in mesh_firsts(model) {
        records[i][1][0] = first as f32;
    }
}

/// Refuses a scene whose mesh colliders take more of the collider buffer than the records'
/// float offsets reach exactly (`collider_mesh::MAX_WORDS`) or than the device binds.
pub(super) fn check_meshes(model: &SimModel, max_buffer: u64) -> Result<(), UserError> {
    let words = mesh_word_count(model);
    let records = model.colliders.len().max(1) as u64 * 5;
    let most = crate::sim::collider_mesh::MAX_WORDS.min(max_buffer / 16);
    if words + records > most {
        return Err(UserError(format!(
            "the mesh colliders take {:.0} MiB with their grids; a scene's may take at most {:.0} MiB on this device (fewer triangles, or a smaller reach)",
            (16 * (words + records)) as f64 / (1 << 20) as f64,
            (16 * most) as f64 / (1 << 20) as f64
        )));
    }
    Ok(())
}

/// How many vec4s `mesh_words` gives (without packing them).
pub(super) fn mesh_word_count(model: &SimModel) -> u64 {
    mesh_firsts(model).map(|(_, mesh, _)| mesh.words() as u64).sum()
}

/// The mesh colliders' vec4s, as they follow the records in the collider buffer.
pub(super) fn mesh_words(model: &SimModel) -> Vec<[f32; 4]> {
    mesh_firsts(model).flat_map(|(_, mesh, _)| mesh.pack()).collect()
}

/// The initial particles of an object (positions, velocities, pinned flags: pos.w is 1 + the
/// pin group of a pinned particle, 0 for a free one) in a model of frames `frame_dt` long: a
/// pinned particle has its pins' velocity at the start (`ObjectModel::initial_velocity`).
pub fn particles(o: &ObjectModel, frame_dt: f64) -> Vec<Particle> {
    (0..o.positions.len())
        .map(|i| {
            let (x, v) = (o.positions[i].as_vec3(), o.initial_velocity(i, frame_dt).as_vec3());
            let w = if o.pinned[i] { 1.0 + o.group_of(i) as f32 } else { 0.0 };
            Particle { pos: [x.x, x.y, x.z, w], vel: [v.x, v.y, v.z, 0.0] }
        })
        .collect()
}
