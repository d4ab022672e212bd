// Inter-object contact through one spatial hash over every object's particles, built each
// substep after every object's physics: contact_count.comp counts each object's particles into
// it, the hash scan (hash_scan.comp, over the scene's table) turns counts into starts,
// contact_scatter.comp writes positions by bucket, and contact.comp queries it for each
// object. Their binding set is each object's own (binding 1: its parameters, 2: its physics
// output, 14: its contact sums) with the scene's hash in place of the object's (6..10), the
// hash's own parameters (12: hash_mask, cell_inv of the scene's table), the object table (13)
// and each scene particle's count of touches (3) and the slots of its partners (5). The CPU
// twin is sim::cpu::inter_object.
// Include after layout.glsl.
#ifndef MSD_CONTACT_COMMON_GLSL
#define MSD_CONTACT_COMMON_GLSL

layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams obj; };
layout(std430, set = 0, binding = 2) readonly buffer StateIn { Particle p_in[]; };
layout(std430, set = 0, binding = 6) buffer SceneCellRank { uvec2 cell_rank[]; };  // per scene particle
layout(std430, set = 0, binding = 7) buffer SceneCounts { uint counts[]; };
layout(std430, set = 0, binding = 8) buffer SceneStarts { uint starts[]; };
layout(std430, set = 0, binding = 9) buffer SceneSorted { vec4 sorted[]; };         // xyz, w: scene index | pinned << 31
layout(std430, set = 0, binding = 16) buffer SceneParticles { vec4 particles[]; };  // the same, by scene index
layout(std430, set = 0, binding = 11) buffer SceneBegun { vec4 begun[]; };          // where each began the substep
layout(std430, set = 0, binding = 15) readonly buffer StartIn { Particle p_start[]; };  // this object's state at the substep's start
layout(std430, set = 0, binding = 10) buffer SceneBlocks { uint block_sums[]; };
layout(std430, set = 0, binding = 12) restrict readonly buffer SceneHash { ObjectParams table; };  // hash_mask, cell_inv
// Per object three rows (OBJECT_ROWS): [first scene index, particle count (float bits),
// contact radius, mass], [grid columns, grid rows (float bits; columns 0 when it touches by
// its segments, a rope), 1 where it keeps its edges from edges (else 0), its pieces' corner
// reach],
// [friction, first work item, lanes (float bits; 0 when its particles look for nothing), 0]
// (contact.comp).
layout(std430, set = 0, binding = 13) restrict readonly buffer Objects { vec4 objects[]; };
layout(std430, set = 0, binding = 14) buffer ContactBuf { vec4 contact[]; };
// Per scene particle: how many particles of other objects it touches (contact.comp's first pass),
// and the contacts it noted in pass 0 (PAIR_MAX a particle, contact.comp).
layout(std430, set = 0, binding = 3) buffer SceneTouches { uint touches[]; };
layout(std430, set = 0, binding = 5) buffer ScenePairs { uint pairs[]; };
// Per scene particle: the sum of its moves in fixed point (x, y, z) and the count of contacts
// it noted in pass 0 (w; contact.comp).
layout(std430, set = 0, binding = 17) buffer SceneMoves { int moves[]; };

layout(push_constant) uniform Which {
    uint object;  // this object's index in `objects`
    uint pass;    // contact.comp: 0 counts each particle's contacts, 1 sums the moves, 2 takes them
    uint work_first;  // contact.comp's passes 0 and 1: the work items of this dispatch
    uint work_end;
} which;

const uint PINNED_BIT = 0x80000000u;

const uint OBJECT_ROWS = 3u;
uint first_of(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q].x); }
uint first_index() { return first_of(which.object); }
uint particle_count() { return obj.dims.x * obj.dims.y; }

#endif
