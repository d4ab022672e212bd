// Inter-object contact through contact lists over every object's particles. Each substep,
// after every object's physics, contact_begin.comp writes each object's particles into the
// scene's entries and notes whether the lists still hold; when they do not, the scene's
// spatial hash is built (contact_hash.comp's count, the hash scan over the scene's table,
// contact_hash.comp's scatter) and contact.comp searches it, listing for each particle the
// pieces within the reach plus the skin; otherwise contact.comp walks the lists. Their
// binding set is each object's own (binding 1: its parameters, 2: its physics output, 14: its
// contact sums) with the scene's hash in place of the object's (6..10), the hash's own
// parameters (12: hash_mask, cell_inv of the scene's table, and the skin), the object table
// (13), each scene particle's count of touches (3) and its list (5), where the lists were
// built (18) and the substeps' control blocks (19). The CPU twin is sim::cpu::inter_object
// (which searches every substep: the lists change what is searched, not what is found).
// Include after layout.glsl.
#ifndef MSD_CONTACT_COMMON_GLSL
#define MSD_CONTACT_COMMON_GLSL

#ifdef BATCHED
// contact_begin.comp and contact.comp run a chunk of objects a dispatch (batch_chunk.glsl):
// the object's own bindings (1, 2, 14, 15) are arrays, one element an object of the chunk;
// the scene's are the same buffer in every element, which they read as element 0.
#include "batch_chunk.glsl"
layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams v; } b_obj[BATCH_CHUNK];
layout(std430, set = 0, binding = 2) readonly buffer StateIn { Particle v[]; } b_in[BATCH_CHUNK];
layout(std430, set = 0, binding = 14) buffer ContactBuf { vec4 v[]; } b_contact[BATCH_CHUNK];
layout(std430, set = 0, binding = 15) readonly buffer StartIn { Particle v[]; } b_start[BATCH_CHUNK];
#define obj b_obj[MSD_Z].v
#define p_in b_in[MSD_Z].v
#define contact b_contact[MSD_Z].v
#define p_start b_start[MSD_Z].v
#else
layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams obj; };
layout(std430, set = 0, binding = 2) readonly buffer StateIn { Particle p_in[]; };
layout(std430, set = 0, binding = 14) buffer ContactBuf { vec4 contact[]; };
layout(std430, set = 0, binding = 15) readonly buffer StartIn { Particle p_start[]; };  // this object's state at the substep's start
#endif
layout(std430, set = 0, binding = 6) buffer SceneCellRank { uvec2 cell_rank[]; };  // per scene particle
layout(std430, set = 0, binding = 7) buffer SceneCounts { uint counts[]; };
layout(std430, set = 0, binding = 8) buffer SceneStarts { uint starts[]; };
layout(std430, set = 0, binding = 9) buffer SceneSorted { vec4 sorted[]; };         // xyz, w: scene index | pinned << 31
// The same by scene index, then each particle's star box: its lower corner (from the scene's
// particle count on), its upper corner (from twice it), xyz (`star_box`).
layout(std430, set = 0, binding = 16) buffer SceneParticles { vec4 particles[]; };
layout(std430, set = 0, binding = 11) buffer SceneBegun { vec4 begun[]; };          // where each began the substep
layout(std430, set = 0, binding = 10) buffer SceneBlocks { uint block_sums[]; };
layout(std430, set = 0, binding = 12) restrict readonly buffer SceneHash { ObjectParams table; };  // hash_mask, cell_inv
// Per object three rows (OBJECT_ROWS): [first scene index, particle count (float bits),
// contact radius, mass], [grid columns, grid rows (float bits; columns 0 when it touches by
// its segments, a rope), 1 where it keeps its edges from other cloths' (else 0), its pieces' corner
// reach],
// [friction, first work item, lanes (float bits; 0 when its particles look for nothing), 0]
// (contact.comp).
layout(std430, set = 0, binding = 13) restrict readonly buffer Objects { vec4 objects[]; };
// Per scene particle: how many particles of other objects it touches (contact.comp's first
// pass), and its list (PAIR_MAX a particle, contact.comp).
layout(std430, set = 0, binding = 3) buffer SceneTouches { uint touches[]; };
layout(std430, set = 0, binding = 5) buffer ScenePairs { uint pairs[]; };
// Per scene particle: the sum of its moves in fixed point (x, y, z) and its count of contacts
// as the particle that found them (w; contact.comp).
layout(std430, set = 0, binding = 17) buffer SceneMoves { int moves[]; };

