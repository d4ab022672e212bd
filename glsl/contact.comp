#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Inter-object contact, 3 of 3, in three passes: 0 and 1 over the scene's particles (read from
// the scene's entries; a particle in several lanes, `lanes_of`), 2 per object. Every contact
// is a particle p of object A against a piece of object B's surface, the reach being the two
// objects' contact radii added:
// - a triangle t of B, a cloth (its triangles as the renderer draws them): p nearer than the
//   reach to t's nearest point (weights b), and t's corner nearest to p (ties to the lower
//   index) nearer than the reach plus B's corner reach (which holds while t's edges are within
//   TRIANGLE_STRETCH times their rest length); p finds t through that corner;
// - when A is a rope (a chain of capsules, its nodes in index order; a lone node a segment of
//   one point), a segment of A against an edge of B (a rope's segment, or a cloth's row,
//   column or diagonal, or a cloth's vertex as an edge of no length: the nearest points of
//   their axes, weights 1 - s, s and 1 - t, t), found once by the lower end of A's segment
//   through the lower end of B's edge (an index rule: no rounding decides who finds it), those
//   two ends within the reach plus both segments' lengths stretched TRIANGLE_STRETCH times
//   (twice the corner reaches); between two ropes only from the one of lower index;
// - when A and B are cloths that keep their edges apart (`sim.inter_object_edges`, or either
//   has self_contact "triangles_and_edges"), an edge of A against an edge of B (rows, columns
//   and diagonals: their nearest points, weights as above), taking part by edge_fade (fully where
//   the nearest points lie inside both edges, fading to nothing at an end, where the
//   vertex-triangle contacts hold), found from the cloth of lower index by the end of A's edge
//   of the two edges' nearest ends (of the four pairs of ends, one of each edge, the nearest;
//   as a cloth's self-contact does), those within the reach plus both corner reaches.
// With n from the nearest point to p (turned back to the side where the pair began the substep
// where it crossed within it: `gap_of`), inverse masses w (0 pinned) and each particle's count of
// contacts n_k (mass splitting, Tonge et al. 2012: a particle in several contacts takes each as
// if its mass were shared among them, so that it moves about its largest overlap, and a light
// particle in many contacts, a rope's node under a cloth, does not hold back its partners'
// corrections), lambda = (reach - gap) / (n_p w_p + sum n_k w_k b_k^2): p moves w_p lambda n,
// corner k -w_k b_k lambda n, so the contact's momentum is unchanged (a segment pair likewise,
// with A's ends in p's place). The particle that finds a contact computes all its moves.
// Pass 0 counts each particle's contacts (touches[], with atomics: a piece's corners are
// counted by the particle that touches it). In a substep that rebuilds the lists
// (contact_common.glsl) it searches the hash for them and lists the pieces within the reach
// plus the skin, each by the rules above (so each is in one list), the first PAIR_MAX of them
// (in the order its lanes find them); a longer list is marked overflowed, so the next substep
// rebuilds. Otherwise it walks the particle's list. Pass 1 sums the moves into moves[] in
// fixed point (integer atomics: exact and in any order) from the list (searching the hash
// again for a particle whose list overflowed). Pass 2 writes each particle's sum (xyz) and
// whether it touches anything (w) into its object's contact[]; the constraint stage adds it
// to its own correction. touches[] and moves[] are cleared by contact_begin.comp. The CPU twin
// is sim::cpu::inter_object.
#define BATCHED
#include "layout.glsl"
#include "contact_common.glsl"
#include "triangle.glsl"

layout(local_size_x = 256) in;

uint object_count() { return uint(objects.length()) / OBJECT_ROWS; }
// Object q's friction coefficient (Coulomb's mu) with others.
float friction_of(uint q) { return objects[OBJECT_ROWS * q + 2u].x; }
float radius_of(uint q) { return objects[OBJECT_ROWS * q].z; }
float mass_of(uint q) { return objects[OBJECT_ROWS * q].w; }
uint count_in(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q].y); }
// (columns, rows) of object q's grid; columns 0 when it touches by its segments (a rope).
uvec2 grid_of(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q + 1u].xy); }
bool is_cloth(uint q) { return grid_of(q).x != 0u; }

