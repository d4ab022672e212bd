// A cloth's contact with itself: particles against triangles, each contact's impulse applied
// equal and opposite. A cloth (a grid of at least 2 x 2) keeps each particle at least the
// self-collision distance h (its thickness) from its triangles, two a grid cell as the
// renderer draws them: triangle t = 2 a + k of the cell whose first corner is a is
// (a, a + cols, a + 1) for k = 0 and (a + 1, a + cols, a + cols + 1) for k = 1.
//
// A pair (particle p, triangle t) is left out when a vertex of t is p or one of its 8 grid
// neighbours (its own triangles and the next ring: folds sharper than a grid cell are left to
// the springs), or when t is nearer than h to p in the rest state (a thickness of two grid
// spacings or more). Any other pair nearer than h is a contact: with the barycentric weights b
// of t's point nearest to p and n the unit vector from there to p, the projection of the
// constraint n . (p - sum b_k x_k) >= h moves p by w_p lambda n and vertex k by
// -w_k b_k lambda n (w: 1 free, 0 pinned; one mass in a cloth), so the pair's momentum is
// unchanged. Of the overlap h - d, the part the substep's approach made (the relative motion
// of p and t's nearest point along -n since the substep began) is undone with the velocity
// that made it, and the rest, left from earlier substeps, in position only (the constraint
// stage's velocity follows the correction but for that part: a late-resolved overlap does not
// bounce). Coulomb friction (mu: the cloth's `friction`) adds to the normal correction the
// relative motion along the tangent, undone whole while within mu times the approach (the
// normal impulse), else that much of it (friction_correction, triangle.glsl), with the same
// weights, so it is equal and opposite too. Several contacts on a particle are combined by
// mass splitting (Tonge et al. 2012): each free particle takes part in each of its n
// contacts with 1 / n of its mass, so lambda = c (h - d) / (n_p w_p + sum n_k w_k b_k^2), and
// its moves are summed. Each contact is still equal and opposite, and one alone is resolved
// whole. The count n is smooth: a contact
// counts by its weight c, fully once its overlap reaches a tenth of h (count_weight), and n is
// at least 1, so a contact that just begins does not halve the others' shares at once; it
// takes part in lambda by the same weight, so a particle's contacts never add up to more than
// its largest overlap.
//
// The passes of a substep (per stage: self_pairs.comp, then the constraints; fused: phases
// between barriers):
// 1. find (self_pass, constraints_body.glsl): each particle, pinned too, notes where it began
//    the substep (the approach and friction read it) and finds its triangles within h through
//    the spatial hash (a triangle within h has its nearest vertex within self_reach(),
//    lists.glsl; it is tested once, from that vertex) or its contact list, which holds the
//    triangles within h plus the skin; it keeps up to PAIR_MAX contacts and counts each in its
//    free particles;
// 2. apply (self_pass): each particle computes its contacts again (those it kept; one that
//    found more searches again: once per stage, else for each further PAIR_MAX; see
//    SELF_APPLY_FOUND) and adds every particle's move to its sum, in fixed point (exact,
//    order-independent integer atomics);
// 2b. with obj.contact_iterations = K > 1, K - 1 times: each free particle's physics output
//    moves by its sum, the velocity following but for the position-only part (self_move), and
//    each particle applies the contacts it kept again from the moved positions (self_reapply;
//    a pair separated by then takes no part; a particle that found more than PAIR_MAX, none),
//    its counts as the find pass made them; only in a substep where some particle found a
//    contact (per stage an indirect dispatch, further_passes_word). A layer landing on several
//    others takes a share of each contact a pass (mass splitting), so one pass stops it only
//    over several substeps, deeper than the thickness;
// 3. the constraint stage adds its particle's sum to its correction whole and clears it
//    (self_take).
// The CPU twin is sim::cpu::self_contact. Buffer self_pairs (binding 17), n particles: words
// [4 i, 4 i + 4) particle i's sum (x, y, z in units of h / 2^26) and count (in units of
// 2^-16); 4 n + i the number of contacts it keeps; (5 + k) n + i its contact k's triangle;
// [(5 + PAIR_MAX) n + 3 i, + 3) where it began the substep; [(8 + PAIR_MAX) n + 3 i, + 3) the
// part of its sum that moves the position only (units as the sum); [(11 + PAIR_MAX) n, + 3)
// the further passes' indirect dispatch per stage (workgroups; zero in a substep where no
// particle found a contact: the find pass writes it, the constraint stage zeroes it).
// Include in constraints_body.glsl (CPOS, CPINNED defined).
#ifndef MSD_SELF_CONTACT_GLSL
#define MSD_SELF_CONTACT_GLSL
#include "lists.glsl"
#include "triangle.glsl"

