//! Rust mirrors of the std430 structs in `glsl/include/layout.glsl` (the source of truth).
//! Each is `#[repr(C)]` + `Pod` with explicit padding and a `const` size assert; `tests/suite/layout.rs`
//! compares every member offset, every scalar's offset and type, and array strides with the
//! compiled SPIR-V.

use crate::sim::turbulence::TURBULENCE_MODES;

/// A struct whose layout must agree with a GLSL struct of the same name.
pub trait GpuLayout {
    const NAME: &'static str;
    const SIZE: usize;
    /// (member name, byte offset) in declaration order.
    fn offsets() -> Vec<(&'static str, usize)>;
    /// Every scalar, (byte offset, kind), in member order.
    fn scalars() -> Vec<(usize, GpuScalar)>;
}

/// What a 32-bit word of a shared struct holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GpuScalar {
    F32,
    U32,
    I32,
}

/// A member type of a shared struct: its scalars from byte `base`.
pub trait GpuMember {
    fn scalars(base: usize, out: &mut Vec<(usize, GpuScalar)>);
}

impl GpuMember for f32 {
    fn scalars(base: usize, out: &mut Vec<(usize, GpuScalar)>) {
        out.push((base, GpuScalar::F32));
    }
}

impl GpuMember for u32 {
    fn scalars(base: usize, out: &mut Vec<(usize, GpuScalar)>) {
        out.push((base, GpuScalar::U32));
    }
}

impl GpuMember for i32 {
    fn scalars(base: usize, out: &mut Vec<(usize, GpuScalar)>) {
        out.push((base, GpuScalar::I32));
    }
}

impl<T: GpuMember, const N: usize> GpuMember for [T; N] {
    fn scalars(base: usize, out: &mut Vec<(usize, GpuScalar)>) {
        for k in 0..N {
            T::scalars(base + k * std::mem::size_of::<T>(), out);
        }
    }
}

