// The per-stage spatial hash of self-collision and its contact lists (lists.glsl). With lists
// on, the pass that writes a substep's new positions notes whether the lists still hold
// (note_position); when they do not, the hash is built from those positions (hash_count.comp
// counts, the scan, hash_scatter.comp), with cells twice the lists' reach wide, and the
// constraints search it and build the lists again. With lists off, that pass counts the
// position into the hash (cells twice the search's reach) and every substep searches it.
// Include after bindings.glsl.
#ifndef MSD_HASH_COUNT_GLSL
#define MSD_HASH_COUNT_GLSL
#include "lists.glsl"

// The per-stage hash's 1 / cell edge: twice the search's reach (obj.cell_inv), with lists
// twice the lists' reach (as fused.comp scales it).
float hash_cell_inv(bool lists) { return lists ? obj.cell_inv * (self_reach() / list_reach()) : obj.cell_inv; }

// Takes a rank in the bucket of position x of particle i (counts[] were zeroed by the last
// scan).
void count_into_bucket(uint i, vec3 x, bool lists) {
    uint h = cell_hash(hash_cell(x, hash_cell_inv(lists), i), obj.hash_mask);
    cell_rank[i] = uvec2(h, atomicAdd(counts[h], 1u));
}

// Particle i of an object whose self-collision searches the hash has its new position x_new
// in substep `substep`. With lists off it is counted into the hash. With lists on, when it has
// moved half the skin from where its list was built (or is not pinned and has no list), the
// substep rebuilds the hash and the lists: the first particle to find so sets the control
// block's indirect dispatches (lists.glsl).
void note_position(uint i, vec3 x_new, bool pinned, uint substep, bool lists) {
    if (!self_hashed()) return;
    if (!lists) {
        count_into_bucket(i, x_new, false);
        return;
    }
    bool moved = !pinned && !(distance(x_new, list_built(i)) <= list_half_skin());
    if (!subgroupAny(moved)) return;
    uint c = list_control(substep);
    if (subgroupElect() && atomicExchange(self_list[c], 1u) == 0u) {
        uint n = particle_count();
        uint buckets = obj.hash_mask + 1u;
        uvec3 groups[2] = uvec3[2](uvec3((n + 255u) / 256u, 1u, 1u),                      // count, scatter
                                   uvec3((buckets + SCAN_BLOCK - 1u) / SCAN_BLOCK, 1u, 1u));  // scan
        [[unroll]] for (uint a = 0u; a < 2u; ++a) {
            [[unroll]] for (uint w = 0u; w < 3u; ++w) self_list[c + LIST_DISPATCHES + 3u * a + w] = groups[a][w];
        }
    }
}

#endif