// The object a scene index belongs to: the last whose first index is at most k (the objects'
// first indices rise with the object), by bisection, since every hash entry a search visits
// asks (a pile of many small objects visits thousands).
uint owner(uint k) {
    uint lo = 0u;
    uint hi = object_count();
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1u;
        if (k >= first_of(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// Passes 0 and 1 run over work items: object q's particles from item work_first(q) on, each
// particle's search and notes split among lanes_of(q) items (a rope's few nodes search large
// blocks of cells, and a cloth's particle tests dozens of candidates' edges where cloths keep
// their edges apart: spread over lanes, their hash entries and candidates are taken side by
// side; otherwise a cloth's particle searches alone; an object whose particles look for
// nothing has none).
// The cloths' items come first, in a dispatch of this shader with SEGMENTS off, then the
// ropes' with it on (ObjectModel::contact_lanes, SceneContact::record).
uint work_first(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q + 2u].y); }
uint lanes_of(uint q) { return floatBitsToUint(objects[OBJECT_ROWS * q + 2u].z); }
// The object whose items hold item i (one of them: the caller checks), 0 if none.
uint work_owner(uint i) {
    uint o = 0u;
    for (uint q = 0u; q < object_count(); ++q) {
        if (i >= work_first(q) && i - work_first(q) < count_in(q) * lanes_of(q)) o = q;
    }
    return o;
}

// Whether this pipeline runs ropes' items (their segments against other objects' edges); off,
// the segment code is compiled out of the cloths' dispatch.
layout(constant_id = 0) const bool SEGMENTS = true;
// Whether the cloths' dispatch keeps cloths' edges from each other's (some cloth keeps its
// edges from edges); off, that code is compiled out.
layout(constant_id = 1) const bool CLOTH_EDGES = false;
// Whether a particle's search may be split among lanes: a rope's node, and a cloth's particle
// where cloths keep their edges apart (it tests dozens of candidates' edges against its own);
// then lanes count and list with atomics.
const bool LANED = SEGMENTS || CLOTH_EDGES;

// Whether cloths a and b keep their edges from each other's: either keeps its edges from every
// other cloth's (SimModel::keeps_cloth_edges_apart).
bool cloth_edges(uint a, uint b) {
    return CLOTH_EDGES && is_cloth(a) && is_cloth(b) && (objects[OBJECT_ROWS * a + 1u].z != 0.0 || objects[OBJECT_ROWS * b + 1u].z != 0.0);
}

// Scene particle k's hash entry: position, and its index with PINNED_BIT.
vec4 entry_of(uint k) { return particles[k]; }

float inverse_mass(vec4 e, uint q) { return (floatBitsToUint(e.w) & PINNED_BIT) != 0u ? 0.0 : 1.0 / mass_of(q); }

// How much farther than the reach a piece's nearest corner may be from a particle touching it:
// half a triangle's rest diagonal or a segment's rest length stretched TRIANGLE_STRETCH times
// (ObjectModel::corner_reach).
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

// A particle's count of contacts for the mass splitting (at least 1; a pinned particle's, of
// inverse mass 0, takes no part).
uint count_of(uint k, float w) { return w > 0.0 ? max(touches[k], 1u) : 1u; }

// The gap of a contact at distance d (within the reach) between its nearest points, whose
// offset is `off` now and `began` at the substep's start (the same weights on the positions in
// begun[]): negative where the two sides crossed within the substep, so that the pair is pushed
// back to the side it began on, not on through the piece (sim::cpu::inter_object::gap). Only
// a contact reads begun[] for it: whether a pair touches is its distance's alone, so a pair
// that crossed deeper than the reach is not one.
float gap_of(vec3 off, float d, vec3 began) { return dot(off, began) < 0.0 ? -d : d; }

// Two objects' friction coefficient with each other: the mean of theirs.
float pair_friction(uint a, uint b) { return 0.5 * (friction_of(a) + friction_of(b)); }

// A particle's list (pairs[], PAIR_MAX a particle, its length in built[4 k + 3]), each entry
// the piece's corner j (scene index; the nearest when listed) << NOTE_SHIFT | the ring index
// r of triangle (j, ring r, ring r + 1) of a cloth (VERTEX_RING), or for a pair of edges
// NOTE_PAIR | j's edge (a rope's SEGMENT_NEXT, the ring index of a cloth's edge (j, ring r), or
// CLOTH_POINT), or between two cloths NOTE_PAIR | 6 ra + rb (k's edge to its ring vertex ra,
// j's to rb). Its count of contacts as the particle (not as a corner) is moves[4 k + 3].
// (Scene indices below 2^25.)
layout(constant_id = 2) const uint PAIR_MAX = 64u;  // sim::gpu::contact::pair_max
const uint NOTE_SHIFT = 7u;
const uint NOTE_PAIR = 64u;
const uint SEGMENT_NEXT = 0u;
const uint SEGMENT_PREVIOUS = 1u;

// Pass 0 of a substep that rebuilds: lists a piece particle k found. A particle's lanes take
// slots in turn (built[4 k + 3] counts them); a particle searching alone counts in `listed`
// and writes its length at the end (cheaper than an atomic an entry, which measurably slowed
// the cloths' search: docs/log.md).
uint listed = 0u;
void list_piece(uint k, uint note) {
    uint slot = LANED ? atomicAdd(built[4u * k + 3u], 1u) : listed;
    listed += 1u;
    if (slot < PAIR_MAX) pairs[k * PAIR_MAX + slot] = note;
}

// Whether pass 0 lists a piece at distance d (`touching`: a contact now) of the reach plus the
// skin: with the lists on, every piece within it (its part in a pair of edges, which motion
// changes, aside); off, the contacts alone, which pass 1 replays.
bool listed_if(bool touching, float d, float reach) {
    return lists_on() ? d < reach + list_skin() : touching;
}

// Pass 0: a contact of particle k with the piece whose corners (or ends) other than k are
// `corners` (repeats of k or of one another counted once, as x, y, z, w in order) counted into
// n and into those corners' touches.
void count_contact(uvec3 corners, uint k, inout uint n) {
    n += 1u;
    if (corners.x != k) atomicAdd(touches[corners.x], 1u);
    atomicAdd(touches[corners.y], 1u);
    if (corners.z != corners.y) atomicAdd(touches[corners.z], 1u);
}

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

// The offset of particle k from the point of triangle tv of weights w where they began the
// substep.
vec3 triangle_began(uint k, uvec3 tv, vec3 w) {
    return begun[k].xyz - (w.x * begun[tv.x].xyz + w.y * begun[tv.y].xyz + w.z * begun[tv.z].xyz);
}

// The offset between the nearest points of a pair of edges (ends sv, weights w, the second
// edge's negative) where they began the substep.
vec3 pair_began(uvec4 sv, vec4 w) {
    return w.x * begun[sv.x].xyz + w.y * begun[sv.y].xyz + w.z * begun[sv.z].xyz + w.w * begun[sv.w].xyz;
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
    vec3 nk = vec3(count_of(tv.x, wk.x), count_of(tv.y, wk.y), count_of(tv.z, wk.z));
    float denom = float(count_of(k, wp)) * wp + dot(nk * wk, w * w);
    if (!(d > 0.0 && d < reach && denom > 0.0)) return;
    vec3 began = triangle_began(k, tv, w);
    float gap = gap_of(off, d, began);
    vec3 n = off * (gap / (d * d));
    // The relative motion over the substep, along the contact's tangent: undone whole within
    // the friction cone, else by mu times the normal correction (Coulomb).
    vec3 moved = off - began;
    vec3 correction = n * (reach - gap) - friction_correction(moved, n, reach - gap, pair_friction(me, q));
    vec3 push = correction / denom;
    add_move(k, wp * push);
    add_move(tv.x, -wk.x * w.x * push);
    add_move(tv.y, -wk.y * w.y * push);
    add_move(tv.z, -wk.z * w.z * push);
}

// Segment r (SEGMENT_NEXT, SEGMENT_PREVIOUS) of rope q at its node j: its other end, or j for
// a lone node; false where there is none.
bool segment_end(uint q, uint j, uint r, out uint other) {
    uint first = first_of(q);
    uint count = count_in(q);
    other = j;
    if (r > SEGMENT_PREVIOUS) return false;
    if (count == 1u) return r == SEGMENT_NEXT;
    if (r == SEGMENT_NEXT) {
        other = j + 1u;
        return j + 1u < first + count;
    }
    other = j - 1u;
    return j > first;
}

// Edge r of object q at its particle j: a rope's segment r, or a cloth's edge to ring vertex r
// (0 to 5) or, r = CLOTH_POINT, the vertex itself (an edge of no length); its other end, false
// where there is none.
const uint CLOTH_POINT = 6u;
bool edge_end(uint q, uint j, uint r, out uint other) {
    if (grid_of(q).x == 0u) return segment_end(q, j, r, other);
    other = j;
    return r == CLOTH_POINT || ring_vertex(q, grid_position(q, j), int(r), other);
}

// The nearest points of the pair of object me's edge (ends e[0], e[1]) and object q's (e[2],
// e[3]), and how much it takes part: a rope's segment against an edge as capsules, in full; two
// cloths' edges as segments, by edge_fade.
vec2 pair_nearest(vec4 e[4], uint me, out float part) {
    part = 1.0;
    if (!is_cloth(me)) return capsule_nearest(e[0].xyz, e[1].xyz, e[2].xyz, e[3].xyz);
    vec2 st = segment_nearest(e[0].xyz, e[1].xyz, e[2].xyz, e[3].xyz);
    part = edge_fade(st);
    return st;
}

// Pass 1: the moves of the pair of object me's edge sv.xy (a rope's segment, or a cloth's edge)
// and object q's edge sv.zw, their ends' entries e, summed into moves[].
void segment_pair_moves(uvec4 sv, vec4 e[4], uint me, uint q) {
    float reach = radius_of(me) + radius_of(q);
    float part;
    vec2 st = pair_nearest(e, me, part);
    vec4 w = vec4(1.0 - st.x, st.x, -(1.0 - st.y), -st.y);  // B's ends negative
    vec3 off = w.x * e[0].xyz + w.y * e[1].xyz + w.z * e[2].xyz + w.w * e[3].xyz;
    float d = length(off);
    vec4 wk = vec4(inverse_mass(e[0], me), inverse_mass(e[1], me), inverse_mass(e[2], q), inverse_mass(e[3], q));
    vec4 nk = vec4(count_of(sv.x, wk.x), count_of(sv.y, wk.y), count_of(sv.z, wk.z), count_of(sv.w, wk.w));
    float denom = dot(nk * wk, w * w);
    if (!(d > 0.0 && d < reach && denom > 0.0 && part > 0.0)) return;
    vec3 began = pair_began(sv, w);
    float gap = gap_of(off, d, began);
    vec3 n = off * (gap / (d * d));
    vec3 moved = off - began;
    vec3 correction = n * (reach - gap) - friction_correction(moved, n, reach - gap, pair_friction(me, q));
    vec3 push = part * correction / denom;
    add_move(sv.x, wk.x * w.x * push);
    if (sv.y != sv.x) add_move(sv.y, wk.y * w.y * push);
    add_move(sv.z, wk.z * w.z * push);
    if (sv.w != sv.z) add_move(sv.w, wk.w * w.w * push);
}

// Rope me's node k (entry ek) against object q's particle j (entry ej): k's segment (k, k + 1)
// (a lone node's: the node) against j's edges that lead to higher indices, each pair found
// once by the lower ends of both (a rope's segment (j, j + 1); a cloth's edges to its ring
// vertices 0 to 2, right, down and the cell's diagonal, and its vertex itself); pass 0 counts
// each contact into n, notes it and counts it into its ends' touches, pass 1 sums its moves.
void edge_pairs_around(uint k, vec4 ek, uint me, uint j, vec4 ej, uint q, bool sum, inout uint n) {
    float reach = radius_of(me) + radius_of(q);
    uint ko;
    if (!segment_end(me, k, SEGMENT_NEXT, ko)) return;
    vec4 eko = entry_of(ko);
    bool cloth = grid_of(q).x != 0u;
    [[dont_unroll]] for (uint rb = 0u; rb <= CLOTH_POINT; ++rb) {
        uint jo;
        if ((cloth ? rb > 2u && rb < CLOTH_POINT : rb != SEGMENT_NEXT) || !edge_end(q, j, rb, jo)) continue;
        uvec4 sv = uvec4(k, ko, j, jo);
        vec4 e[4] = vec4[4](ek, eko, ej, entry_of(jo));
        if (sum) {
            segment_pair_moves(sv, e, me, q);
            continue;
        }
        vec2 st = capsule_nearest(e[0].xyz, e[1].xyz, e[2].xyz, e[3].xyz);
        vec3 off = (1.0 - st.x) * e[0].xyz + st.x * e[1].xyz - (1.0 - st.y) * e[2].xyz - st.y * e[3].xyz;
        float d = length(off);
        bool touching = d > 0.0 && d < reach;
        if (!listed_if(touching, d, reach)) continue;
        list_piece(k, j << NOTE_SHIFT | NOTE_PAIR | rb);
        if (touching) count_contact(uvec3(ko, j, jo), k, n);
    }
}
// Cloth me's particle k (entry ek) against cloth q's particle j (entry ej, at squared
// distance dj): each pair of k's edge (k, ko) and j's edge (j, jo) whose nearest ends are (k,
// j) (of the four pairs of ends, one of each edge, the nearest: `ends_in_order` in steps of
// 1/1000 of the squared reach, keyed (me's end, q's end)), so that each
// pair of edges is found once; pass 0 counts each contact into n, notes it and counts it into
// its ends' touches, pass 1 sums its moves. Nearest ends (k, j) of edges whose nearest points
// are within the reach are within the reach plus half of each edge's length (the candidate's
// bound in `visit`: each half within the object's corner reach).
void cloth_edge_pairs_around(uint k, vec4 ek, uint me, uint j, vec4 ej, float dj, uint q, bool sum, inout uint n) {
    float reach = radius_of(me) + radius_of(q);
    float step = 1000.0 / (reach * reach);
    ivec2 at_k = grid_position(me, k);
    ivec2 at_j = grid_position(q, j);
    [[dont_unroll]] for (uint ra = 0u; ra < 6u; ++ra) {
        uint ko;
        if (!ring_vertex(me, at_k, int(ra), ko)) continue;
        vec4 eko = entry_of(ko);
        vec3 okj = eko.xyz - ej.xyz;
        if (ends_in_order(dot(okj, okj), uvec2(ko, j), dj, uvec2(k, j), step)) continue;
        float half_a = 0.5 * distance(ek.xyz, eko.xyz);
        [[dont_unroll]] for (uint rb = 0u; rb < 6u; ++rb) {
            uint jo;
            if (!ring_vertex(q, at_j, int(rb), jo)) continue;
            vec4 ejo = entry_of(jo);
            float bound = reach + list_skin() + half_a + 0.5 * distance(ej.xyz, ejo.xyz);
            vec3 kjo = ek.xyz - ejo.xyz;
            vec3 kojo = eko.xyz - ejo.xyz;
            if (dj >= bound * bound || ends_in_order(dot(kjo, kjo), uvec2(k, jo), dj, uvec2(k, j), step)
                || ends_in_order(dot(kojo, kojo), uvec2(ko, jo), dj, uvec2(k, j), step)) continue;
            uvec4 sv = uvec4(k, ko, j, jo);
            vec4 e[4] = vec4[4](ek, eko, ej, ejo);
            if (sum) {
                segment_pair_moves(sv, e, me, q);
                continue;
            }
            float part;
            vec2 st = pair_nearest(e, me, part);
            vec3 off = (1.0 - st.x) * ek.xyz + st.x * eko.xyz - (1.0 - st.y) * ej.xyz - st.y * ejo.xyz;
            float d = length(off);
            bool touching = d > 0.0 && d < reach && part > 0.0;
            if (!listed_if(touching, d, reach)) continue;
            list_piece(k, j << NOTE_SHIFT | NOTE_PAIR | (6u * ra + rb));
            if (touching) count_contact(uvec3(ko, j, jo), k, n);
        }
    }
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
        bool touching = d > 0.0 && d < reach;
        if (!listed_if(touching, d, reach)) continue;
        list_piece(k, j << NOTE_SHIFT | uint(r));
        if (touching) count_contact(tv, k, n);
    }
}

