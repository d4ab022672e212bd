// The first pass of the spatial hash, run by whichever pass writes a substep's new positions
// (counts[] were zeroed by the previous substep's scan). Include after bindings.glsl.
#ifndef MSD_HASH_COUNT_GLSL
#define MSD_HASH_COUNT_GLSL

// Takes a rank in the bucket of the new position x_new of particle i.
void count_into_bucket(uint i, vec3 x_new) {
    if ((obj.flags & OBJ_SELF_HASH) == 0u) return;
    uint h = cell_hash(ivec3(floor(x_new * obj.cell_inv)), obj.hash_mask);
    cell_rank[i] = uvec2(h, atomicAdd(counts[h], 1u));
}

#endif
