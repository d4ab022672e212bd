// The per-particle updates of the iterative integrators (sim::cpu::integrators has their
// derivations), shared by their per-stage shaders (xpbd_iterate.comp, implicit_iterate.comp,
// vbd_iterate.comp) and the fused kernel. A particle at grid `cell` with start position x and
// displacement dx (p - x) reads its neighbour j through SX(j) (j's start position), SD(j) (its
// displacement) and SPIN(j) (pinned), which each includer defines. The start is the BDF2 base
// x~ (predict_body.glsl) and the step solve_dt() (bindings.glsl).
// SPRING_DELTA(x, dx, j, dj) may give p_i - p_j another way (the fused kernel's COMPACT layout).
// Include after bindings.glsl and springs.glsl.
// Each body repeats the neighbour lookup at the top of its spring loop on purpose: a shared
// helper (returning j, its displacement and p_i - p_j through out parameters) made the fused
// methods slower (docs/design/integrators.md, "One table").
// SELECT_SPRINGS (the fused kernel defines it true): the Newton step's and the Hessian
// product's spring loops skip a spring with no other end or with coincident ends by selects,
// not branches: one with no other end reads the particle itself (SPRING_OTHER), whose p_i - p_j
// is then exactly zero (the includer's SPRING_DELTA and PP give the particle's own p exactly),
// and a spring whose ends coincide takes no direction (inv = 0), so either adds zero (exactly,
// but for ends so close, under 1e-19 m, that dot(delta, delta) underflows: k delta, negligible).
// One workgroup then overlaps each spring's loads and square root with the next's, where a
// branch between them made a visit's 12 springs run one after the other; per stage, whose
// many workgroups hide that latency, the branches are faster (docs/PERFORMANCE.md,
// "Branch-free spring loops").
#ifndef MSD_SOLVER_BODIES_GLSL
#define MSD_SOLVER_BODIES_GLSL
#include "features.glsl"
#include "mesh_springs.glsl"
#ifndef SELECT_SPRINGS
#define SELECT_SPRINGS false
#endif
// Spring s's other end, or the particle itself where it has none (SELECT_SPRINGS).
#ifndef SPRING_OTHER
#define SPRING_OTHER(cell, s) (SPRING_NEIGHBOUR(cell, s) < 0 ? self_index : SPRING_NEIGHBOUR(cell, s))
#endif

// XPBD, one spring (slot `slot` of SPRINGS, springs.glsl) from particle i (start
// position xi, displacement di, pinned pin_i) to particle j, with multiplier lam: returns
// dlambda = relaxation (-C - alpha~ lambda - gamma n.(dx_i - dx_j)) / ((1 + gamma)(w_i + w_j) + alpha~)
// (the per-type constants and the reciprocal of the denominator from the host, obj.xpbd) and the
// spring's direction n through `normal` (zero for coincident ends: no update). The caller moves
// i by w_i n dlambda and j by -w_j n dlambda (sim::cpu::integrators::xpbd).
#ifndef XPBD_OBJ
#define XPBD_OBJ obj
#endif
#ifndef SPRING_DELTA
#define SPRING_DELTA(x, dx, j, dj) (((x) - SX(j)) + ((dx) - (dj)))
#endif
float xpbd_spring(int slot, vec3 xi, vec3 di, vec3 xj, vec3 dj, bool pin_i, bool pin_j, float lam, out vec3 normal) {
    vec4 c = XPBD_OBJ.xpbd[slot >> 2];  // alpha~, gamma, scale (both ends free, one pinned)
    vec3 rel = di - dj;
    vec3 delta = (xi - xj) + rel;  // p_i - p_j
    float dd = dot(delta, delta);
    normal = vec3(0.0);
    if (dd <= 0.0) return 0.0;
    float inv = inversesqrt(dd);
    normal = delta * inv;
    float scale = (pin_i || pin_j) ? c.w : c.z;
    return scale * (XPBD_OBJ.rest[slot >> 2][slot & 3] - c.x * lam - dd * inv - c.y * dot(normal, rel));
}

