//! A turn over time, shared by moving pins (`sim::pins`) and colliders (`sim::collider`):
//! steady (an angular velocity) or keyed angles about x, then y, then z, joined as a motion's
//! keyframes are. Within a frame it turns at the frame's steady rate (`frame_spin`), which is
//! what the GPU receives each frame.

use crate::sim::collider::Motion;
use glam::{DQuat, DVec3};

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Turn {
    /// The angular velocity [rad/s]; zero: no steady turn.
    pub spin: DVec3,
    /// Or keyframed angles about x, then y, then z [rad] (only their change counts);
    /// `Motion::Fixed` where it turns steadily or not at all.
    pub rotation: Motion,
}

impl Turn {
    /// A steady turn at `spin` [rad/s].
    pub fn steady(spin: DVec3) -> Self {
        Self { spin, rotation: Motion::Fixed }
    }

    pub fn turns(&self) -> bool {
        self.spin != DVec3::ZERO || self.rotation.is_moving()
    }

    /// The turn from t = 0 to `t`.
    pub fn orientation(&self, t: f64) -> DQuat {
        if self.spin != DVec3::ZERO {
            return DQuat::from_scaled_axis(self.spin * t);
        }
        if !self.rotation.is_moving() {
            return DQuat::IDENTITY;
        }
        let at = |t: f64| {
            let a = self.rotation.offset(t);
            DQuat::from_euler(glam::EulerRot::XYZ, a.x, a.y, a.z)
        };
        (at(t) * at(0.0).inverse()).normalize()
    }

    /// The angular velocity over the frame that starts at `t0` and lasts `frame_dt` [rad/s]:
    /// the steady one, or the keyed turn over the frame at a steady rate (the shorter way: a
    /// keyed turn stays under half a turn a frame, scene validation).
    pub fn frame_spin(&self, t0: f64, frame_dt: f64) -> DVec3 {
        if self.spin != DVec3::ZERO || !self.rotation.is_moving() {
            return self.spin;
        }
        let turn = self.orientation(t0 + frame_dt) * self.orientation(t0).inverse();
        // (q and -q are one rotation; w >= 0 is the one of at most half a turn)
        let turn = if turn.w < 0.0 { -turn } else { turn };
        turn.to_scaled_axis() / frame_dt
    }

    /// The fastest it turns [rad/s]: an upper bound (keyed angles: each angle's rate adds, at
    /// most its rate about a unit axis).
    pub fn top_spin(&self) -> f64 {
        let rate = match &self.rotation {
            Motion::Keyframes(keys) => keys
                .windows(2)
                .map(|w| {
                    let r = (w[1].1 - w[0].1) / (w[1].0 - w[0].0);
                    r.x.abs() + r.y.abs() + r.z.abs()
                })
                .fold(0.0, f64::max),
            // (the components' fastest, each at most the bound's length)
            Motion::Smooth(keys) => 3f64.sqrt() * crate::sim::collider::smooth_top_speed(keys),
            Motion::Fixed | Motion::Velocity(_) => 0.0,
        };
        self.spin.length() + rate
    }
}
