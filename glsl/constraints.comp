#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// Constraint stage, one thread per particle: reads p_in (the physics output, and the contact
// lists or the spatial hash built from it), writes p_out (which held the substep's start: its
// own particle's is read first, for the colliders' friction). The work itself is in
// constraints_body.glsl (shared with fused.comp). A pipeline with the self-collision contact
// lists (LISTS) and one without, where their code is compiled out (measured: 3% of this
// stage on a 256 x 256 cloth when it was a push constant).
#define STATE_OUT_READ
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(constant_id = 2) const bool LISTS = false;  // contact lists on (hash_count.glsl)
layout(push_constant) uniform Push {
    uint substep;  // of the frame, 0-based
    BATCH_PUSH
} pc;

#define IN(i) p_in[i]
#define OUT(i) p_out[i]
#define START(i) p_out[i].pos.xyz
#include "hash_count.glsl"
#define CELL_INV hash_cell_inv(LISTS)
void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active);
#define SELF_CANDIDATES listed_candidates
#include "constraints_body.glsl"

void main() {
    if (!batch_begin(pc.batch_mask)) return;
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (LISTS && has(F_SELF) && self_hashed() && cell == uvec2(0u)) {
        // The next substep's control block starts zeroed (this one's is read by the others),
        // and the counters the host's policy reads (lists.glsl).
        uint next = list_control(pc.substep + 1u);
        for (uint w = 0u; w < LIST_CONTROL_WORDS; ++w) self_list[next + w] = 0u;
        atomicAdd(self_list[list_counters()], 1u);
        if (self_list[list_control(pc.substep)] != 0u) atomicAdd(self_list[list_counters() + 1u], 1u);
    }
    if (has(F_SELF) && triangle_contact() && cell == uvec2(0u)) {
        // No further contact passes until a find pass asks for them (self_contact.glsl).
        uint w = further_passes_word();
        self_pairs[w] = 0;
        self_pairs[w + 1u] = 0;
        self_pairs[w + 2u] = 0;
    }
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    constraints_particle(cell, pc.substep, LISTS);
}