// XPBD by Jacobi (sim::cpu::integrators::xpbd_jacobi has the derivation), one particle's
// visit: each of its springs with a stiffness takes xpbd_spring's update from the iterate
// before, and the particle moves by beta w n dlambda summed, beta = min(1, 1 / (w load)) with
// load = sum (1 + gamma) e / D (e = 2, 1 with the other end pinned; D the denominator; the
// host gives this method no relaxation): no sweep overshoots. lam[s / 4][s % 4], the
// particle's own copy of the multiplier of spring s of SPRINGS, advances by beta dlambda.
// Returns the new displacement.
vec3 xpbd_jacobi_particle(uvec2 cell, vec3 x, vec3 dx, inout vec4 lam[3]) {
    float w = 1.0 / obj.mass;
    float load = 0.0;
    vec3 move = vec3(0.0);
    vec4 dl[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        if (obj.stiffness[spring.z] == 0.0) continue;
        int j = SPRING_NEIGHBOUR(cell, s);
        if (j < 0) continue;
        bool pin_j = SPIN(j);
        vec4 c = XPBD_OBJ.xpbd[spring.z];
        load += (1.0 + c.y) * (pin_j ? c.w : 2.0 * c.z);
        vec3 normal;
        float d = xpbd_spring(s, x, dx, SX(j), SD(j), false, pin_j, lam[s >> 2][s & 3], normal);
        dl[s >> 2][s & 3] = d;
        move += normal * d;
    }
    float beta = w * load > 1.0 ? 1.0 / (w * load) : 1.0;
    [[unroll]] for (int q = 0; q < 3; ++q) lam[q] += beta * dl[q];
    return dx + move * (beta * w);
}

#ifdef MESH_LAMBDA
// XPBD on a mesh cloth's spring at entry e of particle a's list (a its lower end; F_CLOTH_MESH,
// per stage only): xpbd_spring's update with its own stiffness and both ends' masses (lumped
// by area, so unequal), moving both ends in place; its multiplier is MESH_LAMBDA(e). No other
// spring of its class shares an end (sim::cloth_mesh::spring_classes).
void xpbd_mesh_spring(uint a, uint e) {
    MeshSpring s = mesh_spring(e);
    if (s.k == 0.0) return;
    uint j = uint(s.other);
    vec4 da = SLICE(a);
    vec4 dj = SLICE(j);
    bool pin_a = da.w > 0.5;
    bool pin_j = dj.w > 0.5;
    float w_a = pin_a ? 0.0 : 1.0 / particle_mass(uvec2(a, 0u));
    float w_j = pin_j ? 0.0 : 1.0 / particle_mass(uvec2(j, 0u));
    if (w_a + w_j == 0.0) return;
    float h = solve_dt();
    float alpha = 1.0 / (s.k * h * h);
    float gamma = (has(F_DAMPING) ? obj.stiffness.w : 0.0) / (s.k * h);
    vec3 rel = da.xyz - dj.xyz;
    vec3 delta = (SX(a) - SX(j)) + rel;
    float dd = dot(delta, delta);
    if (dd <= 0.0) return;
    float inv = inversesqrt(dd);
    vec3 normal = delta * inv;
    float lambda = MESH_LAMBDA(e);
    float dl = g.relaxation * (s.rest - dd * inv - alpha * lambda - gamma * dot(normal, rel))
        / ((1.0 + gamma) * (w_a + w_j) + alpha);
    if (!pin_a) SLICE(a) = vec4(da.xyz + normal * (w_a * dl), da.w);
    if (!pin_j) SLICE(j) = vec4(dj.xyz - normal * (w_j * dl), dj.w);
    MESH_LAMBDA(e) = lambda + dl;
}

