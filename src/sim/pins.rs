//! Moving pins (`pin_motion` in presets): an object's pinned particles carried together by a
//! translation (a velocity, or keyframes of their displacement) and a turn about a pivot that
//! the translation carries (steady, or keyframed angles). Within a frame the translation moves
//! at the frame's chord velocity, as a moving collider does (`ColliderModel::frame_motion`),
//! and the pins turn at the frame's steady rate: each substep by the same share of the
//! frame's turn. The CPU reference takes each substep from `PinStep`, the GPU from the
//! object's parameters (`pin_*`, written each frame) through glsl/include/pins.glsl: the same
//! arithmetic.

use crate::sim::collider::Motion;
use crate::sim::turn::Turn;
use glam::{DQuat, DVec3};

#[derive(Debug, Clone, PartialEq, Default)]
pub struct PinMotion {
    /// The translation: a velocity, or keyframed displacements (only their change counts).
    pub translation: Motion,
    /// The turn about `pivot`: steady or keyed.
    pub turn: Turn,
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
        self.turn.turns()
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
            turn: self.turns().then(|| DQuat::from_scaled_axis(self.turn.frame_spin(t0, frame_dt) * dt)),
            dt,
        }
    }

    /// Where a pinned particle placed at `x` is at time `t` (at the end of every frame, where
    /// the translation's chord meets it, exactly; the app's pin markers).
    pub fn carried(&self, x: DVec3, t: f64) -> DVec3 {
        let moved = self.translation.offset(t) - self.translation.offset(0.0);
        let turned = if self.turns() { self.turn.orientation(t) * (x - self.pivot) } else { x - self.pivot };
        self.pivot + moved + turned
    }

    /// The fastest any of the pinned particles at `at` (where they are placed) moves [m/s]: the
    /// translation's fastest (a velocity, or the steepest keyframe segment) plus the turn's
    /// speed at the one farthest from the pivot (an upper bound: the two may not add up).
    pub fn top_speed(&self, at: &[DVec3]) -> f64 {
        let along = match &self.translation {
            Motion::Fixed => 0.0,
            Motion::Velocity(v) => v.length(),
            Motion::Keyframes(keys) => {
                keys.windows(2).map(|w| (w[1].1 - w[0].1).length() / (w[1].0 - w[0].0)).fold(0.0, f64::max)
            }
            Motion::Smooth(keys) => crate::sim::collider::smooth_top_speed(keys),
        };
        let reach = at.iter().map(|x| x.distance(self.pivot)).fold(0.0, f64::max);
        along + self.turn.top_spin() * reach
    }

    /// The velocity of a pinned particle at `x` at t = 0 (its initial state).
    pub fn initial_velocity(&self, x: DVec3, frame_dt: f64) -> DVec3 {
        let (pivot, velocity) = self.frame(0.0, frame_dt);
        velocity + self.turn.frame_spin(0.0, frame_dt).cross(x - pivot)
    }
}

impl PinStep {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Substep by substep (`step`, `move_of`), over frames whose keys fall inside them, a pin
    /// lands where the closed form (`carried`) has it at every frame's end: the translation's
    /// chords meet its keys there, and the turns compose exactly (to 1e-12 m in f64), steady
    /// or keyed (smooth angles about all three axes, turning back at a key).
    #[test]
    fn substeps_compose_to_the_closed_form_at_every_frame_end() {
        let steady = PinMotion {
            translation: Motion::Keyframes(vec![
                (0.0, DVec3::ZERO),
                (0.11, DVec3::new(0.3, 0.0, 0.0)),
                (0.5, DVec3::new(0.3, 0.2, -0.4)),
            ]),
            turn: Turn::steady(DVec3::new(0.3, 2.0, -0.5)),
            pivot: DVec3::new(0.1, 1.0, 0.2),
        };
        let keyed = PinMotion {
            turn: Turn {
                spin: DVec3::ZERO,
                rotation: Motion::Smooth(vec![
                    (0.0, DVec3::new(0.1, 0.0, 0.0)),
                    (0.2, DVec3::new(0.4, 1.5, -0.2)),
                    (0.45, DVec3::new(0.3, 0.5, 0.6)),
                ]),
            },
            ..steady.clone()
        };
        let (frame_dt, substeps) = (1.0 / 60.0, 7);
        let dt = frame_dt / substeps as f64;
        let start = DVec3::new(0.4, 0.9, -0.3);
        for pins in [steady, keyed] {
            let mut x = start;
            for f in 0..40 {
                for s in 0..substeps {
                    x += pins.step(f as f64 * frame_dt, frame_dt, s, dt).move_of(x);
                }
                let t = (f + 1) as f64 * frame_dt;
                let exact = pins.carried(start, t);
                assert!(x.distance(exact) < 1e-12, "frame {f}: {x} against {exact}");
            }
        }
    }
}
