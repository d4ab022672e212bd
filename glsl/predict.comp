#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// First pass of a substep of the iterative integrators, one thread per particle: the BDF2
// start (predict_body.glsl) from p_in (the state x at the start of the substep) and the
// particle's history: the base x~ into history H_BASE, where the iteration shaders read it
// as the start position, what its rounding left out into H_DV (finish_particle reads it and
// writes the new v_n - v_{n-1} there), and where the iterate starts (the prediction y, or with
// ADAPTIVE_START adaptive_start's) into the iterates. Resets the solver's auxiliary
// data: a copy of y (KEEP_PREDICTION), else the multipliers of XPBD to zero (a grid particle's
// 12; a mesh cloth's, a float an entry of its spring lists: MESH_LAMBDA). The constants
// are the method's row in sim::integrator.
//
// The iterates are displacements from the base, p - x~, not positions: the velocity p - x~
// over h then carries no rounding of the absolute position. With positions in f32 (x ~ 1 m,
// steps ~ 1 mm) each substep's rounding of x entered the velocity and accumulated: measured
// 7e-4 m against the f64 reference after 240 substeps of a falling cloth, versus 1e-6 m here.
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"
#define IN(i) p_in[i]
#include "predict_body.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;
layout(push_constant) uniform Push {
    uint substep;  // of the frame, 0-based (the wind's turbulence)
    BATCH_PUSH
} pc;
layout(constant_id = 4) const bool KEEP_PREDICTION = false;
layout(constant_id = 5) const bool ADAPTIVE_START = false;

void main() {
    if (!batch_begin(pc.batch_mask)) return;
    air_time = float(pc.substep) * g.dt;
    uvec2 cell = gl_GlobalInvocationID.xy;
    if (cell.x >= obj.dims.x || cell.y >= obj.dims.y) return;
    uint i = cell.x + cell.y * obj.dims.x;
    Particle p = p_in[i];
    vec3 x = p.pos.xyz;
    vec3 v = p.vel.xyz;
    vec3 dy = vec3(0.0);  // y - x~
    vec3 guess = vec3(0.0);  // where the iterate starts
    precise vec3 start = x;    // x~, rounded
    precise vec3 lost = vec3(0.0);  // what rounding x~ left out (bdf2_start)
    if (p.pos.w > 0.5) {
        // Moving pins (sim::cpu::integrators::inertial): a base of their steady motion (a
        // move of d a substep), so that y - x~ = 2 d / 3 is their velocity over h, as the free
        // particles' displacements are (implicit Euler: base x, y - x = d).
        vec3 d = pin_move(x, pc.substep, p.pos.w);
        start = x + d * (1.0 - solve_share());
        dy = d * solve_share();
        guess = dy;
    } else {
        vec3 base;
        vec3 pull;
        vec4 hx = history[hist(i, H_DX)];
        vec4 hv = history[hist(i, H_DV)];
        dy = predicted_displacement(cell, x, v, hx, hv.xyz, base, pull);
        bdf2_start(x, base, start, lost);
        dy += lost;
        guess = ADAPTIVE_START ? adaptive_start(cell, dy, pull, hx, hv.w, lost - base, x, pc.substep) : dy;
    }
    history[hist(i, H_DV)] = vec4(lost, 0.0);  // (v_n - v_{n-1} is read; finish_particle rewrites it)
    history[hist(i, H_BASE)] = vec4(start, 0.0);
    iter[i] = vec4(guess, p.pos.w);
    if (KEEP_PREDICTION) {
        aux[i] = vec4(dy, 0.0);
    } else if (is_mesh()) {
        // (XPBD's multipliers of a mesh cloth, by classes or by Jacobi: a float an entry of
        // its lists)
        for (uint e = mesh_first(i); e < mesh_first(i + 1u); ++e) aux[e >> 2u][e & 3u] = 0.0;
    } else {
        for (uint q = 0u; q < 3u; ++q) aux[3u * i + q] = vec4(0.0);
    }
}
