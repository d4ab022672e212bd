#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_memory_scope_semantics : require
#pragma use_vulkan_memory_model
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
    controlBarrier(gl_ScopeWorkgroup, gl_ScopeQueueFamily, gl_StorageSemanticsBuffer,
                   gl_SemanticsAcquireRelease | gl_SemanticsMakeAvailable | gl_SemanticsMakeVisible);
    if (gl_LocalInvocationIndex == 0u) {
        atomicAdd(self_list[0], 1u, gl_ScopeQueueFamily, gl_StorageSemanticsBuffer, gl_SemanticsRelease | gl_SemanticsMakeAvailable);
        uint want = sync_phase * gl_NumWorkGroups.x;
        while (atomicLoad(self_list[0], gl_ScopeQueueFamily, gl_StorageSemanticsBuffer, gl_SemanticsAcquire | gl_SemanticsMakeVisible) < want) {}
    }
    controlBarrier(gl_ScopeWorkgroup, gl_ScopeQueueFamily, gl_StorageSemanticsBuffer,
                   gl_SemanticsAcquireRelease | gl_SemanticsMakeAvailable | gl_SemanticsMakeVisible);
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
