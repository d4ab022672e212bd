#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Inter-object contact, 3 of 3, in three passes: 0 and 1 over the scene's particles (read from
// the hash's copies), 2 per object. Two kinds of contact, the reach
// being the two objects' contact radii added:
// - particle p of object A against triangle t of object B, a cloth (its triangles as the
//   renderer draws them): p nearer than the reach to t's nearest point (weights b), and t's
//   corner nearest to p (ties to the lower index) nearer than the reach plus B's corner reach
//   (which holds while t's edges are within TRIANGLE_STRETCH times their rest length); p
//   finds t through that corner. With n from
//   the nearest point to p and inverse masses w (0 pinned),
//   lambda = (reach - d) / (w_p + sum w_k b_k^2): p moves w_p lambda n, corner k
//   -w_k b_k lambda n, so the contact's momentum is unchanged. p computes all four moves;
// - particle against particle between two objects neither of which is a cloth (ropes): d the
//   distance between them, p moves (reach - d) w_p / (w_p + w_q) away from q (all of it when q
//   is pinned); q, finding p, the opposite.
// Every contact's moves are divided by the largest count of contacts among its free particles, the
// same for all of them (equal and opposite momenta; a particle in n contacts moves at most by
// the largest overlap). Pass 0 counts each particle's contacts (touches[], with atomics: a
// triangle's corners are counted by the particle that touches it) and notes the first
// PAIR_MAX of its own. Pass 1 sums the moves into moves[] in fixed point (integer atomics:
// exact and in any order), from the notes (searching again only for a particle with more).
// Pass 2 writes each particle's sum (xyz) and whether it touches anything (w) into its
// object's contact[]; the constraint stage adds it to its own correction. touches[] and
// moves[] are cleared by contact_count.comp. The CPU twin is sim::cpu::inter_object.
#include "layout.glsl"
#include "contact_common.glsl"
#include "triangle.glsl"

layout(local_size_x = 256) in;

uint object_count() { return uint(objects.length()) / OBJECT_ROWS; }
// Object q's friction coefficient (Coulomb's mu) with others.
float friction_of(uint q) { return objects[OBJECT_ROWS * q + 2u].x; }
float radius_of(uint q) { return objects[OBJECT_ROWS * q].z; }
float mass_of(uint q) { return objects[OBJECT_ROWS * q].w; }
// (columns, rows) of object q's grid; columns 0 when its triangles take no part.
uvec2 grid_of(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q + 1u].xy); }
// Whether object q's particles have anything to look for: another object's triangles, or
// (neither being a cloth) another object's particles.
bool looks(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q + 1u].z) != 0u; }

// The object a scene index belongs to (objects are few: a linear search).
uint owner(uint k) {
    uint o = 0u;
    for (uint q = 1u; q < object_count(); ++q) {
        if (k >= first_of(q)) o = q;
    }
    return o;
}

// Particles in the scene (the last object's first index and count).
uint scene_count() {
    vec4 last = objects[OBJECT_ROWS * (object_count() - 1u)];
    return floatBitsToUint(last.x) + floatBitsToUint(last.y);
}

// Scene particle k's hash entry: position, and its index with PINNED_BIT.
vec4 entry_of(uint k) { return particles[k]; }

float inverse_mass(vec4 e, uint q) { return (floatBitsToUint(e.w) & PINNED_BIT) != 0u ? 0.0 : 1.0 / mass_of(q); }

// How much farther than the reach a triangle's nearest corner may be from a particle touching
// it: half its rest diagonal stretched TRIANGLE_STRETCH times (ObjectModel::corner_reach).
float corner_reach(uint q) { return objects[OBJECT_ROWS * q + 1u].w; }

// Fixed-point units a metre of moves[] (2^28 a cell): a particle's sum stays within its
// largest overlap, under half a cell, far inside the 8 cells an int holds.
float move_fix() { return 268435456.0 * table.cell_inv; }

