// The self-collision contact lists, shared by fused.comp and the per-stage shaders. When the
// spatial hash is built, each particle records in self_list (binding 15) what is within the
// contact distance plus a skin (list_skin() times the self-collision distance): in a rope the
// other particles, rest-state neighbours left out; in a cloth the triangles (and with edge
// contact the edge pairs it owns) not left out (self_contact.glsl); and where it was built. The
// substeps after walk their lists instead of searching the hash, until some particle has moved
// more than half the skin from where its list was built (then no pair missing from a list can
// have come within the contact distance: a distance between particles, from a particle to a
// triangle or between two edges, changes no more than the largest move of the particles
// involved) or a list overflowed (built at infinity: it counts
// as moved). Layout for n particles:
// particle i's header (where its list was built, xyz, and its length, as bits) in words
// [4 i, 4 i + 4), its entry e at list_entry(e, i, n). The host makes every list invalid
// whenever something outside the shaders changes the state or the parameters.
// Include after bindings.glsl.
#ifndef MSD_LISTS_GLSL
#define MSD_LISTS_GLSL
#include "features.glsl"

// The skin, in self-collision distances: for particle contact, and for a cloth's triangles. A
// larger skin rebuilds less often but walks longer lists. In a cloth every triangle nearer
// than the skin's reach in the plane is listed though only a fold can bring it within the
// contact distance, so its lists grow faster with the skin (docs/PERFORMANCE.md, "Contact
// lists of triangle self-contact", has the measurements).
const float LIST_SKIN = 1.0;
const float TRIANGLE_LIST_SKIN = 0.75;

// How far a cloth's diagonals may stretch with every triangle within the contact distance
// still found through its nearest vertex (sim::model::TRIANGLE_STRETCH).
const float TRIANGLE_STRETCH = 1.5;

// Whether self-contact is against triangles (a cloth that asks for it; else particle against
// particle).
// Compiled out where no object asks for it (F_TRIANGLES: the particle search stays as lean).
bool has_triangles() { return has(F_TRIANGLES) && (obj.flags & OBJ_SELF_TRIANGLES) != 0u; }
// The skin of this object's lists.
float list_skin() { return has_triangles() ? TRIANGLE_LIST_SKIN : LIST_SKIN; }

// How far from a particle self-contact candidates (particles; in a cloth the vertices through
// which its triangles are found) are searched when a triangle or particle within `within` of
// it must be found: a triangle has its vertex nearest the particle within half its longest
// edge (a grid diagonal stretched by TRIANGLE_STRETCH) more. The hash's cells are twice the
// reach. sim::model::ObjectModel::self_reach is the twin.
float vertex_reach(float within) {
    return has_triangles() ? within + 0.5 * TRIANGLE_STRETCH * length(obj.spacing) : within;
}
float self_reach() { return vertex_reach(obj.self_distance); }
// What the lists hold: what is within the contact distance plus the skin ...
float list_within() { return (1.0 + list_skin()) * obj.self_distance; }
// ... and how far from a particle candidates are searched while they are built.
float list_reach() { return vertex_reach(list_within()); }

// The object's self-collision searches the spatial hash (and keeps these lists).
bool self_hashed() {
    const uint bits = OBJ_SELF_COLLISION | OBJ_SELF_HASH;
    return (obj.flags & bits) == bits;
}

// Entries a particle at most (sim::gpu::fused::SELF_LIST_ENTRIES).
const uint LIST_ENTRIES = 32u;
// How far a particle may move from where its list was built (2% less, for rounding).
float list_half_skin() { return 0.49 * list_skin() * obj.self_distance; }
uint list_entry(uint e, uint i, uint n) { return 4u * n + e * n + i; }
vec3 list_built(uint i) {
    return vec3(uintBitsToFloat(self_list[4u * i]), uintBitsToFloat(self_list[4u * i + 1u]),
                uintBitsToFloat(self_list[4u * i + 2u]));
}
// Particle i's header as a vec4: where its list was built (xyz) and its length (w, as bits).
vec4 list_header(uint i) {
    return vec4(list_built(i), uintBitsToFloat(self_list[4u * i + 3u]));
}
// Records where particle i's list of `len` entries was built and returns the header; a full
// one (len > LIST_ENTRIES) is built at infinity, so it counts as moved and is built again the
// next substep.
vec4 set_list_header(uint i, vec3 x, uint len) {
    bool full = len > LIST_ENTRIES;
    vec3 at = full ? vec3(uintBitsToFloat(0x7F800000u)) : x;
    uint kept = full ? 0u : len;
    self_list[4u * i] = floatBitsToUint(at.x);
    self_list[4u * i + 1u] = floatBitsToUint(at.y);
    self_list[4u * i + 2u] = floatBitsToUint(at.z);
    self_list[4u * i + 3u] = kept;
    return vec4(at, uintBitsToFloat(kept));
}

// Per stage (the hash built by dispatches of their own) the lists are used while they last:
// the host turns them off for a while (`sim::gpu::hash`'s policy) when most substeps rebuild
// them, and then, as without lists, every substep builds the hash (cells of twice the contact
// distance, the counts taken by the pass that writes the positions) and searches it.
// With lists on, the words after the lists hold, for each substep parity q, a control block at
// list_control(q): word 0 says that this substep rebuilds the hash and the lists; from word
// LIST_DISPATCHES, the indirect dispatches (x, y, z workgroups) of the hash's passes, 3 words
// each: the count and the scatter, then the scan; all zero when the substep rebuilds nothing.
// The pass that writes a substep's new positions sets them (note_position, hash_count.glsl);
// the constraints read word 0 and zero the other parity's block for the next substep; the host
// zeroes both when a frame starts. `sim::gpu::object::list_control_range` and
// `list_dispatch_offset` mirror this.
const uint LIST_DISPATCHES = 1u;
const uint LIST_CONTROL_WORDS = 16u;
uint list_control(uint substep) {
    return (4u + LIST_ENTRIES) * particle_count() + LIST_CONTROL_WORDS * (substep & 1u);
}
// After the two blocks, two counters the constraints keep (never cleared, they wrap): substeps
// run with lists on, and those of them that rebuilt. The surface stage copies them to the
// guard, which the host reads after each frame.
uint list_counters() { return (4u + LIST_ENTRIES) * particle_count() + 2u * LIST_CONTROL_WORDS; }

// Called by one invocation of the surface stage.
void report_lists() {
    if (!self_hashed()) return;
    guard_lists_on = self_list[list_counters()];
    guard_lists_rebuilt = self_list[list_counters() + 1u];
}

#endif
