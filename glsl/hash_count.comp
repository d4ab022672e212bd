#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// Spatial hash with contact lists on, pass 1 of 3 (dispatched indirectly: only in a substep
// that rebuilds the lists, hash_count.glsl): each particle takes a rank in the bucket of its position.
// Reads p_in; writes counts[] and cell_rank[].
#include "bindings.glsl"
#include "hash_count.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    count_into_bucket(i, p_in[i].pos.xyz, true);
}
