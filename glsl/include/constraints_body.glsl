// The constraint stage for one particle, Jacobi: every correction is computed from the physics
// output: the stretch limit on structural and shear springs, self-collision (spatial hash or
// brute force), contact with other objects, then the colliders with friction, and the
// velocity update. The corrections of the stretch limit and self-collision are averaged
// (Jacobi averaging): summing them, as sequential Gauss-Seidel would, overshoots when several
// act at once and diverges. Contact between objects comes split already (contact.comp).
// `constraint_correction` and `collide_all` (its edges here, the particle in colliders.glsl)
// are shared by constraints.comp (through `constraints_particle`, which reads IN(i) and writes
// OUT(i)) and fused.comp. Other
// particles are read through CPOS(j) (position) and CPINNED(j); by default from IN(j). The
// spatial hash's buckets are visited by `visit_bucket`: here the global hash (starts[],
// sorted[]); fused.comp (FUSED_SHARED) defines its own over shared memory, and HASH_MASK.
// Features the scene does not use are compiled out (features.glsl).
// Include after bindings.glsl and springs.glsl, with IN, OUT and START (where particle i began
// the substep) defined, or CPOS and CPINNED.
#ifndef MSD_CONSTRAINTS_BODY_GLSL
#define MSD_CONSTRAINTS_BODY_GLSL
#include "features.glsl"
#include "colliders.glsl"

#ifndef CPOS
#define CPOS(j) IN(j).pos.xyz
#define CPINNED(j) (IN(j).pos.w > 0.5)
#endif
#include "stretch.glsl"
#ifndef HASH_MASK
#define HASH_MASK obj.hash_mask
#endif
#ifndef CELL_INV
#define CELL_INV obj.cell_inv
#endif

#ifndef FUSED_SHARED
// The per-stage contact lists: in a substep that rebuilds them (list_build), what is within
// their reach is recorded in the list of particle `list_particle` (list_len counts the entries,
// past LIST_ENTRIES too); fused.comp declares its own.
uint list_particle;
uint list_len;
bool list_build;
#endif
#include "self_contact.glsl"

// Whether this pipeline's self-contact is against triangles. The stages that include this
// file (constraints, self pairs, fused) are specialized with their object's own features,
// and F_TRIANGLES is set exactly where the object asks for triangles (has_triangles() reads
// the same from its flags), so the choice is made when the pipeline is compiled and only one
// of the two searches is in it.
bool triangle_contact() { return has(F_TRIANGLES); }

// Whether particle j is nearer than `reach` to `cell` in the rest state (or is that particle):
// such pairs never push, the springs keep them apart. In a cloth (whose candidates are the
// vertices of its triangles, self_contact.glsl), whether j is in the particle's one-ring: all
// its triangles are left out; with edge contact, whether j is that particle (the visit of a
// vertex in its one-ring finds edge pairs only, and in the truncation's search a fold's
// triangles too).
bool rest_neighbour(uvec2 cell, uint j, float reach) {
    if (triangle_contact() && is_mesh()) return mesh_linked(cell.x, j);
    if (triangle_contact()) return edge_contact() ? j == cell.x + cell.y * obj.dims.x : in_one_ring(cell, j);
    ivec2 other = ivec2(int(j % obj.dims.x), int(j / obj.dims.x));
    vec2 rest = vec2(other - ivec2(cell)) * obj.spacing;
    return dot(rest, rest) < reach * reach;
}

// Adds the push from particle j when it is within `reach` of x.
void self_push(vec3 x, uint j, float reach, inout vec3 correction, inout uint n_active) {
    vec3 to_j = CPOS(j) - x;
    float d = length(to_j);
    if (d < reach && d > 0.0) {
        correction += (to_j / d) * ((d - reach) * (CPINNED(j) ? 1.0 : 0.5));
        n_active += 1u;
    }
}

