// How creased a cloth's edges are, for its edge-edge contact (self_contact.glsl), which keeps an
// edge pair only where one of its edges is creased. Each particle's six ring edges are judged
// once where the spatial hash is built (hash_scatter.comp, fused.comp; truncation_hash.comp
// and fused.comp's truncation from the substep's starts) into a word of
// self_pairs that the searches read for every candidate (a ring's six positions and six sags
// a candidate otherwise); brute force computes them as it goes.
// Include after bindings.glsl, with CPOS(j) (particle j's position) defined.
#ifndef MSD_CREASES_GLSL
#define MSD_CREASES_GLSL
#include "triangle.glsl"
#include "self_pairs_layout.glsl"

// Whether grid cell q is in the grid.
bool in_grid(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(obj.dims))); }

// An edge pair takes part only where one of its edges is creased. Two edges each inside a
// flat stretch of cloth cannot come through each other without a vertex meeting a triangle
// first (the vertex-triangle contacts hold that), but across a crease (a fold's ridge, the
// border) an edge can: its ends held h from the faces on either side, its middle still
// reaches the ridge. How creased an edge is: the sag, in h, of a chord half a grid diagonal
// long laid across it at the two triangles' dihedral angle phi, (0.5 |spacing| / h) tan(phi / 2);
// on the border, or with a degenerate triangle, infinite. Its weight rises from 0 at a sag of
// CREASE_FROM to 1 at CREASE_TO (smooth, so that f32 and the CPU twin's f64 agree but for
// rounding). Twin: sim::cpu::self_contact::crease_sag.
const float CREASE_FROM = 0.1;
const float CREASE_TO = 0.2;
// While the lists are built, edge pairs are recorded from a sag of this (the crease may grow
// before the next build; a pair whose edges both sag less then and creased past CREASE_FROM
// before the next build is missed until it).
const float CREASE_LIST = 0.05;
float crease_sag(vec3 u, vec3 v, vec3 o1, vec3 o2) {
    vec3 e = v - u;
    vec3 n1 = cross(e, o1 - u);
    vec3 n2 = cross(o2 - u, e);
    float l = length(n1) * length(n2);
    float flat_part = l + dot(n1, n2);
    if (!(l > 0.0) || !(flat_part > 1e-12 * l)) return 1e30;
    return 0.5 * length(obj.spacing) / obj.self_distance * length(cross(n1, n2)) / flat_part;
}
float crease_weight(float sag) { return clamp((sag - CREASE_FROM) * (1.0 / (CREASE_TO - CREASE_FROM)), 0.0, 1.0); }
// Which of grid vertex u's (at x) six ring edges are creased: bit k (the edge to ring vertex k)
// when its sag passes CREASE_LIST, bit 8 + k when it passes CREASE_FROM (an edge on the border
// counts as creased; edges outside the grid, 0). The ring's positions are read once.
uint ring_crease_masks(uint u, vec3 x) {
    ivec2 q = ivec2(int(u % obj.dims.x), int(u / obj.dims.x));
    bool ok[6];
    vec3 r[6];
    [[unroll]] for (int k = 0; k < 6; ++k) {
        ivec2 qk = q + VERTEX_RING[k];
        ok[k] = in_grid(qk);
        r[k] = ok[k] ? CPOS(uint(qk.x + qk.y * int(obj.dims.x))) : x;
    }
    uint masks = 0u;
    [[unroll]] for (int k = 0; k < 6; ++k) {
        if (!ok[k]) continue;
        int k0 = (k + 5) % 6;
        int k2 = (k + 1) % 6;
        bool border = !ok[k0] || !ok[k2];
        float sag = border ? 0.0 : crease_sag(x, r[k], r[k0], r[k2]);
        if (border || sag > CREASE_LIST) masks |= 1u << uint(k);
        if (border || sag > CREASE_FROM) masks |= 0x100u << uint(k);
    }
    return masks;
}

// Of those masks, the one a search uses: while it builds the contact lists (`listing`), from
// CREASE_LIST, else from CREASE_FROM.
uint crease_mask(uint masks, bool listing) { return listing ? masks & 0x3Fu : (masks >> 8u) & 0x3Fu; }

// The fused kernel's word of a particle's creases (self_pairs' creases_word): the masks of this
// build, and in bits 16 to 21 the edges the contact lists hold pairs of, from CREASE_LIST at
// their last build (`listing`: this build's; else kept from the word before, `previous`).
uint listed_crease_word(uint masks, uint previous, bool listing) {
    return masks | (listing ? (masks & 0x3Fu) << 16u : previous & 0x3F0000u);
}
// Whether an edge of the ring creased past CREASE_FROM (`masks` now) that the lists, as their
// word says, hold no pairs of: the lists miss that edge's pairs, so they are rebuilt. (The
// lists' skin bounds how far a particle moves, not how far its ring edges bend.)
bool creased_past_lists(uint masks, uint word) { return ((masks >> 8u) & ~(word >> 16u) & 0x3Fu) != 0u; }

#endif
