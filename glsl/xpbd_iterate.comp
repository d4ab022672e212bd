#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// One vertex colour of one XPBD Gauss-Seidel iteration (xpbd_particle in solver_bodies.glsl),
// one invocation per particle of that colour, its neighbours (other colours) held. In place in
// iter (one slice of displacements p - x from the substep start x in p_in, see predict.comp);
// each particle keeps its own copy of the 12 multipliers of its springs in aux[3i .. 3i + 2].
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#define SX(j) p_in[j].pos.xyz
#define SD(j) iter[j].xyz
#define SPIN(j) (iter[j].w > 0.5)
#include "solver_bodies.glsl"
#include "solver_end.glsl"

void main() {
    uvec2 cell = coloured_cell(gl_GlobalInvocationID.xy);
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec4 di = iter[i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned) {
        vec4 lambda[3] = vec4[3](aux[3u * i], aux[3u * i + 1u], aux[3u * i + 2u]);
        xpbd_particle(cell, p_in[i].pos.xyz, dx, lambda);
        for (uint q = 0u; q < 3u; ++q) aux[3u * i + q] = lambda[q];
        iter[i] = vec4(dx, di.w);
    }
    if (last_iteration()) finish_particle(i, dx, pinned);
}