void add_move(uint k, vec3 v) {
    ivec3 q = ivec3(round(v * move_fix()));
    if (q.x != 0) atomicAdd(moves[4u * k], q.x);
    if (q.y != 0) atomicAdd(moves[4u * k + 1u], q.y);
    if (q.z != 0) atomicAdd(moves[4u * k + 2u], q.z);
}

// A particle's count of contacts for the split (at least 1), none when it is pinned (inverse
// mass w 0: it takes no share of any contact's correction, so its count would only dilute
// its partners' corrections, which friction must make whole within a substep).
uint count_of(uint k, float w) { return w > 0.0 ? max(touches[k], 1u) : 1u; }

// Two objects' friction coefficient with each other: the mean of theirs.
float pair_friction(uint a, uint b) { return 0.5 * (friction_of(a) + friction_of(b)); }

// Contacts a particle notes in pass 0 for pass 1 (pairs[], PAIR_MAX a particle, each the other
// particle's scene index << 3 | the ring index r of triangle (j, ring r, ring r + 1) of j's
// object (VERTEX_RING), or PAIR_NOTE for a particle pair); one with more searches the hash again. Its count
// of contacts as the particle (not as a corner) is moves[4 k + 3].
const uint PAIR_MAX = 8u;
const uint PAIR_NOTE = 7u;

// The scene index of vertex j's ring neighbour r in object q (j's grid position `at`), if any.
bool ring_vertex(uint q, ivec2 at, int r, out uint index) {
    uvec2 grid = grid_of(q);
    ivec2 c = at + VERTEX_RING[r];
    index = first_of(q) + uint(c.x) + uint(c.y) * grid.x;
    return c.x >= 0 && c.y >= 0 && c.x < int(grid.x) && c.y < int(grid.y);
}

ivec2 grid_position(uint q, uint j) {
    uint local = j - first_of(q);
    return ivec2(local % grid_of(q).x, local / grid_of(q).x);
}

// Pass 1: the moves of particle k (entry ek, object me) against triangle (j, a, b) of object q,
// the corners' entries ej, ea, eb, summed into moves[].
void triangle_moves(uint k, vec4 ek, uint me, uvec3 tv, vec4 ej, vec4 ea, vec4 eb, uint q) {
    float reach = radius_of(me) + radius_of(q);
    vec3 w = triangle_nearest(ek.xyz, ej.xyz, ea.xyz, eb.xyz);
    vec3 off = ek.xyz - (w.x * ej.xyz + w.y * ea.xyz + w.z * eb.xyz);
    float d = length(off);
    float wp = inverse_mass(ek, me);
    vec3 wk = vec3(inverse_mass(ej, q), inverse_mass(ea, q), inverse_mass(eb, q));
    float denom = wp + dot(wk, w * w);
    if (!(d > 0.0 && d < reach && denom > 0.0)) return;
    uint split = max(max(count_of(k, wp), count_of(tv.x, wk.x)), max(count_of(tv.y, wk.y), count_of(tv.z, wk.z)));
    vec3 n = off / d;
    // The relative motion over the substep, along the contact's tangent: undone whole within
    // the friction cone, else by mu times the normal correction (Coulomb).
    vec3 moved = (ek.xyz - begun[k].xyz)
               - (w.x * (ej.xyz - begun[tv.x].xyz) + w.y * (ea.xyz - begun[tv.y].xyz) + w.z * (eb.xyz - begun[tv.z].xyz));
    vec3 correction = n * (reach - d) - friction_correction(moved, n, reach - d, pair_friction(me, q));
    vec3 push = correction / (denom * float(split));
    add_move(k, wp * push);
    add_move(tv.x, -wk.x * w.x * push);
    add_move(tv.y, -wk.y * w.y * push);
    add_move(tv.z, -wk.z * w.z * push);
}

