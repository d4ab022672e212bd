#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// One Jacobi iteration of XPBD (sim::cpu::integrators::xpbd has the derivation), one thread
// per particle: reads iterate slice k % 2, writes the other; each particle keeps its own copy
// of the 12 multipliers of its springs in aux[3i .. 3i + 2]. p_in holds the substep's start x;
// the iterates are displacements from it (see predict.comp).
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#include "solver_end.glsl"

void main() {
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    uint n = particle_count();
    uint cur = (it.k & 1u) * n;
    uint next = n - cur;
    vec4 di = iter[cur + i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned) {
        vec3 x = p_in[i].pos.xyz;
        float w_i = 1.0 / obj.mass;
        vec3 sum = vec3(0.0);
        uint count = 0u;
        vec4 dl[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
        [[unroll]] for (int s = 0; s < 12; ++s) {
            ivec3 spring = SPRINGS[s];
            float k = obj.stiffness[spring.z];
            if (k == 0.0) continue;
            int j = neighbour(ivec2(cell), spring.xy, obj.dims);
            if (j < 0) continue;
            vec4 dj = iter[cur + uint(j)];
            vec3 delta = (x - p_in[j].pos.xyz) + (dx - dj.xyz);  // p_i - p_j
            float d = length(delta);
            if (d <= 0.0) continue;
            vec3 normal = delta / d;
            float alpha = 1.0 / (k * g.dt * g.dt);
            float gamma = obj.stiffness.w / (k * g.dt);
            float moved = dot(normal, dx - dj.xyz);
            float w_j = dj.w > 0.5 ? 0.0 : 1.0 / obj.mass;
            float c = d - rest_length(spring, obj.spacing, obj.rest_scale);
            float lambda = aux[3u * i + uint(s / 4)][s % 4];
            float d_lambda = (-c - alpha * lambda - gamma * moved) / ((1.0 + gamma) * (w_i + w_j) + alpha);
            dl[s / 4][s % 4] = d_lambda;
            sum += normal * (w_i * d_lambda);
            count += 1u;
        }
        if (count > 0u) {
            float scale = g.relaxation / float(count);
            dx += sum * scale;
            for (uint q = 0u; q < 3u; ++q) aux[3u * i + q] += dl[q] * scale;
        }
    }
    iter[next + i] = vec4(dx, di.w);
    if (last_iteration()) finish_particle(i, dx, pinned);
}