// Contacts a particle keeps in a substep (sim::gpu::object::SELF_PAIR_MAX); one with more
// searches for them again in the apply pass.
const uint PAIR_MAX = 16u;
uint pairs_len_word(uint i) { return 4u * particle_count() + i; }
uint pair_word(uint k, uint i) { return (5u + k) * particle_count() + i; }
uint start_word(uint i) { return (5u + PAIR_MAX) * particle_count() + 3u * i; }
uint rest_word(uint i) { return (8u + PAIR_MAX) * particle_count() + 3u * i; }
uint further_passes_word() { return (11u + PAIR_MAX) * particle_count(); }
// Where particle i began the substep, as the find pass noted it.
vec3 pair_start(uint i) {
    uint w = start_word(i);
    return vec3(intBitsToFloat(self_pairs[w]), intBitsToFloat(self_pairs[w + 1u]), intBitsToFloat(self_pairs[w + 2u]));
}
void set_pair_start(uint i, vec3 x) {
    uint w = start_word(i);
    self_pairs[w] = floatBitsToInt(x.x);
    self_pairs[w + 1u] = floatBitsToInt(x.y);
    self_pairs[w + 2u] = floatBitsToInt(x.z);
}
// Fixed-point units a metre: the sum of a particle's moves stays within its largest overlap
// plus mu times it, far inside the 32 h an int holds.
float pair_fix() { return 67108864.0 / obj.self_distance; }

uvec3 triangle_vertices(uint t) {
    uint a = t >> 1u;
    uint cols = obj.dims.x;
    return (t & 1u) == 0u ? uvec3(a, a + cols, a + 1u) : uvec3(a + 1u, a + cols, a + cols + 1u);
}

// Whether grid vertex j is the particle at `cell` or one of its 8 neighbours.
bool in_one_ring(uvec2 cell, uint j) {
    ivec2 d = abs(ivec2(int(j % obj.dims.x), int(j / obj.dims.x)) - ivec2(cell));
    return max(d.x, d.y) <= 1;
}

// Whether triangle t is left out for the particle at `cell` (see the top): a vertex of t is in
// the particle's one-ring, or t is nearer than h to it at rest.
bool pair_left_out(uvec2 cell, uint t) {
    uvec3 tv = triangle_vertices(t);
    uint cols = obj.dims.x;
    ivec2 p = ivec2(cell);
    vec2 rest[3];
    [[unroll]] for (int k = 0; k < 3; ++k) {
        ivec2 q = ivec2(int(tv[k] % cols), int(tv[k] / cols));
        ivec2 d = abs(q - p);
        if (max(d.x, d.y) <= 1) return true;
        rest[k] = vec2(q - p) * obj.spacing;
    }
    // A triangle with no vertex in the one-ring is nearer than h at rest only for a thickness
    // of about two grid spacings or more.
    if (obj.self_distance < 1.99 * min(obj.spacing.x, obj.spacing.y)) return false;
    vec3 w = triangle_nearest(vec3(0.0), vec3(rest[0], 0.0), vec3(rest[1], 0.0), vec3(rest[2], 0.0));
    vec2 q = w.x * rest[0] + w.y * rest[1] + w.z * rest[2];
    return dot(q, q) < obj.self_distance * obj.self_distance;
}

// x against triangle (a, b, c): the weights w of its nearest point, the unit vector n from
// there to x, and the distance. One function wherever a contact is found or applied, so that
// every search computes the same distance.
float triangle_distance(vec3 x, vec3 a, vec3 b, vec3 c, out vec3 w, out vec3 n) {
    w = triangle_nearest(x, a, b, c);
    vec3 off = x - (w.x * a + w.y * b + w.z * c);
    float d = length(off);
    n = off / d;
    return d;
}

