#version 460
#extension GL_GOOGLE_include_directive : require
// Spatial hash: exclusive prefix sum of counts[] into starts[0..=buckets] (starts[buckets] is
// the total), in one dispatch. Each workgroup scans SCAN_BLOCK counts into starts[] (zeroing them for
// the next count, hash_count.comp) and writes its total to block_sums[]; the last workgroup to
// finish (a counter in counts[buckets], which it leaves at zero) scans block_sums[] in place.
// A bucket's start is then starts[b] + block_sums[b / SCAN_BLOCK] (`BUCKET_START` in layout.glsl):
// readers add the block's offset instead of a third pass adding it to every start (measured on
// the H100, docs/PERFORMANCE.md).
#define BLOCK_SUMS_COHERENT coherent
#include "bindings.glsl"

layout(local_size_x = 512) in;

const uint PER_THREAD = 16u;  // 512 x 16 = SCAN_BLOCK (layout.glsl)
shared uint partial[512];
shared bool last_group;

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
    uint base = gl_WorkGroupID.x * SCAN_BLOCK + t * PER_THREAD;
    uint v[PER_THREAD];
    uint sum = 0u;
    for (uint k = 0u; k < PER_THREAD; ++k) {
        uint at = base + k;
        v[k] = at < n ? counts[at] : 0u;
        sum += v[k];
    }
    uint prefix = workgroup_scan(sum);
    for (uint k = 0u; k < PER_THREAD; ++k) {
        uint at = base + k;
        if (at < n) {
            starts[at] = prefix;
            counts[at] = 0u;
            if (at == n - 1u) starts[n] = prefix + v[k];  // the block-local end
        }
        prefix += v[k];
    }
    if (t == 511u) block_sums[gl_WorkGroupID.x] = prefix;

    // The block totals written, the last workgroup to get here scans them (no workgroup waits
    // for another, so this needs no promise that they run concurrently).
    memoryBarrierBuffer();
    barrier();
    if (t == 0u) last_group = atomicAdd(counts[n], 1u) == gl_NumWorkGroups.x - 1u;
    barrier();
    if (!last_group) return;
    memoryBarrierBuffer();
    uint blocks = gl_NumWorkGroups.x;
    base = t * PER_THREAD;
    sum = 0u;
    for (uint k = 0u; k < PER_THREAD; ++k) {
        v[k] = base + k < blocks ? block_sums[base + k] : 0u;
        sum += v[k];
    }
    prefix = workgroup_scan(sum);
    for (uint k = 0u; k < PER_THREAD; ++k) {
        if (base + k < blocks) block_sums[base + k] = prefix;
        prefix += v[k];
    }
    if (t == 0u) counts[n] = 0u;
}
