//! `msdsim chart`: accuracy against cost for every integrator (CSV + one SVG per scene).

use super::stdout::{say, Stdout};
use crate::error::UserError;
use crate::scene::{self, ClothPins, Orientation, PerSpring, RopePins, Scene};
use crate::sim::model::Integrator;
use crate::study::chart::{self, Sweep};
use crate::vk::{ContextOptions, GpuContext};
use anyhow::{Context as _, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct ChartArgs {
    /// Scene to chart (default: four built-in scenes: a 16 x 16 curtain hanging from two
    /// corners in a wind cone, a 32-node rope pinned at both ends, sagging and swinging under
    /// gravity from straight, a stiff 12 x 12 cloth of 1 g particles at 1e4 N/m held at its
    /// corners, settling: the large steps the iterative methods are for; the explicit methods
    /// need 95 substeps there; and the curtain preset at 16 x 16 draped over its sphere, with
    /// contact and Coulomb friction).
    #[arg(long, value_name = "FILE")]
    pub preset: Option<PathBuf>,
    /// Built-in scenes to chart when no preset is given.
    #[arg(long, value_delimiter = ',', default_value = "cloth,rope,stiff,contact", value_parser = ["cloth", "rope", "stiff", "contact"])]
    pub scenes: Vec<String>,
    /// Override a preset value (repeatable), as for `simulate`; applies to every scene charted.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Integrators to sweep.
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = Integrator::ALL)]
    pub methods: Vec<Integrator>,
    /// Substeps per 1/60 s frame.
    #[arg(long, value_delimiter = ',', default_value = "1,2,4,8,16,32,64", value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub substeps: Vec<u32>,
    /// Solver iterations per substep (the iterative methods).
    #[arg(long, value_delimiter = ',', default_value = "2,5,10,30", value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub iterations: Vec<u32>,
    /// Substeps per frame of the CPU reference (position Verlet in f64).
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(2..=4096))]
    pub reference_substeps: u32,
    /// Folder for chart.csv and chart-SCENE.svg.
    #[arg(long, default_value = "chart-results")]
    pub out: PathBuf,
}

const CURTAIN: &str = include_str!("../../presets/curtain.toml");
const ROPE: &str = include_str!("../../presets/rope.toml");

/// The built-in chart scenes: smooth motion without contacts or limits, so the error measures
/// the integrators alone. (A cloth falling flat from two corners folds through itself and is
/// chaotic: its reference at 256 and 128 substeps differed by 6.5e-3 of its size. This curtain's
/// differ by 5e-6. Likewise a rope pinned at one end whips chaotically: by t = 2 s every method
/// had the same error, 3e-3; pinned at both ends it sags and sways smoothly.)
fn builtin(names: &[String], overrides: &[String]) -> Result<Vec<(String, Scene)>> {
    let mut cloth = scene::parse(CURTAIN, "presets/curtain.toml", &[])?;
    cloth.clear_colliders();
    for c in &mut cloth.cloths {
        c.resolution = [16, 16];
        c.size = [0.75, 0.75];
        c.origin = [-0.375, 1.5, 0.0];
        c.stretch_limit = None;
        c.self_collision = false;
        c.pin = ClothPins::None;
        c.pinned = vec![[0, 0], [15, 0]];
    }
    cloth.wind = scene::Wind {
        enabled: true,
        model: scene::WindKind::Paper,
        origin: [0.0, 1.0, 2.0],
        direction: [0.0, 0.0, -1.0],
        force: 0.02,
        full_force_radius: 2.0,
        attenuation_radius: 1.0,
        reference_distance: 1.0,
        ..Default::default()
    };
    let mut rope = scene::parse(ROPE, "presets/rope.toml", &[])?;
    rope.clear_colliders();
    for r in &mut rope.ropes {
        r.nodes = 32;
        r.start = [-0.8, 1.1, 0.0];
        r.end = [0.0, 1.1, 0.0];
        r.stretch_limit = None;
        r.self_collision = false;
        r.pin = RopePins::Both;
        r.friction = 0.0;
    }
    // The stiff cloth of docs/ACCURACY.md's "Large steps" (docs/records/accuracy/stiff/stiff-cloth.toml),
    // settling from flat.
    let mut stiff = scene::parse(CURTAIN, "presets/curtain.toml", &[])?;
    stiff.clear_colliders();
    stiff.wind.enabled = false;
    for c in &mut stiff.cloths {
        c.resolution = [12, 12];
        c.size = [0.275, 0.275];
        c.origin = [-0.1375, 1.0, -0.1375];
        c.orientation = Orientation::Horizontal;
        c.mass = 0.001;
        c.stiffness = PerSpring { structural: 1e4, shear: 5e3, bending: 1e3 };
        c.damping = 0.0;
        c.drag = 0.01;
        c.stretch_limit = None;
        c.self_collision = false;
        c.pin = ClothPins::Corners;
        c.pinned = Vec::new();
    }
    // The paper's figure 2 with contact: the curtain preset as shipped (its top row pinned,
    // its sphere 2 cm into the cloth's plane, the ground, Coulomb friction 0.3, a stretch
    // limit) at 16 x 16, without self-collision.
    let mut contact = scene::parse(CURTAIN, "presets/curtain.toml", &[])?;
    for c in &mut contact.cloths {
        c.resolution = [16, 16];
        c.self_collision = false;
    }
    let mut scenes = Vec::new();
    for (name, s) in [("cloth", cloth), ("rope", rope), ("stiff", stiff), ("contact", contact)]
        .into_iter()
        .filter(|(n, _)| names.iter().any(|x| x == n))
    {
        // Overrides apply to the modified scene as to a preset file.
        let text = toml::to_string(&s).context("writing the built-in chart scene")?;
        scenes.push((
            name.to_string(),
            scene::parse(&text, &format!("built-in {name} chart scene"), overrides)?,
        ));
    }
    Ok(scenes)
}

