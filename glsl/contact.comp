#version 460
#extension GL_GOOGLE_include_directive : require
// Inter-object contact, one dispatch per ordered pair of objects (A, B) and substep, after
// every object's physics and spatial hash: each particle of A looks up B's hash for B's
// particles nearer than the sum of the two objects' contact radii and adds, for each, its
// share of the overlap away from it (B's mass over both; all of it when B's particle is
// pinned) and a count to contact[] (the constraint stage takes them into its Jacobi mean
// and clears them). The pair's binding set is A's, with B's physics output, hash and
// parameters in the slots below (the layout is the simulation's: every binding a storage
// buffer). The CPU twin is sim::cpu::inter_object.
#include "layout.glsl"

layout(local_size_x = 256) in;

layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams obj; };   // A
layout(std430, set = 0, binding = 2) readonly buffer StateIn { Particle p_in[]; };               // A after physics
layout(std430, set = 0, binding = 3) readonly buffer OtherState { Particle p_other[]; };         // B after physics
layout(std430, set = 0, binding = 8) readonly buffer OtherStarts { uint starts[]; };             // B's hash
layout(std430, set = 0, binding = 9) readonly buffer OtherSorted { vec4 sorted[]; };
layout(std430, set = 0, binding = 12) restrict readonly buffer OtherBuf { ObjectParams other; }; // B
layout(std430, set = 0, binding = 14) buffer ContactBuf { vec4 contact[]; };                     // A's

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= obj.dims.x * obj.dims.y) return;
    Particle p = p_in[i];
    if (p.pos.w > 0.5) return;  // pinned: the constraint stage leaves it where it is
    vec3 x = p.pos.xyz;
    float reach = obj.contact_radius + other.contact_radius;
    float share = other.mass / (obj.mass + other.mass);
    vec3 correction = vec3(0.0);
    uint n = 0u;
    // B's cells are at least twice the reach wide (object.rs), so every particle of B within
    // reach lies in the 2 x 2 x 2 block of cells nearest to x. Buckets visited once.
    ivec3 base = ivec3(floor(x * other.cell_inv - 0.5));
    uint seen[8];
    for (int c = 0; c < 8; ++c) {
        uint h = cell_hash(base + ivec3(c & 1, (c >> 1) & 1, c >> 2), other.hash_mask);
        seen[c] = h;
        bool again = false;
        for (int k = 0; k < c; ++k) again = again || seen[k] == h;
        if (again) continue;
        uint end = starts[h + 1u];
        for (uint at = starts[h]; at < end; ++at) {
            vec4 e = sorted[at];
            vec3 to_j = e.xyz - x;
            float d = length(to_j);
            if (d < reach && d > 0.0) {
                uint j = floatBitsToUint(e.w);
                float w = p_other[j].pos.w > 0.5 ? 1.0 : share;
                correction += (to_j / d) * ((d - reach) * w);
                n += 1u;
            }
        }
    }
    if (n > 0u) contact[i] += vec4(correction, float(n));
}
