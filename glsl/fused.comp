#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Every substep of a frame for one object in one workgroup, with the state in registers and
// shared memory: physics, the self-collision hash and the constraints of all substeps run
// without a dispatch or a pipeline barrier between them (what bounds small scenes), and
// without global memory traffic between the first load and the last store.
//
// Thread t owns the particles of ranks t, t + THREADS, ... (at most MAX_SLOTS; the rank is the
// index, or for the Gauss-Seidel methods the place in colour order, particle_of_rank): their
// position, velocity and pin live in its registers. Shared memory holds what neighbours read:
//   px/py/pz   every particle's position (for physics drifted by physics_drift() times its
//              velocity, as physics.comp reads its neighbours; for the constraints the new one);
//   pin_bits   which particles are pinned;
//   scratch    during physics: the velocities (for the spring dashpots) of the particles one
//              pass computes plus HALO on each side, in passes of PASS_SLOTS slots when not all
//              fit (a mesh cloth's in one pass, HALO 0); during the constraints: the spatial
//              hash, bucket heads and a linked list, and the stretch limit's counts (STRETCH_AT).
// Registers also hold a copy of the object's parameters (`obj`, taken from the buffer at the
// start: reading them from the storage buffer in every spring loop cost 15 to 25%), each owned
// particle's grid cell and the mask of its springs that have another end (SPRING_NEIGHBOUR).
// The host (src/sim/gpu/fused.rs) sizes all of it from the object and the device's shared
// memory and specializes one pipeline per object shape (and one for a single iteration); the
// step code is physics_body.glsl and constraints_body.glsl, as for the per-stage path, with
// neighbours read from shared memory.
// Phases are separated by barrier(); those a scene does not need are left out.
//
// The iterative integrators (SOLVER) replace the physics step with the BDF2 start (each particle's
// history in registers, from and back to `history`), then their iterations: the displacements
// p - x~ from the base x~ live in registers and, for the neighbours, in scratch (px/py/pz keep the
// bases; COMPACT: the iterates, below); XPBD visits the spring classes in turn (the thread owning a
// spring's first node moves both ends), VBD the vertex colours, a barrier() after each class or
// colour; XPBD by Jacobi computes every new displacement, then a barrier(), the writes, and a
// barrier() (at one iteration nothing is written back); the implicit method's conjugate gradients
// keep their vectors in registers and, while a Newton step's products run, the iterates p in
// px/py/pz and the directions in scratch, with a workgroup_sum (one barrier) for each dot product.
// The updates themselves are solver_bodies.glsl's, as in the per-stage shaders.
#define STATE_FUSED
#define FUSED_SHARED
#define OBJ_COPY
#define XPBD_OBJ obj_buffer
#include "bindings.glsl"
#include "features.glsl"
#define SPRING_NEIGHBOUR(cell, s) (!SPRING_MASKS ? neighbour(ivec2(cell), SPRINGS[s].xy, obj.dims) : \
    ((spring_mask >> uint(s)) & 1u) != 0u ? int((cell).x + (cell).y * obj.dims.x) + SPRINGS[s].x + SPRINGS[s].y * int(obj.dims.x) : -1)
// (solver_bodies.glsl: the other end, or the particle itself, by one select on the mask; XPBD,
// without masks, never reads it)
#define SPRING_OTHER(cell, s) (!SPRING_MASKS ? (SPRING_NEIGHBOUR(cell, s) < 0 ? int((cell).x + (cell).y * obj.dims.x) : SPRING_NEIGHBOUR(cell, s)) : \
    int((cell).x + (cell).y * obj.dims.x) + (((spring_mask >> uint(s)) & 1u) != 0u ? SPRINGS[s].x + SPRINGS[s].y * int(obj.dims.x) : 0))
#include "springs.glsl"

layout(local_size_x_id = 0) in;
// The substeps this dispatch runs: from `first`, `count` of them (a frame's all, or on a device
// that ends long loops early a few a dispatch: sim::gpu::FusedLimits::substeps_per_dispatch).
layout(push_constant) uniform Chunk { uint first; uint count; } chunk;
layout(constant_id = 1) const bool ONE_ITERATION = false;  // an iterative method runs 1 iteration
layout(constant_id = 4) const uint CAP = 1u;         // particles of the object
layout(constant_id = 5) const uint SCRATCH = 1u;     // words of scratch
layout(constant_id = 6) const uint BUCKETS = 1u;     // hash buckets (a power of two)
layout(constant_id = 7) const uint PASS_SLOTS = 1u;  // slots whose physics one pass computes
layout(constant_id = 8) const uint HALO = 2u;        // largest index distance to a spring neighbour
                                                     // (0 for a mesh cloth: one pass holds all)
layout(constant_id = 9) const uint SOLVER = 0u;      // the integrator (METHOD_*, layout.glsl)
layout(constant_id = 10) const uint LIST_MAX = 0u;   // contact list entries a particle (0: none)
// VBD on an object whose displacements do not fit beside the bases (sim::gpu::FusedShape's
// `compact`): during the solve px/py/pz hold the iterates p = x~ + dx and scratch the
// displacements in half precision (8 bytes a particle, not 12), which only the dashpots read;
// each thread keeps its own particles' displacements exact in registers.
layout(constant_id = 11) const bool COMPACT = false;
// Where the stretch limit's counts live (four bits a particle, written before the constraints
// of each substep; FusedShape's `stretch_counts`), in scratch, not an array of their own:
// packed eight a word from its start (STRETCH_PACKED), where the constraints
// read nothing else there; or, where a particle self-collision searches the hash during the
// constraints, in the top bits of the particles' hash links (STRETCH_IN_LINKS).
layout(constant_id = 12) const uint STRETCH_AT = 0u;
const uint STRETCH_PACKED = 1u;
const uint STRETCH_IN_LINKS = 2u;

