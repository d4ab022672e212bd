#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// A cloth's contact with its own triangles on the per-stage path, one thread per particle (pinned
// ones too; with edge pairs, pc.lanes of them), between the spatial hash's build and the
// constraints, one pass a dispatch (PASS): the find pass (each particle's contacts kept and
// counted; the contact lists walked, or searched from the hash and rebuilt), the apply pass (each
// contact's moves summed into its four particles), and with contact_iterations > 1 each further
// pass's move of the physics output by the sums and the kept contacts' application from there. The
// work is in self_contact.glsl and constraints_body.glsl, shared with fused.comp; the constraint
// stage adds the last pass's sums. The find and apply passes read the contact lists' state (LISTS:
// the pipelines with lists on). With a cloth's edge pairs two passes follow the constraint stage
// (after truncation_hash.comp's hash of where the particles began the substep): each particle's
// pairs near there noted in their particles' truncations (note_truncation: CPOS reads the start in
// that pass), then each particle's move truncated (truncate_move), on the stage's result in p_out.
#define STATE_OUT_READ
#define STATE_IN_WRITE
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(constant_id = 2) const bool LISTS = false;  // contact lists on (hash_count.glsl)
// sim::gpu::pipelines::SelfPass, in its order.
const uint PASS_FIND = 0u;
const uint PASS_APPLY = 1u;
const uint PASS_MOVE = 2u;
const uint PASS_REAPPLY = 3u;
const uint PASS_NOTE = 4u;
const uint PASS_TRUNCATE = 5u;
layout(constant_id = 4) const uint PASS = PASS_FIND;
const bool APPLY = PASS == PASS_APPLY;
layout(push_constant) uniform Push {
    uint substep;  // of the frame, 0-based
    // With a cloth's edge pairs, the lanes the find, apply and note passes split each
    // particle's search among (self_contact.glsl's search_lanes), side by side along x: the
    // dispatch is that many times wider (sim::gpu::SEARCH_LANES).
    uint lanes;
} pc;

#define IN(i) p_in[i]
#include "self_pairs_layout.glsl"
// (the truncation's passes search where the particles began the substep)
#define CPOS(j) (PASS == PASS_NOTE ? start_position(uint(j)) : p_in[j].pos.xyz)
#define CPINNED(j) (p_in[j].pos.w > 0.5)
#define TRUNC_POS(j) p_out[j].pos.xyz
#include "hash_count.glsl"
#define CELL_INV hash_cell_inv(LISTS)
void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active);
#define SELF_CANDIDATES listed_candidates
#define SELF_APPLY_FOUND APPLY
#include "constraints_body.glsl"

// The particle the truncation pass moves (`substep_start`, which the colliders' friction asks
// for).
uint visiting = 0u;
vec3 substep_start() { return pair_start(visiting); }

const bool LANED_PASS = PASS == PASS_FIND || PASS == PASS_APPLY || PASS == PASS_NOTE;

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    uint lanes = cloth_edge_pairs() ? max(pc.lanes, 1u) : 1u;
    uint lane = 0u;
    if (LANED_PASS) {
        lane = cell.x % lanes;
        cell.x /= lanes;
    }
    if (!has(F_SELF) || cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec3 x = p_in[i].pos.xyz;
    if (PASS == PASS_MOVE) {
        if (p_in[i].pos.w > 0.5) return;  // (a pinned particle's sums stay zero)
        vec3 v = p_in[i].vel.xyz;
        vec3 before = x;
        self_move(i, x, v);
        if (x == before && v == p_in[i].vel.xyz) return;  // (no contact moved it)
        p_in[i].pos.xyz = x;
        p_in[i].vel.xyz = v;
        return;
    }
    if (PASS == PASS_REAPPLY) {
        self_reapply(i, x);
        return;
    }
    if (PASS == PASS_NOTE) {
        search_lane = lane;
        search_lanes = lanes;
        note_truncation(i);
        return;
    }
    if (PASS == PASS_TRUNCATE) {
        self_pairs[pairs_len_word(i)] = 0;  // (the split find pass's counter, for the next substep)
        Particle q = p_out[i];
        if (q.pos.w > 0.5) return;  // (pinned: nothing noted)
        vec3 v = q.vel.xyz;
        x = q.pos.xyz;
        visiting = i;
        if (!truncate_move(i, pair_start(i), x, v)) return;
        collide(x, v, float(pc.substep + 1u) * g.dt);
        p_out[i] = Particle(vec4(x, 0.0), vec4(v, 0.0));
        return;
    }
    list_state(i, pc.substep, self_hashed(), LISTS);
    // (split only where the pass searches the hash with the lists off: the host passes one
    // lane where it builds or walks them, sim::gpu::GpuSim::lanes_of)
    search_lane = lane;
    search_lanes = lanes;
    // (p_out: the substep's start, which only the find pass notes)
    self_pass(cell, i, x, APPLY ? x : p_out[i].pos.xyz, APPLY);
    if (PASS == PASS_FIND && subgroupAny(pair_len > 0u) && subgroupElect()) {
        // The further passes run: one thread of each subgroup where some particle found a
        // contact writes the dispatch's size (atomically: all write the same; the further
        // passes are not split among lanes).
        uint w = further_passes_word();
        atomicMax(self_pairs[w], int(gl_NumWorkGroups.x / lanes));
        atomicMax(self_pairs[w + 1u], int(gl_NumWorkGroups.y));
        atomicMax(self_pairs[w + 2u], int(gl_NumWorkGroups.z));
    }
    if (!APPLY && list_build) set_list_header(i, x, list_len);
}
