// The last iteration of an iterative integrator writes the substep's result: the position and
// the velocity that reaches it from the start of the substep, v = (x - x_n) / dt, into p_out
// (what the constraint stage reads), and counts it into the spatial hash.
// Include after bindings.glsl.
#ifndef MSD_SOLVER_END_GLSL
#define MSD_SOLVER_END_GLSL
#include "hash_count.glsl"

layout(push_constant) uniform Iteration { uint k; } it;  // 0-based iteration of this substep

bool last_iteration() { return it.k + 1u == g.iterations; }

void finish_particle(uint i, vec3 x, bool pinned) {
    vec3 v = pinned ? vec3(0.0) : (x - p_in[i].pos.xyz) / g.dt;
    p_out[i] = Particle(vec4(x, pinned ? 1.0 : 0.0), vec4(v, 0.0));
    count_into_bucket(i, x);
}

#endif
