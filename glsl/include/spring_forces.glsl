// Adds the springs' force on the particle at grid `cell`, at position x with velocity v, to
// `force`: Hooke's law plus a dashpot along each spring. Spring types and
// dashpots the scene does not use are compiled out (features.glsl).
// A neighbour j is read through NPOS(j) (its position advanced by `drift` times its velocity:
// position Verlet's half drift, 0 otherwise) and NVEL(j) (its velocity). By default both come
// from IN(j); the fused shader defines them to read its shared memory instead.
// Include after bindings.glsl and springs.glsl, with IN (or NPOS and NVEL) defined.
#ifndef MSD_SPRING_FORCES_GLSL
#define MSD_SPRING_FORCES_GLSL
#include "features.glsl"
#include "mesh_springs.glsl"

#ifndef NPOS
#define NPOS(j) (IN(j).pos.xyz + drift * IN(j).vel.xyz)
#define NVEL(j) IN(j).vel.xyz
#endif

// Per stage (STATE_FUSED undefined) the loop skips a spring with no other end or with
// coincident ends by selects, not branches: it reads the particle itself and takes no
// direction, adding exactly zero. Measured faster there (the 1024 x 1024 cloth's physics
// 0.752 -> 0.683 ms a frame), and slower fused (the curtain +2 to 4%), whose kernel keeps the
// branches; solver_bodies.glsl's SELECT_SPRINGS is the same choice the other way round
// (docs/PERFORMANCE.md, "Branch-free spring loops").
void add_spring_forces(uvec2 cell, vec3 x, vec3 v, float drift, inout vec3 force) {
    if (is_mesh()) {
        // (a mesh cloth: its list, each spring's type and rest length in it, in batches)
        uint end = mesh_first(cell.x + 1u);
        for (uint e = mesh_first(cell.x); e < end; e += MESH_BATCH) {
            MeshSpring s[MESH_BATCH];
            vec3 to_j[MESH_BATCH];
            vec3 vel_j[MESH_BATCH];
            [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) s[q] = mesh_batch(e + q, end);
            [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
                to_j[q] = NPOS(s[q].other) - x;
                vel_j[q] = has(F_DAMPING) ? NVEL(s[q].other) : vec3(0.0);
            }
            [[unroll]] for (uint q = 0u; q < MESH_BATCH; ++q) {
                float d = length(to_j[q]);
                if (e + q >= end || d <= 0.0) continue;
                vec3 dir = to_j[q] / d;
                float f = s[q].k * (d - s[q].rest);
                if (has(F_DAMPING)) f += obj.stiffness.w * dot(vel_j[q] - v, dir);
                force += f * dir;
            }
        }
        return;
    }
#ifndef STATE_FUSED
    int self_index = int(cell.x + cell.y * obj.dims.x);
#endif
    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        if (!has(1u << spring.z)) continue;  // F_STRUCTURAL, F_SHEAR, F_BENDING
        float k = obj.stiffness[spring.z];
#ifdef STATE_FUSED
        if (k == 0.0 && !(has(F_DAMPING) && obj.stiffness.w != 0.0)) continue;
        int j = SPRING_NEIGHBOUR(cell, s);
        if (j < 0) continue;
        vec3 to_j = NPOS(j) - x;
        float d = length(to_j);
        if (d <= 0.0) continue;
        vec3 dir = to_j / d;
#else
        int j0 = SPRING_NEIGHBOUR(cell, s);
        int j = j0 < 0 ? self_index : j0;
        vec3 to_j = NPOS(j) - x;
        float d = length(to_j);
        bool on = j0 >= 0 && d > 0.0;
        vec3 dir = on ? to_j / d : vec3(0.0);
#endif
        float rest = rest_length(s);
        float f = k * (d - rest);  // Hooke's law
        if (has(F_DAMPING)) f += obj.stiffness.w * dot(NVEL(j) - v, dir);  // plus a dashpot along the spring
        force += f * dir;
    }
}

// The springs' elastic force alone on the particle at grid `cell` at x (neighbours at NPOS
// with no drift), and the sum of their stiffnesses.
vec3 elastic_spring_force(uvec2 cell, vec3 x, out float stiffness) {
    const float drift = 0.0;
    vec3 force = vec3(0.0);
    stiffness = 0.0;
    if (is_mesh()) {
        for (uint e = mesh_first(cell.x); e < mesh_first(cell.x + 1u); ++e) {
            MeshSpring s = mesh_spring(e);
            int j = s.other;
            float k = s.k;
            vec3 to_j = NPOS(j) - x;
            float d = length(to_j);
            if (k == 0.0 || d <= 0.0) continue;
            force += to_j * (k * (d - s.rest) / d);
            stiffness += k;
        }
        return force;
    }
    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        if (!has(1u << spring.z)) continue;
        float k = obj.stiffness[spring.z];
        int j = SPRING_NEIGHBOUR(cell, s);
        if (k == 0.0 || j < 0) continue;
        vec3 to_j = NPOS(j) - x;
        float d = length(to_j);
        if (d <= 0.0) continue;
        force += to_j * (k * (d - rest_length(s)) / d);
        stiffness += k;
    }
    return force;
}

#endif
