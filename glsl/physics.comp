#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// Physics stage, one thread per particle: reads p_in (the state at the start of the substep),
// writes p_out. The work itself is in physics_body.glsl (shared with fused.comp).
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(push_constant) uniform Push {
    uint substep;  // of the frame, 0-based
    uint lists;    // 1: self-collision contact lists on (hash_count.glsl)
    BATCH_PUSH
} pc;

#define IN(i) p_in[i]
#define OUT(i) p_out[i]
#include "physics_body.glsl"

void main() {
    if (!batch_begin(pc.batch_mask)) return;
    air_time = float(pc.substep) * g.dt;
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    physics_particle(cell, pc.substep, pc.lists != 0u);
}