// Pass 1: particle k's move (entry ek, object me) in its pair with particle j (entry ej,
// object q) into `move`.
void pair_move(uint k, vec4 ek, uint me, uint j, vec4 ej, uint q, inout vec3 move) {
    float reach = radius_of(me) + radius_of(q);
    vec3 to_j = ej.xyz - ek.xyz;
    float d = length(to_j);
    if (!(d > 0.0 && d < reach)) return;
    bool j_pinned = (floatBitsToUint(ej.w) & PINNED_BIT) != 0u;
    float w = j_pinned ? 1.0 : mass_of(q) / (mass_of(me) + mass_of(q));
    float split = 1.0 / float(max(count_of(k, 1.0), count_of(j, j_pinned ? 0.0 : 1.0)));
    vec3 n = -to_j / d;
    vec3 moved = (ek.xyz - begun[k].xyz) - (ej.xyz - begun[j].xyz);
    vec3 correction = n * (reach - d) - friction_correction(moved, n, reach - d, pair_friction(me, q));
    move += correction * (w * split);
}

// Particle k (entry ek, object me) against the triangles of object q around its vertex j (entry
// ej, at squared distance dj) of which j is the corner nearest to k: pass 0 counts each contact
// into n, notes it and counts it into its corners' touches; pass 1 sums its moves.
void triangles_around(uint k, vec4 ek, uint me, uint j, vec4 ej, float dj, uint q, bool sum, inout uint n) {
    ivec2 at = grid_position(q, j);
    float reach = radius_of(me) + radius_of(q);
    vec4 ring[6];
    uint index[6];
    bool closer[6];  // whether j is nearer to k than the neighbour (false where there is none)
    [[unroll]] for (int r = 0; r < 6; ++r) {
        closer[r] = ring_vertex(q, at, r, index[r]);
        if (!closer[r]) continue;
        ring[r] = entry_of(index[r]);
        vec3 dr = ring[r].xyz - ek.xyz;
        closer[r] = nearer(dj, j, dot(dr, dr), index[r]);
    }
    [[unroll]] for (int r = 0; r < 6; ++r) {
        int s = r == 5 ? 0 : r + 1;
        if (!closer[r] || !closer[s]) continue;
        uvec3 tv = uvec3(j, index[r], index[s]);
        if (sum) {
            triangle_moves(k, ek, me, tv, ej, ring[r], ring[s], q);
            continue;
        }
        vec3 w = triangle_nearest(ek.xyz, ej.xyz, ring[r].xyz, ring[s].xyz);
        float d = length(ek.xyz - (w.x * ej.xyz + w.y * ring[r].xyz + w.z * ring[s].xyz));
        if (!(d > 0.0 && d < reach)) continue;
        if (n < PAIR_MAX) pairs[k * PAIR_MAX + n] = j << 3u | uint(r);
        n += 1u;
        atomicAdd(touches[tv.x], 1u);
        atomicAdd(touches[tv.y], 1u);
        atomicAdd(touches[tv.z], 1u);
    }
}

// Hash slots of another cloth's vertices near enough to lead to a contact, gathered by the
// search and tested after it (`test_candidates`): the threads of a subgroup then test their
// candidates side by side instead of one thread after another as each finds one.
const uint CANDIDATE_MAX = 32u;

// The hash entry at slot `at` for scene particle k (entry ek, object me): a vertex of another
// cloth near enough is kept as a candidate (the caller tests them when `candidates` is full);
// a particle of another object neither being a cloth is a pair: pass 0 counts it into n and
// notes it, pass 1 adds k's move to `move`.
void visit(uint at, vec4 ek, uint k, uint me, bool sum, inout uint n, inout vec3 move, inout uint candidates[CANDIDATE_MAX], inout uint found) {
    vec4 e = sorted[at];
    uint j = floatBitsToUint(e.w) & ~PINNED_BIT;
    uint other = owner(j);
    if (other == me) return;
    vec3 to_j = e.xyz - ek.xyz;
    float dj = dot(to_j, to_j);
    if (grid_of(other).x != 0u) {
        float r = radius_of(me) + radius_of(other) + corner_reach(other);
        if (dj < r * r) candidates[found++] = at;
    } else if (grid_of(me).x == 0u) {
        if (sum) {
            pair_move(k, ek, me, j, e, other, move);
            return;
        }
        float reach = radius_of(me) + radius_of(other);
        float d = sqrt(dj);
        if (d < reach && d > 0.0) {
            if (n < PAIR_MAX) pairs[k * PAIR_MAX + n] = j << 3u | PAIR_NOTE;
            n += 1u;
        }
    }
}

