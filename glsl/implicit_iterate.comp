#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// One iteration of BDF2 by projective dynamics (implicit_particle in
// solver_bodies.glsl), one thread per particle: the local step and one damped,
// Chebyshev-accelerated Jacobi sweep. Iterate slices rotate: iteration k reads slice k % 3 (and
// the one before, (k + 2) % 3), writes (k + 1) % 3. The iterates and aux[i] (the prediction y)
// are displacements from the BDF2 base x~ (history H_BASE, see predict.comp).
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#include "solver_end.glsl"
#define SX(j) history[hist(uint(j), H_BASE)].xyz
#define SD(j) iter[(it.k % 3u) * particle_count() + uint(j)].xyz
#define SPIN(j) false
#include "solver_bodies.glsl"

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    uint n = particle_count();
    uint cur = (it.k % 3u) * n;
    uint prev = it.k == 0u ? cur : ((it.k + 2u) % 3u) * n;
    uint next = ((it.k + 1u) % 3u) * n;
    vec4 di = iter[cur + i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned) dx = implicit_particle(cell, chebyshev_omega(it.k, obj.cheb_rho), SX(i), dx, aux[i].xyz, iter[prev + i].xyz);
    iter[next + i] = vec4(dx, di.w);
    if (last_iteration()) finish_particle(i, dx, pinned, 0.0);
}
