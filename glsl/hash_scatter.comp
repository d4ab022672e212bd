#version 460
#extension GL_GOOGLE_include_directive : require
// Spatial hash, pass 3 of 3 (dispatched indirectly, as hash_count.comp): each particle writes
// its position and index at its bucket's start + its rank, so the query reads candidates
// contiguously. Reads p_in, cell_rank[],
// starts[]; writes sorted[].
#include "bindings.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    uvec2 cr = cell_rank[i];
    sorted[BUCKET_START(cr.x, obj.hash_mask) + cr.y] = vec4(p_in[i].pos.xyz, uintBitsToFloat(i));
}
