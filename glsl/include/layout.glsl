// std430 layouts shared by every simulation shader: the single source of truth for GPU structs.
// Mirrored in src/sim/gpu_types.rs (#[repr(C)] + bytemuck); tests/suite/layout.rs checks every member
// offset and array stride of these structs in the compiled SPIR-V against the Rust mirrors.
// Units: metres, seconds, kilograms, newtons.
#ifndef MSD_LAYOUT_GLSL
#define MSD_LAYOUT_GLSL

// Number of tube vertices around each rope node (the paper's eight).
#define ROPE_RING 8

// Bits of ObjectParams.flags.
#define OBJ_STRETCH_LIMIT  1u   // enforce the maximum spring elongation
#define OBJ_SELF_COLLISION 2u   // particle-particle self-collision
#define OBJ_SELF_HASH      4u   // ... found through the spatial hash (else brute force)
#define OBJ_SELF_TRIANGLES 8u   // ... a cloth's particles against its triangles (self_contact.glsl)
#define OBJ_ANCHORED      16u   // a particle is pinned (predict_body.glsl's adaptive_start)
#define OBJ_LINE_SEARCH   32u   // the implicit method searches along its Newton steps
#define OBJ_RIGID_START   64u   // a free object starts its solve from its rigid move (rigid_start.glsl)

// Integrators, as sim::integrator::Integrator's discriminants (the fused kernel's SOLVER).
#define METHOD_SYMPLECTIC_EULER 0u
#define METHOD_VERLET           1u
#define METHOD_XPBD             2u
#define METHOD_IMPLICIT         3u
#define METHOD_VBD              4u
#define METHOD_XPBD_JACOBI      5u

struct Particle {
    vec4 pos;   // xyz position [m]; w = 1 pinned, 0 free
    vec4 vel;   // xyz velocity [m/s]; w unused (0)
};

// What the renderer draws: a cloth particle or a rope tube vertex, with its smoothed normal.
struct SurfaceVertex {
    vec4 pos;     // xyz position [m]; w = 1
    vec4 normal;  // xyz unit normal; w = 0
};

// A collider (sim::collider::ColliderModel::gpu): a.xyz centre or point a, a.w the type id
// (COLLIDER_*, as uint bits); b.xyz half extents or point b, b.w radius; rotation a unit
// quaternion (xyzw); extra.x the friction, negative for the object's; extra.yzw its
// velocity over the frame; spin.xyz its angular velocity [rad/s] about its centre (a
// capsule's midpoint) (positions and rotation are the frame's start).
struct Collider {
    vec4 a;
    vec4 b;
    vec4 rotation;
    vec4 extra;
    vec4 spin;
};

// Fourier modes of the wind's turbulence (sim::turbulence::TURBULENCE_MODES).
#define TURBULENCE_MODES 8

struct Globals {
    vec3 gravity;        float dt;             // [m/s^2], substep length [s]
    vec3 wind_origin;    float wind_force;     // cone apex [m], force at full strength [N per particle]
    vec3 wind_dir;       float wind_cos_full;  // unit axis; cos of the full-force half-angle
    float wind_cos_att;                        // cos of the half-angle where the force reaches 0
    uint wind_enabled;                         // 0 or 1
    uint collider_count;                       // colliders[] entries in use
    uint substeps;                             // per frame (the fused shader loops over them)
    float guard_speed;                         // a particle faster than this [m/s] has run away
    uint iterations;                           // solver iterations per substep (iterative methods)
    float relaxation;                          // XPBD over-relaxation of each Gauss-Seidel correction
    float contact_speed;                       // faster than this [m/s], contacts can tunnel (0: no limit)
    float wind_speed;                          // aerodynamic: air speed at full strength [m/s]
                                               // (0: the paper's force)
    float wind_normal;                         // 1/2 air density x normal drag coefficient
    float wind_tangent;                        // 1/2 air density x tangential drag coefficient
    float guard_strain;                        // a structural spring stretched past this strain is
                                               // implausible (0: no check; sim.max_strain)
    float wind_lift;                           // air density x lift coefficient (air.glsl)
    uint wind_modes;                           // the turbulence's modes in use (0: none; air.glsl)
    float pad1;                                // unused (the arrays start at a multiple of 16)
    float pad2;
    vec4 wind_waves[TURBULENCE_MODES];         // per mode: wave vector [1/m], w its phase's rate [1/s]
    vec4 wind_gusts[TURBULENCE_MODES];         // amplitude [m/s], w its phase at the frame's start
};