// Per scene particle: where the lists were last built (words 4 k to 4 k + 2, float bits; at
// infinity when its list is invalid or overflowed) and the length of its list (4 k + 3).
layout(std430, set = 0, binding = 18) buffer SceneBuilt { uint built[]; };
// Per substep parity a control block of CONTROL_WORDS words: word 0 is 1 when the substep
// rebuilds the hash and the lists; from CONTROL_HASH the indirect dispatch (x, y, z) of
// contact_hash.comp's passes, from CONTROL_SCAN the scan's; all zero when the lists hold.
// contact_begin.comp sets them, contact.comp's pass 2 zeroes the next substep's block, and the
// host zeroes both when a frame starts (sim::gpu::contact::CONTROL_WORDS mirrors this).
layout(std430, set = 0, binding = 19) buffer SceneControl { uint control[]; };
// After the two blocks, two counters (they wrap) of the substeps run with the lists on, and of
// those that rebuilt them (read after each frame for the host's policy, and by tests and
// `simulate`: GpuSim::contact_list_counters).
const uint CONTROL_WORDS = 8u;
const uint CONTROL_HASH = 1u;
const uint CONTROL_SCAN = 4u;
const uint CONTROL_COUNTERS = 2u * CONTROL_WORDS;

layout(push_constant) uniform Which {
    uint object;  // this object's index in `objects` (batched: the chunk's first object's)
    // The pass (bits 0 to 3; contact.comp: 0 counts each particle's contacts, 1 sums the
    // moves, 2 takes them; contact_hash.comp: 0 counts, 1 scatters), the substep's parity
    // (bit 4: its control block) and LISTS_OFF (bit 5).
    uint pass;
    uint work_first;  // contact.comp's passes 0 and 1: the work items of this dispatch
    uint work_end;
#ifdef BATCHED
    BATCH_PUSH
#endif
} which;

const uint PINNED_BIT = 0x80000000u;

const uint OBJECT_ROWS = 3u;
uint first_of(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q].x); }
#ifdef BATCHED
uint this_object() { return which.object + MSD_Z; }
#else
uint this_object() { return which.object; }
#endif
uint first_index() { return first_of(this_object()); }
uint particle_count() { return obj.dims.x * obj.dims.y; }
uint scene_particles() {
    uint last = uint(objects.length()) / OBJECT_ROWS - 1u;
    return first_of(last) + floatBitsToUint(objects[OBJECT_ROWS * last].y);
}
// Scene particle k's star box, of it and, on a cloth of triangles, its six ring neighbours:
// every triangle and edge around it lies inside, so a piece around it is farther than d from
// anything farther than d from the box along some axis (contact.comp's `visit`).
void star_box(uint k, uint scene, out vec3 lo, out vec3 hi) {
    lo = particles[scene + k].xyz;
    hi = particles[2u * scene + k].xyz;
}
uint pass_of() { return which.pass & 15u; }
uint control_block() { return CONTROL_WORDS * ((which.pass >> 4) & 1u); }
// With the lists off (the host's policy, sim::gpu::hash::ListPolicy: while most substeps
// rebuild them) every substep searches the hash, and lists only the contacts (no skin).
const uint LISTS_OFF = 32u;
bool lists_on() { return (which.pass & LISTS_OFF) == 0u; }
// Whether this substep rebuilds the lists.
bool rebuilds() { return control[control_block()] != 0u; }

// The lists hold what is within the reach plus the skin (table.self_distance), so they stay
// exact while no particle has moved half the skin from where they were built: a distance
// between a particle and a triangle or between two edges changes no more than the largest
// move of the particles involved (0.49 of the skin, for rounding).
float list_skin() { return lists_on() ? table.self_distance : 0.0; }
// The hash's 1 / cell edge: with the lists off, without the skin (table.margin).
float hash_cell_inv() { return lists_on() ? table.cell_inv : table.margin; }
float list_half_skin() { return 0.49 * list_skin(); }
vec3 list_built(uint k) {
    return vec3(uintBitsToFloat(built[4u * k]), uintBitsToFloat(built[4u * k + 1u]), uintBitsToFloat(built[4u * k + 2u]));
}
// Notes where particle k's list was built: at `at`, or (`holds` false: a list that overflowed,
// or that holds the contacts alone) at infinity, which counts as moved, so the next substep
// with the lists on rebuilds it.
void set_list_built(uint k, bool holds, vec3 at) {
    uvec3 bits = holds ? floatBitsToUint(at) : uvec3(0x7F800000u);
    built[4u * k] = bits.x;
    built[4u * k + 1u] = bits.y;
    built[4u * k + 2u] = bits.z;
}

#endif
