// Forces that do not come from springs: gravity, the paper's wind cone, Stokes drag.
// Include after bindings.glsl.
#ifndef MSD_FORCES_GLSL
#define MSD_FORCES_GLSL
#include "features.glsl"

// Scales gravity for every object (1 = as the scene says). A knob to try hot reload with:
// edit it while the app runs and the cloth falls faster or slower at once.
const float GRAVITY_SCALE = 1.0;

// The fraction of gravity's pull h^2 g that the solve took back from a particle's prediction,
// from its final displacement `dx` and prediction `dy` (both from the base x~), clamped to
// [0, 1] (sim::cpu::integrators::held_fraction).
float held_fraction(vec3 dx, vec3 dy) {
    vec3 gravity = GRAVITY_SCALE * g.gravity;
    float g2 = dot(gravity, gravity);
    if (g2 == 0.0) return 0.0;
    float h = solve_dt();
    return clamp(-dot(dx - dy, gravity) / (g2 * h * h), 0.0, 1.0);
}

// The wind cone's strength at x: a cone from wind_origin along wind_dir, full inside the
// full-force half-angle, falling linearly (in the cosine) to zero at the attenuation
// half-angle.
float wind_strength(vec3 x) {
    vec3 to_x = x - g.wind_origin;
    float d = length(to_x);
    if (d <= 0.0) return 0.0;
    float c = dot(g.wind_dir, to_x / d);
    if (g.wind_cos_full > g.wind_cos_att) {
        return clamp((c - g.wind_cos_att) / (g.wind_cos_full - g.wind_cos_att), 0.0, 1.0);
    }
    return c >= g.wind_cos_full ? 1.0 : 0.0;
}

// The paper's wind: wind_force newtons along the axis on every particle, times the cone's
// strength (none with the aerodynamic wind, air.glsl).
vec3 wind_force(vec3 x) {
    if (!has(F_WIND) || g.wind_enabled == 0u || g.wind_speed > 0.0) return vec3(0.0);
    return g.wind_dir * (g.wind_force * wind_strength(x));
}

// Gravity, wind and drag on a particle of mass m at x moving at v [N]. The paper's wind and
// Stokes drag are per particle; a mesh cloth's particles, whose areas differ, take them in
// proportion to their mass (their share of the area, `mass_share`): a particle of the mean
// area takes `drag`, and a uniform flow moves the cloth without deforming it.
vec3 external_force(vec3 x, vec3 v, float m) {
    float share = has(F_CLOTH_MESH) ? m / obj.mass : 1.0;
    return m * GRAVITY_SCALE * g.gravity + wind_force(x) * share - obj.drag * v * share;
}

#endif
