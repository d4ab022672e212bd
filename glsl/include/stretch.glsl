// The stretch limit's counts: how many of a particle's structural and shear springs are
// stretched past (1 + stretch_limit) times their rest length. The constraint stage moves the
// two ends of such a spring by half the excess times the mean of one over each end's count,
// so each end needs its neighbours' counts: the per-stage path writes them into the physics output
// (stretch_count.comp, STRETCHED below), the fused kernel into shared memory. Both count from
// the positions the constraint stage reads (CPOS), so both ends of a spring count alike.
// Include after springs.glsl, with CPOS defined.
#ifndef MSD_STRETCH_GLSL
#define MSD_STRETCH_GLSL

// Whether spring s (an index into SPRINGS) of the particle at grid `cell`, at x, is stretched
// past the limit, with its other end in j and the excess.
bool overstretched(ivec2 cell, vec3 x, int s, out int j, out float excess) {
    excess = 0.0;
    j = neighbour(cell, SPRINGS[s].xy, obj.dims);
    if (j < 0 || obj.stiffness[SPRINGS[s].z] == 0.0) return false;
    // (precise: the count pass and the constraint stage compute it alike)
    precise float d = length(CPOS(j) - x) - rest_length(s) * (1.0 + obj.stretch_limit);
    excess = d;
    return excess > 0.0;
}

// A mesh cloth's: entry e of its list, a structural or shear spring (not bending, not a
// seam's, of rest length zero) with a stiffness.
bool mesh_overstretched(vec3 x, uint e, out int j, out float excess) {
    excess = 0.0;
    MeshSpring s = mesh_spring(e);
    j = s.other;
    if (s.type > uint(SPRING_SHEAR) || s.k == 0.0) return false;
    precise float d = length(CPOS(j) - x) - s.rest * (1.0 + obj.stretch_limit);
    excess = d;
    return excess > 0.0;
}

uint stretched_springs(ivec2 cell, vec3 x) {
    uint n = 0u;
    if (is_mesh()) {
        for (uint e = mesh_first(uint(cell.x)); e < mesh_first(uint(cell.x) + 1u); ++e) {
            int j;
            float excess;
            if (mesh_overstretched(x, e, j, excess)) n += 1u;
        }
        return n;
    }
    [[unroll]] for (int s = 0; s < 8; ++s) {
        int j;
        float excess;
        if (overstretched(cell, x, s, j, excess)) n += 1u;
    }
    return n;
}

// Particle j's count, as stretch_count.comp left it in the physics output's velocity w (which
// nothing else reads there).
#ifndef STRETCHED
#define STRETCHED(j) uint(p_in[j].vel.w)
#endif

#endif