// Particle p at x against triangle t: its vertices tv, then as triangle_distance.
float pair_distance(vec3 x, uint t, out uvec3 tv, out vec3 w, out vec3 n) {
    tv = triangle_vertices(t);
    return triangle_distance(x, CPOS(tv.x), CPOS(tv.y), CPOS(tv.z), w, n);
}

// The particle whose contacts the search collects (at pair_x), how many it finds, and
// whether it is the apply pass's search again (apply_pass: a particle with more than
// PAIR_MAX), which counts nothing.
uint pair_particle;
vec3 pair_x;
uint pair_len;
bool apply_pass = false;
// In the apply pass's search, the contacts before pair_skip were applied already: the next
// PAIR_MAX are noted in the particle's slots.
uint pair_skip = 0u;

// A contact's weight in its particles' counts, in units of 2^-16 (sim::cpu::self_contact's
// `count_weight`): 1 once the overlap reaches a tenth of h, less before, so that a contact
// that begins changes the others' shares gradually.
int count_weight(float overlap) { return int(round(65536.0 * min(1.0, overlap / (0.1 * obj.self_distance)))); }
// A free particle's count of contacts (at least 1).
float split_count(uint i) { return max(1.0, float(self_pairs[4u * i + 3u]) * (1.0 / 65536.0)); }

// SELF_APPLY_FOUND (defined by the includer: whether this is the apply pass): the apply
// pass's search again (a particle with more than PAIR_MAX contacts) notes the next PAIR_MAX in
// the slots, to be applied after it together (the threads of a group in step), and applies
// each contact past those as it finds it, so that one search more serves any number of
// contacts. Per stage, where the apply pass is a pipeline of its own (self_pairs.comp), it
// does; in the fused kernel, whose two passes share one search, the application compiled into
// it would make every search heavier, so there each further PAIR_MAX contacts are noted and
// applied after a search of their own.
#ifdef SELF_APPLY_FOUND
void apply_contact(uint p, vec3 x, uint t);
#endif

// Contact (pair_particle, t; overlap h - d), the pair_len-th found: noted in the particle's
// slots when among the PAIR_MAX from pair_skip on (past those applied, SELF_APPLY_FOUND), and
// in the find pass counted in its free particles (the apply pass applies what the slots hold).
void keep_pair(uint t, uvec3 tv, float d) {
    bool free_p = !CPINNED(pair_particle);
    bvec3 free_t = bvec3(!CPINNED(tv.x), !CPINNED(tv.y), !CPINNED(tv.z));
    if (!(free_p || any(free_t))) return;
#ifdef SELF_APPLY_FOUND
    if (SELF_APPLY_FOUND && apply_pass && pair_len >= pair_skip + PAIR_MAX) {
        apply_contact(pair_particle, pair_x, t);
        pair_len += 1u;
        return;
    }
#endif
    uint slot = pair_len - pair_skip;
    if (pair_len >= pair_skip && slot < PAIR_MAX) self_pairs[pair_word(slot, pair_particle)] = int(t);
    pair_len += 1u;
    if (apply_pass) return;
    int weight = count_weight(obj.self_distance - d);
    if (free_p) atomicAdd(self_pairs[4u * pair_particle + 3u], weight);
    [[unroll]] for (int k = 0; k < 3; ++k) {
        if (free_t[k]) atomicAdd(self_pairs[4u * tv[k] + 3u], weight);
    }
}

// Keeps (pair_particle; triangle t, not left out, at distance d) when it is a contact.
void test_contact(uint t, uvec3 tv, float d) {
    if (d < obj.self_distance && d > 0.0) keep_pair(t, tv, d);
}

// A contact list's triangle t (not left out) for the particle at x.
void test_pair(vec3 x, uint t) {
    uvec3 tv;
    vec3 w;
    vec3 n;
    float d = pair_distance(x, t, tv, w, n);
    test_contact(t, tv, d);
}