const uint THREADS = gl_WorkGroupSize.x;
const uint MAX_SLOTS = 4u;  // particles per thread at most (FUSED_SLOTS on the host)
const uint SLOTS = (CAP + THREADS - 1u) / THREADS;
const uint WINDOW = THREADS * PASS_SLOTS + 2u * HALO;  // velocities staged per pass
const uint EMPTY = 0xFFFFFFFFu;
const uint NO_COLOUR = 0xFFu;
const bool ITERATIVE = SOLVER == METHOD_XPBD || SOLVER == METHOD_IMPLICIT || SOLVER == METHOD_VBD
    || SOLVER == METHOD_XPBD_JACOBI;
const bool COLOURED = SOLVER == METHOD_VBD;  // VBD sweeps vertex colours; XPBD spring classes
// Starts its iterate adaptively (sim::integrator's row: `adaptive_start`).
const bool ADAPTIVE_START = SOLVER == METHOD_VBD || SOLVER == METHOD_IMPLICIT;
// The springs of the particle being visited that have another end (bit s of SPRINGS), set
// before each body call. XPBD does without (measured: its class passes ran 20% slower with the
// masks' registers) and reads its spring constants from the buffer (4% faster than from the copy).
uint spring_mask;
const bool SPRING_MASKS = SOLVER != METHOD_XPBD;

shared float px[CAP];
shared float py[CAP];
shared float pz[CAP];
shared uint pin_bits[(CAP + 31u) / 32u];
shared uint scratch[SCRATCH];
shared uint list_flag[2];  // substep parity: some particle moved too far from its list's build
shared uint pairs_kept[2];  // substep parity: some particle found a triangle self-contact

// The self-collision contact lists (LIST_MAX > 0, with the hash; lists.glsl): a substep builds
// the hash when some particle has moved half the skin from where its list was built or a list
// overflowed (list_flag), and then the lists too, unless some particle moves so fast that
// they would not outlast the next substep. The lists and where they were built stay in
// self_list from one dispatch to the next, marked valid by the word after them (LIST_VALID);
// the host clears it whenever something outside the kernel changes the state or the
// parameters (a reset, a dragged or pinned particle, an edit, a reloaded shader), and until
// they are valid every substep builds.
const bool LISTED = LIST_MAX > 0u;  // (LIST_MAX is LIST_ENTRIES or 0)
bool list_rebuild;   // this substep builds the hash (and searches it)
bool list_build;     // ... and the lists
bool lists_built;    // valid lists exist (from this dispatch or an earlier one)
const uint LIST_VALID = (4u + LIST_MAX) * CAP;  // the word of self_list that says so (1)
const uint LIST_MOVED = 1u;  // list_flag bits: build this substep
const uint LIST_FAST = 2u;   // ... but not lists (they would not last)
uint list_particle;  // the particle being visited
uint list_len;       // its list's length (while building: the candidates found so far)

int window_start;  // the particle at scratch[0] in the current physics pass

vec3 spos(uint j) { return vec3(px[j], py[j], pz[j]); }
void set_spos(uint j, vec3 x) {
    px[j] = x.x;
    py[j] = x.y;
    pz[j] = x.z;
}
bool spinned(uint j) { return (pin_bits[j >> 5u] & (1u << (j & 31u))) != 0u; }
vec3 wvel(uint j) {
    uint w = uint(int(j) - window_start);
    return vec3(uintBitsToFloat(scratch[w]), uintBitsToFloat(scratch[WINDOW + w]),
                uintBitsToFloat(scratch[2u * WINDOW + w]));
}

// The displacement of particle j during an iterative method's solve (scratch[0 .. 3 CAP);
// COMPACT: scratch[0 .. 2 CAP), x and y in one word, z in the other, as half floats of dx / h,
// a velocity, which keeps them in half's normal range, 6.1e-5 and up, where a displacement
// would fall below it and may be flushed to zero). Only the dashpots read them there, so
// without dashpots COMPACT keeps none (zero; FusedShape::plan gives them no scratch).
vec3 sdisp(uint j) {
    if (COMPACT && !has(F_DAMPING)) return vec3(0.0);
    if (COMPACT) return vec3(unpackHalf2x16(scratch[j]), unpackHalf2x16(scratch[CAP + j]).x) * solve_dt();
    return vec3(uintBitsToFloat(scratch[j]), uintBitsToFloat(scratch[CAP + j]), uintBitsToFloat(scratch[2u * CAP + j]));
}
void set_sdisp(uint j, vec3 d) {
    if (COMPACT && !has(F_DAMPING)) return;
    if (COMPACT) {
        vec3 u = d * (1.0 / solve_dt());
        scratch[j] = packHalf2x16(u.xy);
        scratch[CAP + j] = packHalf2x16(vec2(u.z, 0.0));
        return;
    }
    scratch[j] = floatBitsToUint(d.x);
    scratch[CAP + j] = floatBitsToUint(d.y);
    scratch[2u * CAP + j] = floatBitsToUint(d.z);
}

// Where the particle whose constraints run began the substep (the colliders' friction).
vec3 visiting_start;
vec3 substep_start() { return visiting_start; }

