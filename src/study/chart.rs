//! The accuracy-against-cost chart: sweeps integrator x substeps x iterations on a scene, runs
//! each setting on the GPU for 2 s of simulated time, and measures its cost (GPU time per
//! simulated second, from timestamps) and its error against the converged CPU reference
//! (`accuracy`). Writes a CSV and an SVG (plotters): error against cost, one curve per method,
//! the Pareto front marked.

use super::accuracy::{self, Error, Reference, Samples, TIMES};
use crate::sim::cpu;
use crate::sim::gpu::{GpuSim, ObjectState};
use crate::sim::model::{Integrator, SimModel};
use crate::sim::stability::GuardTrip;
use crate::vk::GpuContext;
use anyhow::{Context as _, Result};
use glam::DVec3;
use plotters::prelude::*;
use std::fmt::Write as _;

/// What is swept.
#[derive(Debug, Clone)]
pub struct Sweep {
    pub methods: Vec<Integrator>,
    pub substeps: Vec<u32>,
    /// Solver iterations (iterative methods only).
    pub iterations: Vec<u32>,
    /// Substeps per frame of the reference (Verlet on the CPU in f64).
    pub reference_substeps: u32,
}

impl Sweep {
    /// The settings to run: every method at every substep count, the iterative ones also at
    /// every iteration count.
    pub fn settings(&self) -> Vec<(Integrator, u32, u32)> {
        let mut out = Vec::new();
        for &m in &self.methods {
            for &s in &self.substeps {
                if m.iterative() {
                    out.extend(self.iterations.iter().map(|&i| (m, s, i)));
                } else {
                    out.push((m, s, 0));
                }
            }
        }
        out
    }
}

/// One run of the sweep.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Point {
    pub scene: String,
    pub method: Integrator,
    pub substeps: u32,
    /// 0 for the explicit methods.
    pub iterations: u32,
    pub dt: f64,
    /// GPU time per simulated second [ms/s].
    pub gpu_ms_per_s: f64,
    /// At each sample time (`TIMES` in the chart; absent past a guard trip).
    pub errors: Vec<Error>,
    /// Largest structural strain at the sample times.
    pub max_strain: f64,
    /// Total energy at the end minus at the start [J].
    pub energy_change: f64,
    /// Where the runtime guard stopped the run (None: it ran to the end).
    pub unstable: Option<String>,
}

impl Point {
    /// The error the chart plots: the largest RMS error over the sample times.
    pub fn error(&self) -> f64 {
        if self.unstable.is_some() || self.errors.is_empty() {
            return f64::INFINITY;
        }
        self.errors.iter().map(|e| e.rms).fold(0.0, f64::max)
    }
}

fn positions(states: &[ObjectState]) -> (Vec<Vec<DVec3>>, Vec<Vec<DVec3>>) {
    (
        states.iter().map(ObjectState::positions).collect(),
        states.iter().map(ObjectState::velocities).collect(),
    )
}

fn energy(model: &SimModel, x: &[Vec<DVec3>], v: &[Vec<DVec3>]) -> f64 {
    model.objects.iter().zip(x.iter().zip(v)).map(|(o, (x, v))| cpu::energy(model, o, x, v)).sum()
}

/// Runs one setting of `base` on the GPU until the last of `times`, measuring its cost and its
/// error against `reference` (positions at each of `times`).
pub fn run_point(
    ctx: &GpuContext,
    scene: &str,
    base: &SimModel,
    times: &[f64],
    reference: &Samples,
    (method, substeps, iterations): (Integrator, u32, u32),
) -> Result<Point> {
    let mut model = base.clone();
    model.integrator = method;
    model.substeps = substeps;
    model.iterations = iterations.max(1);
    // Each point records its own largest strain (and `auto` judges it), so the guard's
    // plausibility check is off here: it would stop a setting instead of measuring it.
    model.plausibility_off();
    let mut sim = GpuSim::new(ctx, &model)?;
    sim.set_stage_timing(false);
    sim.silence_contact_warning();
    let result = (|| -> Result<Point> {
        let (x0, v0) = positions(&sim.read_states(ctx)?);
        let start_energy = energy(&model, &x0, &v0);
        let mut point = Point {
            scene: scene.to_string(),
            method,
            substeps,
            iterations,
            dt: model.dt(),
            gpu_ms_per_s: 0.0,
            errors: Vec::new(),
            max_strain: 0.0,
            energy_change: f64::NAN,
            unstable: None,
        };
        let mut gpu_ms = 0.0;
        let mut frame = 0;
        for (k, &t) in times.iter().enumerate() {
            while frame < accuracy::frames_until(&model, t) {
                match sim.step_frame(ctx) {
                    Ok(Some(timing)) => gpu_ms += timing.total_ms,
                    Ok(None) => {
                        anyhow::bail!("{} has no GPU timestamps: the chart needs them", ctx.info().name)
                    }
                    Err(e) => match e.downcast::<GuardTrip>() {
                        Ok(trip) => {
                            point.unstable = Some(trip.what.clone());
                            point.gpu_ms_per_s = gpu_ms / ((frame as f64).max(1.0) * model.frame_dt);
                            return Ok(point);
                        }
                        Err(e) => return Err(e),
                    },
                }
                frame += 1;
            }
            let (x, v) = positions(&sim.read_states(ctx)?);
            point.errors.push(accuracy::error(&model, &x, &reference[k]));
            for (o, x) in model.objects.iter().zip(&x) {
                point.max_strain = point.max_strain.max(cpu::max_strain(o, x));
            }
            if k + 1 == times.len() {
                point.energy_change = energy(&model, &x, &v) - start_energy;
            }
        }
        point.gpu_ms_per_s = gpu_ms / (frame as f64 * model.frame_dt);
        Ok(point)
    })();
    sim.destroy(ctx);
    result
}

