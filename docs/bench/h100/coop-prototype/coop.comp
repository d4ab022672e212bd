#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// EXPERIMENT: every substep of a frame for one object in one dispatch of several workgroups,
// which meet at a grid barrier between the physics and the constraints (global memory,
// coherent). Explicit methods, no self-collision hash.
#define STATE_COOP
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x = 256) in;

#define IN(i) p_in[i]
#define OUT(i) p_out[i]
#include "physics_body.glsl"
#undef IN
#undef OUT
#define IN(i) p_out[i]
#define OUT(i) p_in[i]
#include "constraints_body.glsl"

uint sync_phase = 0u;
void grid_sync() {
    sync_phase += 1u;
    memoryBarrierBuffer();
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        atomicAdd(self_list[0], 1u);
        uint want = sync_phase * gl_NumWorkGroups.x;
        while (atomicAdd(self_list[0], 0u) < want) {}
    }
    barrier();
    memoryBarrierBuffer();
}

void main() {
    uint n = particle_count();
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint s = 0u; s < g.substeps; ++s) {
        for (uint i = gl_GlobalInvocationID.x; i < n; i += stride) {
            physics_particle(uvec2(i % obj.dims.x, i / obj.dims.x), s, false);
        }
        grid_sync();
        for (uint i = gl_GlobalInvocationID.x; i < n; i += stride) {
            constraints_particle(uvec2(i % obj.dims.x, i / obj.dims.x), s, false);
        }
        grid_sync();
    }
}