// Self-contact candidates: the hash or the particle's list.
void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active);
#define SELF_CANDIDATES listed_candidates
#define NPOS(j) spos(uint(j))
#define NVEL(j) wvel(uint(j))
#define CPOS(j) spos(uint(j))
#define CPINNED(j) spinned(uint(j))
#define TRUNC_POS(j) p_out[j].pos.xyz
#define HASH_MASK (BUCKETS - 1u)
// The stretch limit's counts (stretch.glsl), and the hash's links below them (visit_bucket).
const uint LINK_BITS = 0x0FFFFFFFu;
uint stretched(uint k) {
    if (STRETCH_AT == STRETCH_IN_LINKS) return scratch[BUCKETS + k] >> 28u;
    return (scratch[k >> 3u] >> ((k & 7u) * 4u)) & 15u;
}
#define STRETCHED(j) stretched(uint(j))
void set_stretched(uint k, uint count) {
    if (STRETCH_AT == STRETCH_IN_LINKS) {
        scratch[BUCKETS + k] = (scratch[BUCKETS + k] & LINK_BITS) | (count << 28u);  // (its own word)
    } else {
        uint shift = (k & 7u) * 4u;
        atomicAnd(scratch[k >> 3u], ~(15u << shift));
        atomicOr(scratch[k >> 3u], count << shift);
    }
}
#include "physics_body.glsl"
#include "constraints_body.glsl"
#include "predict_body.glsl"
#define SX(j) spos(uint(j))
// Every method's iterates are displacements from the bases x~ in px/py/pz, so the positions'
// rounding stays out of the solve (predict.comp says why); COMPACT holds the iterates there and
// each thread its own displacements, so that rounding stays out of the velocities.
#define SD(j) sdisp(uint(j))
// p_i - p_j for particle i at x~ + dx and neighbour j (displacement dj): COMPACT holds p_j.
#define SPRING_DELTA(x, dx, j, dj) (COMPACT ? ((x) + (dx)) - spos(uint(j)) : ((x) - spos(uint(j))) + ((dx) - (dj)))
#define SPIN(j) spinned(uint(j))
// The implicit method's Hessian products: px/py/pz hold the iterates p, scratch the directions.
#define PP(j) spos(uint(j))
#define DD(j) sdisp(uint(j))
#define DP(j) sdisp(uint(j))
#define SELECT_SPRINGS true
#include "solver_bodies.glsl"
// The implicit method's dot products (a quarter of the threads: subgroups of 4 lanes or more).
#define REDUCE_T float
#define REDUCE_SLOTS (SOLVER == METHOD_IMPLICIT ? (THREADS + 3u) / 4u : 1u)
#include "reduce.glsl"
#include "rigid_start.glsl"

// Links particle k, at `at`, into the shared hash (the bucket of its cell, obj.cell_inv).
void hash_insert(uint k, vec3 at) {
    uint h = cell_hash(hash_cell(at, obj.cell_inv, k), BUCKETS - 1u);
    scratch[BUCKETS + k] = atomicExchange(scratch[h], k);
}

// Writes particle k's crease word from its ring at `at` (creases.glsl; `listing`: the contact
// lists are built from there).
void write_creases(uint k, vec3 at, bool listing) {
    uint word = uint(self_pairs[creases_word(k)]);
    self_pairs[creases_word(k)] = int(listed_crease_word(ring_crease_masks(k, at), word, listing));
}

// A free object's rigid start (rigid_start.glsl): the subgroups' 16 sums pass through the
// positions and then scratch (free between the prediction and the solve), as many of each
// subgroup's as fit a round (one round with subgroups of 8 lanes or more; the host keeps room
// for one sum of every subgroup of 4 lanes, FusedShape::plan), their totals through
// rigid_totals.
shared float rigid_totals[ADAPTIVE_START ? 16 : 1];
void set_rigid_word(uint w, float v) {
    if (w < CAP) px[w] = v;
    else if (w < 2u * CAP) py[w - CAP] = v;
    else if (w < 3u * CAP) pz[w - 2u * CAP] = v;
    else scratch[w - 3u * CAP] = floatBitsToUint(v);
}
float rigid_word(uint w) {
    if (w < CAP) return px[w];
    if (w < 2u * CAP) return py[w - CAP];
    if (w < 3u * CAP) return pz[w - 2u * CAP];
    return uintBitsToFloat(scratch[w - 3u * CAP]);
}

// The rigid start of a free object's slots (every invocation calls it): the guesses dx (from
// the bases x; x_n = x - hx.xyz, the prediction's x~ - x_n) moved as rigid_start says. The
// sums are taken about the first particle where the frame started (any point of the object
// does: the fit does not depend on it).
void rigid_start_slots(inout vec3 dx[MAX_SLOTS], vec3 x[MAX_SLOTS], vec4 hx[MAX_SLOTS], uvec2 cells[MAX_SLOTS],
                       uint masks[MAX_SLOTS], uint own[MAX_SLOTS], bool pinned[MAX_SLOTS]) {
    vec3 origin = p_in[0].pos.xyz;
    mat4 mine = mat4(0.0);
    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
        if (s < SLOTS && own[s] < CAP && !pinned[s]) mine += rigid_terms(x[s] - hx[s].xyz - origin, dx[s] + hx[s].xyz);
    }
    [[unroll]] for (int c = 0; c < 4; ++c) mine[c] = subgroupAdd(mine[c]);
    uint t = gl_LocalInvocationID.x;
    uint each = clamp((3u * CAP + SCRATCH) / gl_NumSubgroups, 1u, 16u);  // sums of a subgroup a round
    for (uint first = 0u; first < 16u; first += each) {
        uint last = min(first + each, 16u);
        if (subgroupElect()) {
            for (uint j = first; j < last; ++j) set_rigid_word(each * gl_SubgroupID + j - first, mine[j / 4u][j % 4u]);
        }
        barrier();
        if (t >= first && t < last) {
            float sum = 0.0;
            for (uint q = 0u; q < gl_NumSubgroups; ++q) sum += rigid_word(each * q + t - first);
            rigid_totals[t] = sum;
        }
        barrier();
    }
    mat4 sums;
    [[unroll]] for (uint j = 0u; j < 16u; ++j) sums[j / 4u][j % 4u] = rigid_totals[j];
    RigidMove move = rigid_fit(sums);
    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
        if (s >= SLOTS || own[s] >= CAP || pinned[s]) continue;
        spring_mask = masks[s];
        vec3 moved = hx[s].xyz;
        dx[s] = rigid_start(move, cells[s], x[s] - moved - origin, dx[s] + moved) - moved;
    }
}

