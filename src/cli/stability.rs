//! `msdsim stability`: the stability map of a scene, per integrator.

use super::stdout::{say, Stdout};
use crate::scene;
use crate::sim::model::Integrator;
use crate::study::stability_map::{self, Sweep};
use crate::vk::{ContextOptions, GpuContext};
use anyhow::{Context as _, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct StabilityArgs {
    /// Scene to sweep (default: the curtain preset at 24 x 24 without self-collision).
    #[arg(long, value_name = "FILE")]
    pub preset: Option<PathBuf>,
    /// Override a preset value (repeatable), as for `simulate`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Integrators to map (one map each).
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = Integrator::ALL)]
    pub methods: Vec<Integrator>,
    /// Stiffness scales and substep counts per axis.
    #[arg(long, default_value_t = 9, value_parser = clap::value_parser!(u64).range(2..=64))]
    pub points: u64,
    /// Decades of stiffness swept, centred on the scene's own.
    #[arg(long, default_value_t = 4.0, value_parser = positive_at_most::<12>)]
    pub decades: f64,
    /// Frames simulated per cell.
    #[arg(long, default_value_t = 120, value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub frames: u64,
    /// Largest structural strain (|length / rest - 1|) at the end still counted as stable.
    #[arg(long, default_value_t = 1.0, value_parser = positive_at_most::<1000>)]
    pub max_strain: f64,
    /// Folder for stability.csv and stability-METHOD.svg.
    #[arg(long, default_value = "stability-results")]
    pub out: PathBuf,
}

/// A finite number > 0 and <= MAX (clap's value parser: the message names the argument).
fn positive_at_most<const MAX: u32>(text: &str) -> Result<f64, String> {
    let v: f64 = text.trim().parse().map_err(|_| format!("{text:?} is not a number"))?;
    if v.is_finite() && v > 0.0 && v <= MAX as f64 {
        Ok(v)
    } else {
        Err(format!("must be a number greater than 0 and at most {MAX}"))
    }
}

const DEFAULT_SCENE: &str = include_str!("../../presets/curtain.toml");

pub fn run(args: &StabilityArgs, options: &ContextOptions) -> Result<()> {
    let mut out = Stdout::default();
    let base = match &args.preset {
        Some(p) => scene::load_runnable(p, &args.overrides)?,
        None => {
            let mut overrides =
                vec!["cloth.0.resolution=[24, 24]".to_string(), "cloth.0.self_collision=false".to_string()];
            overrides.extend(args.overrides.iter().cloned());
            scene::parse(DEFAULT_SCENE, "presets/curtain.toml", &overrides)?
        }
    };
    super::out_file::out_folder("--out", &args.out)?;
    let ctx = GpuContext::new(options)?;
    let sweep = Sweep::new(args.points as usize, args.decades, args.frames as usize, args.max_strain);
    let total = sweep.scales.len() * sweep.substeps.len();
    let mut all = Vec::new();
    let mut summary = Vec::new();
    for &method in &args.methods {
        let bar = indicatif::ProgressBar::new(total as u64);
        let cells = stability_map::run(&ctx, &base, method, &sweep, |c| {
            bar.set_message(format!(
                "{}: k x {:.3}, {} substeps: {:?}",
                method.label(),
                c.stiffness_scale,
                c.substeps,
                c.outcome
            ));
            bar.inc(1);
        })?;
        bar.finish_and_clear();
        let stable = cells.iter().filter(|c| c.outcome == stability_map::Outcome::Stable).count();
        let agree = cells
            .iter()
            .filter(|c| c.predicted_stable() == (c.outcome == stability_map::Outcome::Stable))
            .count();
        summary.push(format!(
            "{}: stable in {stable} of {total} cells; the prediction agrees in {agree} of {total}",
            method.label()
        ));
        let title = format!("Stability map: {} ({} frames per cell)", method.label(), args.frames);
        let file = format!("stability-{}.svg", method.label());
        std::fs::write(args.out.join(&file), stability_map::svg(&cells, &sweep, &title))
            .with_context(|| format!("writing {file}"))?;
        all.extend(cells);
    }
    let header = format!(
        "device: {}\ncommand: {}\n{} frames per cell\n{}",
        ctx.info(),
        std::env::args().collect::<Vec<_>>().join(" "),
        args.frames,
        summary.join("\n")
    );
    std::fs::write(args.out.join("stability.csv"), stability_map::csv(&all, &header))
        .context("writing stability.csv")?;
    say!(out, "{header}")?;
    let svgs: Vec<String> = args.methods.iter().map(|m| format!("stability-{}.svg", m.label())).collect();
    say!(out, "wrote {0}/stability.csv and {1} in {0}", args.out.display(), svgs.join(", "))?;
    crate::cli::check_validation(&ctx)
}
