// A cloth's contact with itself: particles against triangles and edges against edges, each
// contact's impulse applied equal and opposite. A cloth (a grid of at least 2 x 2) keeps each
// particle at least the self-collision distance h (its thickness) from its triangles, two a
// grid cell as the renderer draws them: triangle t = 2 a + k of the cell whose first corner is
// a is (a, a + cols, a + 1) for k = 0 and (a + 1, a + cols, a + cols + 1) for k = 1; and, with
// edge contact (F_EDGE_PAIRS: self_contact = "triangles_and_edges"; compiled out otherwise),
// each of those triangles' edges (rows, columns, the cells' diagonals) h from the others where
// their nearest points lie inside both (two layers crossing edge over edge, which no vertex
// of either touches: a pile of layers slips through there otherwise). A rope with
// self-collision (F_SEGMENT_PAIRS, with F_TRIANGLES and F_EDGE_PAIRS) is one row of edges and
// no triangles: its segments, capsules of thickness h, are kept apart by the edge pairs alone
// (rope_segments), which count there wherever their nearest points lie (edge_pair_part; a
// node's two segments against one segment are two contacts, which the mass splitting shares).
// A mesh cloth (F_CLOTH_MESH) keeps its particles from the triangles of its lists
// (mesh_springs.glsl; a triangle's number is its index there), leaving out those a vertex of the
// particle's one-ring touches (mesh_self_triangles); it has no edge pairs.
//
// A pair (particle p, triangle t) is left out when a vertex of t is p or one of its 8 grid
// neighbours (its own triangles and the next ring: folds sharper than a grid cell are left to the
// springs), or when t is nearer than h to p in the rest state (a thickness of two grid spacings or
// more); a pair of edges when they share a vertex or are nearer than 1.33 h at rest
// (EDGE_REST_MARGIN; a rope's segments 1.5 h, SEGMENT_REST_MARGIN), and also when the nearest point of either is an end (that end's contact
// with the triangles around the other edge holds it): so edges of a fold sharper than a cell keep
// apart too, which the measured piles needed. Any other pair nearer than h is a contact. Write its
// offset, from side b's nearest point to side a's, as sum c_k x_k over its particles: for (p, t), c
// = 1 for p and -b_k for t's vertex k, b the barycentric weights of t's point nearest p; for edges
// (p, a) and (j, b) with nearest points at p + s (a - p) and j + u (b - j), c = (1 - s, s, u - 1,
// -u). With n the unit offset, the projection of the constraint n . sum c_k x_k >= h moves particle
// k by w_k c_k lambda n (w: its inverse mass over the object's mass, 0 pinned, 1 free on a grid;
// m_k w_k is the object's mass for every free particle), so the pair's momentum is unchanged.
// Of the overlap h - d, the part the substep's approach made (the relative motion of the
// two nearest points along -n since the substep began) is undone with the velocity that made it,
// and the rest, left from earlier substeps, in position only (the constraint stage's velocity
// follows the correction but for that part: a late-resolved overlap does not bounce). Coulomb
// friction (mu: the cloth's `friction`) adds to the normal correction the relative motion along the
// tangent, undone whole while within mu times the normal impulse the contact applies (its share
// of the approach), else that much of it (friction_correction, triangle.glsl), with the same
// weights, so it is equal and opposite too (its share: apply_contact).
// Several contacts on a particle are combined by mass splitting (Tonge et al. 2012): each free
// particle takes part in each of its n contacts with 1 / n of its mass, so lambda = c (h - d) / sum
// n_k w_k c_k^2, and its moves are summed; with edge contact that share is over-relaxed by
// pair_relaxation() but never past what the contact alone would take, c (h - d) / sum w_k c_k^2
// (without, relaxation 1 never reaches that bound). Each contact is still equal
// and opposite, and one alone is resolved whole. The count n is smooth: a contact counts by its
// weight c, fully once its overlap reaches a tenth of h (contact_weight), and n is at least 1, so a
// contact that just begins does not halve the others' shares at once; it takes part in lambda by
// the same weight, so a particle's contacts never add up to more than its largest overlap.
//
// An edge pair belongs to the lower-indexed particle p of its nearest ends (p, j) (the two ends,
// one of each edge, nearest each other; ties by index), which finds it from candidate j of its
// search (ends_before, self_edges; the search visits the one-ring for these too): a pair whose
// nearest points are within h has its nearest ends within the search's reach while the grid's
// diagonals are stretched by less than about a third (sqrt((0.75 diagonal)^2 2 + h^2) against h +
// 0.75 diagonal); past that it may be missed.
//
// The passes of a substep (per stage: self_pairs.comp, then the constraints; fused: phases
// between barriers):
// 1. find (self_pass, constraints_body.glsl): each particle, pinned too, notes where it began
//    the substep (the approach and friction read it) and finds its triangles and edge pairs
//    within h through the spatial hash (a triangle within h has its nearest vertex within
//    self_reach(), lists.glsl; it is tested once, from that vertex) or its contact list, which
//    holds the triangles and edge pairs within h plus the skin; it keeps up to PAIR_MAX
//    contacts and counts each in its free particles;
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
//    (self_take);
// 4. with a cloth's edge pairs, after the constraint stage: each particle's pairs near at the
//    substep's start noted and each move truncated (TRUNCATION_GAP below).
// The CPU twin is sim::cpu::self_contact; the buffer's layout is in self_pairs_layout.glsl.
// Include in constraints_body.glsl (CPOS, CPINNED defined).
#ifndef MSD_SELF_CONTACT_GLSL
#define MSD_SELF_CONTACT_GLSL
#include "lists.glsl"
#include "creases.glsl"

// Whether this pipeline's cloth keeps its edges from its edges too (its own specialization:
// without it none of the edge-pair code is compiled in).
bool edge_contact() { return has(F_EDGE_PAIRS); }

