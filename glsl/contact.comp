#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, 3 of 3: each particle of this object looks up the scene's hash for
// particles of other objects nearer than the sum of the two objects' contact radii and sums,
// for each, its share of the overlap away from it (the other's mass over both; all of it when
// the other is pinned) and their count into contact[] (every particle written: the constraint
// stage takes them into its Jacobi mean). The CPU twin is sim::cpu::inter_object.
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

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= particle_count()) return;
    vec4 self_entry = objects[which.object];
    vec3 correction = vec3(0.0);
    uint n = 0u;
    Particle p = p_in[i];
    if (p.pos.w <= 0.5) {
        vec3 x = p.pos.xyz;
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
                uint other = owner(bits & ~PINNED_BIT);
                if (other == which.object) continue;
                vec4 them = objects[other];
                float reach = self_entry.z + them.z;
                vec3 to_j = e.xyz - x;
                float d = length(to_j);
                if (d < reach && d > 0.0) {
                    float w = (bits & PINNED_BIT) != 0u ? 1.0 : them.w / (self_entry.w + them.w);
                    correction += (to_j / d) * ((d - reach) * w);
                    n += 1u;
                }
            }
        }
    }
    contact[i] = vec4(correction, float(n));
}
