#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// One vertex colour of one XPBD Gauss-Seidel iteration (sim::cpu::integrators::xpbd has the
// derivation), one invocation per particle of that colour: its neighbours (other colours) are
// held; it applies its share of each of its springs' XPBD updates in turn, in place in iter (one slice of
// displacements p - x from the substep start x in p_in, see predict.comp). Each particle keeps
// its own copy of the 12 multipliers of its springs in aux[3i .. 3i + 2].
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#include "solver_end.glsl"

void main() {
    uvec2 cell = coloured_cell(gl_GlobalInvocationID.xy);
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec4 di = iter[i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    if (!pinned) {
        vec3 x = p_in[i].pos.xyz;
        float w_i = 1.0 / obj.mass;
        [[unroll]] for (int s = 0; s < 12; ++s) {
            ivec3 spring = SPRINGS[s];
            float k = obj.stiffness[spring.z];
            if (k == 0.0) continue;
            int j = neighbour(ivec2(cell), spring.xy, obj.dims);
            if (j < 0) continue;
            vec4 it_j = iter[j];
            vec3 dj = it_j.xyz;
            vec3 delta = (x - p_in[j].pos.xyz) + (dx - dj);  // p_i - p_j
            float d = length(delta);
            if (d <= 0.0) continue;
            vec3 normal = delta / d;
            float alpha = 1.0 / (k * g.dt * g.dt);
            float gamma = obj.stiffness.w / (k * g.dt);
            float moved = dot(normal, dx - dj);
            float w_j = it_j.w > 0.5 ? 0.0 : w_i;
            float c = d - rest_length(spring, obj.spacing, obj.rest_scale);
            uint slot = 3u * i + uint(s / 4);
            float lambda = aux[slot][s % 4];
            float d_lambda = g.relaxation * (-c - alpha * lambda - gamma * moved) / ((1.0 + gamma) * (w_i + w_j) + alpha);
            dx += normal * (w_i * d_lambda);
            aux[slot][s % 4] = lambda + d_lambda;
        }
        iter[i] = vec4(dx, di.w);
    }
    if (last_iteration()) finish_particle(i, dx, pinned);
}
