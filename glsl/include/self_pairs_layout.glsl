// The layout of a cloth's self-contact buffer, self_pairs (binding 17), n particles: words
// [4 i, 4 i + 4) particle i's sum (x, y, z in units of h / 2^26) and count (in units of
// 2^-16); 4 n + i the number of contacts it found (split among lanes, their counter, which
// the truncate pass zeroes); (5 + k) n + i its contact k's code;
// [(5 + PAIR_MAX) n + 3 i, + 3) where it began the substep; [(8 + PAIR_MAX) n + 3 i, + 3) the
// part of its sum that moves the position only (units as the sum); [(11 + PAIR_MAX) n, + 3)
// the further passes' indirect dispatch per stage (workgroups; zero in a substep where no
// particle found a contact: the find pass writes it, the constraint stage zeroes it); with
// edge contact, (11 + PAIR_MAX) n + 3 + i the creases of particle i's ring edges
// (creases.glsl), written where the spatial hash is built (truncation_hash.comp too), and
// (12 + PAIR_MAX) n + 3 + i the
// fraction of its move in the substep it keeps (self_contact.glsl's note_truncation; 0 for
// none).
// sim::gpu::object mirrors the sizes.
// Include after bindings.glsl.
#ifndef MSD_SELF_PAIRS_LAYOUT_GLSL
#define MSD_SELF_PAIRS_LAYOUT_GLSL

// Contacts a particle keeps in a substep (sim::gpu::object::SELF_PAIR_MAX); one with more
// searches for them again in the apply pass.
const uint PAIR_MAX = 16u;
uint pairs_len_word(uint i) { return 4u * particle_count() + i; }
uint pair_word(uint k, uint i) { return (5u + k) * particle_count() + i; }
uint start_word(uint i) { return (5u + PAIR_MAX) * particle_count() + 3u * i; }
uint rest_word(uint i) { return (8u + PAIR_MAX) * particle_count() + 3u * i; }
uint further_passes_word() { return (11u + PAIR_MAX) * particle_count(); }
uint creases_word(uint i) { return further_passes_word() + 3u + i; }
uint truncation_word(uint i) { return creases_word(i) + particle_count(); }
// Where particle i began the substep, as the find pass noted it.
vec3 start_position(uint i) {
    uint w = start_word(i);
    return vec3(intBitsToFloat(self_pairs[w]), intBitsToFloat(self_pairs[w + 1u]), intBitsToFloat(self_pairs[w + 2u]));
}

#endif
