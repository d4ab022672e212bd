#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Constraint stage, one thread per particle: reads p_in (the physics output, and the spatial
// hash built from it), writes p_out. The work itself is in constraints_body.glsl (shared with
// fused.comp).
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(push_constant) uniform Push {
    uint substep;  // of the frame, 0-based
} pc;

#define IN(i) p_in[i]
#define OUT(i) p_out[i]
#include "constraints_body.glsl"

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    constraints_particle(cell, pc.substep);
}
