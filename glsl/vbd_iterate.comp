#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// One vertex colour of one Vertex Block Descent iteration (Chen et al. 2024; vbd_particle in
// solver_bodies.glsl), one invocation per particle of that colour, its neighbours (other
// colours) held. In place in iter (one slice of displacements p - x~ from the BDF2 base x~,
// see predict.comp); aux[i] holds the prediction y - x~.
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#define SX(j) history[hist(uint(j), H_BASE)].xyz
#define SD(j) iter[j].xyz
#define SPIN(j) (iter[j].w > 0.5)
#include "solver_bodies.glsl"
#include "forces.glsl"
#include "solver_end.glsl"

void main() {
    if (!iteration_begin()) return;
    uvec2 cell = coloured_cell(gl_GlobalInvocationID.xy);
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec4 di = iter[i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned) {
        dx = vbd_particle(cell, SX(i), dx, aux[i].xyz);
        iter[i] = vec4(dx, di.w);
    }
    if (last_iteration()) finish_particle(i, dx, pinned, pinned ? 0.0 : held_fraction(dx, aux[i].xyz));
}
