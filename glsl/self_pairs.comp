#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// A cloth's contact with its own triangles on the per-stage path, one thread per particle
// (pinned ones too), between the spatial hash's build and the constraints: APPLY false, the
// find pass (each particle's contacts kept and counted; the contact lists walked, or searched
// from the hash and rebuilt), APPLY true, the apply pass (each contact's moves summed into its
// four particles). The work is in self_contact.glsl and constraints_body.glsl, shared with
// fused.comp; the constraint stage adds the sums. Both passes read the contact lists' state
// (LISTS: the pipelines with lists on).
#define STATE_OUT_READ
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(constant_id = 2) const bool LISTS = false;  // contact lists on (hash_count.glsl)
layout(constant_id = 4) const bool APPLY = false;
layout(push_constant) uniform Push {
    uint substep;  // of the frame, 0-based
} pc;

#define IN(i) p_in[i]
#include "hash_count.glsl"
#define CELL_INV hash_cell_inv(LISTS)
void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active);
#define SELF_CANDIDATES listed_candidates
#define SELF_APPLY_FOUND APPLY
#include "constraints_body.glsl"

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (!has(F_SELF) || cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec3 x = p_in[i].pos.xyz;
    list_state(i, pc.substep, self_hashed(), LISTS);
    // (p_out: the substep's start, which only the find pass notes)
    self_pass(cell, i, x, APPLY ? x : p_out[i].pos.xyz, APPLY);
    if (!APPLY && list_build) set_list_header(i, x, list_len);
}