// The scene's particle count (`star_box`'s offsets), set when main starts.
uint scene = 0u;
// How much more than the reach plus the skin the boxes' test allows, relative: far above a
// float's rounding of the distances the pieces' tests compute.
const float BOX_SLACK = 1e-3;

// Hash slots of other objects' particles near enough to lead to a contact, gathered by the
// search and tested after it (`test_candidates`): the threads of a subgroup then test their
// candidates side by side instead of one thread after another as each finds one.
const uint CANDIDATE_MAX = 32u;

// Whether the hash entry at slot `at` is a candidate for the particle at ek (its object me): a
// particle of another object near enough to be the nearest corner of a piece in contact
// (or, between two ropes, the lower end of a segment; between two cloths that keep their edges
// apart, the other nearest end of a pair of edges). The caller keeps it (not passed in:
// GLSL copies an inout array in and out of every call, which cost the cloths' search a
// quarter on the H100).
// A cloth's particle also skips a candidate whose star box (`star_box`) is farther than the
// reach plus the skin from it along some axis, or from its own star box where their edges
// meet: no piece it would test could be listed. The test is exact, so it finds what the sphere
// alone finds, but in a pile the sphere holds most of the pile and the boxes a few layers
// (docs/design/contact.md).
bool visit(uint at, vec4 ek, uint me, vec3 lo, vec3 hi) {
    vec4 e = sorted[at];
    uint j = floatBitsToUint(e.w) & ~PINNED_BIT;
    uint other = owner(j);
    if (other == me) return false;
    vec3 to_j = e.xyz - ek.xyz;
    float dj = dot(to_j, to_j);
    float reach = radius_of(me) + radius_of(other) + list_skin();
    bool rope = SEGMENTS && !is_cloth(me);  // (its segments against the other's edges too)
    if (is_cloth(other)) {
        // (a pair of edges is found through their lower ends: each within a stretched length)
        // (between cloths, through their nearest ends: each within half a stretched length)
        float r = reach + (rope ? 2.0 * (corner_reach(me) + corner_reach(other)) : corner_reach(other));
        bool edges = cloth_edges(me, other) && me < other;
        if (edges) r += corner_reach(me);
        if (!(dj < r * r)) return false;
        if (rope) return true;
        vec3 lo_j, hi_j;
        star_box(j, scene, lo_j, hi_j);
        // (a rounding's worth more than the reach: the narrow tests round too)
        float slack = reach * (1.0 + BOX_SLACK);
        vec3 a = edges ? lo : ek.xyz;
        vec3 b = edges ? hi : ek.xyz;
        return all(lessThanEqual(lo_j - slack, b)) && all(greaterThanEqual(hi_j + slack, a));
    }
    // (between two ropes, found from the one of lower index)
    float r = reach + 2.0 * (corner_reach(me) + corner_reach(other));
    return rope && other > me && dj < r * r;
}

