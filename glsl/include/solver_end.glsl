// What the iteration shaders of the iterative integrators share: the push constants of a pass,
// the cell a coloured pass's invocation works on, and the end of the substep: the last
// iteration writes the result from the final displacement dx from the BDF2 base x~, the
// position x~ + dx and the velocity that reaches it, v = (dx - lost) / h (predict_body.glsl),
// into p_out (what the constraint stage reads) and the particle's new history, and notes
// whether it leaves its contact list's skin (hash_count.glsl).
// Include after bindings.glsl.
#ifndef MSD_SOLVER_END_GLSL
#define MSD_SOLVER_END_GLSL
#include "hash_count.glsl"
#include "mesh_springs.glsl"
#include "pins.glsl"

// k: 0-based iteration of this substep; colour: the vertex colour of a Gauss-Seidel pass;
// substep: of the frame, 0-based; lists: bit 0 with self-collision contact lists on (bit 1:
// vbd_iterate.comp's CONTACT_ROUNDS).
layout(push_constant) uniform Iteration { uint k; uint colour; uint substep; uint lists; BATCH_PUSH } it;

// Takes this workgroup's object (batch.glsl); false: the workgroup takes no part.
bool iteration_begin() { return batch_begin(it.batch_mask); }

bool last_iteration() { return it.k + 1u == g.iterations; }

// The grid cell of invocation `id` in a pass over vertex colour it.colour (springs.glsl): the
// pass dispatches ceil(columns / C) x rows invocations and id.x counts the row's cells of that
// colour.
// A mesh cloth's pass dispatches its largest colour's count and id.x counts that colour's
// particles (past them: a cell outside the object).
uvec2 coloured_cell(uvec2 id) {
    if (is_mesh()) {
        uint c = it.colour;
        return uvec2(c < mesh_colour_count() && id.x < mesh_colour_size(c) ? mesh_coloured(c, id.x) : obj.dims.x, 0u);
    }
    uint colours = vertex_colours(obj.dims);
    return uvec2(colour_first(it.colour, id.y, colours) + colours * id.x, id.y);
}

// The end of the substep: position x~ + dx with velocity v into p_out, and the history from
// the solve's own displacement `solved`. `held`: the fraction of gravity the solve held
// (held_fraction; 0 without an adaptive start), kept in H_DV's w for the next substep's start.
// vbd_iterate.comp's contact rounds pass a dx and v with the colliders' moves within the solve
// in them and a `solved` without: the history leaves those out, as it leaves out the
// constraint stage's corrections (sim::cpu::integrators::VbdSolve::sweep says why).
void finish_particle_moved(uint i, vec3 dx, vec3 v, vec3 solved, bool pinned, float held) {
    Particle start = p_in[i];
    vec3 base = history[hist(i, H_BASE)].xyz;
    vec3 lost = history[hist(i, H_DV)].xyz;  // (predict.comp)
    vec3 x = base + dx;
    vec3 solved_v = (solved - lost) * (1.0 / solve_dt());
    float w = start.pos.w;
    vec3 pins = pinned ? pin_velocity_of(pin_move(start.pos.xyz, it.substep, w), w) : vec3(0.0);
    p_out[i] = Particle(vec4(x, pinned ? w : 0.0), vec4(pinned ? pins : v, 0.0));
    history[hist(i, H_DX)] = pinned ? vec4(0.0) : vec4((base - start.pos.xyz) + solved, 1.0);
    history[hist(i, H_DV)] = pinned ? vec4(0.0) : vec4(solved_v - start.vel.xyz, held);
    note_position(i, x, pinned, it.substep, (it.lists & 1u) != 0u);
}

// The end of the substep at the solve's displacement dx, with the velocity that reaches it,
// v = (dx - lost) / h (predict_body.glsl).
void finish_particle(uint i, vec3 dx, bool pinned, float held) {
    vec3 lost = history[hist(i, H_DV)].xyz;
    finish_particle_moved(i, dx, (dx - lost) * (1.0 / solve_dt()), dx, pinned, held);
}

#endif
