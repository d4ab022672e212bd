#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Surface stage for ropes, once per frame: ROPE_RING tube vertices around each node on a
// rotation-minimising frame (parallel transport): the frame at node 0 is the paper's (section
// IV-C: side = forward x world up, up = forward x side), and each next node's is the one before
// turned by the smallest rotation that takes the previous node's forward direction to its
// own. So the tube keeps its width and does not twist where the rope turns vertical (where the
// paper's frame flips and the tube pinches). The CPU twin is sim::cpu::rope_surface.
// The frames are a running product of rotations along the rope: one workgroup, each thread a
// run of nodes; the threads' products are combined by a scan in shared memory.
// Reads p_in (the state buffer), writes surface[node * ROPE_RING + k] and the runtime guard
// (with the contact lists' counters, lists.glsl).
// With DRAWN off (nothing draws the rope) only the guard, one thread per node.
#include "bindings.glsl"
#include "springs.glsl"
#include "lists.glsl"

layout(local_size_x = 256) in;
layout(constant_id = 0) const bool DRAWN = true;

const uint THREADS = 256u;
const vec4 IDENTITY = vec4(0.0, 0.0, 0.0, 1.0);
shared vec4 products[THREADS];

vec3 safe_normalize(vec3 v, vec3 fallback) {
    float len = length(v);
    return len > 1e-12 ? v / len : fallback;
}

// Rotation q applied after p (unit quaternions, xyz vector part, w scalar).
vec4 qmul(vec4 q, vec4 p) {
    return vec4(q.w * p.xyz + p.w * q.xyz + cross(q.xyz, p.xyz), q.w * p.w - dot(q.xyz, p.xyz));
}

vec3 qrotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// The smallest rotation taking unit a to unit b (half-turn about a perpendicular when opposite).
vec4 turn(vec3 a, vec3 b) {
    float c = dot(a, b);
    if (c < -0.99999) {
        vec3 axis = abs(a.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
        return vec4(normalize(cross(a, axis)), 0.0);
    }
    return normalize(vec4(cross(a, b), 1.0 + c));
}

// Forward at a node: the mean of the unit directions prev->node and node->next (one of them at
// the ends).
vec3 forward_at(uint node, uint nodes) {
    vec3 x = p_in[node].pos.xyz;
    vec3 to_next = node + 1u < nodes ? safe_normalize(p_in[node + 1u].pos.xyz - x, vec3(0.0)) : vec3(0.0);
    vec3 from_prev = node > 0u ? safe_normalize(x - p_in[node - 1u].pos.xyz, vec3(0.0)) : vec3(0.0);
    return safe_normalize(to_next + from_prev, safe_normalize(to_next, vec3(1.0, 0.0, 0.0)));
}

// How much of a ring vertex's offset `o` a node keeps so that it stays RING_KEEP of the way
// short of the plane halfway to the neighbour at `to` (zero: none): 1 when it points away.
const float RING_KEEP = 0.9;
float ring_reach(vec3 o, vec3 to) {
    float toward = dot(o, to);
    float half_way = 0.5 * dot(to, to);
    return toward > RING_KEEP * half_way ? RING_KEEP * half_way / toward : 1.0;
}

void main() {
    uint nodes = obj.dims.x;
    if (gl_GlobalInvocationID.x == 0u) report_lists();
    if (!DRAWN) {
        uint node = gl_GlobalInvocationID.x;
        if (node < nodes) {
            guard_check(node, p_in[node]);
            guard_strain(uvec2(node, 0u));
        }
        return;
    }
    uint t = gl_LocalInvocationID.x;
    uint per = (nodes + THREADS - 1u) / THREADS;
    uint first = min(t * per, nodes);
    uint last = min(first + per, nodes);
    // This thread's product of the turns at its nodes.
    vec4 mine = IDENTITY;
    for (uint i = first; i < last; ++i) {
        guard_check(i, p_in[i]);
        guard_strain(uvec2(i, 0u));
        if (i > 0u) mine = normalize(qmul(turn(forward_at(i - 1u, nodes), forward_at(i, nodes)), mine));
    }
    // Inclusive scan: products[t] = the turns of threads t, t - 1, ..., 0 (later ones applied
    // after earlier ones).
    products[t] = mine;
    barrier();
    for (uint offset = 1u; offset < THREADS; offset <<= 1u) {
        vec4 earlier = t >= offset ? products[t - offset] : IDENTITY;
        barrier();
        products[t] = normalize(qmul(products[t], earlier));
        barrier();
    }
    vec4 frame = t > 0u ? products[t - 1u] : IDENTITY;
    // Node 0's frame, the paper's: side = forward x world up (forward turned 90 degrees about z
    // when they are colinear), up = forward x side.
    vec3 forward0 = forward_at(0u, nodes);
    vec3 side0 = cross(forward0, vec3(0.0, 1.0, 0.0));
    side0 = length(side0) > 1e-6 ? normalize(side0) : normalize(vec3(forward0.y, -forward0.x, 0.0));
    for (uint i = first; i < last; ++i) {
        vec3 forward = forward_at(i, nodes);
        if (i > 0u) frame = normalize(qmul(turn(forward_at(i - 1u, nodes), forward), frame));
        // Transported, then made exactly perpendicular to this node's forward.
        vec3 side = qrotate(frame, side0);
        side = safe_normalize(side - dot(side, forward) * forward, side0);
        vec3 up = normalize(cross(forward, side));
        vec3 x = p_in[i].pos.xyz;
        // The segments on either side: a ring vertex stays short of the planes halfway along
        // them (on the inside of a sharp bend the rings would cross and turn faces inside out).
        vec3 to_prev = i > 0u ? p_in[i - 1u].pos.xyz - x : vec3(0.0);
        vec3 to_next = i + 1u < nodes ? p_in[i + 1u].pos.xyz - x : vec3(0.0);
        for (uint k = 0u; k < ROPE_RING; ++k) {
            vec4 pair = obj.ring_weights[k / 2u];
            vec2 w = (k & 1u) != 0u ? pair.zw : pair.xy;
            vec3 offset = side * w.x + up * w.y;
            float reach = obj.rope_radius * min(ring_reach(offset * obj.rope_radius, to_prev),
                                                ring_reach(offset * obj.rope_radius, to_next));
            surface[i * ROPE_RING + k] =
                SurfaceVertex(vec4(x + offset * reach, 1.0), vec4(safe_normalize(offset, up), 0.0));
        }
    }
}
