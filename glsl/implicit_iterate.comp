#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// One pass of the implicit method's Newton steps with preconditioned conjugate gradients
// (sim::cpu::integrators::implicit), one invocation per particle. The host records, for each
// Newton step, a linearising pass and then two passes per CG iteration (sim::gpu::step):
//   PHASE_LINEARISE  the force r = -g at the iterate p and the inverse of the particle's 3x3
//                    diagonal block of the Hessian (the preconditioner); z = P r, dp = 0;
//   PHASE_PRODUCT    the direction d = z + beta d (beta = rz / rz before; d = z first) and
//                    q = H d (neighbours' d formed the same way from their z and d);
//   PHASE_UPDATE     alpha = rz / (d.q): dp += alpha d, r -= alpha q, z = P r; the Newton
//                    step's last moves p by dp, the substep's last finishes the particle;
//   PHASE_TOTAL      (one workgroup, on objects of many workgroups) sums the partial sums.
// On an object that searches along its Newton steps (OBJ_LINE_SEARCH, SEARCHED in the pass
// word; sim::cpu::integrators::implicit_searches) the last update leaves p, and
//   PHASE_SEARCH     sums newton_descent (solver_bodies.glsl): G's change for four lengths
//                    of the step, in partial sums of their own (SEARCH_PARTIAL);
//   PHASE_SEARCH_TOTAL  as PHASE_TOTAL, for those sums;
//   PHASE_MOVE       moves p by the chosen length of dp and finishes the particle in the
//                    substep's last Newton step.
// CG's dot products are summed per workgroup into aux (PARTIAL): rz in two slots by the CG
// iteration's parity (rz and the one before), d.q in a third. Each pass reads their totals at
// its start: on objects of few workgroups it sums the partial sums itself (every workgroup the
// same way, so all get the same totals), on others (TOTALS) a PHASE_TOTAL pass after each of
// the others has summed them into the last vec4 of their region (total_slot; every workgroup reading all 4,096 partial
// sums of a 1024 x 1024 cloth cost 4.5 us a pass more on the H100).
// The iterate and the vectors are slices of iter (S_*), displacements from the BDF2 base x~
// (history H_BASE, see predict.comp); aux[i] holds the prediction y - x~.
#define BATCHED
#include "bindings.glsl"
#include "springs.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 1) in;

const uint S_P = 0u;    // p - x~ (w: pinned)
const uint S_DP = 1u;   // the Newton step's move so far
const uint S_R = 2u;    // the residual -g - H dp
const uint S_Z = 3u;    // P r
const uint S_D = 4u;    // the direction, two slices by the CG iteration's parity
const uint S_Q = 6u;    // H d
const uint S_PRE = 7u;  // P: sym3_inverse's two rows, two slices

const uint PHASE_LINEARISE = 0u;
const uint PHASE_PRODUCT = 1u;
const uint PHASE_UPDATE = 2u;
const uint PHASE_TOTAL = 3u;
const uint PHASE_SEARCH = 4u;
const uint PHASE_SEARCH_TOTAL = 5u;
const uint PHASE_MOVE = 6u;
const uint PHASES = 7u;  // the phase's bits
// it.colour: the phase (bits 0-2), the CG iteration's parity (bit 3), whether it is the Newton
// step's first (bit 4) and last (bit 5), whether PHASE_TOTAL passes sum the partial sums
// (bit 6, TOTALS) and whether the object searches (bit 7, SEARCHED) (sim::gpu::step::cg_pass).
const uint FIRST_CG = 16u;
const uint LAST_CG = 32u;
const uint TOTALS = 64u;
const uint SEARCHED = 128u;
uint phase_bits;

#include "solver_end.glsl"

uint n_all;
float beta;
uint parity;

vec3 slice(uint s, uint j) { return iter[s * n_all + j].xyz; }
// Particle j's direction this CG iteration (zero where pinned: its z and d are).
vec3 direction(uint j) {
    bool first = (phase_bits & FIRST_CG) != 0u;
    return first ? slice(S_Z, j) : slice(S_Z, j) + beta * slice(S_D + (parity ^ 1u), j);
}

