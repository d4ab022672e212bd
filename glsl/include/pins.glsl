// Moving pins (sim::pins): how an object's pinned particles move over a substep, from its
// parameters (obj.pin_*, written each frame where they move; where they stay put the velocity
// is zero and pin_pivot.w, the turn's flag, is 0).
// Include after bindings.glsl.
#ifndef MSD_PINS_GLSL
#define MSD_PINS_GLSL

// The fused kernel keeps a copy of the parameters in registers (OBJ_COPY); the groups' records
// are read from the buffer, so the copy does not hold them all.
#ifdef OBJ_COPY
#define PIN_PARAMS obj_buffer
#else
#define PIN_PARAMS obj
#endif

// The pin group of a particle whose pos.w is `w` (1 + the group where it is pinned; a free
// particle's carried move is group 0's).
uint pin_group(float w) { return w > 1.5 ? uint(w + 0.5) - 1u : 0u; }

// The move over substep `sub` of the frame of a particle at x where the substep starts (pos.w
// `w`), carried by its group's pins (sim::pins::PinStep::move_of): the translation's, and where
// the pins turn, the turn about the pivot (which the translation carries) as q r q* - r,
// formed without r's own rounding: r + w t + u x t with t = 2 u x r.
vec3 pin_move(vec3 x, uint sub, float w) {
    uint at = 3u * pin_group(w);
    vec4 velocity = PIN_PARAMS.pins[at];
    vec4 pivot = PIN_PARAMS.pins[at + 1u];
    vec3 along = velocity.xyz * g.dt;
    if (pivot.w == 0.0) return along;
    vec3 r = x - (pivot.xyz + velocity.xyz * (float(sub) * g.dt));
    vec4 q = PIN_PARAMS.pins[at + 2u];
    vec3 t = 2.0 * cross(q.xyz, r);
    return along + q.w * t + cross(q.xyz, t);
}

// The velocity of a pinned particle (pos.w `w`) that moved by d over the substep
// (sim::pins::PinStep::velocity_of): exactly the translation's where its pins do not turn.
vec3 pin_velocity_of(vec3 d, float w) {
    uint at = 3u * pin_group(w);
    return PIN_PARAMS.pins[at + 1u].w == 0.0 ? PIN_PARAMS.pins[at].xyz : d * (1.0 / g.dt);
}

#endif
