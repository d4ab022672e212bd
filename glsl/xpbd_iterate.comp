#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// One spring class of one XPBD Gauss-Seidel iteration (xpbd_spring in solver_bodies.glsl; the
// classes and their order, xpbd_class, in springs.glsl), one invocation per particle: the
// spring of the class whose first node it is, if any, moves both ends (no other spring of the
// class touches them). In place in
// iter (one slice of displacements p - x~ from the BDF2 base x~, see predict.comp;
// w = 1 pinned); aux[3i + dir / 4][dir % 4] holds the multiplier of particle i's forward spring
// of direction dir. Pass XPBD_FINISH, after the last iteration, finishes every particle.
// A mesh cloth's pass c takes its class c (sim::cloth_mesh::spring_classes), an invocation a
// spring (xpbd_mesh_spring), its multiplier in aux's float at the spring's entry in its lower
// end's list (MESH_LAMBDA).
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#define SX(j) history[hist(uint(j), H_BASE)].xyz
#define SD(j) iter[j].xyz
#define SPIN(j) (iter[j].w > 0.5)
#define SLICE(j) iter[uint(j)]
#define MESH_LAMBDA(e) aux[(e) >> 2u][(e) & 3u]
#include "solver_bodies.glsl"
#include "solver_end.glsl"

void main() {
    if (!iteration_begin()) return;
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (is_mesh() && it.colour != XPBD_FINISH) {
        if (cell.x >= mesh_class_size(it.colour)) return;
        uvec2 spring = mesh_class_spring(it.colour, cell.x);
        xpbd_mesh_spring(spring.x, spring.y);
        return;
    }
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    if (it.colour == XPBD_FINISH) {
        vec4 di = iter[i];
        finish_particle(i, di.xyz, di.w > 0.5, 0.0);
        return;
    }
    uint q = xpbd_class(it.colour);
    uint dir = q >> 1u;
    int slot = class_slot(dir);
    if (class_parity(dir, ivec2(cell)) != (q & 1u) || obj.stiffness[slot >> 2] == 0.0) return;
    int j = neighbour(ivec2(cell), class_offset(dir), obj.dims);
    if (j < 0) return;
    vec4 di = iter[i];
    vec4 dj = iter[j];
    bool pin_i = di.w > 0.5;
    bool pin_j = dj.w > 0.5;
    if (pin_i && pin_j) return;
    uint at = 3u * i + dir / 4u;
    float lam = aux[at][dir % 4u];
    vec3 normal;
    float dl = xpbd_spring(class_slot(dir), SX(i), di.xyz, SX(j), dj.xyz, pin_i, pin_j, lam, normal);
    float w = 1.0 / obj.mass;
    if (!pin_i) iter[i] = vec4(di.xyz + normal * (w * dl), di.w);
    if (!pin_j) iter[j] = vec4(dj.xyz - normal * (w * dl), dj.w);
    aux[at][dir % 4u] = lam + dl;
}
