// The inertial prediction of the iterative integrators for a free particle at grid `cell`, at
// x with velocity v: y - x = dt (v + dt F / m), F the external forces and, with `dashpots`
// (a method that treats damping explicitly), the springs' dashpots. Shared by predict.comp and
// the fused kernel. Include after bindings.glsl and springs.glsl, with IN (or NPOS and NVEL)
// defined.
#ifndef MSD_PREDICT_BODY_GLSL
#define MSD_PREDICT_BODY_GLSL
#include "forces.glsl"
#include "spring_forces.glsl"

vec3 predicted_displacement(uvec2 cell, vec3 x, vec3 v, bool dashpots) {
    vec3 force = external_force(x, v);
    if (dashpots) add_spring_forces(cell, x, v, 0.0, false, force);
    return (v + force * (g.dt / obj.mass)) * g.dt;
}

#endif
