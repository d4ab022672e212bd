//! The runtime guard's energy check. With nothing in the scene supplying energy (no wind, no
//! moving collider or pins, no state written by the host since), a simulation's total mechanical energy
//! (kinetic, gravity's, the springs') can only fall: damping, drag, friction and inelastic
//! contact take it away. A run whose energy rises above the lowest it had by more than
//! `sim.max_energy_gain` times its scale is implausible, even while every particle stays slower
//! than `sim.max_speed`: a contact or a solve is making energy (a jittering stack, an
//! unconverged solve that rings). The scale is what the objects would gain falling their own
//! size, plus their kinetic and elastic energy when the watch starts (what sloshes between
//! the two: a method that conserves a modified energy, as symplectic Euler does, shows the
//! true one rising and falling by a share of it), plus a floor of 0.1 m/s for every particle,
//! so that a scene at rest without gravity is not stopped by rounding.
//!
//! Each method is judged by the energy it integrates. A compliant method's solve cut short
//! (XPBD's, `sim::integrator::Method::compliant`) pulls with less than its springs' stiffness,
//! so the energy it integrates lies between the motion's and gravity's alone and the total
//! with the springs' energy at their stiffness: its check counts the springs in the lowest
//! reading and leaves them out of the current one, so that only a gain under every accounting
//! stops it (counting them, a stiff cloth that XPBD hung 3 times too low at one substep, coming
//! to rest, was stopped for 7 times the scale; a blow-up's gain is motion, still counted).
//!
//! The energy is summed on the host, in f64, from a read of the state (`sim::cpu::energy`, the
//! reference's own): every `CHECK_FRAMES` frames, and less often for large scenes (one check
//! per `PARTICLES_PER_FRAME` particles a frame), so that reading costs little next to the
//! frames it checks.

use super::GpuSim;
use crate::sim::gpu_types::Particle;
use crate::sim::model::SimModel;
use crate::sim::stability::{GuardCause, GuardTrip};
use crate::vk::GpuContext;
use anyhow::Result;
use glam::DVec3;

/// Frames between two checks, at least.
const CHECK_FRAMES: u64 = 30;
/// Scenes with more particles than this many a frame are checked less often.
const PARTICLES_PER_FRAME: u64 = 1024;
/// The speed every particle may have from rounding alone, in the scale [m/s].
const FLOOR_SPEED: f64 = 0.1;

/// The lowest total energy so far, with each object's energy at that time.
#[derive(Debug, Clone, Default)]
pub(super) struct EnergyWatch {
    lowest: Option<(f64, Vec<f64>)>,
    scale: f64,
    /// The frame count of the last check.
    checked_at: u64,
}

impl EnergyWatch {
    /// Starts again from the next reading: the host wrote the state or the parameters.
    pub(super) fn restart(&mut self) {
        self.lowest = None;
    }
}

/// Positions and velocities of each object, in f64.
type States = Vec<(Vec<DVec3>, Vec<DVec3>)>;

/// The states of `particles` (one array an object).
pub(super) fn states_of(particles: &[Vec<Particle>]) -> States {
    let v3 = |a: &[f32; 4]| DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64);
    particles
        .iter()
        .map(|ps| (ps.iter().map(|p| v3(&p.pos)).collect(), ps.iter().map(|p| v3(&p.vel)).collect()))
        .collect()
}

/// The energy scale of objects of `masses` [kg per particle] at `states` (positions,
/// velocities) holding `elastic` energy in their springs [J each] under `gravity` [J].
fn scale(masses: &[f64], states: &States, elastic: &[f64], gravity: DVec3) -> f64 {
    (masses.iter().zip(states).zip(elastic))
        .map(|((&m, (x, v)), &elastic)| {
            let (lo, hi) =
                x.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
            let size = if x.is_empty() { 0.0 } else { (hi - lo).length() };
            let kinetic: f64 = v.iter().map(|v| 0.5 * v.length_squared()).sum();
            m * (x.len() as f64 * (gravity.length() * size + 0.5 * FLOOR_SPEED * FLOOR_SPEED) + kinetic)
                + elastic.max(0.0)
        })
        .sum()
}

/// Each object's elastic energy at `states`: its total (`total_energy`) less the kinetic and
/// gravity's [J].
fn elastic_energy(model: &SimModel, states: &States, totals: &[f64]) -> Vec<f64> {
    (model.objects.iter().zip(states).zip(totals))
        .map(|((o, (x, v)), total)| {
            let kinetic: f64 =
                v.iter().enumerate().map(|(i, v)| 0.5 * o.mass_of(i) * v.length_squared()).sum();
            let gravity: f64 = x.iter().enumerate().map(|(i, x)| -o.mass_of(i) * model.gravity.dot(*x)).sum();
            total - kinetic - gravity
        })
        .collect()
}

