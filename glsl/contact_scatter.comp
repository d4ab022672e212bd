#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, 2 of 3: after the scan, writes this object's particles into the
// scene's hash by bucket: position, and the scene index with the pinned flag in its top bit;
// the same by scene index into particles[] (contact.comp reads a triangle's corners there),
// and where it began the substep into begun[] (friction).
#include "layout.glsl"
#include "contact_common.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    uint k = first_index() + i;
    uvec2 cr = cell_rank[k];
    vec4 p = p_in[i].pos;
    vec4 e = vec4(p.xyz, uintBitsToFloat(k | (p.w > 0.5 ? PINNED_BIT : 0u)));
    sorted[BUCKET_START(cr.x, table.hash_mask) + cr.y] = e;
    particles[k] = e;
    begun[k] = vec4(p_start[i].pos.xyz, 0.0);
}
