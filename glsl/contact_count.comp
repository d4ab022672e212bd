#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, 1 of 3: counts this object's particles (after physics) into the
// scene's spatial hash (contact_common.glsl). counts[] is zero here: the scan of the last
// substep (or the upload) cleared it. Clears each particle's contact count, moves and count of
// notes for contact.comp.
#include "layout.glsl"
#include "contact_common.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    uint h = cell_hash(ivec3(floor(p_in[i].pos.xyz * table.cell_inv)), table.hash_mask);
    uint k = first_index() + i;
    cell_rank[k] = uvec2(h, atomicAdd(counts[h], 1u));
    touches[k] = 0u;
    moves[4u * k] = 0;
    moves[4u * k + 1u] = 0;
    moves[4u * k + 2u] = 0;
    moves[4u * k + 3u] = 0;
}
