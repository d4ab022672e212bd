#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, 2 of 3, over the scene's particles, dispatched only in a substep that
// rebuilds the lists (contact_begin.comp sets the dispatches): pass 0 counts each particle
// into the scene's spatial hash (counts[] is zero: the last scan, or the upload, cleared it)
// and empties its list; after the scan, pass 1 writes it into the hash by bucket and records
// where the lists are built (every particle's position: a partner's move counts as the
// finder's).
#include "layout.glsl"
#include "contact_common.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= scene_particles()) return;
    vec4 e = particles[k];
    if (pass_of() == 0u) {
        uint h = cell_hash(hash_cell(e.xyz, hash_cell_inv(), k), table.hash_mask);
        cell_rank[k] = uvec2(h, atomicAdd(counts[h], 1u));
        built[4u * k + 3u] = 0u;
        return;
    }
    uvec2 cr = cell_rank[k];
    sorted[BUCKET_START(cr.x, table.hash_mask) + cr.y] = e;
    // (with the lists off a list holds the contacts alone, not the skin)
    set_list_built(k, lists_on(), e.xyz);
}