#define SX(j) history[hist(uint(j), H_BASE)].xyz
#define SD(j) slice(S_P, uint(j))
#define SPIN(j) (iter[uint(j)].w > 0.5)
#define PP(j) (SX(j) + SD(j))
#define DD(j) direction(uint(j))
#define DP(j) slice(S_DP, uint(j))
#include "solver_bodies.glsl"
#include "forces.glsl"

#define REDUCE_T vec3
#define REDUCE_SLOTS 64
#include "reduce.glsl"

const uint PARTIAL = 1u;  // aux[n + workgroup]: (rz parity 0, rz parity 1, d.q)
const uint SEARCH_PARTIAL = 2u;  // aux[2 n + workgroup]: G's change at the four lengths
// Where PHASE_TOTAL leaves the totals of the partial sums from aux[region * n]: that region's
// last vec4. The partial sums end before it: a workgroup spans 16 x 16 or 64 x 1 cells, so an
// object of n >= 2 particles (scene validation) has fewer than n workgroups.
uint total_slot(uint region) { return (region + 1u) * n_all - 1u; }

// The totals of the workgroups' partial sums (their count from the grid: a PHASE_TOTAL pass
// runs one workgroup).
// The object's workgroups (a batched dispatch has as many as its largest object).
uvec2 object_grid() { return (obj.dims + gl_WorkGroupSize.xy - 1u) / gl_WorkGroupSize.xy; }

vec4 totals(uint region) {
    uint phase = phase_bits & PHASES;
    if ((phase_bits & TOTALS) != 0u && phase != PHASE_TOTAL && phase != PHASE_SEARCH_TOTAL) {
        return aux[total_slot(region)];
    }
    uvec2 grid = object_grid();
    uint groups = grid.x * grid.y;
    uint lanes = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
    vec4 sum = vec4(0.0);
    for (uint w = gl_LocalInvocationIndex; w < groups; w += lanes) sum += aux[region * n_all + w];
    // (the CG's sums use xyz: their w is left out of the reduction)
    vec3 xyz = workgroup_sum(sum.xyz);
    float w = region == SEARCH_PARTIAL ? workgroup_sum(vec3(sum.w, 0.0, 0.0)).x : 0.0;
    return vec4(xyz, w);
}

// This workgroup's sum of `mine` into component `slot` of its partial. Other workgroups read
// every partial in the same pass (totals()), but only the components no pass writes at that
// time: PRODUCT writes d.q and reads the rz pair, UPDATE writes the next rz and reads the
// current one and d.q. Keep it so if the slots change.
void add_partial(float mine, uint slot) {
    float total = workgroup_sum(vec3(mine, 0.0, 0.0)).x;
    uint w = gl_WorkGroupID.x + gl_WorkGroupID.y * object_grid().x;
    if (gl_LocalInvocationIndex == 0u) aux[PARTIAL * n_all + w][slot] = total;
}