// Particle k against the pieces of object q at its particle j (entry ej, at squared distance
// dj) of which j is the corner nearest to k: a cloth's triangles (j within the reach plus q's
// corner reach); and when k is a rope's node, its segments against q's edges (a cloth's
// vertices among them), or between cloths that keep their edges apart, from the one of lower
// index, k's edges against j's whose nearest ends are k and j.
void pieces_around(uint k, vec4 ek, uint me, uint j, vec4 ej, float dj, uint q, bool sum, inout uint n) {
    float sight = radius_of(me) + radius_of(q) + list_skin() + corner_reach(q);
    if (is_cloth(q) && dj < sight * sight) triangles_around(k, ek, me, j, ej, dj, q, sum, n);
    if (SEGMENTS && !is_cloth(me)) edge_pairs_around(k, ek, me, j, ej, q, sum, n);
    if (cloth_edges(me, q) && me < q) cloth_edge_pairs_around(k, ek, me, j, ej, dj, q, sum, n);
}

// The pieces around each candidate particle (see `visit`).
void test_candidates(vec4 ek, uint k, uint me, bool sum, inout uint n, uint candidates[CANDIDATE_MAX], uint found) {
    for (uint c = 0u; c < found; ++c) {
        vec4 e = sorted[candidates[c]];
        uint j = floatBitsToUint(e.w) & ~PINNED_BIT;
        vec3 to_j = e.xyz - ek.xyz;
        pieces_around(k, ek, me, j, e, dot(to_j, to_j), owner(j), sum, n);
    }
}

