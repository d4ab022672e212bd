//! Command-line interface.

mod bench;
mod chart;
mod out_file;
mod simulate;
mod stability;
mod stdout;

use crate::vk::{ContextOptions, GpuContext};
use anyhow::Result;
use clap::{Parser, Subcommand};
use stdout::say;

#[derive(Debug, Parser)]
#[command(
    name = "msdsim",
    version,
    about = "GPU mass-spring-damper simulator for cloth and ropes (Vulkan compute)"
)]
pub struct Cli {
    /// Enable the Vulkan validation layer with synchronization validation; any validation
    /// message makes the command fail. `MSDSIM_VALIDATION` takes 1/0, true/false, yes/no, on/off.
    #[arg(long, global = true, env = "MSDSIM_VALIDATION", action = clap::ArgAction::SetTrue,
          value_parser = clap::builder::BoolishValueParser::new())]
    pub validation: bool,
    /// GPU to use: an index from `msdsim devices` or part of its name (default: discrete >
    /// integrated > CPU).
    #[arg(long, global = true, env = "MSDSIM_DEVICE", value_parser = clap::builder::NonEmptyStringValueParser::new())]
    pub device: Option<String>,
    /// Seconds to wait for the GPU to finish a submission before taking it to be stuck (a
    /// shader that never ends, a hung device): the command then stops with exit code 1 and
    /// says so [default: 60, or 600 on a CPU device such as lavapipe].
    #[arg(long, global = true, env = "MSDSIM_GPU_TIMEOUT", value_name = "SECONDS", value_parser = parse_gpu_timeout)]
    pub gpu_timeout: Option<f64>,
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Open the app: the simulation drawn live with the scene editor (the default command).
    App(AppCommand),
    /// Run a preset headless, print per-frame GPU time and a summary, optionally save the state.
    Simulate(simulate::SimulateArgs),
    /// Time a matrix of scenes with GPU timestamps; write bench.md and bench.csv.
    Bench(bench::BenchArgs),
    /// Chart accuracy against GPU cost for every integrator x substeps x iterations (CSV + SVG).
    Chart(chart::ChartArgs),
    /// Sweep stiffness against substeps and map where the simulation is stable (CSV + SVG).
    Stability(stability::StabilityArgs),
    /// List the Vulkan devices and which one would be chosen.
    Devices,
}

impl Cli {
    fn context_options(&self) -> ContextOptions {
        ContextOptions {
            validation: self.validation,
            device: self.device.clone(),
            gpu_timeout: self.gpu_timeout.map(std::time::Duration::from_secs_f64),
        }
    }
}

fn parse_gpu_timeout(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(s) if (0.1..=86_400.0).contains(&s) => Ok(s),
        _ => Err("must be a number of seconds from 0.1 to 86400".into()),
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    let options = cli.context_options();
    match cli.command.unwrap_or(Command::App(AppCommand::default())) {
        Command::App(args) => args.run(&options),
        Command::Simulate(args) => simulate::run(&args, &options),
        Command::Bench(args) => bench::run(&args, &options),
        Command::Chart(args) => chart::run(&args, &options),
        Command::Stability(args) => stability::run(&args, &options),
        Command::Devices => {
            let ctx = GpuContext::new(&options)?;
            let (devices, skipped) = ctx.devices()?;
            let mut out = stdout::Stdout::default();
            for (i, d) in devices.iter().enumerate() {
                let mark = if d.name == ctx.info().name { "*" } else { " " };
                say!(out, "{mark} [{i}] {d}")?;
                say!(
                    out,
                    "      {:.1} GiB device-local, {} bytes of shared memory per workgroup, subgroups of {}{}",
                    d.device_local_bytes as f64 / (1u64 << 30) as f64,
                    d.max_shared_memory,
                    d.subgroup_size,
                    if d.subgroup_clustered { " (clustered reductions)" } else { "" }
                )?;
            }
            for s in skipped {
                say!(out, "  (skipped) {s}")?;
            }
            say!(out, "* = chosen (select another with --device INDEX|NAME or MSDSIM_DEVICE)")?;
            check_validation(&ctx)
        }
    }
}