// The find pass's visit of candidate vertex j (outside the one-ring of the particle at `cell`,
// at x): each triangle around j whose vertex nearest x is j (so each triangle is visited once)
// and that is not left out is kept when a contact and, while the contact lists are built
// (`list_reach`: h plus the skin, otherwise 0), recorded in the particle's list when nearer
// than that. The ring's positions are read once, and only for vertices outside the particle's
// one-ring (a triangle with a vertex inside is left out before anything is read).
void self_triangles(uvec2 cell, vec3 x, uint j, float list_reach) {
    ivec2 dims = ivec2(obj.dims);
    ivec2 at = ivec2(int(j % obj.dims.x), int(j / obj.dims.x));
    vec3 xj = CPOS(j);
    vec3 dj = x - xj;
    float d2j = dot(dj, dj);
    bool usable[6];
    uint ring[6];
    vec3 at_ring[6];
    float d2[6];
    [[unroll]] for (int r = 0; r < 6; ++r) {
        ivec2 q = at + VERTEX_RING[r];
        ivec2 off = abs(q - ivec2(cell));
        usable[r] = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, dims)) && max(off.x, off.y) > 1;
        ring[r] = usable[r] ? uint(q.x + q.y * dims.x) : j;
        at_ring[r] = CPOS(ring[r]);
        vec3 e = x - at_ring[r];
        d2[r] = usable[r] ? dot(e, e) : 0.0;
    }
    bool thick = obj.self_distance >= 1.99 * min(obj.spacing.x, obj.spacing.y);
    // A triangle farther than this is neither a contact nor a list entry. (The box test and
    // the exact one round differently, so a contact within a rounding error of h may be kept by
    // a search with the lists' reach and culled by one without; its weight is then about 1e-5.
    // A margin of 0.1% here cost the 1024 x 1024 cloth 5% on the H100, so there is none.)
    float farthest = max(obj.self_distance, list_reach);
    [[unroll]] for (int k = 0; k < 6; ++k) {
        int k1 = (k + 1) % 6;
        if (!usable[k] || !usable[k1] || nearer(d2[k], ring[k], d2j, j) || nearer(d2[k1], ring[k1], d2j, j)) continue;
        // Its bounding box grown by that distance must hold x (the nearest point lies in it),
        // a test cheaper than the exact one.
        vec3 lo = min(xj, min(at_ring[k], at_ring[k1])) - farthest;
        vec3 hi = max(xj, max(at_ring[k], at_ring[k1])) + farthest;
        if (any(lessThan(x, lo)) || any(greaterThan(x, hi))) continue;
        ivec2 a = at + VERTEX_TRIANGLES[k].xy;
        uint t = 2u * uint(a.x + a.y * dims.x) + uint(VERTEX_TRIANGLES[k].z);
        if (thick && pair_left_out(cell, t)) continue;
        // The exact test from the positions read above, the vertices in the triangle's own
        // order (triangle_vertices), as pair_distance computes it.
        uvec3 tv = triangle_vertices(t);
        vec3 p[3];
        [[unroll]] for (int c = 0; c < 3; ++c) p[c] = tv[c] == j ? xj : tv[c] == ring[k] ? at_ring[k] : at_ring[k1];
        vec3 w;
        vec3 n;
        float d = triangle_distance(x, p[0], p[1], p[2], w, n);
        test_contact(t, tv, d);
        if (d < list_reach) {
            if (list_len < LIST_ENTRIES) self_list[list_entry(list_len, list_particle, particle_count())] = t;
            list_len += 1u;  // past LIST_ENTRIES the list is full: it is rebuilt the next substep
        }
    }
}

// Adds `move` to particle i's fixed-point sum, and `rest`, the part of it that moves the
// position only, to that sum.
void add_move(uint i, vec3 move, vec3 rest) {
    ivec3 q = ivec3(round(move * pair_fix()));
    if (q.x != 0) atomicAdd(self_pairs[4u * i], q.x);
    if (q.y != 0) atomicAdd(self_pairs[4u * i + 1u], q.y);
    if (q.z != 0) atomicAdd(self_pairs[4u * i + 2u], q.z);
    ivec3 r = ivec3(round(rest * pair_fix()));
    uint w = rest_word(i);
    if (r.x != 0) atomicAdd(self_pairs[w], r.x);
    if (r.y != 0) atomicAdd(self_pairs[w + 1u], r.y);
    if (r.z != 0) atomicAdd(self_pairs[w + 2u], r.z);
}