// The piece of list entry `note` of particle k (entry ek, object me): pass 0 counts it into n
// where it is a contact, pass 1 (`sum`) sums its moves.
void replay(uint note, vec4 ek, uint k, uint me, bool sum, inout uint n) {
    uint j = note >> NOTE_SHIFT;
    uint q = owner(j);
    vec4 ej = entry_of(j);
    uint r = note & (NOTE_PAIR - 1u);
    float reach = radius_of(me) + radius_of(q);
    if ((SEGMENTS || CLOTH_EDGES) && (note & NOTE_PAIR) != 0u) {
        bool cloths = is_cloth(me);
        uint ko, jo;
        edge_end(me, k, cloths ? r / 6u : SEGMENT_NEXT, ko);
        edge_end(q, j, cloths ? r % 6u : r, jo);
        uvec4 sv = uvec4(k, ko, j, jo);
        vec4 e[4] = vec4[4](ek, entry_of(ko), ej, entry_of(jo));
        if (sum) {
            segment_pair_moves(sv, e, me, q);
            return;
        }
        float part;
        vec2 st = pair_nearest(e, me, part);
        float d = length((1.0 - st.x) * e[0].xyz + st.x * e[1].xyz - (1.0 - st.y) * e[2].xyz - st.y * e[3].xyz);
        if (d > 0.0 && d < reach && part > 0.0) count_contact(uvec3(ko, j, jo), k, n);
        return;
    }
    int s = r == 5u ? 0 : int(r) + 1;
    ivec2 at = grid_position(q, j);
    uvec3 tv = uvec3(j, 0u, 0u);
    ring_vertex(q, at, int(r), tv.y);
    ring_vertex(q, at, s, tv.z);
    vec4 ea = entry_of(tv.y);
    vec4 eb = entry_of(tv.z);
    if (sum) {
        triangle_moves(k, ek, me, tv, ej, ea, eb, q);
        return;
    }
    vec3 w = triangle_nearest(ek.xyz, ej.xyz, ea.xyz, eb.xyz);
    float d = length(ek.xyz - (w.x * ej.xyz + w.y * ea.xyz + w.z * eb.xyz));
    if (d > 0.0 && d < reach) count_contact(tv, k, n);
}

