#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Spatial hash: exclusive prefix sum of counts[] into starts[0..=buckets] (starts[buckets] is
// the total), in one dispatch. Each workgroup scans SCAN_BLOCK counts into starts[] (zeroing
// them for the next count, hash_count.comp) and writes its total to block_sums[]; the last
// workgroup to finish (a counter in counts[buckets], which it leaves at zero) scans
// block_sums[] in place. A bucket's start is then starts[b] + block_sums[b / SCAN_BLOCK]
// (`BUCKET_START` in layout.glsl): readers add the block's offset instead of a third pass
// adding it to every start. Within a block each subgroup scans a segment of consecutive values
// in steps of its width (coalesced reads and writes, subgroup adds), then the segments' totals
// are combined: two barriers (measured on the H100, docs/PERFORMANCE.md).
#define BLOCK_SUMS_COHERENT coherent
#include "bindings.glsl"

layout(local_size_x = 512) in;

const uint PER_LANE = SCAN_BLOCK / 512u;
shared uint segment_totals[512];  // per subgroup
shared bool last_group;

uint table_size() { return obj.hash_mask + 1u; }

// The values a scan reads: the counts, or (`totals`) the block totals.
uint scan_load(bool totals, uint at) { return totals ? block_sums[at] : counts[at]; }
void scan_store(bool totals, uint at, uint prefix) {
    if (totals) {
        block_sums[at] = prefix;
    } else {
        starts[at] = prefix;
        counts[at] = 0u;
    }
}

// Replaces the values [base, min(base + SCAN_BLOCK, limit)) by their exclusive prefix sum from
// base; returns their total (to every invocation). Each subgroup takes `steps` = the values /
// 512 (rounded up) steps of its width: a block of a small table takes one or two, not
// PER_LANE (each step waits for the one before).
uint scan_block(bool totals, uint base, uint limit) {
    uint width = gl_SubgroupSize;
    uint steps = (min(limit - base, SCAN_BLOCK) + 511u) / 512u;
    uint first = base + gl_SubgroupID * width * steps + gl_SubgroupInvocationID;
    uint prefix[PER_LANE];
    uint carry = 0u;
    [[unroll]] for (uint k = 0u; k < PER_LANE; ++k) {
        if (k == steps) break;
        uint at = first + k * width;
        uint v = at < limit ? scan_load(totals, at) : 0u;
        prefix[k] = carry + subgroupExclusiveAdd(v);
        carry += subgroupAdd(v);
    }
    if (subgroupElect()) segment_totals[gl_SubgroupID] = carry;
    barrier();
    uint before = 0u;
    uint total = 0u;
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
        uint t = segment_totals[s];
        before += s < gl_SubgroupID ? t : 0u;
        total += t;
    }
    [[unroll]] for (uint k = 0u; k < PER_LANE; ++k) {
        if (k == steps) break;
        uint at = first + k * width;
        if (at < limit) scan_store(totals, at, before + prefix[k]);
    }
    barrier();  // segment_totals is read before it is written again
    return total;
}

void main() {
    uint t = gl_LocalInvocationIndex;
    uint n = table_size();
    uint base = gl_WorkGroupID.x * SCAN_BLOCK;
    uint total = scan_block(false, base, n);
    if (t == 0u) {
        // A table of one block has its offset, 0; the others the block's total for now.
        block_sums[gl_WorkGroupID.x] = gl_NumWorkGroups.x == 1u ? 0u : total;
        if (base + SCAN_BLOCK >= n) starts[n] = total;  // the block-local end
    }
    if (gl_NumWorkGroups.x == 1u) return;

    // The block totals written, the last workgroup to get here scans them (no workgroup waits
    // for another, so this needs no promise that they run concurrently).
    memoryBarrierBuffer();
    barrier();
    if (t == 0u) last_group = atomicAdd(counts[n], 1u) == gl_NumWorkGroups.x - 1u;
    barrier();
    if (!last_group) return;
    memoryBarrierBuffer();
    scan_block(true, 0u, gl_NumWorkGroups.x);
    if (t == 0u) counts[n] = 0u;
}
