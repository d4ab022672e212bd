//! The stability map: sweeps a stiffness scale (rows) against the substep count (columns) on a
//! scene with one integrator, runs each cell on the GPU and classifies it: stable, non-finite (NaN), runaway (a speed
//! past `sim.max_speed`: energy blowing up) or over-stretched (a structural spring strained past a
//! bound at the end). Each cell also carries the predicted explicit limit's verdict
//! (w_max dt <= 2; the iterative methods are predicted stable everywhere). Writes a CSV and an
//! SVG heat map.

use crate::scene::{self, Scene};
use crate::sim::cpu;
use crate::sim::gpu::GpuSim;
use crate::sim::model::Integrator;
use crate::sim::stability::{predict, GuardCause, GuardTrip};
use crate::vk::GpuContext;
use anyhow::Result;
use std::fmt::Write as _;

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    Stable,
    NonFinite,
    Runaway,
    Overstretched,
}

impl Outcome {
    fn color(self) -> &'static str {
        match self {
            Outcome::Stable => "#4caf50",
            Outcome::NonFinite => "#d32f2f",
            Outcome::Runaway => "#f57c00",
            Outcome::Overstretched => "#7b1fa2",
        }
    }

    fn label(self) -> &'static str {
        match self {
            Outcome::Stable => "stable",
            Outcome::NonFinite => "NaN",
            Outcome::Runaway => "runaway",
            Outcome::Overstretched => "over-stretched",
        }
    }
}

#[derive(Debug, Clone)]
pub struct Cell {
    pub method: Integrator,
    pub stiffness_scale: f64,
    pub substeps: u32,
    pub dt: f64,
    /// Predicted largest stable substep of the stiffest object [s].
    pub dt_max: f64,
    pub outcome: Outcome,
}

impl Cell {
    pub fn predicted_stable(&self) -> bool {
        self.method.iterative() || self.dt <= self.dt_max
    }
}

/// The sweep's settings.
pub struct Sweep {
    pub scales: Vec<f64>,
    pub substeps: Vec<u32>,
    pub frames: usize,
    /// Largest structural strain (|length / rest - 1|) still counted as stable.
    pub max_strain: f64,
}

impl Sweep {
    /// `points` log-spaced stiffness scales over `decades` decades centred on 1, and `points`
    /// substep counts from 1 to 64, log-spaced (duplicates removed).
    pub fn new(points: usize, decades: f64, frames: usize, max_strain: f64) -> Self {
        let points = points.max(2);
        let scales = (0..points)
            .map(|i| 10f64.powf(-decades / 2.0 + decades * i as f64 / (points - 1) as f64))
            .collect();
        let mut substeps: Vec<u32> =
            (0..points).map(|i| 2f64.powf(6.0 * i as f64 / (points - 1) as f64).round() as u32).collect();
        substeps.dedup();
        Self { scales, substeps, frames, max_strain }
    }
}

fn scaled(base: &Scene, method: Integrator, scale: f64, substeps: u32) -> Scene {
    let mut s = base.clone();
    s.sim.substeps = substeps;
    s.sim.integrator = crate::scene::IntegratorChoice::Method(method);
    for c in &mut s.cloths {
        c.stiffness.structural *= scale;
        c.stiffness.shear *= scale;
        c.stiffness.bending *= scale;
    }
    for r in &mut s.ropes {
        r.stiffness *= scale;
        r.bending_stiffness *= scale;
    }
    s
}

/// Largest |length / rest - 1| over the structural springs of every object.
fn max_strain(model: &crate::sim::model::SimModel, states: &[crate::sim::gpu::ObjectState]) -> f64 {
    model.objects.iter().zip(states).map(|(o, s)| cpu::max_strain(o, &s.positions())).fold(0.0, f64::max)
}

/// Runs the sweep with `method`; `progress` is called after each cell.
pub fn run(
    ctx: &GpuContext,
    base: &Scene,
    method: Integrator,
    sweep: &Sweep,
    mut progress: impl FnMut(&Cell),
) -> Result<Vec<Cell>> {
    let mut cells = Vec::new();
    for &scale in &sweep.scales {
        for &substeps in &sweep.substeps {
            let scene = scaled(base, method, scale, substeps);
            scene::validate(&scene).map_err(crate::error::UserError)?;
            // The map judges strain itself, at the end of the run (`sweep.max_strain`), so the
            // guard's plausibility check is off here: it would stop a soft cell early.
            let mut model = scene::to_model(&scene);
            model.plausibility_off();
            let dt_max = predict(&model).iter().map(|p| p.dt_max).fold(f64::INFINITY, f64::min);
            let mut sim = GpuSim::new(ctx, &model)?;
            let run = (|| -> Result<Outcome> {
                for _ in 0..sweep.frames {
                    if let Err(e) = sim.step_frame(ctx) {
                        return match e.downcast_ref::<GuardTrip>() {
                            Some(t) => Ok(match t.cause {
                                GuardCause::NonFinite => Outcome::NonFinite,
                                GuardCause::Runaway => Outcome::Runaway,
                                // (The energy check is off here, with the strain's.)
                                GuardCause::Overstretched | GuardCause::EnergyGain => Outcome::Overstretched,
                            }),
                            None => Err(e),
                        };
                    }
                }
                let states = sim.read_states(ctx)?;
                Ok(if max_strain(&model, &states) > sweep.max_strain {
                    Outcome::Overstretched
                } else {
                    Outcome::Stable
                })
            })();
            sim.destroy(ctx);
            let cell =
                Cell { method, stiffness_scale: scale, substeps, dt: model.dt(), dt_max, outcome: run? };
            progress(&cell);
            cells.push(cell);
        }
    }
    Ok(cells)
}

