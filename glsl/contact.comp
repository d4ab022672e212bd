#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, 3 of 3, in two passes, each looking up the scene's hash for particles
// of other objects nearer than the sum of the two objects' contact radii. Pass 0, one dispatch
// over every particle of the scene (read from the hash's sorted copy through cell_rank),
// counts them (touches[], per scene particle). Pass 1, per object, sums for each pair (i, j)
// the overlap C = reach - d split by inverse mass (i moves C w_i / (w_i + w_j) away from j;
// all of C when j is pinned), scaled by 1 / max(n_i, n_j), the larger of the two particles'
// counts: the same for both ends of a pair, so every pair's corrections are equal and opposite
// in momentum (m_i dx_i = -m_j dx_j) and contact between objects conserves linear momentum,
// while a particle touching n others moves at most by the largest overlap. Pass 1 writes every
// particle's sum (xyz) and whether it touches anything (w) into contact[]; the constraint
// stage adds it to its own correction. The CPU twin is sim::cpu::inter_object.
#include "layout.glsl"
#include "contact_common.glsl"

layout(local_size_x = 256) in;

// The object a scene index belongs to (objects are few: a linear search).
uint owner(uint k) {
    uint o = 0u;
    for (uint q = 1u; q < objects.length(); ++q) {
        if (k >= floatBitsToUint(objects[q].x)) o = q;
    }
    return o;
}

// Particles in the scene (the last object's first index and count).
uint scene_count() {
    vec4 last = objects[objects.length() - 1];
    return floatBitsToUint(last.x) + floatBitsToUint(last.y);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool sum = which.pass == 1u;
    // Pass 1: particle i of this object; pass 0: particle i of the scene.
    if (i >= (sum ? particle_count() : scene_count())) return;
    uint me = sum ? which.object : owner(i);
    vec4 self_entry = objects[me];
    uint mine = sum ? touches[first_index() + i] : 0u;
    vec3 correction = vec3(0.0);
    uint n = 0u;
    vec4 p;
    if (sum) {
        p = p_in[i].pos;
    } else {
        uvec2 cr = cell_rank[i];
        p = sorted[BUCKET_START(cr.x, table.hash_mask) + cr.y];
    }
    if (!sum || p.w <= 0.5) {
        vec3 x = p.xyz;
        // Cells are at least twice the largest reach (object.rs), so every particle within
        // reach lies in the 2 x 2 x 2 block of cells nearest to x. Buckets visited once.
        ivec3 base = ivec3(floor(x * table.cell_inv - 0.5));
        uint seen[8];
        for (int c = 0; c < 8; ++c) {
            uint h = cell_hash(base + ivec3(c & 1, (c >> 1) & 1, c >> 2), table.hash_mask);
            seen[c] = h;
            bool again = false;
            for (int q = 0; q < c; ++q) again = again || seen[q] == h;
            if (again) continue;
            uint end = BUCKET_START(h + 1u, table.hash_mask);
            for (uint at = BUCKET_START(h, table.hash_mask); at < end; ++at) {
                vec4 e = sorted[at];
                uint bits = floatBitsToUint(e.w);
                uint k = bits & ~PINNED_BIT;
                uint other = owner(k);
                if (other == me) continue;
                vec4 them = objects[other];
                float reach = self_entry.z + them.z;
                vec3 to_j = e.xyz - x;
                float d = length(to_j);
                if (d < reach && d > 0.0) {
                    n += 1u;
                    if (sum) {
                        float w = (bits & PINNED_BIT) != 0u ? 1.0 : them.w / (self_entry.w + them.w);
                        float split = 1.0 / float(max(mine, touches[k]));
                        correction += (to_j / d) * ((d - reach) * w * split);
                    }
                }
            }
        }
    }
    if (sum) {
        contact[i] = vec4(correction, n > 0u ? 1.0 : 0.0);
    } else {
        touches[i] = n;
    }
}
