//! `sim.integrator = "auto"`: a short calibration that picks the cheapest integrator, substep
//! count and iteration count whose error stays within `sim.tolerance`.
//!
//! The scene runs for a calibration time (`CALIBRATION_TIMES`) on the GPU with each candidate;
//! its error is the RMS
//! position error over the particles at the end, normalised by the object's size (as in the
//! accuracy chart), against a reference: position Verlet at 128 substeps per frame on the GPU
//! (the scene may be far too large for the CPU reference), checked against the same at half the
//! substeps, or at 256 where that check cannot certify the tolerance (`REFERENCE_SUBSTEPS`). The time is the longest of 0.5, 0.25 and 0.1 s at which the reference
//! certifies the tolerance (its own error within 0.3 of it): a scene that flaps in the wind or folds onto
//! itself is chaotic, and over 0.5 s its reference agrees with itself only to a few 1e-3 of its
//! size, while over a shorter time it is exact. For each method (and iteration count) the substep count doubles from 1 to
//! 64 until the tolerance is met (the explicit methods start at their predicted stability
//! limit: a scene's stretch limit can hold an unstable one together through a short
//! calibration, jittering); of the settings that meet it, the one with the least GPU time per
//! simulated second (timestamps) wins. A setting that costs at least as much as the best found
//! so far (`cost_lower_bound`) is not run, nor the rest of its curve.

use super::accuracy::Samples;
use super::chart::{run_point, Point};
use crate::error::UserError;
use crate::scene::{self, Scene};
use crate::sim::gpu::{GpuSim, ObjectState};
use crate::sim::model::{Integrator, SimModel};
use crate::vk::GpuContext;
use anyhow::Result;
use glam::DVec3;

/// Simulated times the calibration tries, longest first [s].
pub const CALIBRATION_TIMES: [f64; 3] = [0.5, 0.25, 0.1];
/// Substeps per frame of the references tried, each checked against itself at half as many.
const REFERENCE_SUBSTEPS: [u32; 2] = [128, 256];
const SUBSTEPS: [u32; 7] = [1, 2, 4, 8, 16, 32, 64];
const ITERATIONS: [u32; 2] = [4, 10];

/// What the calibration picked and why.
#[derive(Debug, Clone)]
pub struct Pick {
    /// The cheapest setting within the tolerance.
    pub best: Point,
    /// Every setting tried, in order.
    pub tried: Vec<Point>,
    /// Methods (with an iteration count) whose doubling stopped before meeting the tolerance
    /// because its next setting could not be cheaper than the best found before it.
    pub cut: usize,
    /// The reference's own error estimate.
    pub reference_error: f64,
    /// The calibration time used [s].
    pub time: f64,
}

impl Pick {
    pub fn describe(&self, tolerance: f64) -> String {
        let b = &self.best;
        let iterations =
            if b.method.iterative() { format!(", {} iterations", b.iterations) } else { String::new() };
        format!(
            "integrator = \"auto\" picked {} with {} substeps{iterations}: error {:.2e} of the object's size after {} s (tolerance {tolerance:.1e}), {:.2} ms of GPU time per simulated second; {} settings tried ({} methods stopped where they could no longer be cheaper)",
            b.method.label(),
            b.substeps,
            b.error(),
            self.time,
            b.gpu_ms_per_s,
            self.tried.len(),
            self.cut
        )
    }

    /// The model with the pick applied.
    pub fn apply(&self, model: &SimModel) -> SimModel {
        let mut m = model.clone();
        m.integrator = self.best.method;
        m.substeps = self.best.substeps;
        m.iterations = self.best.iterations.max(1);
        m
    }
}