// Bits of the runtime guard (GuardBuf.flags).
#define GUARD_NON_FINITE 1u   // a position or velocity is NaN or infinite
#define GUARD_RUNAWAY    2u   // a speed above Globals.guard_speed
#define GUARD_FAST       4u   // a speed above Globals.contact_speed (a warning, not a stop)
#define GUARD_STRAIN     8u   // a structural spring stretched past Globals.guard_strain

// Pin groups of an object (sim::model::PIN_GROUPS): a pinned particle's pos.w is 1 + its group.
#define PIN_GROUPS 8

struct ObjectParams {
    uvec2 dims;            // grid columns, rows (a rope is nodes x 1)
    vec2 spacing;          // rest distance between grid neighbours along columns, rows [m]
    vec4 stiffness;        // x structural, y shear, z bending [N/m]; w spring damping [N s/m]
    vec4 rest_scale;       // rest length = scale * grid distance; x structural, y shear, z bending
    float mass;            // per particle [kg]
    float drag;            // Stokes coefficient c, drag force -c v [N s/m]
    float stretch_limit;   // maximum elongation as a fraction of rest length
    float friction;        // Coulomb's mu: colliders, other objects (the mean), its own triangles
    float margin;          // distance kept from collider surfaces [m]
    float self_distance;   // particles closer than this push apart [m]
    float rope_radius;     // rope tube radius [m]
    uint flags;            // OBJ_* bits
    vec4 ring_weights[ROPE_RING / 2]; // rope tube vertex offsets in (side, up) units of rope_radius,
                                      // two a vec4, so the layout is also valid std140
    uint hash_mask;        // spatial hash table size - 1 (a power of two minus one)
    float cell_inv;        // 1 / hash cell edge [1/m]; the edge is twice self_distance
    uint contact_iterations; // passes over a cloth's self-contacts a substep (SimModel's)
    float seam;            // a mesh cloth's seam springs' stiffness [N/m] (0 without seams)
    vec4 rest[3];          // rest length of spring s (SPRINGS order) in rest[s / 4][s % 4] [m]
    vec4 xpbd[3];          // XPBD per spring type, for the substep: alpha~ = 1 / (k dt^2),
                           // gamma = b / (k dt), and the correction's scale relaxation / denominator
                           // with the other end free (z) or pinned (w); zero for k = 0
    vec4 pins[3 * PIN_GROUPS]; // how each pin group's particles move over this frame's substeps
                           // (pins.glsl), three a group: the translation's velocity [m/s]; the
                           // pivot at the frame's start [m] (w: 1 where they turn); a substep's
                           // turn (unit quaternion, xyzw)
};

// The spatial hash of a grid cell: Teschner et al.'s (2003) mix of y and z, plus x itself, so
// that cells next to each other along x have buckets next to each other. The threads of a warp
// (particles next to each other) then read their candidates' bucket starts and positions from
// a few runs of memory rather than from a random bucket each. A linear mix of all three
// collides in regular patterns (docs/design/contact.md, "Detection", has the figures).
uint cell_hash(ivec3 c, uint mask) {
    return (uint(c.x) + ((uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u))) & mask;
}

// The cell a particle at x goes into, in cells of 1 / inv. A position that is not finite or is
// absurdly far (a blow-up, which the guard stops at the frame's end) goes to a cell of the
// particle's own `index` instead: converting it to integers gives every such particle the same
// cell, and every search there would walk all of them (a blown-up towel with edge contact took
// 8 s a frame on lavapipe instead of 1). Absurdly far is HASH_FAR_CELLS cells (2^22) or more
// from the origin: there a float's spacing is at least half a cell, itself at least the
// contact distance, so no contact can be told apart, and a blown-up cloth's particles round
// onto a few points; a cell holding hundreds of them, each within reach of all the others,
// made every search walk them all (the bound was 1e9 cells: docs/PERFORMANCE.md).
const float HASH_FAR_CELLS = 4194304.0;
ivec3 hash_cell(vec3 x, float inv, uint index) {
    vec3 c = floor(x * inv);
    // (NaN fails the comparison)
    if (all(lessThan(abs(c), vec3(HASH_FAR_CELLS)))) return ivec3(c);
    return ivec3(int(index), 1 << 30, -(1 << 30));
}

// The first slot in `sorted` of bucket b (0 <= b <= mask + 1; b = mask + 1: the total) of a
// per-stage hash of mask + 1 buckets: hash_scan.comp leaves a block-local start per bucket and
// an offset per block of SCAN_BLOCK buckets. Needs `starts` and `block_sums` declared.
const uint SCAN_BLOCK = 8192u;  // sim::gpu::object::SCAN_BLOCK
#define BUCKET_START(b, mask) (starts[b] + block_sums[min(b, mask) / SCAN_BLOCK])

#endif
