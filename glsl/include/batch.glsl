// The per-object bindings of a batched step shader (bindings.glsl with BATCHED): one dispatch
// runs a chunk of objects, workgroup z taking the chunk's object z. Each per-object binding
// is an array of BATCH_CHUNK descriptors, one an object of the chunk (src/sim/gpu/batch.rs
// fills them; the device's descriptor limits size the chunk: 64 objects on a GPU, one on
// lavapipe, which allows 32 storage buffers a stage). The index is the workgroup's, the same
// for all its invocations, as core Vulkan's dynamic indexing asks. The names the bodies use
// (obj, p_in, iter, guard_flags, ...) are those of the single bindings, so the bodies are the
// same for both.
#ifndef MSD_BATCH_GLSL
#define MSD_BATCH_GLSL

#include "batch_chunk.glsl"

layout(std430, set = 0, binding = 1) restrict readonly buffer ObjectBuf { ObjectParams v; uint words[]; } b_obj[BATCH_CHUNK];
// (the state's qualifiers as bindings.glsl gives the single bindings)
#ifdef STATE_IN_WRITE
layout(std430, set = 0, binding = 2) buffer StateIn { Particle v[]; } b_in[BATCH_CHUNK];
#else
layout(std430, set = 0, binding = 2) readonly buffer StateIn { Particle v[]; } b_in[BATCH_CHUNK];
#endif
#ifdef STATE_OUT_READ
layout(std430, set = 0, binding = 3) buffer StateOut { Particle v[]; } b_out[BATCH_CHUNK];
#else
layout(std430, set = 0, binding = 3) writeonly buffer StateOut { Particle v[]; } b_out[BATCH_CHUNK];
#endif
layout(std430, set = 0, binding = 6) buffer HashCellRank { uvec2 v[]; } b_cell_rank[BATCH_CHUNK];
layout(std430, set = 0, binding = 7) buffer HashCounts { uint v[]; } b_counts[BATCH_CHUNK];
layout(std430, set = 0, binding = 8) buffer HashStarts { uint v[]; } b_starts[BATCH_CHUNK];
layout(std430, set = 0, binding = 9) buffer HashSorted { vec4 v[]; } b_sorted[BATCH_CHUNK];
layout(std430, set = 0, binding = 10) buffer HashBlocks { uint v[]; } b_block_sums[BATCH_CHUNK];
layout(std430, set = 0, binding = 11) buffer GuardBuf {
    uint flags; uint first; uint lists_on; uint lists_rebuilt;
} b_guard[BATCH_CHUNK];
layout(std430, set = 0, binding = 12) buffer SolverIter { vec4 v[]; } b_iter[BATCH_CHUNK];
layout(std430, set = 0, binding = 13) buffer SolverAux { vec4 v[]; } b_aux[BATCH_CHUNK];
layout(std430, set = 0, binding = 14) buffer ContactBuf { vec4 v[]; } b_contact[BATCH_CHUNK];
layout(std430, set = 0, binding = 15) buffer SelfListBuf { uint v[]; } b_self_list[BATCH_CHUNK];
layout(std430, set = 0, binding = 16) buffer SolverHistory { vec4 v[]; } b_history[BATCH_CHUNK];
layout(std430, set = 0, binding = 17) coherent buffer SelfPairsBuf { int v[]; } b_self_pairs[BATCH_CHUNK];

#define obj b_obj[MSD_Z].v
#define obj_words b_obj[MSD_Z].words
#define p_in b_in[MSD_Z].v
#define p_out b_out[MSD_Z].v
#define cell_rank b_cell_rank[MSD_Z].v
#define counts b_counts[MSD_Z].v
#define starts b_starts[MSD_Z].v
#define sorted b_sorted[MSD_Z].v
#define block_sums b_block_sums[MSD_Z].v
#define guard_flags b_guard[MSD_Z].flags
#define guard_first b_guard[MSD_Z].first
#define guard_lists_on b_guard[MSD_Z].lists_on
#define guard_lists_rebuilt b_guard[MSD_Z].lists_rebuilt
#define iter b_iter[MSD_Z].v
#define aux b_aux[MSD_Z].v
#define contact b_contact[MSD_Z].v
#define self_list b_self_list[MSD_Z].v
#define history b_history[MSD_Z].v
#define self_pairs b_self_pairs[MSD_Z].v

#endif