// XPBD by Jacobi on a mesh cloth's particle i (F_CLOTH_MESH; per stage only): as
// xpbd_jacobi_particle over its spring list, each spring's constants from its own stiffness and
// both ends' masses, which lumping by area makes unequal: D = (1 + gamma)(w_i + w_j) + alpha~,
// the particle moving by beta w_i n dlambda with beta = min(1, 1 / sum (1 + gamma)(w_i + w_j) / D)
// (the grid's bound, whose w_j is w_i or 0; it needs no positions nor multipliers, so
// xpbd_jacobi_mesh_bound sums it once a substep and each multiplier advances in place). Its
// multipliers, its own copies, are MESH_LAMBDA(e) at its list's entries; `keep`: advance them
// (not in the last iteration). Both loops read a batch of entries and their other ends before
// using any (mesh_batch). Returns the new displacement.
float xpbd_mesh_ends(float k, bool pin_j, float share_j, float w, float b, float h) {
    float w_j = pin_j ? 0.0 : 1.0 / (obj.mass * share_j);
    return (1.0 + b / (k * h)) * (w + w_j);
}
float xpbd_jacobi_mesh_bound(uint i) {
    float h = solve_dt();
    float b = has(F_DAMPING) ? obj.stiffness.w : 0.0;
    float w = 1.0 / particle_mass(uvec2(i, 0u));
    uint first = mesh_first(i);
    uint end = mesh_first(i + 1u);
    float load = 0.0;
    for (uint e = first; e < end; e += MESH_BATCH) {
        MeshSpring s[MESH_BATCH];
        bool pin_j[MESH_BATCH];
        float share_j[MESH_BATCH];
        [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) s[q] = mesh_batch(e + q, end);
        [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
            pin_j[q] = SPIN(s[q].other);
            share_j[q] = mass_share(uint(s[q].other));
        }
        [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
            if (e + q >= end || s[q].k == 0.0) continue;
            float ends = xpbd_mesh_ends(s[q].k, pin_j[q], share_j[q], w, b, h);
            load += ends / (ends + 1.0 / (s[q].k * h * h));
        }
    }
    return load > 1.0 ? 1.0 / load : 1.0;
}
vec3 xpbd_jacobi_mesh(uint i, vec3 x, vec3 dx, bool keep, float beta) {
    float h = solve_dt();
    float b = has(F_DAMPING) ? obj.stiffness.w : 0.0;
    float w = 1.0 / particle_mass(uvec2(i, 0u));
    uint first = mesh_first(i);
    uint end = mesh_first(i + 1u);
    vec3 move = vec3(0.0);
    for (uint e = first; e < end; e += MESH_BATCH) {
        MeshSpring s[MESH_BATCH];
        vec3 xj[MESH_BATCH];
        vec3 dj[MESH_BATCH];
        bool pin_j[MESH_BATCH];
        float share_j[MESH_BATCH];
        [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) s[q] = mesh_batch(e + q, end);
        [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
            xj[q] = SX(s[q].other);
            dj[q] = SD(s[q].other);
            pin_j[q] = SPIN(s[q].other);
            share_j[q] = mass_share(uint(s[q].other));
        }
        [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
            if (e + q >= end || s[q].k == 0.0) continue;
            float alpha = 1.0 / (s[q].k * h * h);
            float gamma = b / (s[q].k * h);
            vec3 rel = dx - dj[q];
            vec3 delta = (x - xj[q]) + rel;
            float dd = dot(delta, delta);
            if (dd <= 0.0) continue;
            float inv = inversesqrt(dd);
            vec3 normal = delta * inv;
            float lambda = MESH_LAMBDA(e + q);
            float ends = xpbd_mesh_ends(s[q].k, pin_j[q], share_j[q], w, b, h);
            float dl = (s[q].rest - dd * inv - alpha * lambda - gamma * dot(normal, rel)) / (ends + alpha);
            move += normal * dl;
            if (keep) MESH_LAMBDA(e + q) = lambda + beta * dl;
        }
    }
    return dx + move * (beta * w);
}
#endif

// Conjugate-gradient iterations of one Newton step of the implicit method: must equal
// sim::integrator::NEWTON_CG_ITERATIONS (the GPU-vs-CPU tests compare).
const uint NEWTON_CG_ITERATIONS = 5u;

// A symmetric 3x3 matrix: a multiple of the identity, a diagonal and three off-diagonal entries.
struct Sym3 {
    float iso;
    vec3 diag;  // xx, yy, zz (besides iso)
    vec3 off;   // xy, xz, yz
};

