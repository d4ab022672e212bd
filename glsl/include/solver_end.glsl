// The last iteration of an iterative integrator writes the substep's result from the final
// displacement dx: the position x_n + dx and the velocity that reaches it, v = dx / dt, into
// p_out (what the constraint stage reads), and counts it into the spatial hash.
// Include after bindings.glsl.
#ifndef MSD_SOLVER_END_GLSL
#define MSD_SOLVER_END_GLSL
#include "hash_count.glsl"

layout(push_constant) uniform Iteration { uint k; } it;  // 0-based iteration of this substep

bool last_iteration() { return it.k + 1u == g.iterations; }

void finish_particle(uint i, vec3 dx, bool pinned) {
    vec3 x = p_in[i].pos.xyz + dx;
    vec3 v = pinned ? vec3(0.0) : dx / g.dt;
    p_out[i] = Particle(vec4(x, pinned ? 1.0 : 0.0), vec4(v, 0.0));
    count_into_bucket(i, x);
}

#endif