void main() {
    if (!iteration_begin()) return;
    phase_bits = it.colour;
    uint phase = phase_bits & PHASES;
    bool total = phase == PHASE_TOTAL || phase == PHASE_SEARCH_TOTAL;
    // Workgroups past this object's own leave its partial sums alone.
    if (!total && any(greaterThanEqual(gl_WorkGroupID.xy, object_grid()))) return;
    parity = (phase_bits >> 3u) & 1u;
    // (an object that searches moves p after the search)
    bool last_cg = (phase_bits & (LAST_CG | SEARCHED)) == LAST_CG;
    n_all = particle_count();
    uvec2 cell = gl_GlobalInvocationID.xy;
    bool inside = cell.x < obj.dims.x && cell.y < obj.dims.y;  // (every invocation sums)
    uint i = inside ? cell.x + cell.y * obj.dims.x : 0u;
    if (total) {
        uint region = phase == PHASE_TOTAL ? PARTIAL : SEARCH_PARTIAL;
        vec4 sums = totals(region);
        if (gl_LocalInvocationIndex == 0u) aux[total_slot(region)] = region == PARTIAL ? vec4(sums.xyz, 0.0) : sums;
        return;
    }
    vec4 pi = iter[i];
    bool moves = inside && pi.w <= 0.5;
    if (phase == PHASE_SEARCH) {
        vec4 change = vec4(0.0);
        if (inside) {
            vec3 dp = slice(S_DP, i);
            float r0dp = 0.0;
            if (moves) {
                Sym3 hessian;  // (unused: r0 is the linearisation's, at the same p)
                r0dp = dot(newton_particle(cell, SX(i), pi.xyz, aux[i].xyz, hessian), dp);
            }
            change = newton_descent(cell, PP(i), dp, r0dp);
        }
        vec3 head = workgroup_sum(change.xyz);
        float tail = workgroup_sum(vec3(change.w, 0.0, 0.0)).x;
        uint w = gl_WorkGroupID.x + gl_WorkGroupID.y * object_grid().x;
        if (gl_LocalInvocationIndex == 0u) aux[SEARCH_PARTIAL * n_all + w] = vec4(head, tail);
        return;
    }
    if (phase == PHASE_MOVE) {
        float step = line_search_step(totals(SEARCH_PARTIAL));
        if (moves) {
            pi.xyz += step * slice(S_DP, i);
            iter[i] = pi;
        }
        if (inside && last_iteration()) {
            bool pinned = !moves;
            finish_particle(i, pi.xyz, pinned, pinned ? 0.0 : held_fraction(pi.xyz, aux[i].xyz));
        }
        return;
    }
    if (phase == PHASE_LINEARISE) {
        vec3 r = vec3(0.0);
        vec3 row0 = vec3(0.0);
        vec3 rest = vec3(0.0);
        if (moves) {
            Sym3 hessian;
            r = newton_particle(cell, SX(i), pi.xyz, aux[i].xyz, hessian);
            sym3_inverse(hessian, row0, rest);
        }
        vec3 z = sym3_apply(row0, rest, r);
        if (inside) {
            iter[S_R * n_all + i] = vec4(r, 0.0);
            iter[S_Z * n_all + i] = vec4(z, 0.0);
            iter[S_DP * n_all + i] = vec4(0.0);
            iter[S_PRE * n_all + i] = vec4(row0, 0.0);
            iter[(S_PRE + 1u) * n_all + i] = vec4(rest, 0.0);
        }
        add_partial(dot(r, z), 0u);
        return;
    }
    vec3 sums = totals(PARTIAL).xyz;
    float rz = parity == 0u ? sums.x : sums.y;
    if (phase == PHASE_PRODUCT) {
        float before = parity == 0u ? sums.y : sums.x;
        beta = before > 0.0 ? rz / before : 0.0;
        vec3 d = moves ? direction(i) : vec3(0.0);
        vec3 q = moves ? hessian_product(cell, PP(i), d) : vec3(0.0);
        if (inside) {
            iter[(S_D + parity) * n_all + i] = vec4(d, 0.0);
            iter[S_Q * n_all + i] = vec4(q, 0.0);
        }
        add_partial(dot(d, q), 2u);
        return;
    }
    float alpha = sums.z > 0.0 ? rz / sums.z : 0.0;
    float mine = 0.0;
    if (moves) {
        vec3 dp = slice(S_DP, i) + alpha * slice(S_D + parity, i);
        vec3 r = slice(S_R, i) - alpha * slice(S_Q, i);
        vec3 z = sym3_apply(slice(S_PRE, i), slice(S_PRE + 1u, i), r);
        iter[S_DP * n_all + i] = vec4(dp, 0.0);
        iter[S_R * n_all + i] = vec4(r, 0.0);
        iter[S_Z * n_all + i] = vec4(z, 0.0);
        mine = dot(r, z);
        if (last_cg) {
            pi.xyz += dp;
            iter[i] = pi;
        }
    }
    add_partial(mine, parity ^ 1u);
    if (inside && last_cg && last_iteration()) {
        bool pinned = !moves;
        finish_particle(i, pi.xyz, pinned, pinned ? 0.0 : held_fraction(pi.xyz, aux[i].xyz));
    }
}
