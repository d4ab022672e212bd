// Descriptor bindings of the simulation pipelines (one set per object and ping-pong direction).
// The host side is src/sim/gpu/object.rs; the order here is part of the layout contract.
// A shader that defines BATCHED runs a chunk of objects a dispatch and declares the per-object
// bindings as arrays instead (batch.glsl); the globals and colliders are the scene's.
#ifndef MSD_BINDINGS_GLSL
#define MSD_BINDINGS_GLSL
#include "layout.glsl"

// Parameters are never written while a frame runs (restrict: the compiler may keep them in
// registers across the shaders' stores and barriers).
layout(std140, set = 0, binding = 0) uniform GlobalsBuf { Globals g; };
layout(std430, set = 0, binding = 4) restrict readonly buffer ColliderBuf { Collider colliders[]; };
// The same buffer as vec4s: the mesh colliders' grids and triangles follow the records
// (sim::gpu::object::mesh_words; read by mesh_distance in colliders.glsl).
layout(std430, set = 0, binding = 4) restrict readonly buffer ColliderWords { vec4 collider_words[]; };
#ifdef BATCHED
#include "batch.glsl"
#else
#ifdef OBJ_COPY
// The fused kernel reads a copy of the parameters (registers), taken at its start.
layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams obj_buffer; uint obj_words[]; };
ObjectParams obj;
#else
// (a mesh cloth's lists follow the parameters: mesh_springs.glsl)
layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams obj; uint obj_words[]; };
#endif
// The fused shader loads its state from p_in and stores it back there (each thread its own
// particles; with a cloth's edge pairs it also writes each substep's constraint results into
// p_out for the truncation to read, fused.comp); the per-stage shaders read one buffer and
// write the other.
#ifdef STATE_FUSED
layout(std430, set = 0, binding = 2) buffer StateIn { Particle p_in[]; };
layout(std430, set = 0, binding = 3) buffer StateOut { Particle p_out[]; };
#else
#ifdef STATE_IN_WRITE
// A cloth's self-contact passes move the physics output between passes (self_pairs.comp).
layout(std430, set = 0, binding = 2) buffer StateIn { Particle p_in[]; };
#else
layout(std430, set = 0, binding = 2) readonly buffer StateIn { Particle p_in[]; };
#endif
#ifdef STATE_OUT_READ
// The constraint stage also reads where its own particle began the substep (collider friction).
layout(std430, set = 0, binding = 3) buffer StateOut { Particle p_out[]; };
#else
layout(std430, set = 0, binding = 3) writeonly buffer StateOut { Particle p_out[]; };
#endif
#endif
layout(std430, set = 0, binding = 5) writeonly buffer SurfaceBuf { SurfaceVertex surface[]; };
// Spatial hash of the self-collision (objects without it bind a placeholder).
layout(std430, set = 0, binding = 6) buffer HashCellRank { uvec2 cell_rank[]; }; // per particle: bucket, rank in it
layout(std430, set = 0, binding = 7) buffer HashCounts { uint counts[]; };       // per bucket: particles in it (zero between substeps)
layout(std430, set = 0, binding = 8) buffer HashStarts { uint starts[]; };       // per bucket + 1: first slot in `sorted` (the last: the total)
layout(std430, set = 0, binding = 9) buffer HashSorted { vec4 sorted[]; };       // by bucket: xyz position, w index bits
#ifndef BLOCK_SUMS_COHERENT
#define BLOCK_SUMS_COHERENT
#endif
layout(std430, set = 0, binding = 10) BLOCK_SUMS_COHERENT buffer HashBlocks { uint block_sums[]; };  // scan: per-block offsets (hash_scan.comp)
// The runtime guard of the object, read by the host after each frame.
// (Then the per-stage contact lists' counters, lists.glsl.)
layout(std430, set = 0, binding = 11) buffer GuardBuf { uint guard_flags; uint guard_first; uint guard_lists_on; uint guard_lists_rebuilt; }; // GUARD_* bits, lowest bad index
// Iterates of the iterative integrators (objects of the explicit ones bind a placeholder).
layout(std430, set = 0, binding = 12) buffer SolverIter { vec4 iter[]; }; // slices of N positions; w = 1 pinned
layout(std430, set = 0, binding = 13) buffer SolverAux { vec4 aux[]; };   // xpbd: 12 multipliers per particle (a mesh: one a list entry); implicit: y
// Inter-object contact: per particle, the summed corrections from other objects (xyz) and
// their count (w), written by contact.comp each substep, read by the constraint stage.
layout(std430, set = 0, binding = 14) buffer ContactBuf { vec4 contact[]; };