#[derive(Debug, clap::Args, Default)]
pub struct AppCommand {
    /// Scene preset (TOML); default: the built-in playground scene.
    #[arg(long, value_name = "FILE")]
    pub preset: Option<std::path::PathBuf>,
    /// Override a preset value (repeatable), as for `simulate`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Window size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "1280x800")]
    pub size: Option<[u32; 2]>,
    /// Present without waiting for vertical sync (mailbox or immediate when available).
    #[arg(long)]
    pub no_vsync: bool,
    /// Start paused.
    #[arg(long)]
    pub paused: bool,
    /// Render this many frames, then exit.
    #[arg(long)]
    pub frames: Option<u64>,
    /// Write the last frame (after --frames N, default 1) as a PNG, then exit.
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<std::path::PathBuf>,
    /// Write every drawn frame as DIR/frame_00000.png, DIR/frame_00001.png, ... (the folder is
    /// created; docs/guide/app.md: turning them into a video).
    #[arg(long, value_name = "DIR")]
    pub record_frames: Option<std::path::PathBuf>,
    /// Shader folder to compile and watch for hot reload (default: the source tree's glsl/
    /// when it exists, else the shaders built into the binary with reload off).
    #[arg(long, value_name = "DIR")]
    pub shaders: Option<std::path::PathBuf>,
    /// Hide the stats window (for screenshots that must not change from run to run).
    #[arg(long)]
    pub no_stats: bool,
    /// Open with an object selected, its editor panel shown: `cloth:N`, `rope:N` or
    /// `mesh_cloth:N` (the N-th of the scene's objects of that kind, from 0), or a collider,
    /// `sphere:N`, `box:N`, `capsule:N` or `mesh:N` (for screenshots of a panel).
    #[arg(long, value_name = "KIND:N", value_parser = crate::app::parse_selection)]
    pub select: Option<crate::app::Selection>,
    /// Hide every window of the UI (pictures of the scene alone; the camera fits the whole
    /// window).
    #[arg(long)]
    pub no_ui: bool,
    /// Resize, minimise and restore the window on a script, then exit (a test of the swapchain).
    #[arg(long, hide = true)]
    pub exercise_window: bool,
    /// Apply edits, a reset, a save and a load on a script, then exit (a test of the editor).
    #[arg(long, hide = true)]
    pub exercise_editor: bool,
}

fn parse_size(s: &str) -> Result<[u32; 2], String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or("expected WIDTHxHEIGHT, e.g. 1280x800")?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|v| (64..=16384).contains(v));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok([w, h]),
        _ => Err("each side must be between 64 and 16384 pixels".into()),
    }
}

impl AppCommand {
    fn run(self, options: &ContextOptions) -> Result<()> {
        let scene = crate::app::load_scene(self.preset.as_ref(), &self.overrides)?;
        if let Some(s) = self.select {
            crate::app::check_selection(s, &scene)?;
        }
        if let Some(dir) = &self.record_frames {
            out_file::out_folder("--record-frames", dir)?;
        }
        let args = crate::app::AppArgs {
            preset_label: crate::app::preset_label(self.preset.as_ref()),
            size: self.size.unwrap_or([1280, 800]),
            vsync: !self.no_vsync,
            paused: self.paused,
            frames: self.frames.or(self.screenshot.as_ref().map(|_| 1)),
            screenshot: self.screenshot,
            exercise_window: self.exercise_window,
            hide_stats: self.no_stats,
            hide_ui: self.no_ui,
            exercise_editor: self.exercise_editor,
            shaders: self.shaders,
            record_frames: self.record_frames,
            select: self.select,
        };
        crate::app::run(options, args, scene)
    }
}

/// Fails when validation is on and reported anything.
pub(crate) fn check_validation(ctx: &GpuContext) -> Result<()> {
    let count = ctx.canary().count();
    if count > 0 {
        anyhow::bail!(
            "{count} Vulkan validation message(s); first: {}",
            ctx.canary().messages().first().cloned().unwrap_or_default()
        );
    }
    Ok(())
}
