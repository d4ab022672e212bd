#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// One iteration of implicit Euler by projective dynamics (sim::cpu::integrators::implicit has
// the derivation), one thread per particle: the local step (each spring's rest-length
// projection) and one Jacobi sweep of the global system, damped by obj.jacobi_damping (it
// follows the substep) and Chebyshev-accelerated. Iterate slices
// rotate: iteration k reads slice k % 3 (and the one before, (k + 2) % 3), writes (k + 1) % 3.
// p_in holds the substep's start x; the iterates and aux[i] (the prediction y) are
// displacements from it (see predict.comp).
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#include "solver_end.glsl"

// Must equal sim::stability::CHEBYSHEV_START (the GPU-vs-CPU tests compare).
const uint CHEBYSHEV_START = 2u;

// Chebyshev weight of iteration k for the Jacobi radius rho (Wang 2015).
float chebyshev_omega(uint k, float rho) {
    float omega = 1.0;
    for (uint step = 1u; step <= k; ++step) {
        omega = step == 1u ? 2.0 / (2.0 - rho * rho) : 4.0 / (4.0 - rho * rho * omega);
    }
    return omega;
}

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    uint n = particle_count();
    uint cur = (it.k % 3u) * n;
    uint prev = it.k == 0u ? cur : ((it.k + 2u) % 3u) * n;
    uint next = ((it.k + 1u) % 3u) * n;
    vec4 di = iter[cur + i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned) {
        vec3 x = p_in[i].pos.xyz;
        float inertia = obj.mass / (g.dt * g.dt);
        vec3 rhs = aux[i].xyz * inertia;
        float diag = inertia;
        [[unroll]] for (int s = 0; s < 12; ++s) {
            ivec3 spring = SPRINGS[s];
            float k = obj.stiffness[spring.z];
            if (k == 0.0) continue;
            int j = neighbour(ivec2(cell), spring.xy, obj.dims);
            if (j < 0) continue;
            vec3 pj = (p_in[j].pos.xyz - x) + iter[cur + uint(j)].xyz;  // p_j - x_i
            vec3 delta = dx - pj;                                       // p_i - p_j
            float d = length(delta);
            vec3 target = d > 0.0 ? delta * (rest_length(spring, obj.spacing, obj.rest_scale) / d) : vec3(0.0);
            rhs += k * (pj + target);
            diag += k;
        }
        vec3 damped = dx + (rhs / diag - dx) * obj.jacobi_damping;
        vec3 before = iter[prev + i].xyz;
        float omega = it.k < CHEBYSHEV_START ? 1.0 : chebyshev_omega(it.k - CHEBYSHEV_START, obj.cheb_rho);
        dx = before + omega * (damped - before);
    }
    iter[next + i] = vec4(dx, di.w);
    if (last_iteration()) finish_particle(i, dx, pinned);
}
