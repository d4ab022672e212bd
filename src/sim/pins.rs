//! Moving pins (`pin_motion` in presets): an object's pinned particles carried together by a
//! translation (a velocity, or keyframes of their displacement) and a steady turn about a
//! pivot that the translation carries. Within a frame the translation moves at the frame's
//! chord velocity, as a moving collider does (`ColliderModel::frame_motion`); each substep the
//! pins turn by the angular velocity times the substep. The CPU reference takes each substep
//! from `PinStep`, the GPU from the object's parameters (`pin_*`, written each frame) through
//! glsl/include/pins.glsl: the same arithmetic.

use crate::sim::collider::Motion;
use glam::{DQuat, DVec3};

#[derive(Debug, Clone, PartialEq, Default)]
pub struct PinMotion {
    /// The translation: a velocity, or keyframed displacements (only their change counts).
    pub translation: Motion,
    /// The angular velocity about `pivot` [rad/s]; zero: the pins do not turn.
    pub spin: DVec3,
    /// What they turn about, where it is at t = 0 [m]; the translation carries it.
    pub pivot: DVec3,
}

/// How the pins move over one substep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinStep {
    /// The translation's velocity over the frame [m/s].
    pub velocity: DVec3,
    /// The pivot where the substep starts [m].
    pub pivot: DVec3,
    /// The substep's turn (`None`: none, the move is the translation's alone).
    pub turn: Option<DQuat>,
    /// The substep [s].
    pub dt: f64,
}

impl PinMotion {
    pub fn is_moving(&self) -> bool {
        self.translation.is_moving() || self.turns()
    }

    pub fn turns(&self) -> bool {
        self.spin != DVec3::ZERO
    }

    /// The frame that starts at `t0` and lasts `frame_dt`: where the pivot is at its start
    /// and the translation's (chord) velocity over it.
    pub fn frame(&self, t0: f64, frame_dt: f64) -> (DVec3, DVec3) {
        let at = self.translation.offset(t0);
        let velocity = (self.translation.offset(t0 + frame_dt) - at) / frame_dt;
        (self.pivot + at - self.translation.offset(0.0), velocity)
    }

    /// Substep `s` (0-based) of `dt` in the frame that starts at `t0`.
    pub fn step(&self, t0: f64, frame_dt: f64, s: u32, dt: f64) -> PinStep {
        let (pivot, velocity) = self.frame(t0, frame_dt);
        PinStep {
            velocity,
            pivot: pivot + velocity * (s as f64 * dt),
            turn: self.turns().then(|| DQuat::from_scaled_axis(self.spin * dt)),
            dt,
        }
    }

    /// The velocity of a pinned particle at `x` at t = 0 (its initial state).
    pub fn initial_velocity(&self, x: DVec3, frame_dt: f64) -> DVec3 {
        let (pivot, velocity) = self.frame(0.0, frame_dt);
        velocity + self.spin.cross(x - pivot)
    }
}

impl PinStep {
    /// Pins that stay put.
    pub const HELD: PinStep = PinStep { velocity: DVec3::ZERO, pivot: DVec3::ZERO, turn: None, dt: 1.0 };

    /// The move over the substep of a particle at `x` where it starts, carried by the pins.
    pub fn move_of(&self, x: DVec3) -> DVec3 {
        let along = self.velocity * self.dt;
        match self.turn {
            None => along,
            Some(q) => along + (q * (x - self.pivot) - (x - self.pivot)),
        }
    }

    /// The velocity of a pinned particle that moved by `d` over the substep: the translation's
    /// where the pins do not turn (exactly), else the chord's.
    pub fn velocity_of(&self, d: DVec3) -> DVec3 {
        match self.turn {
            None => self.velocity,
            Some(_) => d / self.dt,
        }
    }
}