// The shared spatial hash: scratch[h] is the first particle of bucket h, scratch[BUCKETS + j]
// the one after particle j (EMPTY ends a list) in its low bits (LINK_BITS; the top four may
// hold j's stretch count).
uint next_in_bucket(uint j) {
    uint next = scratch[BUCKETS + j] & LINK_BITS;
    return next == LINK_BITS ? EMPTY : next;
}
void visit_bucket(uint h, uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {
    float listed = list_build ? list_reach() : reach;
    for (uint j = scratch[h]; j != EMPTY; j = next_in_bucket(j)) {
        float d = distance(spos(j), x);
        if (d < listed && !rest_neighbour(cell, j, obj.self_distance)) {
            self_candidate(cell, x, j, d, reach, correction, n_active);
        }
    }
}

void listed_candidates(uvec2 cell, vec3 x, float reach, inout vec3 correction, inout uint n_active) {
    if (!LISTED || list_rebuild) {
        visit_cells(cell, x, reach, correction, n_active);
        return;
    }
    // (rest-state neighbours were left out when the list was built)
    for (uint e = 0u; e < list_len; ++e) self_listed(x, e, reach, correction, n_active);
}

// Particles of vertex colour c (springs.glsl: C colours) in row y of a grid of `cols` columns:
// x runs from the row's first of that colour in steps of C.
uint colour_row_count(uint c, uint y, uint cols, uint C) {
    uint first = colour_first(c, y, C);
    return first < cols ? (cols - 1u - first) / C + 1u : 0u;
}
// ... in rows [0, y): C consecutive rows hold every column once.
uint colour_before_row(uint c, uint y, uint cols, uint C) {
    uint sum = (y / C) * cols;
    for (uint q = (y / C) * C; q < y; ++q) sum += colour_row_count(c, q, cols, C);
    return sum;
}

// The particle of rank r: r itself, or for the Gauss-Seidel methods the particle of rank r in
// colour order (colour, row, column), so that the particles of a warp share a colour and a
// colour's pass runs only its own warps (in index order every warp holds all colours and
// each pass runs every warp at a fifth of its lanes).
uint particle_of_rank(uint r) {
    if (!COLOURED || r >= CAP) return r;
    if (is_mesh()) return mesh_coloured(0u, r);  // (the host's colour order: all colours in turn)
    uint cols = obj.dims.x;
    uint rows = obj.dims.y;
    uint C = vertex_colours(obj.dims);
    uint c = 0u;
    for (; c + 1u < C; ++c) {
        uint total = colour_before_row(c, rows, cols, C);
        if (r < total) break;
        r -= total;
    }
    uint y = (r / cols) * C;
    r -= (r / cols) * cols;
    for (uint rc = colour_row_count(c, y, cols, C); r >= rc; rc = colour_row_count(c, y, cols, C)) {
        r -= rc;
        y += 1u;
    }
    return colour_first(c, y, C) + C * r + y * cols;
}

void main() {
    obj = obj_buffer;
    float cell_inv = obj.cell_inv;  // the lists' builds widen the hash's cells to their reach
    uint t = gl_LocalInvocationID.x;
    uint n = particle_count();  // == CAP
    uint cols = obj.dims.x;
    const uint self_bits = OBJ_SELF_COLLISION | OBJ_SELF_HASH;
    bool hashed = has(F_SELF) && (obj.flags & self_bits) == self_bits;
    lists_built = LISTED && hashed && self_list[LIST_VALID] == 1u;
    bool stretch = has(F_STRETCH) && (obj.flags & OBJ_STRETCH_LIMIT) != 0u;
    bool self_any = has(F_SELF) && (obj.flags & OBJ_SELF_COLLISION) != 0u;
    bool self_triangles_on = self_any && triangle_contact();
    bool neighbours = stretch || self_any || has(F_EDGES);  // the constraints read other particles
    float drift = physics_drift();
    // The physics reads the neighbours' velocities for the dashpots (the iterative methods
    // treat them in their solve).
    bool stage_velocities = has(F_DAMPING) && !ITERATIVE;
    uint colours = is_mesh() ? mesh_colour_count() : vertex_colours(obj.dims);

    vec3 x[MAX_SLOTS];
    vec3 v[MAX_SLOTS];
    vec3 v_new[MAX_SLOTS];
    bool pinned[MAX_SLOTS];
    vec3 dy[MAX_SLOTS];  // iterative methods: the prediction y - x~
    vec3 dx[MAX_SLOTS];  // ... the iterate p - x~
    vec4 hx[MAX_SLOTS];  // ... the history x_n - x_{n-1} (w valid); during a solve, x~ - x_n
    vec4 hv[MAX_SLOTS];  // ... v_n - v_{n-1}, w: the fraction of gravity held (adaptive start)
    vec3 lost[MAX_SLOTS];  // ... what rounding the base left out (bdf2_start)
    // VBD's vertex colour of each slot; NO_COLOUR (no pass visits it) for a pinned or empty one,
    // so that a colour pass tests one word a slot.
    uint colour[MAX_SLOTS];
    uint own[MAX_SLOTS];  // the particle of each slot
    uvec2 cells[MAX_SLOTS];  // ... and its grid cell
    uint masks[MAX_SLOTS];   // ... and its springs (spring_mask)
    // Each particle's contact list header (list_header), kept here from the dispatch's start
    // on (read from the buffer every substep, it cost 1.5 to 2%).
    vec4 header[MAX_SLOTS];
    vec3 began[MAX_SLOTS];  // where each particle began the substep (friction)
    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
        uint k = particle_of_rank(t + s * THREADS);
        own[s] = k;
        cells[s] = uvec2(k % cols, k / cols);
        masks[s] = 0u;
        if (SPRING_MASKS) [[unroll]] for (int q = 0; q < 12; ++q) {
            if (neighbour(ivec2(cells[s]), SPRINGS[q].xy, obj.dims) >= 0) masks[s] |= 1u << uint(q);
        }
        x[s] = vec3(0.0);
        v[s] = vec3(0.0);
        v_new[s] = vec3(0.0);
        pinned[s] = true;
        dy[s] = vec3(0.0);
        dx[s] = vec3(0.0);
        hx[s] = vec4(0.0);
        hv[s] = vec4(0.0);
        lost[s] = vec3(0.0);
        header[s] = lists_built && s < SLOTS && k < n ? list_header(k) : vec4(0.0);
        if (s < SLOTS && k < n) {
            Particle p = p_in[k];
            pinned[s] = p.pos.w > 0.5;
            x[s] = p.pos.xyz;
            v[s] = p.vel.xyz;  // (a pinned particle's: its pins', physics_particle)
            if (ITERATIVE) {
                hx[s] = history[hist(k, H_DX)];
                hv[s] = history[hist(k, H_DV)];
            }
        }
        colour[s] = NO_COLOUR;
        if (COLOURED && !pinned[s]) colour[s] = is_mesh() ? mesh_colour_of_rank(t + s * THREADS) : vertex_colour(cells[s], colours);
    }
    for (uint w = t; w < (CAP + 31u) / 32u; w += THREADS) pin_bits[w] = 0u;
    if (t < 2u) list_flag[t] = 0u;
    if (t < 2u) pairs_kept[t] = 0u;
    barrier();
    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
        if (s >= SLOTS) break;
        uint k = own[s];
        if (k >= n) continue;
        if (pinned[s]) atomicOr(pin_bits[k >> 5u], 1u << (k & 31u));
        set_spos(k, x[s] + drift * v[s]);
    }

    for (uint sub = chunk.first; sub < chunk.first + chunk.count; ++sub) {
        air_time = float(sub) * g.dt;
        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) began[s] = has(F_COLLIDERS) || self_triangles_on ? x[s] : vec3(0.0);
        // Physics: forces on the drifted positions (and, with dashpots, the neighbours'
        // velocities staged pass by pass), new state into registers.
        [[unroll]] for (uint chunk = 0u; chunk < MAX_SLOTS; ++chunk) {
            if (chunk * PASS_SLOTS >= SLOTS) break;
            if (stage_velocities) {
                if (chunk > 0u) barrier();  // the pass before has read its window
                window_start = int(chunk * PASS_SLOTS * THREADS) - int(HALO);
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    int w = int(k) - window_start;
                    if (k < n && w >= 0 && w < int(WINDOW)) {
                        scratch[w] = floatBitsToUint(v[s].x);
                        scratch[WINDOW + uint(w)] = floatBitsToUint(v[s].y);
                        scratch[2u * WINDOW + uint(w)] = floatBitsToUint(v[s].z);
                    }
                }
            }
            barrier();
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                if (s / PASS_SLOTS != chunk || k >= n) continue;
                if (pinned[s]) {
                    // Moved with its pins (physics_particle, predict.comp: the iterative
                    // methods' base of the pins' steady motion, displacement 2 d / 3).
                    float pin_w = p_in[k].pos.w;  // (its pin group; the state is stored at the end)
                    vec3 d = pin_move(x[s], sub, pin_w);
                    v_new[s] = pin_velocity_of(d, pin_w);
                    if (ITERATIVE) {
                        x[s] += d * (1.0 - solve_share());
                        dy[s] = d * solve_share();
                        dx[s] = dy[s];
                    } else {
                        x[s] += d;
                    }
                    continue;
                }
                if (ITERATIVE) {
                    spring_mask = masks[s];
                    vec3 base;
                    vec3 pull;
                    dy[s] = predicted_displacement(cells[s], x[s], v[s], hx[s], hv[s].xyz, base, pull);
                    // The solve's start (shared after the barrier below).
                    precise vec3 start;
                    precise vec3 missed;
                    bdf2_start(x[s], base, start, missed);
                    dy[s] += missed;
                    lost[s] = missed;
                    precise vec3 moved = start - x[s];  // x~ - x_n, exact
                    dx[s] = ADAPTIVE_START ? adaptive_start(cells[s], dy[s], pull, hx[s], hv[s].w, -moved, x[s], sub) : dy[s];
                    hx[s].xyz = moved;
                    x[s] = start;
                    continue;
                }
                vec3 xs = x[s] + drift * v[s];
                vec3 vs = v[s];
                spring_mask = masks[s];
                physics_step(cells[s], xs, vs);
                x[s] = xs;
                v_new[s] = vs;
            }
        }
        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
            if (s < SLOTS && !ITERATIVE) v[s] = v_new[s];
        }
        barrier();  // every read of this substep's positions and velocities is done

        if (ITERATIVE) {
            if (ADAPTIVE_START && (obj.flags & OBJ_RIGID_START) != 0u) {
                rigid_start_slots(dx, x, hx, cells, masks, own, pinned);
            }
            // The solve, from where the iterate starts (dx: the prediction dy, or VBD's
            // adaptive start); px/py/pz hold the bases x~ (COMPACT: the iterates x~ + dx).
            // XPBD: the multipliers of each particle's forward springs (by Jacobi: of its 12)
            vec4 lambda[MAX_SLOTS][3];
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                lambda[s] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
                if (k < n) {
                    set_spos(k, COMPACT ? x[s] + dx[s] : x[s]);
                    set_sdisp(k, dx[s]);
                }
            }
            barrier();
            // One iteration (a pipeline of its own): XPBD's multipliers start and stay at zero.
            uint iterations = ONE_ITERATION ? 1u : g.iterations;
            if (SOLVER == METHOD_IMPLICIT) {
                // Newton steps of preconditioned conjugate gradients (implicit_iterate.comp's
                // passes, here parted by barriers, the dot products by workgroup_sum).
                vec3 dp[MAX_SLOTS];   // the Newton step's move
                vec3 r[MAX_SLOTS];    // the residual
                vec3 z[MAX_SLOTS];    // P r
                vec3 d[MAX_SLOTS];    // the direction
                vec3 q[MAX_SLOTS];    // H d
                vec3 pre0[MAX_SLOTS]; // P (sym3_inverse's rows)
                vec3 pre1[MAX_SLOTS];
                for (uint k0 = 0u; k0 < iterations; k0 += NEWTON_CG_ITERATIONS) {
                    float mine = 0.0;
                    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                        if (s >= SLOTS) break;
                        r[s] = vec3(0.0);
                        pre0[s] = vec3(0.0);
                        pre1[s] = vec3(0.0);
                        dp[s] = vec3(0.0);
                        if (own[s] < n && !pinned[s]) {
                            spring_mask = masks[s];
                            Sym3 hessian;
                            r[s] = newton_particle(cells[s], x[s], dx[s], dy[s], hessian);
                            sym3_inverse(hessian, pre0[s], pre1[s]);
                        }
                        z[s] = sym3_apply(pre0[s], pre1[s], r[s]);
                        mine += dot(r[s], z[s]);
                    }
                    float rz = workgroup_sum(mine);  // (after its barrier every linearisation is done)
                    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                        if (s < SLOTS && own[s] < n) set_spos(own[s], x[s] + dx[s]);
                    }
                    uint count = min(NEWTON_CG_ITERATIONS, iterations - k0);
                    float rz_before = 0.0;
                    for (uint c = 0u; c < count; ++c) {
                        float beta = rz_before > 0.0 ? rz / rz_before : 0.0;
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s >= SLOTS) break;
                            d[s] = c == 0u ? z[s] : z[s] + beta * d[s];
                            if (own[s] < n) set_sdisp(own[s], d[s]);
                        }
                        barrier();
                        mine = 0.0;
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s >= SLOTS) break;
                            q[s] = vec3(0.0);
                            if (own[s] < n && !pinned[s]) {
                                spring_mask = masks[s];
                                q[s] = hessian_product(cells[s], x[s] + dx[s], d[s]);
                            }
                            mine += dot(d[s], q[s]);
                        }
                        float dq = workgroup_sum(mine);
                        float alpha = dq > 0.0 ? rz / dq : 0.0;
                        mine = 0.0;
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s >= SLOTS) break;
                            dp[s] += alpha * d[s];
                            r[s] -= alpha * q[s];
                            z[s] = sym3_apply(pre0[s], pre1[s], r[s]);
                            mine += dot(r[s], z[s]);
                        }
                        rz_before = rz;
                        rz = workgroup_sum(mine);
                    }
                    if ((obj.flags & OBJ_LINE_SEARCH) != 0u) {
                        // The line search (implicit_iterate.comp's PHASE_SEARCH and PHASE_MOVE):
                        // r0.dp from the linearisation's state again (bases and displacements
                        // shared: r0 kept in registers through CG would cost every run), then
                        // newton_descent from p and the steps.
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s < SLOTS && own[s] < n) {
                                set_spos(own[s], x[s]);
                                set_sdisp(own[s], dx[s]);
                            }
                        }
                        barrier();
                        float r0dp[MAX_SLOTS];
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            r0dp[s] = 0.0;
                            if (s < SLOTS && own[s] < n && !pinned[s]) {
                                spring_mask = masks[s];
                                Sym3 hessian;
                                r0dp[s] = dot(newton_particle(cells[s], x[s], dx[s], dy[s], hessian), dp[s]);
                            }
                        }
                        barrier();
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s < SLOTS && own[s] < n) {
                                set_spos(own[s], x[s] + dx[s]);
                                set_sdisp(own[s], dp[s]);
                            }
                        }
                        barrier();
                        vec4 change = vec4(0.0);
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s < SLOTS && own[s] < n) {
                                spring_mask = masks[s];
                                change += newton_descent(cells[s], x[s] + dx[s], dp[s], r0dp[s]);
                            }
                        }
                        vec4 total = vec4(workgroup_sum(change.x), workgroup_sum(change.y), workgroup_sum(change.z), workgroup_sum(change.w));
                        float step = line_search_step(total);
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) dp[s] *= step;
                    }
                    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                        if (s >= SLOTS) break;
                        dx[s] += dp[s];
                        if (own[s] < n) {
                            set_spos(own[s], x[s]);
                            set_sdisp(own[s], dx[s]);
                        }
                    }
                    barrier();
                }
            } else for (uint it = 0u; it < iterations; ++it) {
                if (SOLVER == METHOD_XPBD) {
                    // The spring classes (springs.glsl) in turn: the thread owning a spring's
                    // first node moves both ends (no other spring of the class touches them).
                    float w = 1.0 / obj_buffer.mass;
                    [[unroll]] for (uint pass = 0u; pass < SPRING_CLASS_COUNT; ++pass) {
                        uint q = xpbd_class(pass);
                        uint dir = q >> 1u;
                        int slot = class_slot(dir);
                        if (obj_buffer.stiffness[slot >> 2] != 0.0) {
                            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                                if (s >= SLOTS) break;
                                uint i = own[s];
                                if (i >= n) continue;
                                ivec2 a = ivec2(cells[s]);
                                if (class_parity(dir, a) != (q & 1u)) continue;
                                int j = neighbour(a, class_offset(dir), obj.dims);
                                if (j < 0) continue;
                                bool pin_j = spinned(uint(j));
                                if (pinned[s] && pin_j) continue;
                                vec3 di = sdisp(i);
                                vec3 dj = sdisp(uint(j));
                                vec3 normal;
                                float lam = ONE_ITERATION ? 0.0 : lambda[s][dir / 4u][dir % 4u];
                                float dl = xpbd_spring(class_slot(dir), x[s], di, spos(uint(j)), dj, pinned[s], pin_j, lam, normal);
                                if (!pinned[s]) set_sdisp(i, di + normal * (w * dl));
                                if (!pin_j) set_sdisp(uint(j), dj - normal * (w * dl));
                                if (!ONE_ITERATION) lambda[s][dir / 4u][dir % 4u] = lam + dl;
                            }
                        }
                        barrier();  // the next class reads this one's displacements
                    }
                } else if (SOLVER == METHOD_XPBD_JACOBI) {
                    vec3 next[MAX_SLOTS];
                    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                        if (s >= SLOTS) break;
                        next[s] = dx[s];
                        if (own[s] < n && !pinned[s]) {
                            spring_mask = masks[s];
                            next[s] = xpbd_jacobi_particle(cells[s], x[s], dx[s], lambda[s]);
                        }
                    }
                    barrier();  // every read of this iteration's displacements is done
                    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                        if (s >= SLOTS) break;
                        dx[s] = next[s];
                        if (!ONE_ITERATION && own[s] < n) set_sdisp(own[s], dx[s]);
                    }
                    if (!ONE_ITERATION) barrier();
                } else if (COLOURED) {
                    for (uint c = 0u; c < colours; ++c) {
                        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                            if (s >= SLOTS) break;
                            uint k = own[s];
                            if (colour[s] != c) continue;
                            uvec2 cell = cells[s];
                            spring_mask = masks[s];
                            dx[s] = vbd_particle(cell, x[s], dx[s], dy[s]);
                            set_sdisp(k, dx[s]);
                            if (COMPACT) set_spos(k, x[s] + dx[s]);
                        }
                        barrier();  // the next colour reads this one's displacements
                    }
                }
            }
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                if (pinned[s]) {
                    x[s] += dx[s];  // (where its pins are at the substep's end)
                    v[s] = v_new[s];
                    continue;
                }
                if (SOLVER == METHOD_XPBD && own[s] < n) dx[s] = sdisp(own[s]);  // moved by springs
                x[s] += dx[s];
                vec3 v_next = (dx[s] - lost[s]) * (1.0 / solve_dt());  // (v[s] is still v_n)
                hx[s] = vec4(hx[s].xyz + dx[s], 1.0);  // x_{n+1} - x_n
                hv[s] = vec4(v_next - v[s], ADAPTIVE_START ? held_fraction(dx[s], dy[s]) : 0.0);
                v[s] = v_next;
            }
            // XPBD read its displacements back from scratch, which the self-collision hash reuses.
            if (SOLVER == METHOD_XPBD && hashed) barrier();
        }

        // Constraints on the new positions: shared for the neighbours, hashed for contacts.
        if (neighbours) {
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                if (k < n) set_spos(k, x[s]);
            }
            if (hashed && LISTED) {
                // Has a particle moved half the skin since its list was built (or did its
                // list overflow: built at infinity)? Is one so fast that a list built now
                // would not outlast the next substep?
                float half_skin = list_half_skin();
                bool moved = false;
                bool fast = false;
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k >= n || pinned[s]) continue;
                    moved = moved || !(distance(x[s], header[s].xyz) <= half_skin);
                    fast = fast || length(v[s]) * g.dt > half_skin;
                }
                uint flags = (moved ? LIST_MOVED : 0u) | (fast ? LIST_FAST : 0u);
                if (flags != 0u) atomicOr(list_flag[sub & 1u], flags);
            } else if (hashed) {
                for (uint b = t; b < BUCKETS; b += THREADS) scratch[b] = EMPTY;
            }
            barrier();
            if (hashed && LISTED && lists_built && cloth_edge_pairs()) {
                // Has an edge creased that the lists hold no pairs of (creases.glsl)? Every
                // position is shared by now.
                bool creased = false;
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k >= n) continue;
                    creased = creased || creased_past_lists(ring_crease_masks(k, x[s]), uint(self_pairs[creases_word(k)]));
                }
                if (creased) atomicOr(list_flag[sub & 1u], LIST_MOVED);
                barrier();
            }
            bool rebuild = hashed;
            list_build = false;
            if (hashed && LISTED) {
                // The same for every thread. A substep whose lists would not outlast it
                // searches the hash alone, with cells of the contact distance, and builds no
                // lists (those of an earlier build stay exact while nothing has moved half
                // the skin from it).
                uint flags = list_flag[sub & 1u];
                rebuild = !lists_built || (flags & LIST_MOVED) != 0u;
                list_build = rebuild && (flags & LIST_FAST) == 0u;
                lists_built = lists_built || list_build;
                if (list_build && t == 0u) self_list[LIST_VALID] = 1u;  // read by the next dispatch
                if (t == 0u) list_flag[(sub + 1u) & 1u] = 0u;  // read again after two barriers
                if (rebuild) {
                    obj.cell_inv = list_build ? cell_inv * (self_reach() / list_reach()) : cell_inv;
                    for (uint b = t; b < BUCKETS; b += THREADS) scratch[b] = EMPTY;
                    barrier();
                }
            }
            list_rebuild = rebuild;
            bool creases = cloth_edge_pairs();  // (a rope's are all creased)
            if (rebuild) {
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k >= n) continue;
                    hash_insert(k, x[s]);
                    // (how creased its ring edges are, which the search reads for every
                    // candidate)
                    if (creases) write_creases(k, x[s], list_build);
                }
                if (creases) memoryBarrierBuffer();
                barrier();
            }
        }
        if (self_triangles_on) {
            // A cloth's contact with its own triangles (self_contact.glsl): every particle
            // finds and counts its contacts, then applies them, into sums in self_pairs that
            // the constraints read (global memory: a buffer barrier with each barrier). The
            // two passes are one loop, so that the contact tests are compiled once.
            [[dont_unroll]] for (uint pass = 0u; pass < 2u; ++pass) {
                bool apply = pass == 1u;
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k >= n) continue;
                    list_particle = k;
                    list_len = LISTED && hashed && !list_rebuild ? floatBitsToUint(header[s].w) : 0u;
                    self_pass(cells[s], k, x[s], began[s], apply);
                    if (!apply && pair_len > 0u) pairs_kept[sub & 1u] = 1u;
                    if (!apply && LISTED && hashed && list_build) header[s] = set_list_header(k, x[s], list_len);
                }
                memoryBarrierBuffer();
                barrier();
            }
            // Further passes (obj.contact_iterations, where some particle found a contact): the
            // positions and velocities moved by the sums, then the kept contacts applied again
            // from there.
            uint passes = pairs_kept[sub & 1u] != 0u ? obj.contact_iterations : 1u;
            if (t == 0u) pairs_kept[(sub + 1u) & 1u] = 0u;  // read again after many barriers
            [[dont_unroll]] for (uint pass = 1u; pass < passes; ++pass) {
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k >= n || pinned[s]) continue;
                    self_move(k, x[s], v[s]);
                    set_spos(k, x[s]);
                }
                memoryBarrierBuffer();
                barrier();
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k < n) self_reapply(k, x[s]);
                }
                memoryBarrierBuffer();
                barrier();
            }
        }
        if (STRETCH_AT != 0u && stretch) {
            // Each particle's count of stretched springs, from the shared positions (final
            // since the last barrier), for its neighbours' constraints.
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                if (k >= n) continue;
                set_stretched(k, stretched_springs(ivec2(cells[s]), x[s]));
            }
            barrier();
        }
        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
            if (s >= SLOTS) break;
            uint k = own[s];
            if (k >= n || pinned[s]) continue;
            vec3 xs = x[s];
            vec3 vs = v[s];
            if (neighbours) {
                spring_mask = masks[s];
                list_particle = k;
                list_len = LISTED && hashed && !list_rebuild ? floatBitsToUint(header[s].w) : 0u;
                vec3 correction = constraint_correction(cells[s], xs);
                if (LISTED && hashed && list_build && !self_triangles_on) {
                    header[s] = set_list_header(k, xs, list_len);
                }
                xs += correction;
                vs += (correction - position_only) / g.dt;  // velocity follows the position correction
            }
            visiting_start = began[s];
            float since = float(sub + 1u) * g.dt;
            collide_all(cells[s], xs, vs, since);
            x[s] = xs;
            v[s] = vs;
        }
        if (neighbours) barrier();  // every read of the shared positions and hash is done
        if (neighbours && self_triangles_on && cloth_edge_pairs()) {
            // Each particle's move truncated by the pairs near where the particles began the
            // substep (self_contact.glsl's note_truncation): the constraints' results into
            // p_out (TRUNC_POS), the starts into the shared positions, the shared hash built
            // from there with cells of the search's reach and each particle's ring creases
            // there, each particle's pairs noted, then each move truncated.
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                if (k >= n) continue;
                p_out[k].pos.xyz = x[s];
                set_spos(k, began[s]);
            }
            if (hashed) {
                obj.cell_inv = cell_inv;
                for (uint b = t; b < BUCKETS; b += THREADS) scratch[b] = EMPTY;
            }
            memoryBarrierBuffer();
            barrier();
            if (hashed) {
                [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                    if (s >= SLOTS) break;
                    uint k = own[s];
                    if (k >= n) continue;
                    hash_insert(k, began[s]);
                    write_creases(k, began[s], false);
                }
                memoryBarrierBuffer();
                barrier();
            }
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                if (k < n) note_truncation(k);
            }
            memoryBarrierBuffer();
            barrier();
            [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
                if (s >= SLOTS) break;
                uint k = own[s];
                if (k >= n || pinned[s]) continue;
                visiting_start = began[s];
                if (truncate_move(k, began[s], x[s], v[s])) collide(x[s], v[s], float(sub + 1u) * g.dt);
            }
        }
        [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
            if (s >= SLOTS) break;
            uint k = own[s];
            if (k < n) set_spos(k, x[s] + drift * v[s]);
        }
    }

    [[unroll]] for (uint s = 0u; s < MAX_SLOTS; ++s) {
        if (s >= SLOTS) break;
        uint k = own[s];
        if (k < n) p_in[k] = Particle(vec4(x[s], pinned[s] ? p_in[k].pos.w : 0.0), vec4(v[s], 0.0));
        if (ITERATIVE && k < n) {
            history[hist(k, H_DX)] = pinned[s] ? vec4(0.0) : hx[s];
            history[hist(k, H_DV)] = pinned[s] ? vec4(0.0) : hv[s];
        }
    }
}
