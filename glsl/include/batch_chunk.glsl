// What every batched shader shares (batch.glsl has the step shaders' bindings, and
// contact_common.glsl contact's): the chunk's size, the push constants' mask of the chunk's
// objects that take part, and workgroup z as the chunk's object.
#ifndef MSD_BATCH_CHUNK_GLSL
#define MSD_BATCH_CHUNK_GLSL

// Objects a batched dispatch spans at most (sim::gpu::batch::chunk_size).
layout(constant_id = 8) const uint BATCH_CHUNK = 1u;

// The push constants after a shader's own four words: which of the chunk's objects take
// part in the pass (bit z).
#define BATCH_PUSH layout(offset = 16) uvec2 batch_mask;

#define MSD_Z gl_WorkGroupID.z

// Whether this workgroup's object takes part in the pass (else the whole workgroup returns).
bool batch_begin(uvec2 mask) {
    uint z = gl_WorkGroupID.z;
    uint bits = z < 32u ? mask.x : mask.y;
    return ((bits >> (z & 31u)) & 1u) != 0u;
}

#endif
