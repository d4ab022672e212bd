// The spring network of a grid: 12 springs per interior particle (the paper's structural, shear
// and bending springs). A rope is a grid of nodes x 1: its vertical springs fall out of bounds.
#ifndef MSD_SPRINGS_GLSL
#define MSD_SPRINGS_GLSL

#define SPRING_STRUCTURAL 0
#define SPRING_SHEAR 1
#define SPRING_BENDING 2

// xy: grid offset to the other particle, z: spring type. Indexed by a loop variable, glslang
// gives each invocation a copy of the array (an "indexable" function variable); the loops over
// it are marked [[unroll]] (GL_EXT_control_flow_attributes, in every shader that includes
// this) so the driver can fold the indices into constants.
const ivec3 SPRINGS[12] = ivec3[12](
    ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
    ivec3(1, 1, 1), ivec3(-1, -1, 1), ivec3(1, -1, 1), ivec3(-1, 1, 1),
    ivec3(2, 0, 2), ivec3(-2, 0, 2), ivec3(0, 2, 2), ivec3(0, -2, 2));

// Index of the particle at `cell + offset`, or -1 when it falls outside the grid.
int neighbour(ivec2 cell, ivec2 offset, uvec2 dims) {
    ivec2 o = cell + offset;
    if (o.x < 0 || o.y < 0 || o.x >= int(dims.x) || o.y >= int(dims.y)) return -1;
    return o.x + o.y * int(dims.x);
}

// The particle at the other end of spring s (an index into SPRINGS) of `cell`, or -1. The
// fused kernel replaces it with a lookup of the particle's valid springs.
#ifndef SPRING_NEIGHBOUR
#define SPRING_NEIGHBOUR(cell, s) neighbour(ivec2(cell), SPRINGS[s].xy, obj.dims)
#endif

#include "mesh_springs.glsl"

// Rest length of spring s (an index into SPRINGS; a constant in the unrolled spring loops),
// computed on the host. Include after bindings.glsl.
float rest_length(int s) { return obj.rest[s >> 2][s & 3]; }

// The guard's plausibility check of the particle at `cell` (the surface stage, once a frame):
// one of its structural springs stretched past sim.max_strain (g.guard_strain; 0: no check)
// flags it (GUARD_STRAIN).
void guard_strain(uvec2 cell) {
    float most = g.guard_strain;
    if (!(most > 0.0) || obj.stiffness[SPRING_STRUCTURAL] == 0.0) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec3 x = p_in[i].pos.xyz;
    if (is_mesh()) {
        for (uint e = mesh_first(i); e < mesh_first(i + 1u); ++e) {
            MeshSpring s = mesh_spring(e);
            if (s.type == SPRING_STRUCTURAL && distance(p_in[s.other].pos.xyz, x) > (1.0 + most) * s.rest) {
                atomicOr(guard_flags, GUARD_STRAIN);
                atomicMin(guard_first, i);
                return;
            }
        }
        return;
    }
    [[unroll]] for (int s = 0; s < 4; ++s) {
        int j = neighbour(ivec2(cell), SPRINGS[s].xy, obj.dims);
        if (j < 0) continue;
        if (distance(p_in[j].pos.xyz, x) > (1.0 + most) * rest_length(s)) {
            atomicOr(guard_flags, GUARD_STRAIN);
            atomicMin(guard_first, i);
            return;
        }
    }
}

// The spring classes XPBD sweeps (sim::integrator::SPRING_CLASSES and spring_class_parity):
// class q = 2 dir + parity; direction dir is the offset from a spring's first node to its
// second, its springs split by the parity of the first node's coordinate along the line (halved
// for bending). No two springs of a class share a particle. A pass per class, then a pass
// (XPBD_FINISH, sim::gpu::step's) that finishes every particle.
const uint SPRING_CLASS_COUNT = 12u;
const uint XPBD_FINISH = 0xFFFFFFFEu;
// The class XPBD sweeps in its pass-th pass of an iteration: from the last class to the first,
// so the structural springs come last (sim::integrator::xpbd_class_order says why).
uint xpbd_class(uint pass) { return SPRING_CLASS_COUNT - 1u - pass; }
ivec2 class_offset(uint dir) {
    return dir == 0u ? ivec2(1, 0) : dir == 1u ? ivec2(0, 1) : dir == 2u ? ivec2(1, 1)
         : dir == 3u ? ivec2(-1, 1) : dir == 4u ? ivec2(2, 0) : ivec2(0, 2);
}
// The direction's slot in SPRINGS (its type is slot / 4).
int class_slot(uint dir) { return dir == 0u ? 0 : dir == 1u ? 2 : dir == 2u ? 4 : dir == 3u ? 7 : dir == 4u ? 8 : 10; }
uint class_parity(uint dir, ivec2 cell) {
    int u = (dir == 0u || dir == 2u || dir == 4u) ? cell.x : cell.y;
    return uint(dir >= 4u ? u >> 1 : u) & 1u;
}

// The vertex colouring the Gauss-Seidel integrators sweep (sim::integrator::vertex_colours and
// vertex_colour): particle (x, y) has colour (x + 2 y) mod C, C = 5 colours, 3 for one row; no
// spring joins two particles of one colour.
uint vertex_colours(uvec2 dims) { return dims.y == 1u ? 3u : 5u; }
uint vertex_colour(uvec2 cell, uint colours) { return (cell.x + 2u * cell.y) % colours; }
// The first column of row y with colour c; the others follow every C columns.
uint colour_first(uint c, uint y, uint colours) { return (c + colours - (2u * y) % colours) % colours; }

#endif
