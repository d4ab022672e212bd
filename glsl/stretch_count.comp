#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// The stretch limit's counts on the per-stage path (stretch.glsl), one thread a particle: from
// the physics output as the constraint stage reads it (after a cloth's self-contact moved it),
// into that output's velocity w, for the constraint stage to read each spring's other end's.
// Dispatched only for objects with a stretch limit.
#define STATE_IN_WRITE
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(push_constant) uniform Push {
    BATCH_PUSH
} pc;

#define CPOS(j) p_in[j].pos.xyz
#include "stretch.glsl"

void main() {
    if (!batch_begin(pc.batch_mask)) return;
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    p_in[i].vel.w = float(stretched_springs(ivec2(cell), p_in[i].pos.xyz));
}