// The triangles around each candidate vertex (see `visit`).
void test_candidates(vec4 ek, uint k, uint me, bool sum, inout uint n, uint candidates[CANDIDATE_MAX], uint found) {
    for (uint c = 0u; c < found; ++c) {
        vec4 e = sorted[candidates[c]];
        uint j = floatBitsToUint(e.w) & ~PINNED_BIT;
        vec3 to_j = e.xyz - ek.xyz;
        triangles_around(k, ek, me, j, e, dot(to_j, to_j), owner(j), sum, n);
    }
}

// Pass 1: the moves of the contact particle k noted in pass 0.
void replay(uint note, vec4 ek, uint k, uint me, inout vec3 move) {
    uint j = note >> 3u;
    uint q = owner(j);
    vec4 ej = entry_of(j);
    if ((note & 7u) == PAIR_NOTE) {
        pair_move(k, ek, me, j, ej, q, move);
        return;
    }
    int r = int(note & 7u);
    int s = r == 5 ? 0 : r + 1;
    ivec2 at = grid_position(q, j);
    uvec3 tv = uvec3(j, 0u, 0u);
    ring_vertex(q, at, r, tv.y);
    ring_vertex(q, at, s, tv.z);
    triangle_moves(k, ek, me, tv, ej, entry_of(tv.y), entry_of(tv.z), q);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (which.pass == 2u) {
        if (i >= particle_count()) return;
        uint k = first_index() + i;
        vec3 sum = vec3(moves[4u * k], moves[4u * k + 1u], moves[4u * k + 2u]) / move_fix();
        contact[i] = vec4(sum, touches[k] > 0u ? 1.0 : 0.0);
        return;
    }
    if (i >= scene_count()) return;
    bool sum = which.pass == 1u;
    uint k = i;
    uint me = owner(k);
    if (!looks(me)) return;
    uint own = sum ? uint(moves[4u * k + 3u]) : 0u;
    if (sum && own == 0u) return;
    vec4 ek = entry_of(k);
    uint n = 0u;
    vec3 move = vec3(0.0);
    if (sum && own <= PAIR_MAX) {
        for (uint e = 0u; e < own; ++e) replay(pairs[k * PAIR_MAX + e], ek, k, me, move);
    } else {
        // Cells are sized so that everything a contact needs lies in the 2 x 2 x 2 block of
        // cells nearest to the particle (SimModel::contact_cell). Buckets visited once.
        ivec3 base = ivec3(floor(ek.xyz * table.cell_inv - 0.5));
        uint candidates[CANDIDATE_MAX];
        uint found = 0u;
        uint seen[8];
        for (int c = 0; c < 8; ++c) {
            uint h = cell_hash(base + ivec3(c & 1, (c >> 1) & 1, c >> 2), table.hash_mask);
            seen[c] = h;
            bool again = false;
            for (int q = 0; q < c; ++q) again = again || seen[q] == h;
            if (again) continue;
            uint end = BUCKET_START(h + 1u, table.hash_mask);
            for (uint at = BUCKET_START(h, table.hash_mask); at < end; ++at) {
                visit(at, ek, k, me, sum, n, move, candidates, found);
                if (found == CANDIDATE_MAX) {
                    test_candidates(ek, k, me, sum, n, candidates, found);
                    found = 0u;
                }
            }
        }
        test_candidates(ek, k, me, sum, n, candidates, found);
    }
    if (sum) {
        bool pinned = (floatBitsToUint(ek.w) & PINNED_BIT) != 0u;
        add_move(k, pinned ? vec3(0.0) : move);
    } else if (n > 0u) {
        atomicAdd(touches[k], n);
        moves[4u * k + 3u] = int(n);
    }
}