// Contact (p at x, t), computed again from the same positions as when it was found: moves its
// free particles (see the top).
void apply_contact(uint p, vec3 x, uint t) {
    uvec3 tv;
    vec3 w;
    vec3 n;
    float d = pair_distance(x, t, tv, w, n);
    // (A further pass: the pair may have parted, or, moved, lost its normal.)
    if (!(d > 0.0 && d < obj.self_distance)) return;
    float w_p = CPINNED(p) ? 0.0 : 1.0;
    vec3 free_t = vec3(CPINNED(tv.x) ? 0.0 : 1.0, CPINNED(tv.y) ? 0.0 : 1.0, CPINNED(tv.z) ? 0.0 : 1.0);
    // Each free particle's mass split among its contacts: inverse mass w n, n its count.
    vec3 split_t = vec3(0.0);
    [[unroll]] for (int q = 0; q < 3; ++q) {
        if (free_t[q] > 0.0) split_t[q] = split_count(tv[q]);
    }
    float split_p = w_p > 0.0 ? split_count(p) : 0.0;
    float overlap = max(obj.self_distance - d, 0.0);
    // A contact takes part by its weight in the counts: one that begins (overlap under h / 10)
    // moves its particles by that fraction of its share, so that the counts' smoothing never
    // lets a particle's contacts add up to more than its largest overlap.
    float weight = min(1.0, overlap / (0.1 * obj.self_distance));
    // The relative motion of p and t's nearest point over the substep: the overlap it made
    // (its approach along n) is undone with the velocity that made it; what overlap remains
    // from before is undone in position only (no bounce from an overlap resolved late).
    vec3 moved = (x - pair_start(p))
               - (w.x * (CPOS(tv.x) - pair_start(tv.x)) + w.y * (CPOS(tv.y) - pair_start(tv.y))
                  + w.z * (CPOS(tv.z) - pair_start(tv.z)));
    float approach = clamp(-dot(moved, n), 0.0, overlap);
    // Coulomb: the tangential slip undone within mu times the normal impulse (the approach).
    vec3 correction = n * overlap - friction_correction(moved, n, approach, obj.friction);
    float k = weight / (split_p + dot(w * w, split_t));
    vec3 push = correction * k;
    vec3 rest = n * ((overlap - approach) * k);
    if (w_p > 0.0) add_move(p, push, rest);
    [[unroll]] for (int q = 0; q < 3; ++q) {
        if (free_t[q] > 0.0) add_move(tv[q], push * -w[q], rest * -w[q]);
    }
}

// Another pass over particle i's (at x) contacts of the substep, from the positions the
// passes before moved. A particle that found more than PAIR_MAX takes part in the first pass
// only: it keeps only some of them, which ones depends on the search's order, and a search
// from the moved positions would find others.
void self_reapply(uint i, vec3 x) {
    uint found = uint(self_pairs[pairs_len_word(i)]);
    if (found > PAIR_MAX) return;
    for (uint k = 0u; k < found; ++k) apply_contact(i, x, uint(self_pairs[pair_word(k, i)]));
}

// Particle i's summed moves of the last pass (and in `rest` the part of them that moves the
// position only), cleared for the next; `last`: the substep's last pass, which clears the
// particle's count of contacts too (the constraint stage's share; the passes before move
// the physics output by theirs, see self_move).
vec3 self_take(uint i, out vec3 rest, bool last) {
    ivec3 q = ivec3(self_pairs[4u * i], self_pairs[4u * i + 1u], self_pairs[4u * i + 2u]);
    uint w = rest_word(i);
    rest = vec3(ivec3(self_pairs[w], self_pairs[w + 1u], self_pairs[w + 2u])) * (1.0 / pair_fix());
    self_pairs[4u * i] = 0;
    self_pairs[4u * i + 1u] = 0;
    self_pairs[4u * i + 2u] = 0;
    if (last) self_pairs[4u * i + 3u] = 0;
    self_pairs[w] = 0;
    self_pairs[w + 1u] = 0;
    self_pairs[w + 2u] = 0;
    return vec3(q) * (1.0 / pair_fix());
}

// Between two passes (contact_iterations > 1): free particle i's physics output (x, v) moved
// by the last pass's sums, the velocity following but for the position-only part.
void self_move(uint i, inout vec3 x, inout vec3 v) {
    vec3 rest;
    vec3 move = self_take(i, rest, false);
    x += move;
    v += (move - rest) / g.dt;
}

#endif
