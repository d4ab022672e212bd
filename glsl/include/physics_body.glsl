// The physics stage for one particle (shared by physics.comp and fused.comp): forces
// (gravity, springs with damping, wind cone, Stokes drag) and symplectic Euler, or position
// Verlet (VERLET: the forces at the half-drifted positions x + v dt / 2). Reads IN(i),
// writes OUT(i): the including shader defines both. For objects whose self-collision uses the
// spatial hash it also counts the new position into its bucket (counts[] were zeroed by the
// previous substep's scan) and records its rank there.
// Include after bindings.glsl and springs.glsl, with IN and OUT defined.
#ifndef MSD_PHYSICS_BODY_GLSL
#define MSD_PHYSICS_BODY_GLSL
#include "forces.glsl"
#include "hash_count.glsl"
#include "spring_forces.glsl"

// Position Verlet instead of symplectic Euler (a pipeline per choice).
layout(constant_id = 2) const bool VERLET = false;

void physics_particle(uvec2 cell) {
    uint i = cell.x + cell.y * obj.dims.x;
    Particle p = IN(i);
    if (p.pos.w > 0.5) {  // pinned: keep the position, no velocity
        OUT(i) = Particle(p.pos, vec4(0.0));
        count_into_bucket(i, p.pos.xyz);
        return;
    }
    float drift = VERLET ? 0.5 * g.dt : 0.0;
    vec3 x = p.pos.xyz + drift * p.vel.xyz;
    vec3 v = p.vel.xyz;

    vec3 force = external_force(x, v);
    add_spring_forces(cell, x, v, drift, true, force);

    vec3 v_new = v + force * (g.dt / obj.mass);
    vec3 x_new = x + v_new * (g.dt - drift);
    OUT(i) = Particle(vec4(x_new, 0.0), vec4(v_new, 0.0));
    count_into_bucket(i, x_new);
}

#endif
