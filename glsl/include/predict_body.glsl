// The inertial prediction of the iterative integrators, shared by predict.comp and the fused
// kernel. Include after bindings.glsl and springs.glsl, with IN (or NPOS and NVEL)
// defined.
#ifndef MSD_PREDICT_BODY_GLSL
#define MSD_PREDICT_BODY_GLSL
#include "forces.glsl"
#include "spring_forces.glsl"
#include "air.glsl"
#include "pins.glsl"

// The BDF2 start of a substep (sim::cpu::integrators::inertial has the formulas; implicit
// Euler's for an object with `implicit_euler()`) of a free particle at grid `cell`, at x with
// velocity v and history `hx` (x_n - x_{n-1}, w valid) and `hv` (v_n - v_{n-1}): returns the
// prediction y - x~ and sets `base` to x~ - x, where x~ = x + (x_n - x_{n-1}) / 3 is what the
// solve's displacements are measured from. F is the external force (every method treats the
// dashpots in its solve). Without history the last substep is taken to have been one Jacobi
// step of implicit Euler (sim::cpu::integrators::inertial and restart). `pull` is the
// prediction's part h^2 F / m.
vec3 predicted_displacement(uvec2 cell, vec3 x, vec3 v, vec4 hx, vec3 hv, out vec3 base, out vec3 pull) {
    float m = particle_mass(cell);
    vec3 force = external_force(x, v, m) + air_force(cell, x, v, 0.0);
    vec3 a = force / m;
    if (implicit_euler()) {
        // implicit Euler's start: base x_n, y = x_n + dt v_n + dt^2 F / m
        base = vec3(0.0);
        pull = a * (g.dt * g.dt);
        return v * g.dt + pull;
    }
    bool known = hx.w > 0.5;
    vec3 dx = hx.xyz;
    vec3 dv = hv;
    if (!known) {
        float stiffness;
        vec3 elastic = elastic_spring_force(cell, x, stiffness);
        vec3 ar = (force + elastic) / (m + g.dt * g.dt * stiffness);
        dx = (v + ar * g.dt) * g.dt;
        dv = ar * g.dt;
    }
    float h = solve_dt();
    base = dx * (1.0 / 3.0);
    pull = a * (h * h);
    return v * (BDF2_STEP * g.dt) + dv * ((2.0 / 9.0) * g.dt) + pull;
}

// Must equal sim::integrator::STIFF_START.
const float STIFF_START = 10.0;

// How stiff the springs of the particle at `cell` are against its inertia over the solve's
// step h: (h^2 sum k + h sum b) / m over its springs that have a stiffness
// (sim::cpu::integrators::stiffness_ratio).
float stiffness_ratio(uvec2 cell, float h) {
    float sum = 0.0;
    if (is_mesh()) {
        for (uint e = mesh_first(cell.x); e < mesh_first(cell.x + 1u); ++e) {
            float k = mesh_spring(e).k;
            if (k != 0.0) sum += h * (h * k + obj.stiffness.w);
        }
        return sum / particle_mass(cell);
    }
    [[unroll]] for (int s = 0; s < 12; ++s) {
        ivec3 spring = SPRINGS[s];
        if (!has(1u << spring.z)) continue;
        float k = obj.stiffness[spring.z];
        if (k == 0.0 || SPRING_NEIGHBOUR(cell, s) < 0) continue;
        sum += h * (h * k + obj.stiffness.w);
    }
    return sum / obj.mass;
}

// `guess` (a displacement) moved towards `rest` by the share kappa / (kappa + STIFF_START) of
// the way, kappa the particle at `cell`'s stiffness ratio (sim::cpu::integrators::toward_rest
// says why).
vec3 toward_rest(uvec2 cell, vec3 rest, vec3 guess) {
    float kappa = stiffness_ratio(cell, solve_dt());
    return rest + (guess - rest) * (STIFF_START / (STIFF_START + kappa));
}

// Where a method with an adaptive start (sim::integrator's row) starts the iterate of the
// particle at `cell`, as a displacement from the solve's base: the prediction `dy` less the
// fraction of its `pull` that the springs held last substep (`held`, history H_DV's w; none
// without history, hx.w = 0; sim::cpu::integrators::held_fraction says why); on an anchored
// object, moved towards where the particle is (`here`, x - base), carried on by its pins'
// group 0's move over the substep (pin_move at x, in substep `sub`): `toward_rest`.
vec3 adaptive_start(uvec2 cell, vec3 dy, vec3 pull, vec4 hx, float held, vec3 here, vec3 x, uint sub) {
    vec3 guess = hx.w > 0.5 ? dy - pull * held : dy;
    if ((obj.flags & OBJ_ANCHORED) == 0u) return guess;
    return toward_rest(cell, here + pin_move(x, sub, 0.0), guess);
}

// The solve's base x~ = x + base rounded to f32 (`start`) and what the rounding left out
// (`lost` = x~ - start, exact): the solve measures its displacements d from `start`, with the
// prediction moved by `lost`, and the velocity is (d - lost) / h. Dropped, the rounding of x~
// (up to half an ulp of the position, every substep, in the same direction while the motion
// is steady) entered the positions on top of the final position's own rounding and the
// history carried it on: on a swinging 16 x 16 cloth at 256 substeps the GPU parted from the
// f64 reference five times faster than symplectic Euler's. (precise: kept from being
// simplified to exact algebra.)
void bdf2_start(vec3 x, vec3 base, out precise vec3 start, out precise vec3 lost) {
    start = x + base;
    precise vec3 moved = start - x;
    lost = base - moved;
}

#endif
