#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, 3 of 3, in two passes over the particles of other objects nearer than
// the sum of the two objects' contact radii. Pass 0, one dispatch over every particle of the
// scene (read from the hash's sorted copy through cell_rank), finds them in the scene's hash
// and counts them (touches[], per scene particle), noting the first PAIR_MAX of them (their
// slots in the hash, pairs[]). Pass 1, per object, visits those again (searching the hash
// only for a particle with more) and sums for each pair (i, j)
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

// Partners a particle keeps from the count pass; one with more searches the hash again.
const uint PAIR_MAX = 8u;

// The pair of the particle at x (scene index `k_self`, object `me`, `mine` touches) and the
// hash entry at slot `at`, if they touch: counted into n; pass 0 notes the slot (its first
// PAIR_MAX), pass 1 adds the particle's share of the overlap to `correction`.
void visit(uint at, vec3 x, uint k_self, uint me, uint mine, bool sum, inout uint n, inout vec3 correction) {
    vec4 e = sorted[at];
    uint bits = floatBitsToUint(e.w);
    uint k = bits & ~PINNED_BIT;
    uint other = owner(k);
    if (other == me) return;
    vec4 self_entry = objects[me];
    vec4 them = objects[other];
    float reach = self_entry.z + them.z;
    vec3 to_j = e.xyz - x;
    float d = length(to_j);
    if (d < reach && d > 0.0) {
        if (!sum && n < PAIR_MAX) pairs[k_self * PAIR_MAX + n] = at;
        n += 1u;
        if (sum) {
            float w = (bits & PINNED_BIT) != 0u ? 1.0 : them.w / (self_entry.w + them.w);
            float split = 1.0 / float(max(mine, touches[k]));
            correction += (to_j / d) * ((d - reach) * w * split);
        }
    }
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool sum = which.pass == 1u;
    // Pass 1: particle i of this object; pass 0: particle i of the scene.
    if (i >= (sum ? particle_count() : scene_count())) return;
    uint me = sum ? which.object : owner(i);
    uint k_self = sum ? first_index() + i : i;
    uint mine = sum ? touches[k_self] : 0u;
    vec3 correction = vec3(0.0);
    uint n = 0u;
    vec4 p;
    if (sum) {
        p = p_in[i].pos;
    } else {
        uvec2 cr = cell_rank[i];
        p = sorted[BUCKET_START(cr.x, table.hash_mask) + cr.y];
    }
    vec3 x = p.xyz;
    if (sum && mine <= PAIR_MAX) {
        // The partners the count pass noted (none for most particles).
        if (p.w <= 0.5) {
            for (uint e = 0u; e < mine; ++e) visit(pairs[k_self * PAIR_MAX + e], x, k_self, me, mine, true, n, correction);
        }
    } else if (!sum || p.w <= 0.5) {
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
            for (uint at = BUCKET_START(h, table.hash_mask); at < end; ++at) visit(at, x, k_self, me, mine, sum, n, correction);
        }
    }
    if (sum) {
        contact[i] = vec4(correction, n > 0u ? 1.0 : 0.0);
    } else {
        touches[i] = n;
    }
}