// Whether those edges are a cloth's (creased, each particle's move truncated), not a rope's
// segments (sim::model::ObjectModel::has_cloth_edge_pairs).
bool cloth_edge_pairs() { return edge_contact() && !has(F_SEGMENT_PAIRS); }

// Where particle i began the substep, as the find pass noted it.
vec3 pair_start(uint i) { return start_position(i); }
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
    if (is_mesh()) return mesh_triangle(t);
    uint a = t >> 1u;
    uint cols = obj.dims.x;
    return (t & 1u) == 0u ? uvec3(a, a + cols, a + 1u) : uvec3(a + 1u, a + cols, a + cols + 1u);
}

// A contact's code in a particle's slots and contact list: a triangle's number t (under
// 2^29), or for an edge pair EDGE_PAIR, the particle's own edge k1 (to its ring vertex k1,
// VERTEX_RING) in bits 28 to 30, and the other edge, particle j's to its ring vertex k2, as
// 6 j + k2 below (under 2^28 for any cloth whose self_pairs buffer, 112 bytes a particle with
// edge contact, a device can bind: at most 2^32 bytes, 38.3 million particles).
const uint EDGE_PAIR = 0x80000000u;
uint edge_pair_code(uint k1, uint j, uint k2) { return EDGE_PAIR | (k1 << 28u) | (6u * j + k2); }
bool is_edge_pair(uint code) { return edge_contact() && (code & EDGE_PAIR) != 0u; }
// Grid vertex v's ring vertex k (one in the grid: only such are coded).
uint ring_vertex(uint v, uint k) {
    ivec2 q = ivec2(int(v % obj.dims.x), int(v / obj.dims.x)) + VERTEX_RING[k];
    return uint(q.x + q.y * int(obj.dims.x));
}

// The number of triangle k around the grid vertex at `at` (VERTEX_TRIANGLES).
uint vertex_triangle(ivec2 at, int k) {
    ivec2 a = at + VERTEX_TRIANGLES[k].xy;
    return 2u * uint(a.x + a.y * int(obj.dims.x)) + uint(VERTEX_TRIANGLES[k].z);
}

// Whether grid vertex j is `cell` or one of its 8 grid neighbours.
bool in_one_ring(uvec2 cell, uint j) {
    ivec2 d = abs(ivec2(int(j % obj.dims.x), int(j / obj.dims.x)) - ivec2(cell));
    return max(d.x, d.y) <= 1;
}