// BDF2's incremental potential (step h = solve_dt()) at the particle at grid `cell` with start
// x and displacement dx, its neighbours read through SX/SD: the force on it (inertia towards
// the prediction dy, springs, dashpots: minus the gradient) and its 3x3 diagonal block of the
// Hessian. Each spring adds (k + b / h) n n^T + k t (I - n n^T) = c n n^T + k t I
// (c = k + b / h - k t, t = max(0, 1 - L / d) clamped at compression: positive definite),
// written in delta = d n below (sim::cpu::integrators::spring_newton).
vec3 newton_particle(uvec2 cell, vec3 x, vec3 dx, vec3 dy, out Sym3 hessian) {
    float h = solve_dt();
    float inertia = particle_mass(cell) / (h * h);
    float b = has(F_DAMPING) ? obj.stiffness.w : 0.0;
    float damp = b / h;  // a dashpot's stiffness on the displacement
    vec3 force = (dy - dx) * inertia;
    float iso = inertia;
    vec3 diag = vec3(0.0);
    vec3 off = vec3(0.0);
    if (is_mesh()) {
        // (a mesh cloth: its list, as the grid's loop below with branches, a batch's loads
        // issued together: mesh_batch)
        uint end = mesh_first(cell.x + 1u);
        for (uint e = mesh_first(cell.x); e < end; e += MESH_BATCH) {
            MeshSpring s[MESH_BATCH];
            vec3 dj[MESH_BATCH];
            vec3 delta[MESH_BATCH];
            [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) s[q] = mesh_batch(e + q, end);
            [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
                dj[q] = SD(s[q].other);
                delta[q] = SPRING_DELTA(x, dx, s[q].other, dj[q]);
            }
            [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
                float dd = dot(delta[q], delta[q]);
                if (e + q >= end || dd <= 0.0) continue;
                float k = s[q].k;
                float inv = inversesqrt(dd);
                float inv2 = inv * inv;
                float stretch = k - (k * s[q].rest) * inv;
                float kt = max(stretch, 0.0);
                force -= delta[q] * (stretch + (damp * inv2) * dot(delta[q], dx - dj[q]));
                vec3 cd = ((k + damp - kt) * inv2) * delta[q];
                iso += kt;
                diag += cd * delta[q];
                off += cd.xxy * delta[q].yzz;
            }
        }
        hessian = Sym3(iso, diag, off);
        return force;
    }
    int self_index = int(cell.x + cell.y * obj.dims.x);
    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        if (!has(1u << spring.z)) continue;  // F_STRUCTURAL, F_SHEAR, F_BENDING: no stiffness, no dashpot
        float k = obj.stiffness[spring.z];
        int j = SELECT_SPRINGS ? SPRING_OTHER(cell, s) : SPRING_NEIGHBOUR(cell, s);
        if (!SELECT_SPRINGS && j < 0) continue;
        vec3 dj = SD(j);
        vec3 delta = SPRING_DELTA(x, dx, j, dj);  // p_i - p_j = d n
        float dd = dot(delta, delta);
        if (!SELECT_SPRINGS && dd <= 0.0) continue;
        bool on = dd > 0.0;
        float inv = on ? inversesqrt(dd) : 0.0;  // 1 / d
        float inv2 = inv * inv;
        // In delta rather than n: the spring's force k (d - L) n = k (1 - L / d) delta, the
        // dashpot's (b / h) n (n.e) = (b / h) delta (delta.e) / d^2 and the block
        // c n n^T = (c / d^2) delta delta^T (fewer products a spring). A spring that is off
        // reads the particle itself or has coincident ends: its delta is zero (SELECT_SPRINGS).
        float stretch = k - (k * rest_length(s)) * inv;
        float kt = on ? max(stretch, 0.0) : 0.0;
        force -= delta * (stretch + (damp * inv2) * dot(delta, dx - dj));
        vec3 cd = ((k + damp - kt) * inv2) * delta;
        iso += kt;
        diag += cd * delta;
        off += cd.xxy * delta.yzz;
    }
    hessian = Sym3(iso, diag, off);
    return force;
}

// The adjugate of a symmetric Sym3, as the rows (c00, c01, c02) and (c11, c12, c22); returns
// the determinant.
float sym3_adjugate(Sym3 m, out vec3 row0, out vec3 rest) {
    vec3 a = m.diag + m.iso;
    vec3 off = m.off;
    float c00 = a.y * a.z - off.z * off.z;
    float c01 = off.y * off.z - off.x * a.z;
    float c02 = off.x * off.z - off.y * a.y;
    float c11 = a.x * a.z - off.y * off.y;
    float c12 = off.x * off.y - a.x * off.z;
    float c22 = a.x * a.y - off.x * off.x;
    row0 = vec3(c00, c01, c02);
    rest = vec3(c11, c12, c22);
    return a.x * c00 + off.x * c01 + off.y * c02;
}