/// Positions of every object after `t` seconds of Verlet at `substeps` per frame on the GPU.
fn gpu_reference(ctx: &GpuContext, model: &SimModel, t: f64, substeps: u32) -> Result<Vec<Vec<DVec3>>> {
    let mut m = model.clone();
    m.integrator = Integrator::Verlet;
    m.substeps = substeps;
    // Its accuracy is certified against itself, and the run that follows the pick keeps the
    // guard's plausibility checks; here they would stop the calibration instead.
    m.plausibility_off();
    let mut sim = GpuSim::new(ctx, &m)?;
    let result = (|| -> Result<Vec<Vec<DVec3>>> {
        for _ in 0..super::accuracy::frames_until(&m, t) {
            sim.step_frame(ctx)?;
        }
        Ok(sim.read_states(ctx)?.iter().map(ObjectState::positions).collect())
    })();
    sim.destroy(ctx);
    result
}

/// What `(method, substeps, iterations)` costs at least, from the settings already tried: no
/// less GPU time per simulated second than the same method at no more substeps and iterations
/// (a substep's work does not shrink as they grow; measured on lavapipe, doubling the substeps
/// costs 1.14 to 2.2 times as much). A setting whose bound reaches the best cost so far cannot
/// win, and neither can the rest of its curve, so the calibration skips them.
fn cost_lower_bound(tried: &[Point], method: Integrator, substeps: u32, iterations: u32) -> f64 {
    tried
        .iter()
        .filter(|q| q.method == method && q.substeps <= substeps && q.iterations <= iterations)
        .filter(|q| q.unstable.is_none() && q.gpu_ms_per_s.is_finite())
        .map(|q| q.gpu_ms_per_s)
        .fold(0.0, f64::max)
}

/// Calibrates `model` for `tolerance`; `progress` is called after each setting.
pub fn calibrate(
    ctx: &GpuContext,
    model: &SimModel,
    tolerance: f64,
    mut progress: impl FnMut(&Point),
) -> Result<Pick> {
    let mut certified = None;
    let mut best_reference = f64::INFINITY;
    'times: for time in CALIBRATION_TIMES {
        // The cheaper reference first; where it cannot certify the tolerance, the finer one,
        // checked against it. Where Verlet at the coarsest count blows up (a stiff scene), the
        // check starts at the next pair.
        let mut coarse = match gpu_reference(ctx, model, time, REFERENCE_SUBSTEPS[0] / 2) {
            Ok(states) => Some(states),
            Err(e) if e.downcast_ref::<crate::sim::stability::GuardTrip>().is_some() => None,
            Err(e) => return Err(e),
        };
        for substeps in REFERENCE_SUBSTEPS {
            let fine = gpu_reference(ctx, model, time, substeps)?;
            if let Some(coarse) = &coarse {
                let reference_error = super::accuracy::error(model, coarse, &fine).rms / 3.0;
                best_reference = best_reference.min(reference_error);
                if reference_error <= 0.3 * tolerance {
                    certified = Some((time, fine, reference_error));
                    break 'times;
                }
            }
            coarse = Some(fine);
        }
    }
    let Some((time, fine, reference_error)) = certified else {
        return Err(UserError(format!(
            "sim.tolerance = {tolerance:.1e} cannot be certified on this scene: certifying it needs a reference good to {:.1e} \
             (0.3 of it), and the reference (Verlet at up to {} substeps per frame, against itself at half \
             that) is good to {best_reference:.1e} at best over {:?} s; choose sim.tolerance = {:.1e} or more, or an \
             integrator and substep count by hand",
            0.3 * tolerance,
            REFERENCE_SUBSTEPS[1],
            CALIBRATION_TIMES,
            best_reference / 0.3
        ))
        .into());
    };
    let reference: Samples = vec![fine];
    let mut curves: Vec<(Integrator, u32)> = Vec::new();
    // (a mesh cloth runs with the methods sim::cloth_mesh::METHODS names)
    let meshes = model.objects.iter().any(|o| o.mesh.is_some());
    for m in Integrator::ALL.into_iter().filter(|m| !meshes || crate::sim::cloth_mesh::METHODS.contains(m)) {
        if m.iterative() {
            curves.extend(ITERATIONS.iter().map(|&i| (m, i)));
        } else {
            curves.push((m, 0));
        }
    }
    let mut tried = Vec::new();
    let mut cut = 0;
    let mut best: Option<Point> = None;
    let min_explicit = crate::sim::stability::predict(model)
        .iter()
        .map(|p| p.min_substeps(model.frame_dt))
        .max()
        .unwrap_or(1);
    for (method, iterations) in curves {
        let start = if method.iterative() { 1 } else { min_explicit };
        for substeps in SUBSTEPS.into_iter().filter(|&s| s >= start) {
            if best
                .as_ref()
                .is_some_and(|b| cost_lower_bound(&tried, method, substeps, iterations) >= b.gpu_ms_per_s)
            {
                cut += 1;
                break;
            }
            let point = run_point(ctx, "auto", model, &[time], &reference, (method, substeps, iterations))?;
            progress(&point);
            let ok = point.error() <= tolerance;
            if ok && best.as_ref().is_none_or(|b| point.gpu_ms_per_s < b.gpu_ms_per_s) {
                best = Some(point.clone());
            }
            tried.push(point);
            if ok {
                break;
            }
        }
    }
    let Some(best) = best else {
        let closest = tried.iter().map(Point::error).fold(f64::INFINITY, f64::min);
        return Err(UserError(format!(
            "no integrator met sim.tolerance = {tolerance:.1e} within 64 substeps per frame (the best error was {closest:.2e}): raise the tolerance, or set sim.integrator and sim.substeps by hand"
        ))
        .into());
    };
    Ok(Pick { best, tried, cut, reference_error, time })
}

