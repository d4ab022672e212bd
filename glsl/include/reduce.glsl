// Sums over a workgroup for the implicit method's conjugate gradients: subgroupAdd, then the
// subgroups' sums through shared memory. Every invocation of the workgroup must call it (it
// holds a barrier) and gets the same total. The includer defines REDUCE_T (float, vec2, ...)
// and REDUCE_SLOTS (at least the workgroup's subgroups: its size over the smallest subgroup
// size a device reports, 4). The slots alternate between calls, so one barrier a call keeps a
// call's writes from meeting the reads of the call before.
// Include with GL_KHR_shader_subgroup_arithmetic enabled.
#ifndef MSD_REDUCE_GLSL
#define MSD_REDUCE_GLSL

shared REDUCE_T reduce_slots[2][REDUCE_SLOTS];
uint reduce_parity = 0u;

REDUCE_T workgroup_sum(REDUCE_T v) {
    REDUCE_T s = subgroupAdd(v);
    if (subgroupElect()) reduce_slots[reduce_parity][gl_SubgroupID] = s;
    barrier();
    REDUCE_T total = REDUCE_T(0.0);
    for (uint q = 0u; q < gl_NumSubgroups; ++q) total += reduce_slots[reduce_parity][q];
    reduce_parity ^= 1u;
    return total;
}

#endif