pub fn csv(cells: &[Cell], header: &str) -> String {
    let mut out = String::new();
    for line in header.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let _ = writeln!(out, "method,stiffness_scale,substeps,dt_s,predicted_dt_max_s,predicted_stable,outcome");
    for c in cells {
        let _ = writeln!(
            out,
            "{},{},{},{:.6e},{:.6e},{},{}",
            c.method.label(),
            c.stiffness_scale,
            c.substeps,
            c.dt,
            c.dt_max,
            c.predicted_stable(),
            serde_json::to_value(c.outcome)
                .ok()
                .and_then(|v| v.as_str().map(String::from))
                .unwrap_or_default()
        );
    }
    out
}

/// A heat map: rows are stiffness scales (stiffest on top), columns substep counts; the colour
/// is the measured outcome, a white dot marks cells the prediction calls unstable.
pub fn svg(cells: &[Cell], sweep: &Sweep, title: &str) -> String {
    let (cw, ch, left, top) = (64.0, 34.0, 120.0, 60.0);
    let cols = sweep.substeps.len() as f64;
    let rows = sweep.scales.len() as f64;
    let (w, h) = (left + cw * cols + 190.0, top + ch * rows + 70.0);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(out, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(out, r#"<text x="{left}" y="24" font-size="15">{}</text>"#, escape(title));
    for (ri, &scale) in sweep.scales.iter().rev().enumerate() {
        let y = top + ri as f64 * ch;
        let _ = writeln!(
            out,
            r#"<text x="{}" y="{}" text-anchor="end">k x {:.3}</text>"#,
            left - 8.0,
            y + ch * 0.6,
            scale
        );
        for (ci, &substeps) in sweep.substeps.iter().enumerate() {
            let Some(c) = cells.iter().find(|c| c.stiffness_scale == scale && c.substeps == substeps) else {
                continue;
            };
            let x = left + ci as f64 * cw;
            let _ = writeln!(
                out,
                r#"<rect x="{x}" y="{y}" width="{cw}" height="{ch}" fill="{}" stroke="white"/>"#,
                c.outcome.color()
            );
            if !c.predicted_stable() {
                let _ = writeln!(
                    out,
                    r#"<circle cx="{}" cy="{}" r="4" fill="white"/>"#,
                    x + cw / 2.0,
                    y + ch / 2.0
                );
            }
        }
    }
    for (ci, &substeps) in sweep.substeps.iter().enumerate() {
        let x = left + ci as f64 * cw + cw / 2.0;
        let _ = writeln!(
            out,
            r#"<text x="{x}" y="{}" text-anchor="middle">{substeps}</text>"#,
            top + rows * ch + 18.0
        );
    }
    let _ = writeln!(
        out,
        r#"<text x="{}" y="{}" text-anchor="middle">substeps per frame (dt = frame_dt / substeps)</text>"#,
        left + cw * cols / 2.0,
        top + rows * ch + 40.0
    );
    let lx = left + cw * cols + 20.0;
    for (i, o) in
        [Outcome::Stable, Outcome::NonFinite, Outcome::Runaway, Outcome::Overstretched].iter().enumerate()
    {
        let y = top + i as f64 * 24.0;
        let _ = writeln!(out, r#"<rect x="{lx}" y="{y}" width="16" height="16" fill="{}"/>"#, o.color());
        let _ = writeln!(out, r#"<text x="{}" y="{}">{}</text>"#, lx + 22.0, y + 12.0, o.label());
    }
    let y = top + 4.0 * 24.0;
    let _ = writeln!(
        out,
        r##"<rect x="{lx}" y="{y}" width="16" height="16" fill="#888"/><circle cx="{}" cy="{}" r="4" fill="white"/>"##,
        lx + 8.0,
        y + 8.0
    );
    let _ = writeln!(out, r#"<text x="{}" y="{}">predicted unstable</text>"#, lx + 22.0, y + 12.0);
    let _ = writeln!(out, "</svg>");
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
