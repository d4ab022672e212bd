#version 460
#extension GL_GOOGLE_include_directive : require
// Spatial hash: exclusive prefix sum of counts[] into starts[0..=buckets] (starts[buckets] is
// the total), in one dispatch for tables of up to one block, else three, selected by the
// specialization constant SCAN_PHASE:
//   0: each workgroup scans BLOCK counts into starts[] (zeroing them for the next count,
//      hash_count.comp) and writes its total to block_sums[];
//   1: one workgroup scans block_sums[] (at most BLOCK blocks) in place;
//   2: every start gets the scanned total of the blocks before it.
#include "bindings.glsl"

layout(constant_id = 0) const uint SCAN_PHASE = 0u;
layout(local_size_x = 512) in;

const uint PER_THREAD = 16u;
const uint BLOCK = 512u * PER_THREAD;
shared uint partial[512];

uint table_size() { return obj.hash_mask + 1u; }

// Exclusive scan of `value` across the workgroup; returns this thread's prefix.
uint workgroup_scan(uint value) {
    uint t = gl_LocalInvocationID.x;
    partial[t] = value;
    barrier();
    for (uint offset = 1u; offset < 512u; offset <<= 1u) {
        uint add = t >= offset ? partial[t - offset] : 0u;
        barrier();
        partial[t] += add;
        barrier();
    }
    return partial[t] - value;
}

void main() {
    uint t = gl_LocalInvocationID.x;
    uint n = table_size();
    if (SCAN_PHASE == 2u) {
        uint k = gl_GlobalInvocationID.x;
        if (k <= n) starts[k] += block_sums[min(k, n - 1u) / BLOCK];
        return;
    }
    uint base = (SCAN_PHASE == 0u ? gl_WorkGroupID.x * BLOCK : 0u) + t * PER_THREAD;
    uint limit = SCAN_PHASE == 0u ? n : (n + BLOCK - 1u) / BLOCK;
    uint v[PER_THREAD];
    uint sum = 0u;
    for (uint k = 0u; k < PER_THREAD; ++k) {
        uint at = base + k;
        v[k] = at < limit ? (SCAN_PHASE == 0u ? counts[at] : block_sums[at]) : 0u;
        sum += v[k];
    }
    uint prefix = workgroup_scan(sum);
    for (uint k = 0u; k < PER_THREAD; ++k) {
        uint at = base + k;
        if (at < limit) {
            if (SCAN_PHASE == 0u) {
                starts[at] = prefix;
                counts[at] = 0u;
                if (at == limit - 1u) starts[n] = prefix + v[k];  // the block-local end
            } else {
                block_sums[at] = prefix;
            }
        }
        prefix += v[k];
    }
    if (SCAN_PHASE == 0u && t == 511u) block_sums[gl_WorkGroupID.x] = prefix;
}