// The inverse of a symmetric positive definite Sym3 by its adjugate, as the rows (c00, c01,
// c02) and (c11, c12, c22) over the determinant.
void sym3_inverse(Sym3 m, out vec3 row0, out vec3 rest) {
    float inv_det = 1.0 / sym3_adjugate(m, row0, rest);
    row0 *= inv_det;
    rest *= inv_det;
}

// A symmetric matrix (the rows of sym3_inverse or sym3_adjugate) times v.
vec3 sym3_apply(vec3 row0, vec3 rest, vec3 v) {
    return vec3(dot(row0, v), dot(vec3(row0.y, rest.x, rest.y), v), dot(vec3(row0.z, rest.y, rest.z), v));
}

// VBD, one Gauss-Seidel visit: one Newton step on BDF2's incremental potential as a function
// of the particle's position (newton_particle), solved by the adjugate. Returns the new
// displacement.
vec3 vbd_particle(uvec2 cell, vec3 x, vec3 dx, vec3 dy) {
    Sym3 hessian;
    vec3 force = newton_particle(cell, x, dx, dy, hessian);
    vec3 row0;
    vec3 rest;
    float det = sym3_adjugate(hessian, row0, rest);
    return dx + sym3_apply(row0, rest, force) * (1.0 / det);  // (the adjugate's product, scaled once)
}

// The implicit method's conjugate gradients (sim::cpu::integrators::implicit): row i of the
// Hessian of BDF2's incremental potential, linearised at the iterate p, times the direction d.
// The particle at `cell` is at p_i with direction d_i; PP(j) gives neighbour j's p and DD(j)
// its direction (zero where pinned), defined by the includer. Each spring adds
// c n (n.e) + k t e, e = d_i - d_j (newton_particle's block).
#if defined(PP) && defined(DD)
vec3 hessian_product(uvec2 cell, vec3 pi, vec3 di) {
    float h = solve_dt();
    float damp = has(F_DAMPING) ? obj.stiffness.w / h : 0.0;
    vec3 q = di * (particle_mass(cell) / (h * h));
    if (is_mesh()) {
        // (a mesh cloth's list in batches, as newton_particle's)
        uint end = mesh_first(cell.x + 1u);
        for (uint f = mesh_first(cell.x); f < end; f += MESH_BATCH) {
            MeshSpring s[MESH_BATCH];
            vec3 pj[MESH_BATCH];
            vec3 dj[MESH_BATCH];
            [[unroll]] for (uint b = 0u; b < MESH_BATCH; ++b) s[b] = mesh_batch(f + b, end);
            [[unroll]] for (uint b = 0u; b < MESH_BATCH; ++b) {
                pj[b] = PP(s[b].other);
                dj[b] = DD(s[b].other);
            }
            [[unroll]] for (uint b = 0u; b < MESH_BATCH; ++b) {
                vec3 delta = pi - pj[b];
                float dd = dot(delta, delta);
                if (f + b >= end || dd <= 0.0) continue;
                float inv = inversesqrt(dd);
                float kt = max(s[b].k - (s[b].k * s[b].rest) * inv, 0.0);
                vec3 e = di - dj[b];
                q += delta * (((s[b].k + damp - kt) * (inv * inv)) * dot(delta, e)) + kt * e;
            }
        }
        return q;
    }
    int self_index = int(cell.x + cell.y * obj.dims.x);
    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        if (!has(1u << spring.z)) continue;  // (as newton_particle)
        float k = obj.stiffness[spring.z];
        int j = SELECT_SPRINGS ? SPRING_OTHER(cell, s) : SPRING_NEIGHBOUR(cell, s);
        if (!SELECT_SPRINGS && j < 0) continue;
        vec3 delta = pi - PP(j);
        float dd = dot(delta, delta);
        if (!SELECT_SPRINGS && dd <= 0.0) continue;
        bool on = dd > 0.0;
        float inv = on ? inversesqrt(dd) : 0.0;
        float kt = on ? max(k - (k * rest_length(s)) * inv, 0.0) : 0.0;
        vec3 e = di - DD(j);
        q += delta * (((k + damp - kt) * (inv * inv)) * dot(delta, e)) + kt * e;
    }
    return q;
}
#endif

