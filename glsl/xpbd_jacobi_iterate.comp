#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// One iteration of XPBD by Jacobi with its step bound (xpbd_jacobi_particle in
// solver_bodies.glsl), one thread per particle. Iterate slices alternate: iteration k reads
// slice k % 2 (displacements p - x~ from the BDF2 base x~, see predict.comp) and writes
// (k + 1) % 2; aux[3i .. 3i + 3) holds the multipliers of particle i's 12 springs (its own
// copy: both ends of a spring compute the same update); a mesh cloth's, aux's floats at its
// list's entries (MESH_LAMBDA), and its step bound, summed in the first iteration of a
// substep, kept negated in the iterate's w (a free particle's w is 0 there, a pinned one's
// its pin code over 0.5, which SPIN reads: the bound in (0, 1] keeps it free).
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#include "solver_end.glsl"
#define SLICE(j) iter[(it.k % 2u) * particle_count() + uint(j)]
#define SX(j) history[hist(uint(j), H_BASE)].xyz
#define SD(j) SLICE(j).xyz
#define SPIN(j) (SLICE(j).w > 0.5)
#define MESH_LAMBDA(e) aux[(e) >> 2u][(e) & 3u]
#include "solver_bodies.glsl"

void main() {
    if (!iteration_begin()) return;
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    uint next = ((it.k + 1u) % 2u) * particle_count();
    vec4 di = SLICE(i);
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned && is_mesh()) {
        float beta = it.k == 0u ? xpbd_jacobi_mesh_bound(i) : -di.w;
        dx = xpbd_jacobi_mesh(i, SX(i), dx, !last_iteration(), beta);
        di.w = -beta;
    } else if (!pinned) {
        vec4 lam[3] = vec4[3](aux[3u * i], aux[3u * i + 1u], aux[3u * i + 2u]);
        dx = xpbd_jacobi_particle(cell, SX(i), dx, lam);
        if (!last_iteration()) {
            for (uint q = 0u; q < 3u; ++q) aux[3u * i + q] = lam[q];
        }
    }
    iter[next + i] = vec4(dx, di.w);
    if (last_iteration()) finish_particle(i, dx, pinned, 0.0);
}
