// The aerodynamic wind (Globals.wind_speed > 0): air flowing along the cone's axis at
// wind_speed, with its turbulence added (`turbulence`), times the cone's strength there pushes
// on the cloth by its velocity u relative to the particle. A cloth particle's share of the
// area is a = (x_right - x_left) x (x_down - x_up) / 4 (a missing neighbour replaced by the
// particle itself: half the share on an edge, a quarter at a corner), along its normal n =
// a / |a|; the force is |a| (wind_normal |u.n| (u.n) n + wind_tangent |u_t| u_t): normal drag
// on the area the air meets, so an edge-on sheet feels only the small tangential drag, and
// none once it moves with the air; plus the lift wind_lift |u| (u.n) (n - (u.n) u / |u|^2),
// across u in the plane of u and n: a flat plate's 1/2 rho C_L sin(2 alpha) |u|^2 at an angle
// of attack alpha, none face-on or edge-on. A rope node's area is the diameter times half its
// two segments, the drag across the rope (normal) and along it (tangent). A mesh cloth
// particle's area is a third of each of its triangles' area vectors. The CPU twin is
// sim::cpu::air_force.
// Neighbours are read through NPOS(j) with `drift`, as the springs read them.
// Include after spring_forces.glsl.
#ifndef MSD_AIR_GLSL
#define MSD_AIR_GLSL
#include "forces.glsl"

// When within the frame the forces are taken: the substep's start [s] (the calling shader's main
// sets it; the turbulence's phases are the frame's start's).
float air_time = 0.0;

// The air's turbulent velocity at x: a sum of Fourier modes, each amplitude across its wave
// vector, so the field has no divergence (sim::turbulence, which draws them from the seed).
// At `drift` [s] after air_time (position Verlet takes the forces at the half-drifted state).
vec3 turbulence(vec3 x, float drift) {
    vec3 u = vec3(0.0);
    for (uint m = 0u; m < g.wind_modes; ++m) {
        vec4 k = g.wind_waves[m];
        vec4 a = g.wind_gusts[m];
        u += a.xyz * sin(dot(k.xyz, x) + a.w - k.w * (air_time + drift));
    }
    return u;
}

vec3 air_force(uvec2 cell, vec3 x, vec3 v, float drift) {
    if (!has(F_WIND) || g.wind_enabled == 0u || g.wind_speed <= 0.0) return vec3(0.0);
    vec3 u = (g.wind_dir * g.wind_speed + turbulence(x, drift)) * wind_strength(x) - v;
    uint cols = obj.dims.x;
    uint i = cell.x + cell.y * cols;
    if (obj.dims.y > 1u || is_mesh()) {
        vec3 area = vec3(0.0);
        if (is_mesh()) {
            // (a mesh cloth's: a third of each of its triangles' area vectors)
            for (uint k = mesh_ring_first(i); k < mesh_ring_first(i + 1u); ++k) {
                uvec3 t = mesh_triangle(mesh_ring_triangle(k));
                vec3 a = t.x == i ? x : NPOS(t.x);
                vec3 b = t.y == i ? x : NPOS(t.y);
                vec3 c = t.z == i ? x : NPOS(t.z);
                area += cross(b - a, c - a) * (1.0 / 6.0);
            }
        } else {
            vec3 left = cell.x > 0u ? NPOS(i - 1u) : x;
            vec3 right = cell.x + 1u < cols ? NPOS(i + 1u) : x;
            vec3 up = cell.y > 0u ? NPOS(i - cols) : x;
            vec3 down = cell.y + 1u < obj.dims.y ? NPOS(i + cols) : x;
            area = 0.25 * cross(right - left, down - up);
        }
        float a = length(area);
        if (a <= 0.0) return vec3(0.0);
        vec3 n = area / a;
        float un = dot(u, n);
        vec3 ut = u - n * un;
        float speed = length(u);
        // Lift across u in the plane of u and n (sim::cpu::air_force).
        vec3 lift = speed > 0.0 ? (n * speed - u * (un / speed)) * (g.wind_lift * un) : vec3(0.0);
        return a * (n * (g.wind_normal * abs(un) * un) + ut * (g.wind_tangent * length(ut)) + lift);
    }
    vec3 axis = (cell.x + 1u < cols ? NPOS(i + 1u) : x) - (cell.x > 0u ? NPOS(i - 1u) : x);
    float len = length(axis);
    if (len <= 0.0) return vec3(0.0);
    vec3 t = axis / len;
    float along = dot(u, t);
    vec3 across = u - t * along;
    vec3 drag = across * (g.wind_normal * length(across)) + t * (g.wind_tangent * abs(along) * along);
    return (obj.rope_radius * len) * drag;
}

#endif