// The implicit method's line search (sim::cpu::integrators::descent): particle i's share of
// G(p + a dp) - G(p) for each trial length a of LINE_SEARCH_STEPS, i at p_i with Newton step
// dp_i and r0dp = r0.dp_i (r0 = -g at p): its inertia's change and the first-order change
// -a r0.dp_i, then for each of its forward springs (each spring once) the exact change of its
// energy less its first-order part and its dashpot's, along the spring's direction at p. PP(j)
// gives neighbour j's p and DP(j) its step (zero where pinned). A pinned particle takes part
// (dp_i and r0dp zero) for its springs.
#if defined(PP) && defined(DP)
// Must equal sim::cpu::integrators::LINE_SEARCH_STEPS.
const vec4 LINE_SEARCH_STEPS = vec4(1.0, 0.5, 0.25, 0.125);

// One spring's part of newton_descent: stiffness k, rest length `rest`, p_i - p_j `delta`,
// dp_i - dp_j `e`, the dashpots' stiffness `damp` on the displacement.
vec4 spring_descent(float k, float rest, vec3 delta, vec3 e, float damp) {
    vec4 a = LINE_SEARCH_STEPS;
    float dd = dot(delta, delta);
    if (dd <= 0.0) return vec4(0.0);
    float inv = inversesqrt(dd);
    float d = dd * inv;
    float ne = dot(delta, e) * inv;
    float stretch = d - rest;
    // d' - d from d'^2 - d^2 = a e.(2 delta + a e): exact where a e is small against delta.
    vec4 grown = a * (2.0 * dot(delta, e)) + (a * a) * dot(e, e);
    // (d'^2 >= 0: rounding can take a nearly collapsed trial below it)
    vec4 moved = grown / (sqrt(max(dd + grown, vec4(0.0))) + d);
    return (0.5 * k) * moved * (moved + 2.0 * stretch) - a * (k * stretch * ne) + (0.5 * damp * ne * ne) * (a * a);
}

vec4 newton_descent(uvec2 cell, vec3 pi, vec3 dpi, float r0dp) {
    float h = solve_dt();
    float damp = has(F_DAMPING) ? obj.stiffness.w / h : 0.0;
    vec4 a = LINE_SEARCH_STEPS;
    vec4 change = -a * r0dp + ((0.5 * particle_mass(cell) / (h * h)) * dot(dpi, dpi)) * (a * a);
    if (is_mesh()) {
        // (a mesh cloth's list, each spring once: from its lower end)
        for (uint e = mesh_first(cell.x); e < mesh_first(cell.x + 1u); ++e) {
            MeshSpring s = mesh_spring(e);
            if (uint(s.other) < cell.x) continue;
            change += spring_descent(s.k, s.rest, pi - PP(s.other), dpi - DP(s.other), damp);
        }
        return change;
    }
    [[unroll]] for (int s = 0; s < 12; s += 2) {
        ivec3 spring = SPRINGS[s];
        if (!has(1u << spring.z)) continue;  // (as newton_particle)
        int j = SPRING_NEIGHBOUR(cell, s);
        if (j < 0) continue;
        change += spring_descent(obj.stiffness[spring.z], rest_length(s), pi - PP(j), dpi - DP(j), damp);
    }
    return change;
}

// The length the line search takes a Newton step at: the trial length whose total change
// (newton_descent summed over the object) is lowest, or 0 where none lowers G.
float line_search_step(vec4 change) {
    float best = min(min(change.x, change.y), min(change.z, change.w));
    if (!(best < 0.0)) return 0.0;
    return best == change.x ? LINE_SEARCH_STEPS.x : best == change.y ? LINE_SEARCH_STEPS.y
         : best == change.z ? LINE_SEARCH_STEPS.z : LINE_SEARCH_STEPS.w;
}
#endif

#endif
