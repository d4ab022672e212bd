#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// A free object's rigid start per stage (glsl/include/rigid_start.glsl), after predict.comp
// has left each particle's guess in the iterates (iter: p - x~, w pinned) and its base x~ in
// history H_BASE. The host records it for the free objects of the methods that start
// adaptively (sim::gpu::step), in three passes (`phase` in the push constants):
//   PHASE_PARTIAL  each workgroup's sums of rigid_terms into aux from RIGID_AT + 4 + 4 w;
//   PHASE_TOTAL    (one workgroup) their totals into aux[RIGID_AT .. RIGID_AT + 4);
//   PHASE_APPLY    each particle's iterate moved to where rigid_start starts it.
// The region of aux from the particle count on is free between the prediction and the first
// iteration: VBD keeps its contact rounds' moves there and the implicit method its partial
// sums, each written before it is read.
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"
#define IN(i) p_in[i]
#include "predict_body.glsl"
#include "rigid_start.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(push_constant) uniform Push {
    uint phase;
    BATCH_PUSH
} pc;

// (a workgroup of 256 invocations at most, subgroups of 4 or more)
#define REDUCE_T vec4
#define REDUCE_SLOTS 64
#include "reduce.glsl"

const uint PHASE_PARTIAL = 0u;
const uint PHASE_TOTAL = 1u;
const uint PHASE_APPLY = 2u;

uint rigid_at() { return particle_count(); }

// The object's workgroups (a batched dispatch has as many as its largest object).
uvec2 object_grid() { return (obj.dims + gl_WorkGroupSize.xy - 1u) / gl_WorkGroupSize.xy; }

// The workgroup's sum of `mine` (every invocation calls it).
mat4 group_sum(mat4 mine) {
    mat4 total;
    [[unroll]] for (int c = 0; c < 4; ++c) total[c] = workgroup_sum(mine[c]);
    return total;
}

void main() {
    if (!batch_begin(pc.batch_mask)) return;
    uvec2 grid = object_grid();
    uint lanes = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
    if (pc.phase == PHASE_TOTAL) {
        mat4 sum = mat4(0.0);
        for (uint w = gl_LocalInvocationIndex; w < grid.x * grid.y; w += lanes) {
            [[unroll]] for (int c = 0; c < 4; ++c) sum[c] += aux[rigid_at() + 4u + 4u * w + uint(c)];
        }
        mat4 total = group_sum(sum);
        if (gl_LocalInvocationIndex == 0u) {
            [[unroll]] for (int c = 0; c < 4; ++c) aux[rigid_at() + uint(c)] = total[c];
        }
        return;
    }
    if (any(greaterThanEqual(gl_WorkGroupID.xy, grid))) return;
    uvec2 cell = gl_GlobalInvocationID.xy;
    bool inside = cell.x < obj.dims.x && cell.y < obj.dims.y;  // (every invocation sums)
    uint i = inside ? cell.x + cell.y * obj.dims.x : 0u;
    vec4 guess = iter[i];
    vec3 x = p_in[i].pos.xyz;
    vec3 here = x - history[hist(i, H_BASE)].xyz;  // x - x~
    vec3 q = x - p_in[0].pos.xyz;
    vec3 d = guess.xyz - here;
    if (pc.phase == PHASE_PARTIAL) {
        // (pinned particles left out, as the fused kernel does: a particle dragged in the app)
        mat4 total = group_sum(inside && guess.w < 0.5 ? rigid_terms(q, d) : mat4(0.0));
        uint w = gl_WorkGroupID.x + gl_WorkGroupID.y * grid.x;
        if (gl_LocalInvocationIndex == 0u) {
            [[unroll]] for (int c = 0; c < 4; ++c) aux[rigid_at() + 4u + 4u * w + uint(c)] = total[c];
        }
        return;
    }
    if (!inside || guess.w > 0.5) return;
    uint at = rigid_at();
    RigidMove move = rigid_fit(mat4(aux[at], aux[at + 1u], aux[at + 2u], aux[at + 3u]));
    iter[i] = vec4(here + rigid_start(move, cell, q, d), guess.w);
}
