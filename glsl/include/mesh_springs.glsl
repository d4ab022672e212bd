// A cloth made from a mesh (F_CLOTH_MESH; sim::cloth_mesh): its springs, colours, triangles
// and each particle's ring of triangles as lists, in the words after the object's parameters
// (obj_words; ClothMesh::pack writes them). A mesh cloth's dims are (particles, 1), so a
// particle's "cell" is (i, 0). The grid's loops stay as they are; each has a mesh branch that
// the feature bit compiles out of a grid's pipelines.
// Include after bindings.glsl.
#ifndef MSD_MESH_SPRINGS_GLSL
#define MSD_MESH_SPRINGS_GLSL
#include "features.glsl"

bool is_mesh() { return has(F_CLOTH_MESH); }

// Where the lists start: the header's six words.
uint mesh_springs_at() { return obj_words[0]; }
uint mesh_colours_at() { return obj_words[1]; }
uint mesh_triangles_at() { return obj_words[2]; }
uint mesh_rings_at() { return obj_words[3]; }
uint mesh_masses_at() { return obj_words[4]; }
uint mesh_classes_at() { return obj_words[5]; }

// Particle i's springs are entries [mesh_first(i), mesh_first(i + 1)).
uint mesh_first(uint i) { return obj_words[6u + i]; }

// Particle i's mass over the object's `mass`: 1 for a grid's; for a mesh's its share, an equal
// part of each of its faces' area over the mean (ClothMesh::mass_share).
float mass_share(uint i) { return is_mesh() ? uintBitsToFloat(obj_words[mesh_masses_at() + i]) : 1.0; }
// The mass of particle `cell` [kg].
float particle_mass(uvec2 cell) { return obj.mass * mass_share(cell.x); }

// The stiffness of a spring of `type`: the grid's three types, or 3 a seam (rest length zero,
// sim::cloth_mesh::SEAM) [N/m].
const uint SPRING_SEAM = 3u;
float mesh_stiffness(uint type) { return type == SPRING_SEAM ? obj.seam : obj.stiffness[type]; }

// Entry e of the lists: the other end, the type (SPRING_STRUCTURAL, _SHEAR, _BENDING,
// SPRING_SEAM), the rest length (the object's rest_scale in it) and the stiffness.
struct MeshSpring {
    int other;
    uint type;
    float rest;
    float k;
};
MeshSpring mesh_spring(uint e) {
    uint at = mesh_springs_at() + 2u * e;
    uint a = obj_words[at];
    uint type = a >> 30;
    return MeshSpring(int(a & 0x3FFFFFFFu), type, uintBitsToFloat(obj_words[at + 1u]), mesh_stiffness(type));
}

// The hot loops (forces, VBD's Newton step) walk a particle's list in batches of MESH_BATCH
// entries: a batch's records, then its neighbours' positions, are read before any is used, so
// that their loads are in flight together rather than one dependent pair a spring. An entry
// at or past the list's end (e >= end; the loops run only over a list of one entry or more)
// reads the last entry again, which the loop skips.
const uint MESH_BATCH = 4u;
MeshSpring mesh_batch(uint e, uint end) { return mesh_spring(min(e, end - 1u)); }

// Whether mesh vertex w is u or joined to it by a structural, shear or seam spring.
bool mesh_joined(uint u, uint w) {
    if (w == u) return true;
    for (uint e = mesh_first(u); e < mesh_first(u + 1u); ++e) {
        uint a = obj_words[mesh_springs_at() + 2u * e];
        if ((a & 0x3FFFFFFFu) == w && (a >> 30) != SPRING_BENDING) return true;
    }
    return false;
}

// Whether mesh vertex j is in particle p's one-ring, as a grid's eight neighbours are: joined
// to it by a structural, shear or seam spring, vertices a seam sews together counting as one
// (the one-ring of either is both's; sim::cloth_mesh::ClothMesh::linked). Self-contact leaves
// out the triangles it touches.
bool mesh_linked(uint p, uint j) {
    if (mesh_joined(p, j)) return true;
    for (uint e = mesh_first(p); e < mesh_first(p + 1u); ++e) {
        uint a = obj_words[mesh_springs_at() + 2u * e];
        if ((a >> 30) != SPRING_SEAM) continue;
        uint u = a & 0x3FFFFFFFu;
        if (mesh_joined(u, j)) return true;
        for (uint f = mesh_first(j); f < mesh_first(j + 1u); ++f) {
            uint b = obj_words[mesh_springs_at() + 2u * f];
            if ((b >> 30) == SPRING_SEAM && mesh_joined(u, b & 0x3FFFFFFFu)) return true;
        }
    }
    for (uint f = mesh_first(j); f < mesh_first(j + 1u); ++f) {
        uint b = obj_words[mesh_springs_at() + 2u * f];
        if ((b >> 30) == SPRING_SEAM && mesh_joined(p, b & 0x3FFFFFFFu)) return true;
    }
    return false;
}

// The colouring the Gauss-Seidel sweeps take: its count, and the k-th particle of colour c
// (k < mesh_colour_size(c)).
uint mesh_colour_count() { return obj_words[mesh_colours_at()]; }
uint mesh_colour_size(uint c) {
    uint at = mesh_colours_at() + 1u;
    return obj_words[at + c + 1u] - obj_words[at + c];
}
uint mesh_coloured(uint c, uint k) {
    uint at = mesh_colours_at() + 1u;
    return obj_words[at + mesh_colour_count() + 1u + obj_words[at + c] + k];
}

// The colour of the particle at place r of the colour order (mesh_coloured(0, r)).
uint mesh_colour_of_rank(uint r) {
    uint at = mesh_colours_at() + 1u;
    uint c = 0u;
    while (c + 1u < mesh_colour_count() && obj_words[at + c + 1u] <= r) ++c;
    return c;
}

// XPBD's spring classes (packed with XPBD by spring classes only): their count, and the k-th
// spring of class c (k < mesh_class_size(c)) as its lower end and its entry in that end's list.
uint mesh_class_count() { return obj_words[mesh_classes_at()]; }
uint mesh_class_size(uint c) {
    uint at = mesh_classes_at() + 1u;
    return obj_words[at + c + 1u] - obj_words[at + c];
}
uvec2 mesh_class_spring(uint c, uint k) {
    uint at = mesh_classes_at() + 1u;
    uint first = at + mesh_class_count() + 1u + 2u * (obj_words[at + c] + k);
    return uvec2(obj_words[first], obj_words[first + 1u]);
}

// Triangle t's corners.
uvec3 mesh_triangle(uint t) {
    uint at = mesh_triangles_at() + 3u * t;
    return uvec3(obj_words[at], obj_words[at + 1u], obj_words[at + 2u]);
}
// Particle i's triangles are mesh_ring_triangle(k) for k in [mesh_ring_first(i),
// mesh_ring_first(i + 1)).
uint mesh_ring_first(uint i) { return obj_words[mesh_rings_at() + i]; }
uint mesh_ring_triangle(uint k) { return obj_words[mesh_rings_at() + particle_count() + 1u + k]; }

#endif
