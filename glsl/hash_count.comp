#version 460
#extension GL_GOOGLE_include_directive : require
// Spatial hash, pass 1 of 3: each particle finds its bucket and takes a rank in it.
// Reads p_in (the physics output); writes cell_rank[], counts[] (cleared before this pass).
#include "bindings.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    uint h = cell_hash(ivec3(floor(p_in[i].pos.xyz * obj.cell_inv)), obj.hash_mask);
    cell_rank[i] = uvec2(h, atomicAdd(counts[h], 1u));
}