/// Each object's energy at `states` as its check counts it now: `totals` (`total_energy`), less
/// the springs' energy for a compliant method (the module's comment says why).
fn judged_energy(model: &SimModel, states: &States, totals: &[f64]) -> Vec<f64> {
    if !model.integrator.method().compliant {
        return totals.to_vec();
    }
    let elastic = elastic_energy(model, states, totals);
    totals.iter().zip(elastic).map(|(total, elastic)| total - elastic.max(0.0)).collect()
}

/// Each object's energy at `states` (`sim::cpu::energy`) [J].
fn total_energy(model: &SimModel, states: &States) -> Vec<f64> {
    (model.objects.iter().zip(states)).map(|(o, (x, v))| crate::sim::cpu::energy(model, o, x, v)).collect()
}

impl GpuSim {
    /// Whether the energy check runs: asked for, and nothing in the scene supplies energy.
    fn energy_checked(&self) -> bool {
        self.model.max_energy_gain > 0.0
            && self.model.wind.is_none()
            && !self.model.colliders.iter().any(|c| c.is_moving())
            && !self.model.objects.iter().any(|o| o.pins_move())
    }

    /// Starts the energy check from `states` (what the host wrote, or the first reading).
    pub(super) fn start_energy(&mut self, states: &States) {
        if !self.energy_checked() {
            return;
        }
        let masses: Vec<f64> = self.model.objects.iter().map(|o| o.mass).collect();
        let energies = total_energy(&self.model, states);
        let elastic = elastic_energy(&self.model, states, &energies);
        self.energy.scale = scale(&masses, states, &elastic, self.model.gravity);
        self.energy.lowest = Some((energies.iter().sum(), energies));
    }

    /// The energy check (after a frame's fence, with the guard): the report when the energy grew
    /// past the bound, naming the object that gained most and its fastest particle.
    pub fn check_energy(&mut self, ctx: &GpuContext) -> Result<Option<GuardTrip>> {
        let particles: u64 = self.objects.iter().map(|o| o.particles as u64).sum();
        let every = CHECK_FRAMES.max(particles / PARTICLES_PER_FRAME);
        // After a restart too, the next reading waits a whole interval: a particle held by the
        // app is written every frame, and reading the state each time would stall every frame.
        let due = self.frames >= self.energy.checked_at + every;
        if !self.energy_checked() || !due {
            return Ok(None);
        }
        self.energy.checked_at = self.frames;
        if self.dragged.iter().any(|d| *d != DVec3::ZERO) || !self.pending_writes.is_empty() {
            self.energy.restart();
            return Ok(None);
        }
        let states: States = self.read_states(ctx)?.iter().map(|s| (s.positions(), s.velocities())).collect();
        let Some((lowest, at_lowest)) = &self.energy.lowest else {
            self.start_energy(&states);
            return Ok(None);
        };
        let energies = total_energy(&self.model, &states);
        let total: f64 = energies.iter().sum();
        let judged = judged_energy(&self.model, &states, &energies);
        let gain = judged.iter().sum::<f64>() - lowest;
        if gain > self.model.max_energy_gain * self.energy.scale {
            let (object, _) = (judged.iter().zip(at_lowest).map(|(e, l)| e - l).enumerate())
                .fold((0, f64::NEG_INFINITY), |best, (i, g)| if g > best.1 { (i, g) } else { best });
            let v = &states[object].1;
            let fastest =
                (0..v.len()).max_by(|&a, &b| v[a].length_squared().total_cmp(&v[b].length_squared()));
            let mut trip = GuardTrip::new(
                &self.model,
                object,
                fastest.unwrap_or(0) as u32,
                GuardCause::EnergyGain,
                self.time(),
            );
            trip.what.push_str(&format!(
                ": {gain:.3e} J, {:.2} times the scale of {:.3e} J",
                gain / self.energy.scale,
                self.energy.scale
            ));
            self.energy.restart();
            return Ok(Some(trip));
        }
        if total < *lowest {
            self.energy.lowest = Some((total, energies));
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scale is each object's weight times its size, plus its kinetic and elastic energy,
    /// plus the floor.
    #[test]
    fn scale_is_weight_times_size_plus_kinetic_and_elastic_energy() {
        let x = vec![DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)];
        let v = vec![DVec3::new(2.0, 0.0, 0.0), DVec3::ZERO];
        let s = scale(&[0.5], &vec![(x, v)], &[0.25], DVec3::new(0.0, -10.0, 0.0));
        let expected = 0.5 * (2.0 * (10.0 * 5.0 + 0.5 * FLOOR_SPEED * FLOOR_SPEED) + 2.0) + 0.25;
        assert!((s - expected).abs() < 1e-12, "{s} against {expected}");
    }
}