// The self-contact of the particle at `cell` (at x) with candidate j at distance d, not a
// rest-state neighbour: in a rope its push when within `reach`, in a cloth the find pass's
// visit of j's triangles (which records the list's entries itself).
void self_candidate(uvec2 cell, vec3 x, uint j, float d, float reach, inout vec3 correction, inout uint n_active) {
    if (triangle_contact()) {
        // (By brute force every particle is a candidate; with edge pairs only those within the
        // hash's reach are visited, so that both find the same pairs and the search's loops
        // stay within lavapipe's limit.)
        if (!edge_contact() || d < (list_build ? list_reach() : reach)) self_triangles(cell, x, j, recorded_within());
        return;
    }
    if (d < reach) self_push(x, j, reach, correction, n_active);
    if (list_build) {
        if (list_len < LIST_ENTRIES) self_list[list_entry(list_len, list_particle, particle_count())] = j;
        list_len += 1u;  // past LIST_ENTRIES the list is full: it is rebuilt the next substep
    }
}

// A contact list's entry e of the particle at x: a rope's particle or a cloth's triangle.
void self_listed(vec3 x, uint e, float reach, inout vec3 correction, inout uint n_active) {
    uint entry = self_list[list_entry(e, list_particle, particle_count())];
    if (triangle_contact()) {
        test_pair(x, entry);
    } else {
        self_push(x, entry, reach, correction, n_active);
    }
}

// Calls self_candidate for the particles in hash bucket h within `reach` of x (while the
// lists are built, within list_reach()).
void visit_bucket(uint h, uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active);

