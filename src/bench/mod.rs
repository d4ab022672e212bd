//! `msdsim bench`: a matrix of generated scenes timed with GPU timestamps, a bandwidth probe
//! for the roofline, and the Markdown and CSV reports.

pub mod bandwidth;
pub mod cases;
pub mod report;

use crate::scene;
use crate::shaders::ShaderSet;
use crate::sim::gpu::{FrameTiming, FusedLimits, GpuSim};
use crate::vk::GpuContext;
use anyhow::{Context as _, Result};

/// Median and spread of one quantity over the measured frames [ms].
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct Spread {
    pub median: f64,
    pub p10: f64,
    pub p90: f64,
}

impl Spread {
    pub fn of(values: &[f64]) -> Self {
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let at = |q: f64| v.get(((v.len() - 1) as f64 * q).round() as usize).copied().unwrap_or(0.0);
        Self { median: at(0.5), p10: at(0.1), p90: at(0.9) }
    }
}

/// The measurement of one case.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Measurement {
    pub group: String,
    pub case: String,
    pub particles: u64,
    pub substeps: u32,
    /// "fused" when every object ran its substeps in one workgroup, else "per stage".
    pub path: &'static str,
    pub frames: usize,
    pub total: Spread,
    pub physics: Spread,
    pub constraints: Spread,
    pub surface: Spread,
}

/// What an end-to-end run measured. Wall-clock figures cover the measured frames from the
/// first submission to the last fence; GPU figures are per-frame timestamps.
#[derive(Debug, Clone, Default)]
pub struct EndToEnd {
    pub case: String,
    pub particles: u64,
    pub frames: usize,
    /// Wall-clock time per frame: the run's elapsed time over its frames [ms].
    pub wall_ms: f64,
    /// Spread of the wall-clock intervals between consecutive submissions [ms].
    pub interval: Spread,
    /// The host's time to record and submit a frame [ms].
    pub record: Spread,
    /// GPU time of the simulation part of a frame [ms] (`None`: no timestamps).
    pub sim_gpu: Option<Spread>,
    /// GPU time of the drawing [ms].
    pub render_gpu: Option<Spread>,
    /// "fused" when every object ran fused, else "per stage".
    pub path: &'static str,
    /// The last frame, RGBA8, when asked for.
    pub pixels: Option<Vec<u8>>,
}

impl EndToEnd {
    pub fn frames_per_second(&self) -> f64 {
        1e3 / self.wall_ms.max(1e-9)
    }
}

/// Runs `case` for `warmup` frames, then measures `frames` frames twice: with only a start and
/// an end timestamp per frame (the totals), then with timestamps between the stages (the
/// per-stage times; those timestamps cost a little themselves, so totals come from the first).
/// `fused_slots`: objects of up to that many particles per thread run fused (where they fit the
/// shared memory; `None`: the default, `Some(0)`: every object per stage).
pub fn measure(
    ctx: &GpuContext,
    case: &cases::Case,
    warmup: usize,
    frames: usize,
    fused_slots: Option<u32>,
    shaders: &mut ShaderSet,
) -> Result<Measurement> {
    // The bench times scenes, whatever they stretch to (a 1024-row cloth of the bench's springs
    // hangs far past twice its rest length at the top): the guard's plausibility check is off.
    let mut model = scene::to_model(&case.scene);
    model.plausibility_off();
    let limits = FusedLimits::for_device(ctx.info()).with_slots(fused_slots);
    let mut sim = GpuSim::with_fused_limits(ctx, &model, limits, shaders)
        .with_context(|| format!("setting up {}", case.name))?;
    sim.set_drawn(false); // headless: the surface stage runs the guard only
    let path = if (0..model.objects.len()).all(|i| sim.runs_fused(i)) { "fused" } else { "per stage" };
    let run = (|| -> Result<(Vec<FrameTiming>, Vec<FrameTiming>)> {
        for _ in 0..warmup {
            sim.step_frame(ctx)?;
        }
        let mut timed = |stages: bool| -> Result<Vec<FrameTiming>> {
            sim.set_stage_timing(stages);
            (0..frames)
                .map(|_| sim.step_frame(ctx)?.context("the device has no timestamps: nothing to measure"))
                .collect()
        };
        let totals = timed(false)?;
        let stages = timed(true)?;
        Ok((totals, stages))
    })();
    sim.destroy(ctx);
    let (totals, timings) = run?;
    let spread = |f: fn(&FrameTiming) -> f64| Spread::of(&timings.iter().map(f).collect::<Vec<_>>());
    Ok(Measurement {
        group: case.group.to_string(),
        case: case.name.clone(),
        particles: model.objects.iter().map(|o| o.particle_count() as u64).sum(),
        substeps: model.substeps,
        path,
        frames,
        total: Spread::of(&totals.iter().map(|t| t.total_ms).collect::<Vec<_>>()),
        physics: spread(|t| t.physics_ms),
        constraints: spread(|t| t.constraints_ms),
        surface: spread(|t| t.surface_ms),
    })
}