// Whether triangle t is nearer than h at rest to the particle at `cell` (possible only for a
// thickness of 0.7 grid spacings or more: a cell's diagonal and the vertex next to it are
// sx sy / |s| apart; past the one-ring, two spacings).
bool near_at_rest(uvec2 cell, uint t) {
    if (obj.self_distance < 0.7 * min(obj.spacing.x, obj.spacing.y)) return false;
    uvec3 tv = triangle_vertices(t);
    uint cols = obj.dims.x;
    vec3 rest[3];
    [[unroll]] for (int k = 0; k < 3; ++k) {
        ivec2 q = ivec2(int(tv[k] % cols), int(tv[k] / cols));
        rest[k] = vec3(vec2(q - ivec2(cell)) * obj.spacing, 0.0);
    }
    vec3 w = triangle_nearest(vec3(0.0), rest[0], rest[1], rest[2]);
    vec3 q = w.x * rest[0] + w.y * rest[1] + w.z * rest[2];
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

// Edge (x, xa) against edge (xj, xb): the parameters st of their nearest points and the
// offset from the second's to the first's. One function wherever an edge pair is found or
// applied.
vec3 edge_offset(vec3 x, vec3 xa, vec3 xj, vec3 xb, out vec2 st) {
    st = segment_nearest(x, xa, xj, xb);
    return mix(x, xa, st.x) - mix(xj, xb, st.y);
}

// (An edge pair fades near its edges' ends, edge_fade in triangle.glsl; a rope's segment
// pairs do not, edge_pair_part.)

// The sag of grid vertex u's edge to its ring vertex k (in the grid): its triangles are those
// of ring vertices k - 1 and k + 1.
float edge_sag(uint u, uint k) {
    ivec2 q = ivec2(int(u % obj.dims.x), int(u / obj.dims.x));
    ivec2 q1 = q + VERTEX_RING[(k + 5u) % 6u];
    ivec2 q2 = q + VERTEX_RING[(k + 1u) % 6u];
    if (!in_grid(q1) || !in_grid(q2)) return 1e30;
    uint cols = obj.dims.x;
    return crease_sag(CPOS(u), CPOS(ring_vertex(u, k)), CPOS(uint(q1.x + q1.y * int(cols))), CPOS(uint(q2.x + q2.y * int(cols))));
}
// Edge pair `code` of particle p: the larger of its edges' crease weights.
float pair_crease(uint p, uint code) {
    uint e2 = code & 0x0FFFFFFFu;
    return max(crease_weight(edge_sag(p, (code >> 28u) & 7u)), crease_weight(edge_sag(e2 / 6u, e2 % 6u)));
}
// How much edge pair `code` of particle p, its nearest points at st along its edges, takes
// part: its fade times its crease weight.
float edge_pair_part(uint p, uint code, vec2 st) {
    return has(F_SEGMENT_PAIRS) ? 1.0 : edge_fade(st) * pair_crease(p, code);
}
// ... for contact `code` of particle p of weights c (pair_geometry): 1 for a triangle.
float pair_part(uint p, uint code, vec4 c) { return is_edge_pair(code) ? edge_pair_part(p, code, vec2(c.y, -c.w)) : 1.0; }
// Particle j's (at xj) ring crease masks (creases.glsl): as the spatial hash's build wrote
// them for the positions it was built from (the truncation's, the starts), or by brute force
// computed here.
uint ring_creases(uint j, vec3 xj) {
    return self_hashed() ? uint(self_pairs[creases_word(j)]) : ring_crease_masks(j, xj);
}
// The ring creases of the particle whose contacts the search collects (set by self_pass).
uint own_creases;

// Contact `code` of particle p: its particles, p first (see pair_geometry).
uvec4 pair_members(uint p, uint code) {
    if (!is_edge_pair(code)) return uvec4(p, triangle_vertices(code));
    uint e2 = code & 0x0FFFFFFFu;
    uint j = e2 / 6u;
    return uvec4(p, ring_vertex(p, (code >> 28u) & 7u), j, ring_vertex(j, e2 % 6u));
}

// A contact's offset from side b's nearest point to side a's with its particles at x0 to x3,
// and its signed weights c (see pair_geometry).
vec3 pair_offset(bool edges, vec3 x0, vec3 x1, vec3 x2, vec3 x3, out vec4 c) {
    if (edges) {
        vec2 st;
        vec3 off = edge_offset(x0, x1, x2, x3, st);
        c = vec4(1.0 - st.x, st.x, st.y - 1.0, -st.y);
        return off;
    }
    vec3 w = triangle_nearest(x0, x1, x2, x3);
    c = vec4(1.0, -w);
    return x0 - (w.x * x1 + w.y * x2 + w.z * x3);
}

// Contact `code` of particle p at x: its particles m (p first) and signed weights c, so that
// sum c_k x_k is the offset from side b's nearest point to side a's (a triangle: m = (p, its
// vertices), c = (1, -w), w the weights of its point nearest p; an edge pair: m = (p, a, j,
// b), c = (1 - s, s, t - 1, -t)), the unit normal n along it; returns its length, as the find
// pass computed it.
float pair_geometry(uint p, vec3 x, uint code, out uvec4 m, out vec4 c, out vec3 n) {
    m = pair_members(p, code);
    vec3 off = pair_offset(is_edge_pair(code), x, CPOS(m.y), CPOS(m.z), CPOS(m.w), c);
    float d = length(off);
    n = off / d;
    return d;
}

// The particle whose contacts the search collects (at pair_x), how many it finds, and
// whether it is the apply pass's search again (apply_pass: a particle with more than
// PAIR_MAX), which counts nothing.
uint pair_particle;
vec3 pair_x;
uint pair_len;
bool apply_pass = false;
// The search runs for the truncation (note_truncation): it notes the pairs within h it finds
// and keeps no contact.
bool noting = false;
// How near a pair the search records: in the contact list while the lists are built, the
// lists' reach; in the truncation, h; else none.
float recorded_within() { return list_build ? list_within() : noting ? obj.self_distance : 0.0; }
// In the apply pass's search, the contacts before pair_skip were applied already: the next
// PAIR_MAX are noted in the particle's slots.
uint pair_skip = 0u;
// The lane of a search and the lanes it is split among, which take the hash's entries (in the
// truncation's note pass, by brute force the particles) side by side: per stage, a cloth with
// edge pairs (a wrung or piled cloth's particle has hundreds of candidates, each with up to 36
// edge pairs, and a cloth of a few thousand particles fills a fraction of the GPU); else one.
// Split, the apply pass's search applies every contact as it finds it (apply_found;
// constraints_body.glsl's self_pass).
uint search_lane = 0u;
uint search_lanes = 1u;
bool apply_found = false;

// A contact's weight in its particles' counts (sim::cpu::self_contact's `count_weight`): 1
// once the overlap reaches a tenth of h, less before, so that a contact that begins changes
// the others' shares gradually; an edge pair's times its edge_fade.
float contact_weight(float overlap) { return min(1.0, overlap / (0.1 * obj.self_distance)); }
// A free particle's count of contacts, each by its weight (the mass splitting takes at least 1).
float pair_count(uint i) { return float(self_pairs[4u * i + 3u]) * (1.0 / 65536.0); }

// SELF_APPLY_FOUND (defined by the includer: whether this is the apply pass): the apply
// pass's search again (a particle with more than PAIR_MAX contacts) notes the next PAIR_MAX in
// the slots, to be applied after it together (the threads of a group in step), and applies
// each contact past those as it finds it, so that one search more serves any number of
// contacts. Per stage, where the apply pass is a pipeline of its own (self_pairs.comp), it
// does; in the fused kernel, whose two passes share one search, the application compiled into
// it would make every search heavier, so there each further PAIR_MAX contacts are noted and
// applied after a search of their own.
#ifdef SELF_APPLY_FOUND
void apply_contact(uint p, vec3 x, uint code);
#endif

// Contact `code` of pair_particle (its particles m, overlap h - d), the pair_len-th found
// (split among lanes, numbered by the particle's counter): noted in the particle's slots when
// among the PAIR_MAX from pair_skip on (past those applied, SELF_APPLY_FOUND, and every one
// with apply_found), and in the find pass counted in its free particles (the apply pass
// applies what the slots hold).
void keep_pair(uint code, uvec4 m, float d, float fade) {
    bvec4 free_m = bvec4(!CPINNED(m.x), !CPINNED(m.y), !CPINNED(m.z), !CPINNED(m.w));
    if (!any(free_m)) return;
#ifdef SELF_APPLY_FOUND
    if (SELF_APPLY_FOUND && (apply_found || apply_pass && pair_len >= pair_skip + PAIR_MAX)) {
        apply_contact(pair_particle, pair_x, code);
        pair_len += 1u;
        return;
    }
#endif
    // (split among lanes: numbered by the particle's counter)
    uint index = search_lanes > 1u ? uint(atomicAdd(self_pairs[pairs_len_word(pair_particle)], 1)) : pair_len;
    uint slot = index - pair_skip;
    if (index >= pair_skip && slot < PAIR_MAX) self_pairs[pair_word(slot, pair_particle)] = int(code);
    pair_len += 1u;
    if (apply_pass) return;
    int weight = int(round(65536.0 * contact_weight(obj.self_distance - d) * fade));
    [[unroll]] for (int k = 0; k < 4; ++k) {
        if (free_m[k]) atomicAdd(self_pairs[4u * m[k] + 3u], weight);
    }
}

// Keeps contact `code` of pair_particle (not left out; its particles m, at distance d, taking
// part by `fade`) when it is one.
void test_contact(uint code, uvec4 m, float d, float fade) {
    if (d < obj.self_distance && d > 0.0 && fade > 0.0 && !noting) keep_pair(code, m, d, fade);
}

// Records the find pass's pair `code` (its particles m) in the particle's contact list, or
// in the truncation's search (`noting`) notes it there (note_start_pair).
void note_start_pair(uvec4 m, bool edges);
void list_record(uint code, uvec4 m) {
    if (noting) {
        note_start_pair(m, is_edge_pair(code));
        return;
    }
    if (list_len < LIST_ENTRIES) self_list[list_entry(list_len, list_particle, particle_count())] = code;
    list_len += 1u;  // past LIST_ENTRIES the list is full: it is rebuilt the next substep
}

// A contact list's entry `code` (not left out) for the particle at x: a triangle, or an edge
// pair whose nearest points lie inside both edges.
void test_pair(vec3 x, uint code) {
    uvec4 m;
    vec4 c;
    vec3 n;
    float d = pair_geometry(pair_particle, x, code, m, c, n);
    test_contact(code, m, d, pair_part(pair_particle, code, c));
}

// Whether the pair of ends (a0, a1) at squared distance da comes before (b0, b1) at db: the
// nearer, distances compared in steps of h^2 / 1000 and ties broken by the ends' indices, so
// that of an edge pair's four pairs of ends exactly one comes first (the pair's nearest ends;
// a total order). A regular fold has many pairs of ends equally far apart: compared exactly,
// their rounding, which the fused and per-stage kernels and the CPU twin do differently, would
// pick the owner (and so which contacts take part in the further passes); in steps it seldom
// can. Twin: sim::cpu::self_contact::ends_before.
bool ends_before(float da, uint a0, uint a1, float db, uint b0, uint b1) {
    float step = 1000.0 / (obj.self_distance * obj.self_distance);
    return ends_in_order(da, uvec2(min(a0, a1), max(a0, a1)), db, uvec2(min(b0, b1), max(b0, b1)), step);
}

// A cloth's edge pairs nearer than this many times h at rest are left out (sim::cpu::
// self_contact's EDGE_REST_MARGIN): those a compression of less than a quarter of their rest
// gap (1 - 1 / 1.33) would bring within h. A cloth whose thickness nears the gap between a
// cell's diagonal and the vertex next to it (0.707 spacings) would otherwise hold those apart
// wherever it is compressed a little, every particle in contact everywhere (the towel, 0.65
// spacings thick, took 120 s a frame on lavapipe). At the default thickness, half a spacing,
// those pairs (1.41 h apart) are kept: a pile's folds sharper than a cell bring a diagonal
// through the next cell's edges there (a strip piling on itself let 2 to 46 edges through its
// triangles with them left out, at 1.5, and 0 to 25 with them kept; docs/ACCURACY.md).
const float EDGE_REST_MARGIN = 1.33;

// A rope's segment pairs nearer than this many times h at rest are left out (rope_segments;
// sim::cpu::self_contact's SEGMENT_REST_MARGIN).
const float SEGMENT_REST_MARGIN = 1.5;

// Whether two edges that share no vertex can be nearer than EDGE_REST_MARGIN h in the rest
// state: the nearest are a cell's diagonal and the vertex next to it, sx sy / |s| >= 0.707
// min(sx, sy) apart.
bool edges_near_at_rest_possible() {
    return EDGE_REST_MARGIN * obj.self_distance >= 0.7 * min(obj.spacing.x, obj.spacing.y);
}

// Whether edges (qp, qa) and (qj, qb) (grid cells) are nearer than EDGE_REST_MARGIN h in the
// rest state.
bool edges_near_at_rest(ivec2 qp, ivec2 qa, ivec2 qj, ivec2 qb) {
    vec3 rp = vec3(0.0);
    vec3 ra = vec3(vec2(qa - qp) * obj.spacing, 0.0);
    vec3 rj = vec3(vec2(qj - qp) * obj.spacing, 0.0);
    vec3 rb = vec3(vec2(qb - qp) * obj.spacing, 0.0);
    vec2 st;
    vec3 off = edge_offset(rp, ra, rj, rb, st);
    float near = EDGE_REST_MARGIN * obj.self_distance;
    return dot(off, off) < near * near;
}

// Whether edge pair (p, a) against (j, b) (positions x, xa, xj, xb; d2j the squared distance
// of its ends p and j, lo1 and hi1 the first edge's box grown by the farthest reach) is not
// p's to find or is too far: (p, j) are not its nearest ends, or the boxes are apart.
bool edge_pair_culled(uvec4 m, vec3 x, vec3 xa, vec3 xj, vec3 xb, float d2j, vec3 lo1, vec3 hi1) {
    vec3 epb = x - xb;
    vec3 eab = xa - xb;
    if (ends_before(dot(epb, epb), m.x, m.w, d2j, m.x, m.z) || ends_before(dot(eab, eab), m.y, m.w, d2j, m.x, m.z)) {
        return true;
    }
    return any(greaterThan(lo1, max(xj, xb))) || any(lessThan(hi1, min(xj, xb)));
}

// The find pass's edge pair `code` (its particles m, at distance d, taking part by `part`):
// kept when a contact, and recorded in the particle's contact list when nearer than
// list_reach.
void keep_edge_pair(uint code, uvec4 m, float d, float part, float list_reach) {
    test_contact(code, m, d, part);
    if (d < list_reach) list_record(code, m);
}

// The find pass's edge pairs of the particle p (pair_particle, at `cell`, at x) with vertex
// j > p (at `at`, xj, squared distance d2j): each pair of p's edge (p, a) and j's edge (j, b)
// whose nearest ends are (p, j) (so each pair is visited once), left out when the edges share
// a vertex or are nearer than EDGE_REST_MARGIN h at rest, is kept when a contact whose nearest
// points lie inside both edges, and recorded in the list when nearer than list_reach. (The
// rings are read as the loops reach them, not into arrays: lavapipe compiled the arrays'
// dynamic indexing for seconds.)
void self_edges(uvec2 cell, vec3 x, uint j, ivec2 at, vec3 xj, float d2j, float farthest, float list_reach) {
    uint p = pair_particle;
    ivec2 qp = ivec2(cell);
    ivec2 dims = ivec2(obj.dims);
    bool rest_check = edges_near_at_rest_possible();
    uint j_creases = crease_mask(ring_creases(j, xj), list_reach > 0.0 && !noting);
    if ((own_creases | j_creases) == 0u) return;
    [[dont_unroll]] for (int k1 = 0; k1 < 6; ++k1) {
        bool own_creased = ((own_creases >> uint(k1)) & 1u) != 0u;
        if (!own_creased && j_creases == 0u) continue;
        ivec2 qa = qp + VERTEX_RING[k1];
        if (!in_grid(qa)) continue;
        uint a = uint(qa.x + qa.y * dims.x);
        if (a == j) continue;
        vec3 xa = CPOS(a);
        vec3 eaj = xa - xj;
        if (ends_before(dot(eaj, eaj), a, j, d2j, p, j)) continue;
        vec3 lo1 = min(x, xa) - farthest;
        vec3 hi1 = max(x, xa) + farthest;
        [[dont_unroll]] for (int k2 = 0; k2 < 6; ++k2) {
            ivec2 qb = at + VERTEX_RING[k2];
            if (!in_grid(qb)) continue;
            uint b = uint(qb.x + qb.y * dims.x);
            if (b == p || b == a || !own_creased && ((j_creases >> uint(k2)) & 1u) == 0u) continue;
            vec3 xb = CPOS(b);
            if (edge_pair_culled(uvec4(p, a, j, b), x, xa, xj, xb, d2j, lo1, hi1)) continue;
            vec2 st;
            float d = length(edge_offset(x, xa, xj, xb, st));
            if (!(d < farthest) || rest_check && edges_near_at_rest(qp, qa, at, qb)) continue;
            uint code = edge_pair_code(uint(k1), j, uint(k2));
            keep_edge_pair(code, uvec4(p, a, j, b), d, edge_pair_part(p, code, st), list_reach);
        }
    }
}

// self_edges for a rope (F_SEGMENT_PAIRS): the particle p's (pair_particle, at x) segments to
// its neighbours p + 1 and p - 1 (ring vertices 0 and 3) against node j's (j > p, at xj,
// squared distance d2j), by index instead of the grid's ring and with no crease (a rope's
// edges are all on its border): the same pairs, owners and codes. Two segments are nearer
// than SEGMENT_REST_MARGIN h at rest when the nodes between them span less: their gap along
// the straight rope.
void rope_segments(vec3 x, uint j, vec3 xj, float d2j, float farthest, float list_reach) {
    uint p = pair_particle;
    int nodes = int(obj.dims.x);
    float margin = SEGMENT_REST_MARGIN * obj.self_distance;
    [[unroll]] for (int e1 = 0; e1 < 2; ++e1) {
        int ia = int(p) + (e1 == 0 ? 1 : -1);
        if (ia < 0 || ia >= nodes || uint(ia) == j) continue;
        uint a = uint(ia);
        vec3 xa = CPOS(a);
        vec3 eaj = xa - xj;
        if (ends_before(dot(eaj, eaj), a, j, d2j, p, j)) continue;
        vec3 lo1 = min(x, xa) - farthest;
        vec3 hi1 = max(x, xa) + farthest;
        [[unroll]] for (int e2 = 0; e2 < 2; ++e2) {
            int ib = int(j) + (e2 == 0 ? 1 : -1);
            if (ib < 0 || ib >= nodes || uint(ib) == p || uint(ib) == a) continue;
            uint b = uint(ib);
            uvec2 one = uvec2(min(p, a), max(p, a));
            uvec2 two = uvec2(min(j, b), max(j, b));
            uint gap = two.x > one.y ? two.x - one.y : one.x - two.y;
            if (float(gap) * obj.spacing.x < margin) continue;
            vec3 xb = CPOS(b);
            if (edge_pair_culled(uvec4(p, a, j, b), x, xa, xj, xb, d2j, lo1, hi1)) continue;
            vec2 st;
            float d = length(edge_offset(x, xa, xj, xb, st));
            if (!(d < farthest)) continue;
            keep_edge_pair(edge_pair_code(e1 == 0 ? 0u : 3u, j, e2 == 0 ? 0u : 3u), uvec4(p, a, j, b), d, 1.0, list_reach);
        }
    }
}

// self_triangles' visit of the triangles around candidate j (at `at`, xj, squared distance
// d2j from x) outside the particle's one-ring (in the truncation's search, `noting`, every
// triangle without the particle: a fold's are noted, not kept as contacts).
void self_triangles_of(uvec2 cell, vec3 x, uint j, ivec2 at, vec3 xj, float d2j, float farthest, float list_reach) {
    ivec2 dims = ivec2(obj.dims);
    bool unfiltered = noting;  // (the truncation's search: a fold's pairs too)
    bool usable[6];
    bool far[6];  // (outside the particle's one-ring)
    uint ring[6];
    vec3 at_ring[6];
    float d2[6];
    ivec2 from_j = abs(at - ivec2(cell));
    bool j_far = max(from_j.x, from_j.y) > 1;
    [[unroll]] for (int r = 0; r < 6; ++r) {
        ivec2 q = at + VERTEX_RING[r];
        ivec2 off = abs(q - ivec2(cell));
        far[r] = max(off.x, off.y) > 1;
        usable[r] = in_grid(q) && (unfiltered ? max(off.x, off.y) > 0 : far[r]);
        ring[r] = usable[r] ? uint(q.x + q.y * dims.x) : j;
        at_ring[r] = CPOS(ring[r]);
        vec3 e = x - at_ring[r];
        d2[r] = usable[r] ? dot(e, e) : 0.0;
    }
    bool thick = obj.self_distance >= 1.99 * min(obj.spacing.x, obj.spacing.y);
    // Which triangles are contacts (bit k: the k-th around j), tested after the loop below
    // in one place, so that the code keeping (and per stage applying) them is compiled once,
    // not six times (lavapipe took 45 s to compile the apply pass so), and without an array
    // indexed in a loop (which NVIDIA keeps in local memory: the 1024 x 1024 cloth's
    // constraints took 20% longer so).
    uint hits = 0u;
    [[unroll]] for (int k = 0; k < 6; ++k) {
        int k1 = (k + 1) % 6;
        if (!usable[k] || !usable[k1] || nearer(d2[k], ring[k], d2j, j) || nearer(d2[k1], ring[k1], d2j, j)) continue;
        // Its bounding box grown by that distance must hold x (the nearest point lies in it),
        // a test cheaper than the exact one.
        vec3 lo = min(xj, min(at_ring[k], at_ring[k1])) - farthest;
        vec3 hi = max(xj, max(at_ring[k], at_ring[k1])) + farthest;
        if (any(lessThan(x, lo)) || any(greaterThan(x, hi))) continue;
        uint t = vertex_triangle(at, k);
        if ((thick || unfiltered) && near_at_rest(cell, t)) continue;
        // (a fold's pair: no contact, but the truncation's)
        bool left_out = !j_far || !far[k] || !far[k1];
        if (left_out && !unfiltered) continue;
        // The exact test from the positions read above, the vertices in the triangle's own
        // order (triangle_vertices), as pair_geometry computes it.
        uvec3 tv = triangle_vertices(t);
        vec3 p[3];
        [[unroll]] for (int c = 0; c < 3; ++c) p[c] = tv[c] == j ? xj : tv[c] == ring[k] ? at_ring[k] : at_ring[k1];
        vec3 w;
        vec3 n;
        float d = triangle_distance(x, p[0], p[1], p[2], w, n);
        if (d < obj.self_distance && !left_out) hits |= 1u << uint(k);
        if (d < list_reach) {
            list_record(t, uvec4(pair_particle, tv));
        }
    }
    // (A contact's distance computed again from the same positions: the same value.)
    [[dont_unroll]] while (hits != 0u) {
        int k = findLSB(hits);
        hits &= hits - 1u;
        test_pair(x, vertex_triangle(at, k));
    }
}

// A mesh cloth's find pass (F_CLOTH_MESH; the grid's self_triangles_of): each triangle of
// candidate j's ring whose vertex nearest x is j (ties by index: each triangle is visited
// once) and that no vertex of the particle's one-ring touches (mesh_linked) is kept when a
// contact and recorded in the list when nearer than list_reach. (j itself is outside the
// one-ring: rest_neighbour.) The thickness is below every vertex's distance from the triangles
// outside its one-ring at rest (sim::cloth_mesh::ClothMesh::rest_clearance, checked on load),
// so no other pair is left out.
void mesh_self_triangles(vec3 x, uint j, float list_reach) {
    uint p = pair_particle;
    vec3 xj = CPOS(j);
    vec3 dj = x - xj;
    float d2j = dot(dj, dj);
    float farthest = max(obj.self_distance, list_reach);
    for (uint k = mesh_ring_first(j); k < mesh_ring_first(j + 1u); ++k) {
        uint t = mesh_ring_triangle(k);
        uvec3 tv = mesh_triangle(t);
        vec3 a = CPOS(tv.x);
        vec3 b = CPOS(tv.y);
        vec3 c = CPOS(tv.z);
        vec3 ea = x - a;
        vec3 eb = x - b;
        vec3 ec = x - c;
        if (tv.x != j && nearer(dot(ea, ea), tv.x, d2j, j) || tv.y != j && nearer(dot(eb, eb), tv.y, d2j, j)
            || tv.z != j && nearer(dot(ec, ec), tv.z, d2j, j)) {
            continue;
        }
        vec3 lo = min(a, min(b, c)) - farthest;
        vec3 hi = max(a, max(b, c)) + farthest;
        if (any(lessThan(x, lo)) || any(greaterThan(x, hi))) continue;
        vec3 w;
        vec3 n;
        float d = triangle_distance(x, a, b, c, w, n);
        // (the distance before the one-ring: mesh_linked walks three spring lists, the
        // distance is a few dozen flops, and most boxes within reach hold no point within it)
        if (!(d < farthest)) continue;
        if (mesh_linked(p, tv.x) || mesh_linked(p, tv.y) || mesh_linked(p, tv.z)) continue;
        if (d < obj.self_distance) test_pair(x, t);
        if (d < list_reach) {
            list_record(t, uvec4(pair_particle, tv));
        }
    }
}

// The find pass's visit of candidate vertex j (not the particle at `cell`, at x): when j is
// outside the particle's one-ring (or in the truncation's search), each triangle around j whose vertex nearest x is j (so each
// triangle is visited once) and that is not left out is kept when a contact and, while the
// contact lists are built (`list_reach`: h plus the skin, otherwise 0), recorded in the
// particle's list when nearer than that; then, for j past the particle, their edge pairs
// (self_edges). The ring's positions are read once.
void self_triangles(uvec2 cell, vec3 x, uint j, float list_reach) {
    if (is_mesh()) {
        mesh_self_triangles(x, j, list_reach);
        return;
    }
    ivec2 at = ivec2(int(j % obj.dims.x), int(j / obj.dims.x));
    vec3 xj = CPOS(j);
    vec3 dj = x - xj;
    float d2j = dot(dj, dj);
    // A triangle or edge pair farther than this is neither a contact nor a list entry. (The box test and
    // the exact one round differently, so a contact within a rounding error of h may be kept by
    // a search with the lists' reach and culled by one without; its weight is then about 1e-5.
    // A margin of 0.1% here cost the 1024 x 1024 cloth 5% on the H100, so there is none.)
    float farthest = max(obj.self_distance, list_reach);
    if (has(F_SEGMENT_PAIRS)) {
        if (j > pair_particle) rope_segments(x, j, xj, d2j, farthest, list_reach);
        return;
    }
    ivec2 from_p = abs(at - ivec2(cell));
    if (max(from_p.x, from_p.y) > 1 || noting) {
        self_triangles_of(cell, x, j, at, xj, d2j, farthest, list_reach);
    }
    if (edge_contact() && j > pair_particle) self_edges(cell, x, j, at, xj, d2j, farthest, list_reach);
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

// How far each contact's correction is over-relaxed with edge contact
// (sim::cpu::self_contact::RELAXATION): a particle's share of a contact is 1 / n of it (mass
// splitting), which a pile of layers needs many passes to sum to what holds it; 1.5 its
// share, but never more than the contact alone would take (then its whole overlap), so that a
// lone contact does not overshoot. Without edge contact 1 (colliding layers part at 0.004 to
// 0.010 m/s after, against 0.011 to 0.034 with it and 1.5; tests/suite/self_contact.rs).
float pair_relaxation() { return edge_contact() ? 1.5 : 1.0; }

// With a cloth's edge pairs, every pair (particle and triangle, edge and edge) nearer than h at the
// substep's start keeps its two sides apart over the whole substep, whatever moved them (the solve,
// the contacts' passes, the colliders): each free particle's move from where it began is cut short
// (scaled, velocity too) where it would come nearer than TRUNCATION_GAP h / 2 to the plane halfway
// between the pair's nearest points at the substep's start, square to their offset. Each side then
// stays in its own half-space for the whole substep (a move along a segment, and the sides convex),
// so no particle passes through a triangle and no edge through an edge among those pairs, at any
// speed; the contacts' response still pushes the sides out to h. Moving away or along the plane is
// never cut. The pairs (note_truncation) include a fold's, which contacts leave out: a cloth wrung
// by kinematic handles squeezes exactly those through; edge pairs count where one edge is creased.
// A plain fraction of the gap (no floor), as Newton's VBD truncation has it, lets a pair squeezed
// without limit close it geometrically until rounding passes one side through; a fixed gap instead
// stops the squeeze where it is. (Offset Geometric Contact and Newton's planar truncation bound
// each vertex this way; the response there is inside the solve.) Twin: sim::cpu::self_contact's
// truncation.
const float TRUNCATION_GAP = 0.5;

// The truncation holds every pair nearer than h at a substep's start, but a pair a little farther
// can still cross within the substep where its sides close more than that gap (a cloth's free
// border snapping through a crumple at 4 m/s). Each free particle's move in a substep is also held
// to TRUNCATION_MOVE h (scaled as the truncation scales it), so that no two sides close more than
// h: past (h / 2) / dt a particle is slowed, which `simulate` states as its contact speed
// (sim::collider::contact_speed). Twin: sim::cpu::self_contact::TRUNCATION_MOVE.
const float TRUNCATION_MOVE = 0.5;

// TRUNC_POS(j): particle j's position after the constraint stage (defined by the includer
// where it is not CPOS).
#ifndef TRUNC_POS
#define TRUNC_POS(j) CPOS(j)
#endif

// Notes contact m (an edge pair or not, its particles at the substep's start at s) in the
// truncations of its free particles, where its sides were nearer than `within` then: the
// smallest fraction of each one's move that keeps it out of the gap, kept as 0x7f800000 minus
// the float's bits, the largest kept (atomicMax: the least fraction), so that 0, as the buffer
// is cleared, is none. Twin: sim::cpu::self_contact's truncation.
void note_pair(uvec4 m, bool edges, vec3 s[4], float within) {
    vec4 c;
    vec3 off = pair_offset(edges, s[0], s[1], s[2], s[3], c);
    float d = length(off);
    if (!(d > 0.0 && d < within)) return;
    vec3 n = off / d;
    uint a_side = edges ? 2u : 1u;
    // (side a's nearest point, less half the offset)
    vec3 middle = c.x * s[0] + (edges ? c.y * s[1] : vec3(0.0)) - 0.5 * off;
    float half_gap = 0.5 * TRUNCATION_GAP * obj.self_distance;
    [[unroll]] for (uint q = 0u; q < 4u; ++q) {
        if (CPINNED(m[q])) continue;
        float side = q < a_side ? 1.0 : -1.0;
        float room = max(side * dot(n, s[q] - middle) - half_gap, 0.0);
        float approach = -side * dot(n, TRUNC_POS(m[q]) - s[q]);
        if (approach > room) atomicMax(self_pairs[truncation_word(m[q])], 0x7f800000 - floatBitsToInt(room / approach));
    }
}

// The truncation's search for particle p (constraints_body.glsl).
void truncation_search(uint p);

// Pair m (an edge pair or not) in the truncations of its free particles where it was nearer
// than h at the substep's start.
void note_start_pair(uvec4 m, bool edges) {
    vec3 s[4] = vec3[4](pair_start(m.x), pair_start(m.y), pair_start(m.z), pair_start(m.w));
    note_pair(m, edges, s, obj.self_distance);
}

// Particle p's pairs in the truncations: those nearer than h at the substep's start, found by
// a search of the positions there (CPOS reads them, and the hash, where there is one, holds
// them: truncation_search), none left out as the contacts leave a fold's out, but the pairs
// near at rest and pairs of edges neither of which is creased (crease_weight) at the start.
void note_truncation(uint p) {
    if (cloth_edge_pairs()) truncation_search(p);
}

// Particle i at x with velocity v, which began the substep at `start`: moved back towards there
// by the fraction its pairs noted (note_truncation), which it clears, or less where its move
// passes TRUNCATION_MOVE h, and its velocity scaled as its move is (moving the velocity by the
// position's change instead would leave a particle held out of an overlap, a move its velocity
// does not follow, moving back into it).
// Returns whether it moved the particle (then the caller runs its colliders again, so that a
// moving collider still wins: against a fixed convex one, which the particle began outside,
// the cut keeps it outside and that changes nothing).
bool truncate_move(uint i, vec3 start, inout vec3 x, inout vec3 v) {
    if (!cloth_edge_pairs()) return false;
    uint w = truncation_word(i);
    int word = self_pairs[w];
    float t = 1.0;
    if (word != 0) {
        self_pairs[w] = 0;
        t = intBitsToFloat(0x7f800000 - word);
    }
    float moved = length(x - start);
    float most = TRUNCATION_MOVE * obj.self_distance;
    // (A move past the guard's speed is not held: held, a blow-up's positions and velocities
    // would stay finite and slow, and the guard would never stop it.)
    if (moved > most && moved <= g.guard_speed * g.dt) t = min(t, most / moved);
    if (!(t < 1.0)) return false;
    x = start + (x - start) * t;
    v *= t;
    return true;
}

// Contact `code` of particle p at x, computed again from the same positions as when it was
// found: moves its free particles (see the top).
void apply_contact(uint p, vec3 x, uint code) {
    uvec4 m;
    vec4 c;
    vec3 n;
    float d = pair_geometry(p, x, code, m, c, n);
    // (A further pass: the pair may have parted, or, moved, lost its normal.)
    if (!(d > 0.0 && d < obj.self_distance)) return;
    vec4 free_m = vec4(CPINNED(m.x) ? 0.0 : 1.0, CPINNED(m.y) ? 0.0 : 1.0, CPINNED(m.z) ? 0.0 : 1.0,
                       CPINNED(m.w) ? 0.0 : 1.0);
    // Each particle's inverse mass over the object's: 0 pinned, 1 free on a grid, the inverse
    // of its mass_share on a mesh.
    vec4 w = free_m;
    if (is_mesh()) w /= vec4(mass_share(m.x), mass_share(m.y), mass_share(m.z), mass_share(m.w));
    // Each free particle's count of contacts.
    vec4 shares = vec4(0.0);
    [[unroll]] for (int q = 0; q < 4; ++q) {
        if (free_m[q] > 0.0) shares[q] = pair_count(m[q]);
    }
    float overlap = max(obj.self_distance - d, 0.0);
    // A contact takes part by its weight in the counts: one that begins (overlap under h / 10)
    // moves its particles by that fraction of its share, so that the counts' smoothing never
    // lets a particle's contacts add up to more than its largest overlap.
    float weight = contact_weight(overlap) * pair_part(p, code, c);
    // Each free particle's mass split among its contacts: inverse mass w n, n its count (at
    // least 1).
    vec4 split_m = max(shares, free_m) * w;
    // The relative motion of the two sides' nearest points over the substep: the overlap it
    // made (its approach along n) is undone with the velocity that made it; what overlap
    // remains from before is undone in position only (no bounce from an overlap resolved late).
    vec3 moved = c.x * (x - pair_start(p));
    [[unroll]] for (int q = 1; q < 4; ++q) moved += c[q] * (CPOS(m[q]) - pair_start(m[q]));
    float approach = clamp(-dot(moved, n), 0.0, overlap);
    vec4 c2 = c * c;
    float split = dot(c2, split_m);
    float whole = dot(c2, w);
    // (Weights on pinned particles only: nothing to move.)
    if (!(whole > 0.0)) return;
    float k = weight * min(pair_relaxation() / split, 1.0 / whole);
    // Coulomb: the tangential slip undone at the contact's weight over its particles' counts,
    // over-relaxed as the normal share and never past the contact's whole, within mu times the
    // normal impulse it applies (k times the approach). The counts are not floored at one
    // contact here: a lone resting contact, whose overlap (so its weight) is small, still
    // undoes all of its slip (floored, it undid its weight's fraction a pass and the rest crept
    // on as velocity: a rope resting on itself below the friction angle slid at a steady 5 mm/s),
    // while a particle's weak contacts together undo no more than one would (times the
    // over-relaxation). The counts are fixed point (1 / 65536): a contact of weight near 1e-5
    // takes a somewhat smaller share on the GPU than on the reference, within a cone that small.
    float counted = dot(c2, max(shares, weight * free_m) * w);
    float share = weight > 0.0 ? min(pair_relaxation() * weight / counted, 1.0 / whole) : 0.0;
    vec3 slip = share > 0.0 ? friction_correction(moved, n, k * approach / share, obj.friction) * share : vec3(0.0);
    vec3 push = n * (overlap * k) - slip;
    vec3 rest = n * ((overlap - approach) * k);
    [[unroll]] for (int q = 0; q < 4; ++q) {
        if (free_m[q] > 0.0 && c[q] != 0.0) add_move(m[q], push * (c[q] * w[q]), rest * (c[q] * w[q]));
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