macro_rules! gpu_struct {
    ($(#[$meta:meta])* $name:ident, size $size:expr, { $($(#[$fmeta:meta])* $field:ident : $ty:ty,)* }) => {
        $(#[$meta])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct $name { $($(#[$fmeta])* pub $field: $ty,)* }
        const _: () = assert!(std::mem::size_of::<$name>() == $size);
        impl GpuLayout for $name {
            const NAME: &'static str = stringify!($name);
            const SIZE: usize = $size;
            fn offsets() -> Vec<(&'static str, usize)> {
                vec![$((stringify!($field), std::mem::offset_of!($name, $field)),)*]
            }
            fn scalars() -> Vec<(usize, GpuScalar)> {
                let mut out = Vec::new();
                $(<$ty as GpuMember>::scalars(std::mem::offset_of!($name, $field), &mut out);)*
                out
            }
        }
    };
}

use crate::sim::model::PIN_GROUPS;

/// Tube vertices around each rope node (`ROPE_RING` in the header).
pub const ROPE_RING: usize = 8;
/// `ObjectParams::flags` bits (`OBJ_*` in the header).
pub const OBJ_STRETCH_LIMIT: u32 = 1;
pub const OBJ_SELF_COLLISION: u32 = 2;
pub const OBJ_SELF_HASH: u32 = 4;
pub const OBJ_SELF_TRIANGLES: u32 = 8;
/// A particle is pinned (`sim::cpu::integrators::toward_rest`).
pub const OBJ_ANCHORED: u32 = 16;
/// The implicit method searches along its Newton steps (`sim::cpu::implicit_searches`).
pub const OBJ_LINE_SEARCH: u32 = 32;
/// A free object starts its solve from its rigid move (`sim::cpu::integrators::rigid_starts`).
pub const OBJ_RIGID_START: u32 = 64;
/// Bits of the `FEATURES` specialization constant (`F_*` in `glsl/include/features.glsl`).
pub const FEATURE_STRUCTURAL: u32 = 1;
pub const FEATURE_SHEAR: u32 = 2;
pub const FEATURE_BENDING: u32 = 4;
pub const FEATURE_DAMPING: u32 = 8;
pub const FEATURE_WIND: u32 = 16;
pub const FEATURE_SPHERES: u32 = 32;
pub const FEATURE_STRETCH: u32 = 64;
pub const FEATURE_SELF: u32 = 128;
pub const FEATURE_GROUND: u32 = 256;
pub const FEATURE_BOX: u32 = 512;
pub const FEATURE_CAPSULE: u32 = 1024;
pub const FEATURE_CONTACT: u32 = 2048;
pub const FEATURE_EDGES: u32 = 4096;
pub const FEATURE_TRIANGLES: u32 = 8192;
pub const FEATURE_EDGE_PAIRS: u32 = 16384;
pub const FEATURE_SEGMENT_PAIRS: u32 = 32768;
pub const FEATURE_TURNING: u32 = 65536;
pub const FEATURE_MESH: u32 = 131072;
/// The features a shader created without the constant has (glsl/include/features.glsl's
/// default: all but a rope's segment pairs and a mesh cloth's lists).
pub const FEATURES_DEFAULT: u32 = 0x37FFF;
/// A cloth made from a mesh: its lists after its parameters (glsl/include/mesh_springs.glsl).
pub const FEATURE_CLOTH_MESH: u32 = 262144;

/// Whether an object of `FEATURES` `f` keeps a cloth's edges from its edges (edge pairs that
/// are not a rope's segment pairs): its search loops over six ring edges a candidate and reads
/// crease words.
pub fn has_cloth_edge_pairs(f: u32) -> bool {
    f & (FEATURE_EDGE_PAIRS | FEATURE_SEGMENT_PAIRS) == FEATURE_EDGE_PAIRS
}

gpu_struct!(
    /// One simulated particle (cloth particle or rope node).
    Particle, size 32, {
    /// xyz position [m]; w = 1 pinned, 0 free.
    pos: [f32; 4],
    /// xyz velocity [m/s].
    vel: [f32; 4],
});

gpu_struct!(
    /// One collider as the shaders read it (`ColliderModel::gpu` packs these five in order).
    Collider, size 80, {
    a: [f32; 4],
    b: [f32; 4],
    rotation: [f32; 4],
    extra: [f32; 4],
    spin: [f32; 4],
});

gpu_struct!(
    /// A drawable vertex with its normal (cloth particle or rope tube vertex).
    SurfaceVertex, size 32, {
    pos: [f32; 4],
    normal: [f32; 4],
});

gpu_struct!(
    /// Scene-wide parameters.
    Globals, size 368, {
    gravity: [f32; 3],
    dt: f32,
    wind_origin: [f32; 3],
    wind_force: f32,
    wind_dir: [f32; 3],
    wind_cos_full: f32,
    wind_cos_att: f32,
    wind_enabled: u32,
    collider_count: u32,
    substeps: u32,
    guard_speed: f32,
    iterations: u32,
    relaxation: f32,
    contact_speed: f32,
    wind_speed: f32,
    wind_normal: f32,
    wind_tangent: f32,
    guard_strain: f32,
    wind_lift: f32,
    /// The turbulence's modes in use (0 or `TURBULENCE_MODES`).
    wind_modes: u32,
    pad1: f32,
    pad2: f32,
    /// Per mode its wave vector and its phase's rate (`sim::turbulence::Turbulence::gpu`).
    wind_waves: [[f32; 4]; TURBULENCE_MODES],
    /// Per mode its amplitude and its phase at the frame's start (rewritten each frame).
    wind_gusts: [[f32; 4]; TURBULENCE_MODES],
});

/// Runtime guard bits (`GUARD_*` in the header).
pub const GUARD_NON_FINITE: u32 = 1;
pub const GUARD_RUNAWAY: u32 = 2;
pub const GUARD_FAST: u32 = 4;
pub const GUARD_STRAIN: u32 = 8;

gpu_struct!(
    /// Per-object parameters (std430; every array is of 16-byte elements, so the layout is
    /// also valid std140, as a uniform buffer would need).
    ObjectParams, size 640, {
    dims: [u32; 2],
    spacing: [f32; 2],
    stiffness: [f32; 4],
    rest_scale: [f32; 4],
    mass: f32,
    drag: f32,
    stretch_limit: f32,
    friction: f32,
    margin: f32,
    self_distance: f32,
    rope_radius: f32,
    flags: u32,
    /// Two (side, up) pairs a vec4 in the shaders.
    ring_weights: [[f32; 2]; ROPE_RING],
    hash_mask: u32,
    cell_inv: f32,
    /// Passes over a cloth's contacts with its own triangles a substep.
    contact_iterations: u32,
    /// A mesh cloth's seam springs' stiffness [N/m] (0 without seams; glsl/include/mesh_springs.glsl).
    seam: f32,
    /// Rest length of each spring, in the shaders' SPRINGS order [m].
    rest: [[f32; 4]; 3],
    /// XPBD per spring type for the substep: alpha~, gamma, relaxation over the denominator
    /// with the other end free, and with it pinned.
    xpbd: [[f32; 4]; 3],
    /// How each pin group's particles move over this frame's substeps (`sim::pins`, written
    /// each frame where they move), three a group: the translation's velocity [m/s] (w
    /// unused), the pivot at the frame's start [m] (w: 1 where the pins turn), and a
    /// substep's turn (a unit quaternion, xyzw).
    pins: [[f32; 4]; 3 * PIN_GROUPS],
});

gpu_struct!(
    /// Per-frame camera and light for the scene shaders (`render.glsl`, std140).
    Camera, size 112, {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    light_pos: [f32; 4],
    light_color: [f32; 4],
});

gpu_struct!(
    /// Per-draw push constants of the scene shaders (`render.glsl`).
    Draw, size 112, {
    model: [[f32; 4]; 4],
    front: [f32; 4],
    back: [f32; 4],
    params: [f32; 4],
});
