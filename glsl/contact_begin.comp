#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
// Inter-object contact, 1 of 3, per object after its physics: writes each particle's entry
// (position, scene index and pinned flag) by scene index into particles[] (contact.comp reads
// a piece's corners there) and where it began the substep into begun[] (friction); clears its
// count of contacts and its moves. A particle that has moved half the lists' skin from where
// the lists were built (or whose list is invalid or overflowed: built at infinity), or any
// particle while the lists are off, makes the substep rebuild the hash and the lists: the
// first to find so sets the control block's flag and the indirect dispatches of
// contact_hash.comp and the scan (contact_common.glsl). It also writes each particle's star
// box (contact_common.glsl, `star_box`), which contact.comp's search tests candidates by.
#define BATCHED
#include "layout.glsl"
#include "contact_common.glsl"
#include "triangle.glsl"

layout(local_size_x = 256) in;

void main() {
    if (!batch_begin(which.batch_mask)) return;
    uint i = gl_GlobalInvocationID.x;
    bool moved = false;
    if (i < particle_count()) {
        uint k = first_index() + i;
        vec4 p = p_in[i].pos;
        particles[k] = vec4(p.xyz, uintBitsToFloat(k | (p.w > 0.5 ? PINNED_BIT : 0u)));
        vec3 lo = p.xyz;
        vec3 hi = p.xyz;
        uvec2 grid = obj.dims;
        if (grid.x > 1u && grid.y > 1u) {
            ivec2 at = ivec2(i % grid.x, i / grid.x);
            [[unroll]] for (int r = 0; r < 6; ++r) {
                ivec2 c = at + VERTEX_RING[r];
                if (c.x < 0 || c.y < 0 || c.x >= int(grid.x) || c.y >= int(grid.y)) continue;
                vec3 x = p_in[uint(c.x) + uint(c.y) * grid.x].pos.xyz;
                lo = min(lo, x);
                hi = max(hi, x);
            }
        }
        uint scene = scene_particles();
        particles[scene + k] = vec4(lo, 0.0);
        particles[2u * scene + k] = vec4(hi, 0.0);
        begun[k] = vec4(p_start[i].pos.xyz, 0.0);
        touches[k] = 0u;
        moves[4u * k] = 0;
        moves[4u * k + 1u] = 0;
        moves[4u * k + 2u] = 0;
        moves[4u * k + 3u] = 0;
        moved = !lists_on() || !(distance(p.xyz, list_built(k)) <= list_half_skin());
    }
    if (!subgroupAny(moved)) return;
    uint c = control_block();
    if (subgroupElect() && atomicExchange(control[c], 1u) == 0u) {
        uint scene = scene_particles();
        uint buckets = table.hash_mask + 1u;
        control[c + CONTROL_HASH] = (scene + 255u) / 256u;
        control[c + CONTROL_HASH + 1u] = 1u;
        control[c + CONTROL_HASH + 2u] = 1u;
        control[c + CONTROL_SCAN] = (buckets + SCAN_BLOCK - 1u) / SCAN_BLOCK;
        control[c + CONTROL_SCAN + 1u] = 1u;
        control[c + CONTROL_SCAN + 2u] = 1u;
        if (lists_on()) control[CONTROL_COUNTERS + 1u] += 1u;
    }
}
