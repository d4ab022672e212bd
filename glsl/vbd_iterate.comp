#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
// One vertex colour of one Vertex Block Descent iteration (Chen et al. 2024; vbd_particle in
// solver_bodies.glsl), one invocation per particle of that colour, its neighbours (other
// colours) held. In place in iter (one slice of displacements p - x~ from the BDF2 base x~,
// see predict.comp); aux[i] holds the prediction y - x~.
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

#define SX(j) history[hist(uint(j), H_BASE)].xyz
#define SD(j) iter[j].xyz
#define SPIN(j) (iter[j].w > 0.5)
#include "solver_bodies.glsl"
#include "forces.glsl"
#include "solver_end.glsl"
#include "colliders.glsl"

// The flags word's bit (it.lists) for contact between objects after every iteration
// (sim::model::SimModel::contact_rounds): each iteration but the last writes the iterate's
// positions into p_out for contact_begin.comp, and each but the first first adds the
// particle's contact sum (contact[], from the round after the iteration before) to its
// iterate and to its prediction, so that the solve keeps the correction instead of pulling
// it back towards the prediction. Each iteration also takes the particle out of the
// colliders after its solve (the particle's response, with friction): in all but the last
// its prediction moves likewise; in the last the response gives its velocity too. A pile's
// lowest layer then holds on the ground within the iterations, as the layers above it hold on
// it. Contact's moves are the solve's own: in the velocity (x - x~) / h and the history. The
// colliders' are kept apart (in aux's second slice) and taken as the constraint stage takes
// them: out of the history and the velocity, which their response in the last iteration gives
// (sim::cpu::integrators::VbdSolve says why). Their moves take aux's second slice, which the
// object has with contact rounds only (sim::gpu::object::SolverBuffers).
const uint CONTACT_ROUNDS = 2u;

// The particle a visit solves (`substep_start`, which the colliders' friction asks for).
uint visiting = 0u;
vec3 substep_start() { return p_in[visiting].pos.xyz; }

void main() {
    if (!iteration_begin()) return;
    uvec2 cell = coloured_cell(gl_GlobalInvocationID.xy);
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    vec4 di = iter[i];
    vec3 dx = di.xyz;
    bool pinned = di.w > 0.5;
    bool rounds = (it.lists & CONTACT_ROUNDS) != 0u;
    bool last = last_iteration();
    // With contact rounds: this substep's moves of the colliders so far (before the last
    // iteration's), the last iteration's, and the velocity their response gives.
    vec3 kept = vec3(0.0);
    vec3 last_move = vec3(0.0);
    vec3 v = vec3(0.0);
    if (!pinned) {
        vec4 y = aux[i];
        if (rounds && it.k > 0u) {
            vec3 moved = contact[i].xyz;
            kept = aux[particle_count() + i].xyz;
            dx += moved;
            y.xyz += moved;
            aux[i] = y;
        }
        dx = vbd_particle(cell, SX(i), dx, y.xyz);
        if (rounds) {
            visiting = i;
            v = (dx - kept - history[hist(i, H_DV)].xyz) * (1.0 / solve_dt());
            vec3 x = SX(i) + dx;
            vec3 before = x;
            // (the last: touching within a few f32 steps of the margin, where the iterations
            // before held it)
            collide_within(x, v, float(it.substep + 1u) * g.dt, last ? position_slack(x) : 0.0);
            vec3 moved = x - before;
            dx += moved;
            if (last) {
                last_move = moved;
            } else {
                kept += moved;
                y.xyz += moved;
                aux[i] = y;
                aux[particle_count() + i] = vec4(kept, 0.0);
            }
        }
        iter[i] = vec4(dx, di.w);
    }
    if (last) {
        float held = pinned ? 0.0 : held_fraction(dx, aux[i].xyz);
        if (rounds) {
            finish_particle_moved(i, dx, v, dx - kept - last_move, pinned, held);
        } else {
            finish_particle(i, dx, pinned, held);
        }
    } else if (rounds) {
        p_out[i] = Particle(vec4(SX(i) + dx, di.w), vec4(0.0));
    }
}