// Searches the hash around particle k (entry ek, object me) for the pieces near it: pass 0
// lists them and counts the contacts into n, pass 1 (`sum`) sums the contacts' moves. Cells
// are sized so that everything within the reach plus the skin lies in the 2 x 2 x 2 block of
// cells nearest to the particle (SimModel::contact_cell). Buckets visited once; a rope node's
// split among its lanes.
void search(vec4 ek, uint k, uint me, uint lane, uint lanes, bool sum, inout uint n) {
    ivec3 base = ivec3(floor(ek.xyz * hash_cell_inv() - 0.5));
    vec3 lo, hi;
    star_box(k, scene, lo, hi);
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
        for (uint at = BUCKET_START(h, table.hash_mask) + lane; at < end; at += lanes) {
            if (visit(at, ek, me, lo, hi)) candidates[found++] = at;
            if (found == CANDIDATE_MAX) {
                test_candidates(ek, k, me, sum, n, candidates, found);
                found = 0u;
            }
        }
    }
    test_candidates(ek, k, me, sum, n, candidates, found);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint pass = pass_of();
    // (passes 0 and 1 run over the scene as layer 0)
    if (!batch_begin(which.batch_mask)) return;
    if (pass == 2u) {
        // (the next substep's control block starts at zero)
        if (this_object() == 0u && i < CONTROL_WORDS) control[CONTROL_WORDS - control_block() + i] = 0u;
        if (this_object() == 0u && i == 0u && lists_on()) control[CONTROL_COUNTERS] += 1u;
        if (i >= particle_count()) return;
        uint k = first_index() + i;
        vec3 sum = vec3(moves[4u * k], moves[4u * k + 1u], moves[4u * k + 2u]) / move_fix();
        contact[i] = vec4(sum, touches[k] > 0u ? 1.0 : 0.0);
        return;
    }
    bool sum = pass == 1u;
    scene = scene_particles();
    // Work item i: lane `lane` of particle k of object me (see `lanes_of`).
    i += which.work_first;
    uint me = work_owner(i);
    uint lanes = LANED ? lanes_of(me) : 1u;
    uint local = i - work_first(me);
    if (i >= which.work_end || local >= count_in(me) * lanes) return;
    uint k = first_of(me) + local / lanes;
    uint lane = local % lanes;
    bool rebuild = rebuilds();
    uint len = built[4u * k + 3u];
    bool overflowed = rebuild && len > PAIR_MAX;
    if (sum && overflowed && lane == 0u) set_list_built(k, false, vec3(0.0));
    uint own = sum ? uint(moves[4u * k + 3u]) : 0u;
    if (sum && own == 0u) return;
    vec4 ek = entry_of(k);
    uint n = 0u;
    if (rebuild && (!sum || overflowed)) {
        search(ek, k, me, lane, lanes, sum, n);
    } else {
        for (uint e = lane; e < len; e += lanes) replay(pairs[k * PAIR_MAX + e], ek, k, me, sum, n);
    }
    if (sum) return;
    if (rebuild && !LANED) built[4u * k + 3u] = listed;
    if (n > 0u) {
        atomicAdd(touches[k], n);
        if (LANED) {
            atomicAdd(moves[4u * k + 3u], int(n));
        } else {
            moves[4u * k + 3u] = int(n);
        }
    }
}
