// The physics stage for one particle: forces (gravity, springs with damping, wind cone, Stokes
// drag) and symplectic Euler, or position Verlet (VERLET: the forces at the half-drifted
// positions x + v dt / 2). `physics_step` is the step itself, shared by physics.comp (through
// `physics_particle`, which reads IN(i) and writes OUT(i)) and fused.comp (which keeps the
// state in registers and shared memory). For objects whose self-collision uses the spatial
// hash, `physics_particle` also notes whether the new position leaves its contact list's
// skin (hash_count.glsl).
// Include after bindings.glsl and springs.glsl, with IN and OUT (or NPOS and NVEL) defined.
#ifndef MSD_PHYSICS_BODY_GLSL
#define MSD_PHYSICS_BODY_GLSL
#include "forces.glsl"
#include "hash_count.glsl"
#include "spring_forces.glsl"
#include "air.glsl"
#include "pins.glsl"

// Position Verlet instead of symplectic Euler (a pipeline per choice).
layout(constant_id = 2) const bool VERLET = false;

// How far neighbours are drifted before the forces are evaluated [s].
float physics_drift() { return VERLET ? 0.5 * g.dt : 0.0; }

// Advances a free particle by one substep: x, its position drifted by physics_drift() times v,
// becomes the new position; v the new velocity.
void physics_step(uvec2 cell, inout vec3 x, inout vec3 v) {
    float drift = physics_drift();
    float m = particle_mass(cell);
    vec3 force = external_force(x, v, m) + air_force(cell, x, v, drift);
    add_spring_forces(cell, x, v, drift, force);
    v += force * (g.dt / m);
    x += v * (g.dt - drift);
}

#ifdef OUT
// `substep`: which of the frame's substeps this is; `lists`: contact lists on.
void physics_particle(uvec2 cell, uint substep, bool lists) {
    uint i = cell.x + cell.y * obj.dims.x;
    Particle p = IN(i);
    if (p.pos.w > 0.5) {  // pinned: moved with its pins (pins.glsl; usually not at all)
        vec3 d = pin_move(p.pos.xyz, substep, p.pos.w);
        vec3 x = p.pos.xyz + d;
        OUT(i) = Particle(vec4(x, p.pos.w), vec4(pin_velocity_of(d, p.pos.w), 0.0));
        note_position(i, x, true, substep, lists);
        return;
    }
    vec3 x = p.pos.xyz + physics_drift() * p.vel.xyz;
    vec3 v = p.vel.xyz;
    physics_step(cell, x, v);
    OUT(i) = Particle(vec4(x, 0.0), vec4(v, 0.0));
    note_position(i, x, false, substep, lists);
}
#endif

#endif
