#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// One vertex colour of one Vertex Block Descent iteration (Chen et al. 2024;
// sim::cpu::integrators::vbd has the derivation), one invocation per particle of that colour:
// its neighbours (other colours) held, one Newton step on implicit Euler's incremental
// potential as a function of its own position (inertia, springs, dashpots), with a 3x3
// Hessian. In place in iter (one slice of displacements p - x from the substep start x in
// p_in); aux[i] holds the prediction y - x (predict.comp).
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
        float inertia = obj.mass / (g.dt * g.dt);
        float b = obj.stiffness.w;
        float damp = b / g.dt;  // a dashpot's stiffness on the displacement
        vec3 force = (aux[i].xyz - dx) * inertia;
        mat3 hessian = mat3(inertia);
        [[unroll]] for (int s = 0; s < 12; ++s) {
            ivec3 spring = SPRINGS[s];
            float k = obj.stiffness[spring.z];
            if (k == 0.0 && b == 0.0) continue;
            int j = neighbour(ivec2(cell), spring.xy, obj.dims);
            if (j < 0) continue;
            vec3 dj = iter[j].xyz;
            vec3 delta = (x - p_in[j].pos.xyz) + (dx - dj);  // p_i - p_j
            float d = length(delta);
            if (d <= 0.0) continue;
            vec3 n = delta / d;
            mat3 nn = outerProduct(n, n);
            float rest = rest_length(spring, obj.spacing, obj.rest_scale);
            float transverse = max(1.0 - rest / d, 0.0);  // clamped at compression: positive definite
            force -= n * (k * (d - rest) + damp * dot(n, dx - dj));
            hessian += nn * (k + damp) + (mat3(1.0) - nn) * (k * transverse);
        }
        dx += inverse(hessian) * force;
        iter[i] = vec4(dx, di.w);
    }
    if (last_iteration()) finish_particle(i, dx, pinned);
}
