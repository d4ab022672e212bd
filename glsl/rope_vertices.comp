#version 460
#extension GL_GOOGLE_include_directive : require
// Surface stage for ropes, once per frame: ROPE_RING tube vertices around each node, on a frame
// built from the directions to the previous and next nodes (the paper's section IV-C).
// Reads p_in (the state buffer), writes surface[node * ROPE_RING + k] and the runtime guard
// (first vertex of each node). One thread per vertex; with DRAWN off (nothing draws the
// rope), only the guard, one thread per node.
#include "bindings.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
layout(constant_id = 0) const bool DRAWN = true;

vec3 safe_normalize(vec3 v, vec3 fallback) {
    float len = length(v);
    return len > 1e-12 ? v / len : fallback;
}

void main() {
    uint vtx = gl_GlobalInvocationID.x;
    uint nodes = obj.dims.x;
    if (!DRAWN) {
        if (vtx < nodes) guard_check(vtx, p_in[vtx]);
        return;
    }
    if (vtx >= nodes * ROPE_RING) return;
    uint node = vtx / ROPE_RING;
    uint k = vtx % ROPE_RING;

    if (k == 0u) guard_check(node, p_in[node]);
    vec3 x = p_in[node].pos.xyz;
    vec3 prev = p_in[node > 0u ? node - 1u : node].pos.xyz;
    vec3 next = p_in[node + 1u < nodes ? node + 1u : node].pos.xyz;
    // Forward: the mean of the unit directions prev->node and node->next (one of them at the ends).
    vec3 to_next = node + 1u < nodes ? safe_normalize(next - x, vec3(0.0)) : vec3(0.0);
    vec3 from_prev = node > 0u ? safe_normalize(x - prev, vec3(0.0)) : vec3(0.0);
    vec3 forward = safe_normalize(to_next + from_prev, safe_normalize(to_next, vec3(1.0, 0.0, 0.0)));
    // Side: forward x world-up; when they are colinear, forward turned 90 degrees about z.
    vec3 side = cross(forward, vec3(0.0, 1.0, 0.0));
    side = length(side) > 1e-6 ? normalize(side) : normalize(vec3(forward.y, -forward.x, 0.0));
    vec3 up = normalize(cross(forward, side));

    vec2 w = obj.ring_weights[k];
    vec3 offset = side * w.x + up * w.y;
    surface[vtx] = SurfaceVertex(vec4(x + offset * obj.rope_radius, 1.0),
                                 vec4(safe_normalize(offset, up), 0.0));
}