/// Keeps the GPU busy for a second of wall time before measuring: the sweep's frames are short
/// and separated by host waits, and a GPU that idled through the CPU reference starts at a low
/// clock. (Measured on an H100 without this: the first setting of a sweep cost 4 times as
/// much as the same work a minute later.)
fn warm_up(ctx: &GpuContext, model: &SimModel) -> Result<()> {
    let mut m = model.clone();
    m.integrator = Integrator::Verlet;
    m.substeps = 64;
    let mut sim = GpuSim::new(ctx, &m)?;
    sim.set_stage_timing(false);
    let start = std::time::Instant::now();
    let mut result = Ok(());
    while start.elapsed() < std::time::Duration::from_secs(1) && result.is_ok() {
        result = sim.step_frame(ctx).map(|_| ());
    }
    sim.destroy(ctx);
    // A blow-up while warming up only means the scene needs more substeps: the sweep says so.
    match result {
        Err(e) if !e.is::<GuardTrip>() => Err(e),
        _ => Ok(()),
    }
}

/// The largest difference between the reference and itself at half its substeps (a fraction
/// of the object's size) that still charts errors down to about 1e-3.
const REFERENCE_MAX_CHECK: f64 = 1e-3;

/// Runs the sweep on one scene: the reference first, then every setting; `progress` is called
/// after each.
pub fn run(
    ctx: &GpuContext,
    scene: &str,
    model: &SimModel,
    sweep: &Sweep,
    mut progress: impl FnMut(&Point),
) -> Result<(Reference, Vec<Point>)> {
    let reference = accuracy::reference(model, &TIMES, sweep.reference_substeps);
    // The reference at N and N/2 substeps must agree to a small fraction of the object's size,
    // or every error charted against it is meaningless (a scene that blows up or is chaotic).
    if reference.check.is_nan() || reference.check >= REFERENCE_MAX_CHECK {
        return Err(crate::error::UserError(format!(
            "chart of {scene}: the reference (Verlet at {} substeps per frame on the CPU) is not converged: it differs from \
             itself at half the substeps by {:.1e} of the object's size (at most {REFERENCE_MAX_CHECK:e} is needed); raise \
             --reference-substeps, or chart a scene that is stable and smooth at that step",
            sweep.reference_substeps,
            reference.check
        ))
        .into());
    }
    warm_up(ctx, model)?;
    let mut points = Vec::new();
    for setting in sweep.settings() {
        let point = run_point(ctx, scene, model, &TIMES, &reference.samples, setting)
            .with_context(|| format!("chart of {scene}: {setting:?}"))?;
        progress(&point);
        points.push(point);
    }
    Ok((reference, points))
}

/// Indices of the points on the Pareto front (no other point is both cheaper and more
/// accurate), by increasing cost.
pub fn pareto(points: &[Point]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).filter(|&i| points[i].error().is_finite()).collect();
    order.sort_by(|&a, &b| points[a].gpu_ms_per_s.total_cmp(&points[b].gpu_ms_per_s));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in order {
        if points[i].error() < best {
            best = points[i].error();
            front.push(i);
        }
    }
    front
}

