#version 460
#extension GL_GOOGLE_include_directive : require
// Fused substeps for a small object (at most FUSED_MAX particles, without a spatial hash): one
// workgroup runs every substep of the frame, physics (A -> B) then constraints (B -> A), the
// same code as physics.comp and constraints.comp. The phases are ordered by barrier() with
// memory barriers on the coherent state buffers instead of pipeline barriers, which removes
// the per-stage dispatch and barrier latency that bounds small scenes.
#define STATE_FUSED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x = 1024) in;

#define IN(i) p_in[i]
#define OUT(i) p_out[i]
#include "physics_body.glsl"
#undef IN
#undef OUT
#define IN(i) p_out[i]
#define OUT(i) p_in[i]
#include "constraints_body.glsl"

void main() {
    uint n = particle_count();
    uint cols = obj.dims.x;
    for (uint s = 0u; s < g.substeps; ++s) {
        for (uint k = gl_LocalInvocationID.x; k < n; k += 1024u) physics_particle(uvec2(k % cols, k / cols));
        memoryBarrierBuffer();
        barrier();
        for (uint k = gl_LocalInvocationID.x; k < n; k += 1024u) constraints_particle(uvec2(k % cols, k / cols));
        memoryBarrierBuffer();
        barrier();
    }
}