// Visits the hash buckets that can hold particles within reach of x (or of the contact lists'
// reach while they are built): cells are at least twice that wide (1 / CELL_INV), so every
// such particle lies in the 2 x 2 x 2 block of cells nearest to x. Buckets two cells share are
// visited once. Per stage the two cells of each x pair have neighbouring buckets (cell_hash),
// which are one run of the sorted candidates: 4 runs, not 8 buckets (measured on the H100:
// 3.52 against 3.82 ms a frame on the 1024 x 1024 cloth with self-collision).
#ifndef FUSED_SHARED
void visit_range(uint from, uint to, uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active);
#endif
void visit_cells(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {
    // A particle absurdly far (hash_cell's rule: a blow-up) has no contact to find, and the
    // cells about it, converted to integers, would be anyone's.
    if (!all(lessThan(abs(floor(x * CELL_INV)), vec3(HASH_FAR_CELLS)))) return;
    ivec3 base = ivec3(floor(x * CELL_INV - 0.5));
    // The buckets (fused) or runs of sorted candidates (per stage) are gathered first and
    // visited in one loop, so that the visit, with every contact test in it, is compiled once
    // (unrolled over the cells it made the fused kernel's triangle contact take a minute to
    // compile on lavapipe).
#ifdef FUSED_SHARED
    uint seen[8];
    uint count = 0u;
    [[unroll]] for (int c = 0; c < 8; ++c) {
        uint h = cell_hash(base + ivec3(c & 1, (c >> 1) & 1, c >> 2), HASH_MASK);
        bool again = false;
        for (uint k = 0u; k < count; ++k) again = again || seen[k] == h;
        if (!again) {
            seen[count] = h;
            count += 1u;
        }
    }
    for (uint k = 0u; k < count; ++k) visit_bucket(seen[k], cell, x, reach, correction, n_active);
#else
    uint seen[4];
    uvec2 runs[8];
    uint count = 0u;
    [[unroll]] for (int c = 0; c < 4; ++c) {
        uint h = cell_hash(base + ivec3(0, c & 1, c >> 1), HASH_MASK);
        seen[c] = h;
        bool a0 = false;
        bool a1 = false;
        for (int k = 0; k < c; ++k) {
            uint d = (h - seen[k]) & HASH_MASK;
            a0 = a0 || d <= 1u;
            a1 = a1 || d == 0u || d == HASH_MASK;
        }
        if (!a0 && !a1 && h < HASH_MASK) {
            runs[count] = uvec2(BUCKET_START(h, HASH_MASK), BUCKET_START(h + 2u, HASH_MASK));
            count += 1u;
        } else {
            if (!a0) {
                runs[count] = uvec2(BUCKET_START(h, HASH_MASK), BUCKET_START(h + 1u, HASH_MASK));
                count += 1u;
            }
            if (!a1) {
                uint h1 = (h + 1u) & HASH_MASK;
                runs[count] = uvec2(BUCKET_START(h1, HASH_MASK), BUCKET_START(h1 + 1u, HASH_MASK));
                count += 1u;
            }
        }
    }
    for (uint k = 0u; k < count; ++k) visit_range(runs[k].x, runs[k].y, cell, x, reach, correction, n_active);
#endif
}

// The candidates for self-contact: the hash's buckets (fused.comp may read a contact list).
#ifndef SELF_CANDIDATES
#define SELF_CANDIDATES visit_cells
#endif

// Self-contact of the particle at `cell` (at x) with its candidates: from the spatial hash (or
// the contact list) or, as the reference, every particle.
void self_search(uvec2 cell, vec3 x, inout vec3 correction, inout uint n_active) {
    float reach = self_reach();
    if ((obj.flags & OBJ_SELF_HASH) != 0u) {
        SELF_CANDIDATES(cell, x, reach, correction, n_active);
    } else {
        uint n = particle_count();
        for (uint j = search_lane; j < n; j += search_lanes) {
            if (!rest_neighbour(cell, j, obj.self_distance)) {
                self_candidate(cell, x, j, distance(CPOS(j), x), reach, correction, n_active);
            }
        }
    }
}

// A pass of a cloth's self-contact (self_contact.glsl) for particle i at `cell`, at x: the
// find pass (`apply` false; the particle began the substep at `start`) searches for its
// contacts, keeps the first PAIR_MAX and counts them all; the apply pass applies those it
// kept and, when it found more, searches again (without recording contact lists) for the
// rest (SELF_APPLY_FOUND: once, else for each further PAIR_MAX of them). Both passes find the
// same contacts in the same order (the same positions and candidates: the contact list, or
// the hash's buckets in the same order). The search is in one place, so the compiled kernel
// holds the contact tests once.
// Split among lanes (search_lanes; per stage, a cloth with edge pairs searching its hash), the
// find pass's lanes number the contacts they keep with the particle's counter
// (pairs_len_word, which the truncate pass zeroes for the next substep), so the slots hold the
// first PAIR_MAX found in whatever order; the apply pass applies the slots split among the
// lanes, or where more were found, searches again applying each contact as it finds it
// (apply_found). The same contacts are applied, each once, and their moves are summed in fixed
// point in any order, so the result is one lane's bit for bit.
void self_pass(uvec2 cell, uint i, vec3 x, vec3 start, bool apply) {
    uint len = apply ? uint(self_pairs[pairs_len_word(i)]) : 0u;
    if (!apply && search_lane == 0u) set_pair_start(i, start);
    bool split = search_lanes > 1u;
    if (split && apply && len <= PAIR_MAX) {
        for (uint k = search_lane; k < len; k += search_lanes) apply_contact(i, x, uint(self_pairs[pair_word(k, i)]));
        return;
    }
    uint from = 0u;
    do {
        if (!apply || from > 0u || split) {
            pair_particle = i;
            pair_x = x;
            pair_len = 0u;
            pair_skip = from;
            apply_pass = apply;
            apply_found = split && apply;
            bool building = list_build;
            list_build = building && !apply;
            if (cloth_edge_pairs()) own_creases = crease_mask(ring_creases(i, x), list_build);
            vec3 unused = vec3(0.0);
            uint unused_count = 0u;
            self_search(cell, x, unused, unused_count);
            list_build = building;
            apply_pass = false;
            apply_found = false;
            pair_skip = 0u;
            if (!apply) {
                if (!split) self_pairs[pairs_len_word(i)] = int(pair_len);
                return;
            }
            if (split) return;  // (each contact applied as found)
            len = pair_len;
        }
        uint batch = min(len - from, PAIR_MAX);
        for (uint k = 0u; k < batch; ++k) apply_contact(i, x, uint(self_pairs[pair_word(k, i)]));
        from += PAIR_MAX;
#ifdef SELF_APPLY_FOUND
        if (SELF_APPLY_FOUND && from > PAIR_MAX) break;  // the search applied those past the batch
#endif
    } while (from < len);
}

// The part of the last constraint_correction that moves the position only, not the velocity
// (a cloth's self-contact undoing an overlap from an earlier substep).
vec3 position_only;

// The share of a stretched spring's excess its end moves by, the end counting `n` stretched
// springs and the other, j, its own (it counted this spring too, from the same positions; at
// least one in case rounding of a spring at the limit told it otherwise), times `weight` (the
// end's part by inverse mass, 1 on a grid): all over n where j is pinned.
float stretch_split(int j, uint n, float weight) {
    if (CPINNED(j)) return 1.0 / float(n);
    return 0.25 * (1.0 / float(n) + 1.0 / float(max(STRETCHED(j), 1u))) * weight;
}

// The position correction of the free particle at grid `cell`, at x after physics; the
// velocity follows it but for position_only.
vec3 constraint_correction(uvec2 cell, vec3 x) {
    vec3 correction = vec3(0.0);
    position_only = vec3(0.0);

    // Springs may not stretch past (1 + stretch_limit) * rest: the two ends of a stretched
    // spring move towards each other by half the excess times the mean of their shares, one
    // over each end's count of stretched springs (stretch.glsl), so their moves are equal and
    // opposite and momentum is kept (each end's own share, a Jacobi mean, was not: 57% of a
    // thrown rope's momentum with a 1% limit; the smaller share, over the larger count, let
    // edges of a piling strip through each other); the end of one held by a pin moves all of
    // it over its own count.
    // A mesh cloth's ends move by their inverse masses w, 2 w_i / (w_i + w_j) of that, so that
    // their momenta stay equal and opposite (1 on a grid).
    uint n_stretched = 0u;
    if (has(F_STRETCH) && (obj.flags & OBJ_STRETCH_LIMIT) != 0u) {
        n_stretched = STRETCHED(cell.x + cell.y * obj.dims.x);
        if (is_mesh()) {
            for (uint e = mesh_first(cell.x); n_stretched > 0u && e < mesh_first(cell.x + 1u); ++e) {
                int j;
                float excess;
                if (!mesh_overstretched(x, e, j, excess)) continue;
                float wi = 1.0 / mass_share(cell.x), wj = 1.0 / mass_share(uint(j));
                correction += normalize(CPOS(j) - x) * (excess * stretch_split(j, n_stretched, 2.0 * wi / (wi + wj)));
            }
        } else {
            [[unroll]] for (int s = 0; s < 8; ++s) {
                int j;
                float excess;
                if (n_stretched == 0u || !overstretched(ivec2(cell), x, s, j, excess)) continue;
                correction += normalize(CPOS(j) - x) * (excess * stretch_split(j, n_stretched, 1.0));
            }
        }
    }

    // A rope's self-collision: particles closer than self_distance push apart, except pairs
    // that are closer than that in the rest state (grid neighbours), which the springs
    // already keep: the mean of the pushes, and where springs are stretched too the mean of
    // both (the stretch limit's share weighted by its count). A cloth's contact with its own
    // triangles was summed by its passes (self_contact.glsl) and is added below.
    bool self_on = has(F_SELF) && (obj.flags & OBJ_SELF_COLLISION) != 0u;
    if (self_on && !triangle_contact()) {
        vec3 pushes = vec3(0.0);
        uint n_pushes = 0u;
        self_search(cell, x, pushes, n_pushes);
        if (n_pushes > 0u) correction = (correction * float(n_stretched) + pushes) / float(n_stretched + n_pushes);
    }

    if (self_on && triangle_contact()) correction += self_take(cell.x + cell.y * obj.dims.x, position_only, true);

    // Inter-object contact: what contact.comp summed from the other objects' particles, added
    // whole (each pair's share is already split so that the pair conserves momentum).
    if (has(F_CONTACT)) correction += contact[cell.x + cell.y * obj.dims.x].xyz;
    return correction;
}

// The edge from the particle at `here` to particle j against collider c: where its midpoint
// is within the margin, its move out (twice that where j is pinned) into push, one more edge.
void edge_push(Collider c, ColliderPose pose, vec3 here, int j, inout vec3 push, inout uint edges) {
    vec3 n;
    float d = collider_distance_at(c, pose, 0.5 * (here + CPOS(j)), n);
    if (d < obj.margin) {
        push += n * ((obj.margin - d) * (CPINNED(j) ? 2.0 : 1.0));
        edges += 1u;
    }
}

// Colliders against the object's edges as well as its particles (F_EDGES: a collider thinner
// than a couple of grid spacings, or a box's edges and corners, could otherwise pass between
// the particles or poke through a face). The midpoints of the particle's structural edges and
// of its shear diagonals (the centres of its quads) are tested against each collider but the
// ground (a plane cannot reach between particles); an edge whose midpoint is within the margin
// moves both its ends out along the normal there by the depth (so its midpoint reaches the
// margin; by twice the depth when the other end is pinned), the particle taking the mean of
// its edges' moves against that collider through the same response as a particle
// (contact_response: no approach, Coulomb friction). Read from the physics output, like the
// constraints, so each end of an edge computes the same move. A collider farther from the
// particle than the margin plus half a shear diagonal stretched to twice its rest length is
// skipped without reading the neighbours: a signed distance changes no faster than the
// distance along it, so no midpoint of an edge up to twice its rest length is within the
// margin. A mesh cloth's edges are its structural and shear springs. The CPU twin is
// sim::cpu::collide_edges.
void collide_edges(uvec2 cell, inout vec3 x, inout vec3 v, float since) {
    if (!has(F_EDGES)) return;
    vec3 here = CPOS(cell.x + cell.y * obj.dims.x);
    float reach = obj.margin + sqrt(2.0) * max(obj.spacing.x, obj.spacing.y);
    for (uint k = 0u; k < g.collider_count; ++k) {
        Collider c = colliders[k];
        if (floatBitsToUint(c.a.w) == COLLIDER_GROUND) continue;
        ColliderPose pose = collider_pose(c, since);
        vec3 n;
        if (collider_distance_at(c, pose, here, n) >= reach) continue;
        vec3 push = vec3(0.0);
        uint edges = 0u;
        if (is_mesh()) {
            // (a mesh cloth: its structural and shear springs from its list)
            for (uint e = mesh_first(cell.x); e < mesh_first(cell.x + 1u); ++e) {
                MeshSpring s = mesh_spring(e);
                if (s.type <= uint(SPRING_SHEAR)) edge_push(c, pose, here, s.other, push, edges);
            }
        } else {
            [[unroll]] for (int s = 0; s < 8; ++s) {
                int j = SPRING_NEIGHBOUR(cell, s);
                if (j >= 0) edge_push(c, pose, here, j, push, edges);
            }
        }
        float depth = length(push);  // the mean move is push / edges
        if (depth > 0.0) {
            vec3 surface = collider_surface_velocity(pose, here);  // (at the particle)
            contact_response(x, v, push / depth, depth / float(edges), collider_friction(c), surface);
        }
    }
}

// Every collider response of a particle: its edges (where compiled in), then itself.
void collide_all(uvec2 cell, inout vec3 x, inout vec3 v, float since) {
    collide_edges(cell, x, v, since);
    collide(x, v, since);
}

#ifndef FUSED_SHARED
// The per-stage hash (hash_count.glsl): candidates are stored contiguously by bucket with
// their positions, so most are rejected without reading their particle.
void visit_bucket(uint h, uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {
    visit_range(BUCKET_START(h, HASH_MASK), BUCKET_START(h + 1u, HASH_MASK), cell, x, reach, correction, n_active);
}
void visit_range(uint from, uint end, uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {
    float listed = list_build ? list_reach() : reach;
    for (uint at = from + search_lane; at < end; at += search_lanes) {
        vec4 e = sorted[at];
        float d = distance(e.xyz, x);
        uint j = floatBitsToUint(e.w);
        if (d < listed && !rest_neighbour(cell, j, obj.self_distance)) {
            if (triangle_contact()) {
                self_triangles(cell, x, j, recorded_within());
                continue;
            }
            if (d < reach) self_push(x, j, reach, correction, n_active);
            if (list_build && list_len < LIST_ENTRIES) self_list[list_entry(list_len, list_particle, particle_count())] = j;
            list_len += 1u;
        }
    }
}

// Per stage, self-contact candidates come from the particle's contact list, or from the hash
// in a substep that searches it (with lists off, every substep; with them on, one that
// rebuilds them).
bool list_rebuild;
void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {
    if (list_rebuild) {
        visit_cells(cell, x, reach, correction, n_active);
        return;
    }
    // (rest-state neighbours were left out when the list was built)
    for (uint e = 0u; e < list_len; ++e) self_listed(x, e, reach, correction, n_active);
}

// The contact list state of particle i in `substep` of an object whose self-collision
// searches the hash (with `lists` on, the control block's word 0 says whether the substep
// rebuilds them, lists.glsl); `listed` false: no lists, no search.
void list_state(uint i, uint substep, bool listed, bool lists) {
    list_particle = i;
    list_build = listed && lists && self_list[list_control(substep)] != 0u;
    list_rebuild = listed && (!lists || list_build);
    list_len = listed && !list_rebuild ? self_list[4u * i + 3u] : 0u;
}
#endif

// The truncation's search for particle p (self_contact.glsl's note_truncation): the search of
// the find pass, from where p began the substep, noting the pairs within h it finds instead of
// keeping contacts. The includer has CPOS read where each particle began the substep and the
// hash, where there is one, built from there with cells of the search's reach.
void truncation_search(uint p) {
    noting = true;
    pair_particle = p;
    list_particle = p;
    list_build = false;
    list_rebuild = true;  // (the hash, not the list)
    list_len = 0u;
    uvec2 cell = uvec2(p % obj.dims.x, p / obj.dims.x);
    vec3 x = CPOS(p);
    own_creases = crease_mask(ring_creases(p, x), false);
    vec3 unused = vec3(0.0);
    uint unused_count = 0u;
    self_search(cell, x, unused, unused_count);
    noting = false;
}

#ifdef OUT
uint visiting;  // the particle whose constraints run
vec3 substep_start() { return START(visiting); }

// `substep`: which of the frame's substeps this is (the colliders move within the frame).
// With self-collision through the hash and `lists` on, a rope's contact list is walked, or in
// a substep that rebuilds the lists built from the hash.
void constraints_particle(uvec2 cell, uint substep, bool lists) {
    uint i = cell.x + cell.y * obj.dims.x;
    Particle p = IN(i);
    if (p.pos.w > 0.5) {
        OUT(i) = p;  // (at its pins' place and velocity)
        return;
    }
    vec3 x = p.pos.xyz;
    vec3 v = p.vel.xyz;
    bool listed = has(F_SELF) && self_hashed() && !triangle_contact();  // (a cloth's: self_pairs.comp)
    list_state(i, substep, listed, lists);
    vec3 correction = constraint_correction(cell, x);
    if (list_build) set_list_header(i, x, list_len);
    x += correction;
    v += (correction - position_only) / g.dt;  // velocity follows the position correction
    visiting = i;
    float since = float(substep + 1u) * g.dt;
    collide_all(cell, x, v, since);
    OUT(i) = Particle(vec4(x, 0.0), vec4(v, 0.0));
}
#endif

#endif