pub fn csv(points: &[Point], header: &str) -> String {
    let mut out = String::new();
    for line in header.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let times: Vec<String> = TIMES.iter().flat_map(|t| [format!("rms_{t}s"), format!("max_{t}s")]).collect();
    let _ = writeln!(
        out,
        "scene,method,substeps,iterations,dt_s,gpu_ms_per_simulated_s,{},max_strain,energy_change_j,pareto,unstable",
        times.join(",")
    );
    let front = pareto(points);
    for (i, p) in points.iter().enumerate() {
        let errors: Vec<String> = (0..TIMES.len())
            .flat_map(|k| match p.errors.get(k) {
                Some(e) => [format!("{:.4e}", e.rms), format!("{:.4e}", e.max)],
                None => [String::new(), String::new()],
            })
            .collect();
        let _ = writeln!(
            out,
            "{},{},{},{},{:.6e},{:.4},{},{:.4e},{:.4e},{},{}",
            p.scene,
            p.method.label(),
            p.substeps,
            p.iterations,
            p.dt,
            p.gpu_ms_per_s,
            errors.join(","),
            p.max_strain,
            p.energy_change,
            front.contains(&i),
            p.unstable.as_deref().unwrap_or("").replace(',', ";")
        );
    }
    out
}

fn color(m: Integrator) -> RGBColor {
    let (r, g, b) = m.method().colour;
    RGBColor(r, g, b)
}

/// Error against cost on log axes: a curve per method and iteration count (explicit methods:
/// one curve over the substep counts), unstable runs as crosses on the top edge, the Pareto
/// front as a dashed black line through circled points.
pub fn svg(points: &[Point], title: &str) -> Result<String> {
    let finite: Vec<&Point> =
        points.iter().filter(|p| p.error().is_finite() && p.gpu_ms_per_s > 0.0).collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in points.iter().filter(|p| p.gpu_ms_per_s > 0.0) {
        x0 = x0.min(p.gpu_ms_per_s);
        x1 = x1.max(p.gpu_ms_per_s);
    }
    for p in &finite {
        y0 = y0.min(p.error());
        y1 = y1.max(p.error());
    }
    if finite.is_empty() {
        (y0, y1) = (1e-6, 1.0);
    }
    if x0 > x1 {
        (x0, x1) = (1.0, 10.0);
    }
    let (x0, x1) = (x0 / 1.5, x1 * 1.5);
    let (y0, y1) = (y0.max(1e-12) / 2.0, y1 * 4.0);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (960, 640)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("GPU time per simulated second [ms]")
            .y_desc("position error (RMS / object size, worst of t = 0.5, 1, 2 s)")
            .x_label_formatter(&|v| if *v >= 10.0 { format!("{v:.0}") } else { format!("{v:.2}") })
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        let mut curves: Vec<(Integrator, u32)> = points.iter().map(|p| (p.method, p.iterations)).collect();
        curves.sort_by_key(|c| (c.0 as u32, c.1));
        curves.dedup();
        for (method, iterations) in curves {
            let mut line: Vec<(f64, f64)> = finite
                .iter()
                .filter(|p| p.method == method && p.iterations == iterations)
                .map(|p| (p.gpu_ms_per_s, p.error()))
                .collect();
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            let c = color(method);
            let label = if method.iterative() {
                format!("{} ({iterations} it.)", method.label())
            } else {
                method.label().to_string()
            };
            let style = if method.iterative() && iterations > 0 {
                c.mix(0.35 + 0.65 * (iterations as f64).log10().min(2.0) / 2.0).stroke_width(2)
            } else {
                c.stroke_width(2)
            };
            chart
                .draw_series(LineSeries::new(line.clone(), style))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
            chart.draw_series(line.iter().map(|&(x, y)| Circle::new((x, y), 3, c.filled())))?;
        }
        let unstable: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| !p.error().is_finite() && p.gpu_ms_per_s > 0.0)
            .map(|p| (p.gpu_ms_per_s, y1 / 1.5))
            .collect();
        if !unstable.is_empty() {
            chart
                .draw_series(unstable.iter().map(|&(x, y)| Cross::new((x, y), 5, BLACK.stroke_width(2))))?
                .label("unstable (guard tripped)")
                .legend(|(x, y)| Cross::new((x + 10, y), 5, BLACK.stroke_width(2)));
        }
        let front: Vec<(f64, f64)> =
            pareto(points).into_iter().map(|i| (points[i].gpu_ms_per_s, points[i].error())).collect();
        chart
            .draw_series(DashedLineSeries::new(front.clone(), 6, 4, BLACK.stroke_width(1)))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
        chart.draw_series(front.iter().map(|&(x, y)| Circle::new((x, y), 7, BLACK.stroke_width(1))))?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()?;
        root.present()?;
    }
    Ok(out)
}
