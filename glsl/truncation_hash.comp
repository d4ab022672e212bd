#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// The spatial hash built again after the constraint stage from where each particle began the
// substep (a cloth that keeps its edges apart: its truncation searches there, self_contact.glsl's
// note_truncation), with cells of the search's reach: the count (SCATTER false; the scan is
// hash_scan.comp's), then the scatter, which also notes each particle's ring creases there. A
// shader of its own, not passes of self_pairs.comp: validation counts every binding a shader
// touches as touched by each of its dispatches, and the find pass does not write the hash.
// Reads self_pairs' starts; writes counts[] and cell_rank[], or sorted[] and the creases.
#include "bindings.glsl"
#include "self_pairs_layout.glsl"

layout(local_size_x = 256) in;
layout(constant_id = 0) const bool SCATTER = false;

#define CPOS(j) start_position(uint(j))
#include "hash_count.glsl"
#include "creases.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    vec3 start = start_position(i);
    if (!SCATTER) {
        count_into_bucket(i, start, false);
        return;
    }
    uvec2 cr = cell_rank[i];
    sorted[BUCKET_START(cr.x, obj.hash_mask) + cr.y] = vec4(start, uintBitsToFloat(i));
    self_pairs[creases_word(i)] = int(ring_crease_masks(i, start));
}