// The fused kernel's self-collision contact list (fused.comp): per particle a header (the
// position the list was built at, xyz, and its length, w as bits) in words [4 i, 4 i + 4),
// then entry e of particle i at 4 n + e n + i.
layout(std430, set = 0, binding = 15) buffer SelfListBuf { uint self_list[]; };

// The iterative integrators' BDF2 history (sim::integrator::BDF2_STEP), three arrays of a vec4
// a particle (history[hist(i, H_*)]): H_DX its last substep's x_n - x_{n-1} as the solve made
// it (w: 1 valid, 0 none: a first substep, or a state written by the host), H_DV v_n -
// v_{n-1}. During a substep the per-stage shaders keep the solve's base x~ in H_BASE, read by
// the neighbours, and what its rounding left out (bdf2_start) in H_DV. All zero is "no
// history". Arrays, not a record a particle: the passes that read the neighbours' bases then
// read 16 bytes a particle, not one vec4 of every 48 (docs/design/integrators.md, "BDF2").
layout(std430, set = 0, binding = 16) buffer SolverHistory { vec4 history[]; };
// A cloth's contact with its own triangles (self_contact.glsl): per particle its summed moves
// in fixed point and its count of contacts, then the contacts each keeps. Coherent: the fused
// kernel's phases read what others' atomics wrote, between barriers.
layout(std430, set = 0, binding = 17) coherent buffer SelfPairsBuf { int self_pairs[]; };

#endif  // BATCHED

const uint H_DX = 0u;
const uint H_DV = 1u;
const uint H_BASE = 2u;
// Must equal sim::integrator::BDF2_STEP.
const float BDF2_STEP = 2.0 / 3.0;
// The step of the iterative integrators' solve: h = 2 dt / 3 (BDF2), or dt (implicit Euler)
// for a free object that starts from its rigid move (OBJ_RIGID_START;
// sim::cpu::integrators::inertial says why).
bool implicit_euler() { return (obj.flags & OBJ_RIGID_START) != 0u; }
float solve_share() { return implicit_euler() ? 1.0 : BDF2_STEP; }
float solve_dt() { return solve_share() * g.dt; }

// Flags particle i when its state is non-finite or runs away (called once per frame). A
// pinned particle's speed is its pins' (sim::pins), given, not a runaway.
void guard_check(uint i, Particle p) {
    bool bad = any(isnan(p.pos.xyz)) || any(isinf(p.pos.xyz)) || any(isnan(p.vel.xyz)) || any(isinf(p.vel.xyz));
    float speed2 = p.pos.w > 0.5 ? 0.0 : dot(p.vel.xyz, p.vel.xyz);
    uint flag = bad ? GUARD_NON_FINITE : (speed2 > g.guard_speed * g.guard_speed ? GUARD_RUNAWAY : 0u);
    if (flag == 0u && g.contact_speed > 0.0 && speed2 > g.contact_speed * g.contact_speed) flag = GUARD_FAST;
    if (flag != 0u) {
        atomicOr(guard_flags, flag);
        atomicMin(guard_first, i);
    }
}

uint particle_count() { return obj.dims.x * obj.dims.y; }
uint hist(uint i, uint what) { return what * particle_count() + i; }
bool is_pinned(uint i) { return p_in[i].pos.w > 0.5; }

#endif
