#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// Inter-object contact, 1 of 3, per object after its physics: writes each particle's entry
// (position, scene index and pinned flag) by scene index into particles[] (contact.comp reads
// a piece's corners there) and where it began the substep into begun[] (friction); clears its
// count of contacts and its moves. A particle that has moved half the lists' skin from where
// the lists were built (or whose list is invalid or overflowed: built at infinity), or any
// particle while the lists are off, makes the substep rebuild the hash and the lists: the
// first to find so sets the control block's flag and the indirect dispatches of
// contact_hash.comp and the scan (contact_common.glsl).
#include "layout.glsl"
#include "contact_common.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool moved = false;
    if (i < particle_count()) {
        uint k = first_index() + i;
        vec4 p = p_in[i].pos;
        particles[k] = vec4(p.xyz, uintBitsToFloat(k | (p.w > 0.5 ? PINNED_BIT : 0u)));
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
