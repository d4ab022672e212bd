// Adds the springs' force on the particle at grid `cell`, at position x with velocity v, to
// `force`: Hooke's law (when `elastic`) plus a dashpot along each spring. Neighbours are read through IN(j), their
// positions advanced by `drift` times their velocity (position Verlet's half drift; 0 otherwise).
// Include after bindings.glsl and springs.glsl, with IN defined.
#ifndef MSD_SPRING_FORCES_GLSL
#define MSD_SPRING_FORCES_GLSL

void add_spring_forces(uvec2 cell, vec3 x, vec3 v, float drift, bool elastic, inout vec3 force) {
    for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        float k = elastic ? obj.stiffness[spring.z] : 0.0;
        if (k == 0.0 && obj.stiffness.w == 0.0) continue;
        int j = neighbour(ivec2(cell), spring.xy, obj.dims);
        if (j < 0) continue;
        vec3 to_j = IN(j).pos.xyz + drift * IN(j).vel.xyz - x;
        float d = length(to_j);
        if (d <= 0.0) continue;
        vec3 dir = to_j / d;
        float rest = rest_length(spring, obj.spacing, obj.rest_scale);
        float damping = obj.stiffness.w * dot(IN(j).vel.xyz - v, dir);
        force += (k * (d - rest) + damping) * dir;  // Hooke's law plus a dashpot along the spring
    }
}

#endif
