//! The error metric of the accuracy study: a run's positions against a converged reference of
//! the same scene at t = 0.5, 1 and 2 s, RMS and max over the particles, normalised by the
//! object's size; the largest spring strain over the run; the energy drift.
//!
//! The reference is the f64 CPU simulation with position Verlet (second order) at a fine step.
//! It is shown to have converged by running it again at half the substeps: by Richardson, the
//! fine run's own error is about a third of the difference between the two.

use crate::sim::cpu::{self, CpuSim};
use crate::sim::model::{Integrator, ObjectModel, SimModel};
use glam::DVec3;

/// The times at which errors are measured [s].
pub const TIMES: [f64; 3] = [0.5, 1.0, 2.0];

/// Positions of every object at each sample time: `[time][object][particle]`.
pub type Samples = Vec<Vec<Vec<DVec3>>>;

/// A run on the CPU reference.
#[derive(Debug, Clone)]
pub struct CpuRun {
    pub samples: Samples,
    /// Largest structural strain seen at any frame.
    pub max_strain: f64,
    /// Total energy at the start and at the end [J].
    pub energy: (f64, f64),
    pub finite: bool,
}

/// Frames until time `t` (rounded to the nearest frame).
pub fn frames_until(model: &SimModel, t: f64) -> u64 {
    (t / model.frame_dt).round() as u64
}

fn total_energy(model: &SimModel, sim: &CpuSim) -> f64 {
    model.objects.iter().zip(sim.objects()).map(|(o, s)| cpu::energy(model, o, &s.x, &s.v)).sum()
}

/// Runs `model` on the CPU reference, sampling positions at `times` (ascending).
pub fn cpu_run(model: &SimModel, times: &[f64]) -> CpuRun {
    let mut sim = CpuSim::new(model);
    let start = total_energy(model, &sim);
    let mut samples = Vec::with_capacity(times.len());
    let mut max_strain = 0.0f64;
    let mut frame = 0;
    for &t in times {
        while frame < frames_until(model, t) {
            sim.step_frame();
            frame += 1;
            for (o, s) in model.objects.iter().zip(sim.objects()) {
                max_strain = max_strain.max(cpu::max_strain(o, &s.x));
            }
        }
        samples.push(sim.objects().iter().map(|s| s.x.clone()).collect());
    }
    let end = total_energy(model, &sim);
    let finite = samples.iter().flatten().flatten().all(|p: &DVec3| p.is_finite());
    CpuRun { samples, max_strain, energy: (start, end), finite }
}

/// The size an object's errors are normalised by: the diagonal of its rest grid (of a mesh
/// cloth's box) [m].
pub fn object_size(o: &ObjectModel) -> f64 {
    // (a mesh cloth: the diagonal of its placed vertices' box)
    if o.mesh.is_some() {
        let (lo, hi) = crate::sim::collider_mesh::bounds(&o.positions);
        return (hi - lo).length().max(1e-9);
    }
    let w = (o.dims[0].max(1) - 1) as f64 * o.spacing[0];
    let h = (o.dims[1].max(1) - 1) as f64 * o.spacing[1];
    w.hypot(h).max(1e-9)
}

/// Position error of one sample, normalised by each object's size.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Error {
    /// Root mean square over every particle of every object.
    pub rms: f64,
    /// Largest over every particle.
    pub max: f64,
}

/// The error of positions `run` against `reference` (one entry per object); non-finite
/// positions give an infinite error.
pub fn error(model: &SimModel, run: &[Vec<DVec3>], reference: &[Vec<DVec3>]) -> Error {
    let (mut sum, mut count, mut max) = (0.0, 0usize, 0.0f64);
    for ((o, a), b) in model.objects.iter().zip(run).zip(reference) {
        let size = object_size(o);
        for (p, q) in a.iter().zip(b) {
            let e = if p.is_finite() { p.distance(*q) / size } else { f64::INFINITY };
            sum += e * e;
            max = max.max(e);
            count += 1;
        }
    }
    Error { rms: (sum / count.max(1) as f64).sqrt(), max }
}

/// The converged reference of a scene.
#[derive(Debug, Clone)]
pub struct Reference {
    pub samples: Samples,
    pub substeps: u32,
    /// The largest RMS difference over the sample times between the reference and the same
    /// run at half the substeps: about three times the reference's own error (second order).
    pub check: f64,
}

/// Runs the reference (Verlet, `substeps` per frame, the CPU in f64) and its check at half
/// the substeps.
pub fn reference(model: &SimModel, times: &[f64], substeps: u32) -> Reference {
    let at = |n: u32| {
        let mut m = model.clone();
        m.integrator = Integrator::Verlet;
        m.substeps = n;
        (m.clone(), cpu_run(&m, times).samples)
    };
    let (fine_model, fine) = at(substeps);
    let (_, coarse) = at((substeps / 2).max(1));
    let check = fine.iter().zip(&coarse).map(|(a, b)| error(&fine_model, b, a).rms).fold(0.0, f64::max);
    Reference { samples: fine, substeps, check }
}