pub fn run(args: &ChartArgs, options: &ContextOptions) -> Result<()> {
    let mut out = Stdout::default();
    let scenes = match &args.preset {
        Some(p) => {
            let name =
                p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
            vec![(name, scene::load_runnable(p, &args.overrides)?)]
        }
        None => builtin(&args.scenes, &args.overrides)?,
    };
    let sweep = Sweep {
        methods: args.methods.clone(),
        substeps: args.substeps.clone(),
        iterations: args.iterations.clone(),
        reference_substeps: args.reference_substeps,
    };
    super::out_file::out_folder("--out", &args.out)?;
    let ctx = GpuContext::new(options)?;
    let mut all = Vec::new();
    let mut notes = Vec::new();
    for (name, s) in &scenes {
        scene::validate(s).map_err(UserError)?;
        let model = scene::to_model(s);
        crate::sim::gpu::check_fits(ctx.info(), &scene::shapes(s))?;
        let bar = indicatif::ProgressBar::new(sweep.settings().len() as u64);
        bar.set_message(format!("{name}: CPU reference ({} substeps per frame)", sweep.reference_substeps));
        let (reference, points) = chart::run(&ctx, name, &model, &sweep, |p| {
            bar.set_message(format!(
                "{name}: {} {} substeps {} iterations",
                p.method.label(),
                p.substeps,
                p.iterations
            ));
            bar.inc(1);
        })?;
        bar.finish_and_clear();
        let note = format!(
            "{name}: reference = Verlet at {} substeps per frame on the CPU (f64); against {} substeps it differs by {:.2e} (RMS / size), so its own error is about {:.1e}",
            reference.substeps,
            reference.substeps / 2,
            reference.check,
            reference.check / 3.0
        );
        let title = format!("{name}: error against GPU cost ({})", ctx.info().name);
        std::fs::write(args.out.join(format!("chart-{name}.svg")), chart::svg(&points, &title)?)
            .with_context(|| format!("writing chart-{name}.svg"))?;
        for i in chart::pareto(&points) {
            let p = &points[i];
            say!(
                out,
                "{name} Pareto: {:<16} {:>3} substeps {:>3} iterations  {:>9.3} ms/s  error {:.2e}",
                p.method.label(),
                p.substeps,
                p.iterations,
                p.gpu_ms_per_s,
                p.error()
            )?;
        }
        notes.push(note);
        all.extend(points);
    }
    let header = format!(
        "device: {}\ncommand: {}\n{}",
        ctx.info(),
        std::env::args().collect::<Vec<_>>().join(" "),
        notes.join("\n")
    );
    std::fs::write(args.out.join("chart.csv"), chart::csv(&all, &header)).context("writing chart.csv")?;
    say!(out, "{header}")?;
    let svgs: Vec<String> = scenes.iter().map(|(name, _)| format!("chart-{name}.svg")).collect();
    say!(out, "wrote {0}/chart.csv and {1} in {0}", args.out.display(), svgs.join(", "))?;
    crate::cli::check_validation(&ctx)
}
