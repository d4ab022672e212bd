#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Spatial hash, pass 3 of 3 (dispatched indirectly, as hash_count.comp): each particle writes
// its position and index at its bucket's start + its rank, so the query reads candidates
// contiguously; a cloth with edge-edge contact (CREASES) also notes how creased its ring edges
// are, which the search reads for every candidate (creases.glsl). Reads p_in, cell_rank[],
// starts[]; writes sorted[] (and self_pairs).
#include "bindings.glsl"

layout(local_size_x = 256) in;
layout(constant_id = 0) const bool CREASES = false;

#define CPOS(j) p_in[j].pos.xyz
#include "creases.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    uvec2 cr = cell_rank[i];
    vec3 x = p_in[i].pos.xyz;
    sorted[BUCKET_START(cr.x, obj.hash_mask) + cr.y] = vec4(x, uintBitsToFloat(i));
    if (CREASES) self_pairs[creases_word(i)] = int(ring_crease_masks(i, x));
}