/// The model of a validated scene, calibrated when it asks for `integrator = "auto"`; the
/// description of the pick comes with it.
pub fn model_for(ctx: &GpuContext, scene: &Scene) -> Result<(SimModel, Option<String>)> {
    let model = scene::to_model(scene);
    if scene.sim.integrator.method().is_some() {
        return Ok((model, None));
    }
    crate::sim::gpu::check_fits(ctx.info(), &scene::shapes(scene))?;
    let tolerance = scene.sim.tolerance;
    let pick = calibrate(ctx, &model, tolerance, |p| {
        log::info!(
            "auto: {} {} substeps {} iterations: error {:.2e}, {:.1} ms of GPU time per simulated second",
            p.method.label(),
            p.substeps,
            p.iterations,
            p.error(),
            p.gpu_ms_per_s
        )
    })?;
    Ok((pick.apply(&model), Some(pick.describe(tolerance))))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(method: Integrator, substeps: u32, iterations: u32, gpu_ms_per_s: f64) -> Point {
        Point {
            scene: "s".into(),
            method,
            substeps,
            iterations,
            dt: 0.0,
            gpu_ms_per_s,
            errors: Vec::new(),
            max_strain: 0.0,
            energy_change: 0.0,
            unstable: None,
        }
    }

    /// The bound is the same method's dearest setting at no more substeps and iterations; other
    /// methods, more substeps or iterations, and runs the guard stopped do not count.
    #[test]
    fn cost_bound_counts_only_cheaper_settings_of_the_same_method() {
        let mut stopped = point(Integrator::Vbd, 1, 4, 900.0);
        stopped.unstable = Some("blew up".into());
        let tried = vec![
            point(Integrator::Vbd, 1, 4, 10.0),
            point(Integrator::Vbd, 2, 4, 30.0),
            point(Integrator::Vbd, 4, 4, 70.0),
            point(Integrator::Vbd, 1, 10, 50.0),
            point(Integrator::Xpbd, 1, 4, 500.0),
            stopped,
        ];
        assert_eq!(cost_lower_bound(&tried, Integrator::Vbd, 4, 4), 70.0);
        assert_eq!(cost_lower_bound(&tried, Integrator::Vbd, 8, 4), 70.0);
        assert_eq!(cost_lower_bound(&tried, Integrator::Vbd, 2, 10), 50.0);
        assert_eq!(cost_lower_bound(&tried, Integrator::Vbd, 1, 4), 10.0);
        assert_eq!(cost_lower_bound(&tried, Integrator::Implicit, 64, 10), 0.0);
    }
}
