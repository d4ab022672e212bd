// Moving pins (sim::pins): how an object's pinned particles move over a substep, from its
// parameters (obj.pin_*, written each frame where they move; where they stay put the velocity
// is zero and pin_pivot.w, the turn's flag, is 0).
// Include after bindings.glsl.
#ifndef MSD_PINS_GLSL
#define MSD_PINS_GLSL

// The move over substep `sub` of the frame of a particle at x where the substep starts,
// carried by the pins (sim::pins::PinStep::move_of): the translation's, and where the pins
// turn, the turn about the pivot (which the translation carries) as q r q* - r, formed
// without r's own rounding: r + w t + u x t with t = 2 u x r.
vec3 pin_move(vec3 x, uint sub) {
    vec3 along = obj.pin_velocity.xyz * g.dt;
    if (obj.pin_pivot.w == 0.0) return along;
    vec3 r = x - (obj.pin_pivot.xyz + obj.pin_velocity.xyz * (float(sub) * g.dt));
    vec4 q = obj.pin_turn;
    vec3 t = 2.0 * cross(q.xyz, r);
    return along + q.w * t + cross(q.xyz, t);
}

// The velocity of a pinned particle that moved by d over the substep
// (sim::pins::PinStep::velocity_of): exactly the translation's where the pins do not turn.
vec3 pin_velocity_of(vec3 d) {
    return obj.pin_pivot.w == 0.0 ? obj.pin_velocity.xyz : d * (1.0 / g.dt);
}

#endif
