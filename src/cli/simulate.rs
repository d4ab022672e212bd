//! `msdsim simulate`: headless run of a preset.

use super::out_file::OutFile;
use super::stdout::{say, Stdout};
use crate::export::{same_file, Format, Recording};
use crate::scene;
use crate::shaders::ShaderSet;
use crate::sim::gpu::{self, FrameTiming, GpuSim};
use crate::sim::model::ObjectKind;
use crate::sim::stability;
use crate::vk::{ContextOptions, GpuContext};
use anyhow::{Context as _, Result};
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct SimulateArgs {
    /// Scene preset (TOML), e.g. presets/curtain.toml.
    #[arg(long, value_name = "FILE")]
    pub preset: PathBuf,
    /// Frames to simulate (each `sim.frame_dt` seconds of `sim.substeps` substeps).
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub frames: u64,
    /// Override a preset value, e.g. --set sim.substeps=32 --set cloth.curtain.mass=0.02 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Write the final state (time, substeps, every object's positions and velocities) as JSON.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Print only the summary, not a line per frame.
    #[arg(long)]
    pub quiet: bool,
    /// Record the animated surfaces, a mesh per object: FILE.usda is USD with points and
    /// normals time-sampled every frame (opens in Blender, Houdini, usdview, Omniverse);
    /// FILE.obj is a sequence FILE_00001.obj, FILE_00002.obj, ... one OBJ file per frame;
    /// FILE.glb is glTF 2.0 binary, each frame a morph target; FILE.pc2 is a PC2 point cache
    /// FILE_NAME.pc2 per mesh, with the meshes in FILE.obj (Blender's Mesh Cache modifier).
    #[arg(long, value_name = "FILE.usda|FILE.obj|FILE.glb|FILE.pc2")]
    pub record: Option<PathBuf>,
    /// Compile the shaders from this GLSL folder (with DIR/include for headers) instead of
    /// using the ones built into the binary: to run an edited shader without rebuilding.
    #[arg(long, value_name = "DIR")]
    pub shaders: Option<PathBuf>,
}

#[derive(serde::Serialize)]
struct StateFile<'a> {
    preset: String,
    device: String,
    /// Simulated time [s].
    time: f64,
    frames: u64,
    substeps: u64,
    substep_dt: f64,
    objects: Vec<ObjectOut<'a>>,
}

#[derive(serde::Serialize)]
struct ObjectOut<'a> {
    kind: ObjectKind,
    name: &'a str,
    /// [columns, rows]; a rope is [nodes, 1].
    dims: [u32; 2],
    pinned: Vec<usize>,
    /// [m]
    positions: Vec<[f32; 3]>,
    /// [m/s]
    velocities: Vec<[f32; 3]>,
}

/// Whether `path` is a shader source the `--shaders` folder `dir` holds or may hold (a GLSL
/// file in it or in its include folder): an output there would replace an edited shader.
fn shader_source(dir: &Path, path: &Path) -> bool {
    let glsl = path.extension().and_then(|e| e.to_str()).is_some_and(|e| SHADER_EXTENSIONS.contains(&e));
    let folder = std::path::absolute(path).ok().and_then(|p| p.parent().map(Path::to_path_buf));
    glsl && folder.is_some_and(|f| same_file(&f, dir) || same_file(&f, &dir.join("include")))
}

/// The extensions of the files a shader folder compiles or includes.
const SHADER_EXTENSIONS: [&str; 4] = ["comp", "vert", "frag", "glsl"];

/// Refuses outputs that would destroy an input or each other, before any work: `--out` naming
/// the preset or a shader source of `--shaders`; `--record` replacing or removing the preset
/// (the recording itself, a frame, mesh or point cache it writes, or an earlier frame it
/// cleans up); `--out` naming the recording or a file it writes. (A recording's files end in
/// .usda, .obj, .glb or .pc2, never a shader's extension.)
fn check_outputs(args: &SimulateArgs) -> Result<(), crate::error::UserError> {
    let refuse = |what: &str, path: &Path, other: &str| {
        Err(crate::error::UserError(format!("{what} {}: the same file as {other}", path.display())))
    };
    if let Some(out) = &args.out {
        if same_file(out, &args.preset) {
            return refuse("--out", out, "the preset (it would be replaced)");
        }
        if args.shaders.as_deref().is_some_and(|dir| shader_source(dir, out)) {
            return refuse("--out", out, "a shader source of --shaders (it would be replaced)");
        }
    }
    if let Some(record) = &args.record {
        let format = Format::of(record).ok();
        if same_file(record, &args.preset) {
            return refuse("--record", record, "the preset (it would be replaced)");
        }
        if format.is_some_and(|f| f.endangers(record, &args.preset)) {
            return Err(crate::error::UserError(format!(
                "--record {}: the recording would replace or remove the preset {} (a file it writes or cleans up beside it); record under another name",
                record.display(),
                args.preset.display()
            )));
        }
    }
    if let (Some(out), Some(record)) = (&args.out, &args.record) {
        if same_file(out, record) {
            return refuse("--out", out, "--record");
        }
        if Format::of(record).is_ok_and(|f| f.writes(record, out)) {
            return refuse("--out", out, "a file --record writes");
        }
    }
    Ok(())
}

/// `seconds` in milliseconds, readable at any size (a substep of microseconds does not print
/// as zero).
fn milliseconds(seconds: f64) -> String {
    significant(seconds * 1e3)
}

/// `x` as the stability line prints it: fixed with 0 to 4 decimals from 0.01 to 1e6 (as
/// before: 657, 3.043), else in exponent form with three digits.
fn significant(x: f64) -> String {
    if x == 0.0 || (x.abs() >= 0.01 && x.abs() < 1e6) {
        let decimals = if x.abs() >= 100.0 {
            0
        } else if x.abs() >= 1.0 {
            3
        } else {
            4
        };
        format!("{x:.decimals$}")
    } else {
        format!("{x:.2e}")
    }
}

pub fn run(args: &SimulateArgs, options: &ContextOptions) -> Result<()> {
    check_outputs(args)?;
    let scene = scene::load_runnable(&args.preset, &args.overrides)?;
    // Claim the output file before simulating, so a bad path fails before any work is done.
    let out_file = args.out.as_deref().map(|p| OutFile::claim("--out", p)).transpose()?;
    // A USD or glTF recording is one file written at the end, claimed like --out; OBJ and PC2
    // write theirs as the frames come (Recording::new checks their folder).
    let record_file = match &args.record {
        Some(path) => {
            let format = Format::of(path).map_err(|e| crate::error::UserError(format!("--record {e}")))?;
            format.keeps_frames().then(|| OutFile::claim("--record", path)).transpose()?
        }
        None => None,
    };
    // A folder of shaders (an edited copy of glsl/) is checked before any work, compiled later.
    let mut shaders = match &args.shaders {
        Some(dir) => Some(ShaderSet::directory(dir)?.without_fallback()),
        None => None,
    };
    let mut out = Stdout::default();

    let ctx = GpuContext::new(options)?;
    say!(out, "device: {}", ctx.info())?;
    gpu::check_fits(ctx.info(), &scene::shapes(&scene))?;
    let (model, picked) = crate::study::integrator_choice::model_for(&ctx, &scene)?;
    if let Some(p) = picked {
        say!(out, "{p}")?;
    }
    say!(
        out,
        "preset: {} ({}, {}, {} with {} substeps of {} ms per frame{})",
        args.preset.display(),
        counted(model.objects.len(), "object"),
        counted(model.colliders.len(), "collider"),
        model.integrator.label(),
        model.substeps,
        milliseconds(model.dt()),
        if model.integrator.iterative() {
            format!(", {} iterations", model.iterations)
        } else {
            String::new()
        }
    )?;
    for p in stability::predict(&model).into_iter().filter(|_| !model.integrator.iterative()) {
        let dt = model.dt();
        let verdict = if dt <= p.dt_max {
            "within it".to_string()
        } else {
            format!("PAST IT: expect a blow-up; {}", p.substep_advice(model.frame_dt))
        };
        let limit = if p.dt_max.is_finite() {
            format!("explicit limit dt <= {} ms", milliseconds(p.dt_max))
        } else {
            "no explicit limit (no spring acts)".to_string()
        };
        say!(
            out,
            "stability: {} '{}': w_max <= {} rad/s, {limit}; substep {} ms is {verdict}",
            p.kind.label(),
            p.name,
            significant(p.omega_max),
            milliseconds(dt)
        )?;
    }
    if let Some(limit) = crate::sim::collider::contact_speed(&model) {
        say!(out, "contact: {limit}")?;
    }
    for note in crate::sim::cloth_mesh::notes(&model) {
        say!(out, "mesh: {note}")?;
    }
    let recording = match &args.record {
        Some(path) => {
            let colors = crate::export::colors(&scene);
            let recording = Recording::new(&model, &colors, path, Some(args.frames)).map_err(|e| {
                match e.downcast::<crate::error::UserError>() {
                    Ok(refused) => crate::error::UserError(format!("--record {}", refused.0)).into(),
                    Err(e) => e,
                }
            })?;
            Some((recording, record_file))
        }
        None => None,
    };
    let mut sim = match &mut shaders {
        Some(set) => GpuSim::with_shaders(&ctx, &model, set)?,
        None => GpuSim::new(&ctx, &model)?,
    };
    let result = simulate(&ctx, &mut sim, args, &model, &mut out, out_file, recording);
    sim.destroy(&ctx);
    result?;
    crate::cli::check_validation(&ctx)
}

fn simulate(
    ctx: &GpuContext,
    sim: &mut GpuSim,
    args: &SimulateArgs,
    model: &crate::sim::model::SimModel,
    out: &mut Stdout,
    out_file: Option<OutFile>,
    mut recording: Option<(Recording, Option<OutFile>)>,
) -> Result<()> {
    let mut timings: Vec<FrameTiming> = Vec::with_capacity(args.frames.min(100_000) as usize);
    let mut report = |out: &mut Stdout, t: FrameTiming| -> Result<()> {
        timings.push(t);
        if !args.quiet {
            say!(
                out,
                "frame {:>6}  gpu {:>8.3} ms  (physics {:.3}, constraints {:.3}, surface {:.3})",
                timings.len(),
                t.total_ms,
                t.physics_ms,
                t.constraints_ms,
                t.surface_ms
            )?;
        }
        Ok(())
    };
    if let Some((r, _)) = &mut recording {
        // The initial state, at time code 0 (its surface computed without simulating).
        sim.take_surface_stale();
        ctx.one_shot("the initial surface", |rec| {
            sim.record_surface(rec, crate::vk::Access::ComputeReadWrite);
            Ok(())
        })?;
        r.add(&sim.read_states(ctx)?, sim.time())?;
    }
    // A recording is kept when a signal stops the run: the first SIGINT, SIGTERM or SIGHUP ends
    // the frames (a streamed one between two, so none is cut), a recording written at the end
    // is written with those so far, and the process then ends by the signal.
    let graceful = recording.as_ref().map(|_| crate::atomic_file::Graceful::new());
    let mut interrupted = None;
    // Frames stay in flight as in the app: each submission first collects the frame that
    // used its slot, so timings (and a tripped guard) arrive a frame or two late.
    for frame in 1..=args.frames {
        // (Only a `Graceful` alive lets a signal ask for a stop.)
        interrupted = crate::atomic_file::stop_requested();
        if interrupted.is_some() {
            break;
        }
        if let Some(t) = sim.submit_frame(ctx).with_context(|| format!("frame {frame}"))? {
            report(out, t)?;
        }
        if let Some((r, _)) = &mut recording {
            // Recording reads every frame back (it waits for the frames in flight).
            r.add(&sim.read_states(ctx)?, sim.time())?;
        }
    }
    // From here a signal ends the process at once again (a write it interrupts leaves the
    // file as it was).
    drop(graceful);
    interrupted = interrupted.or_else(crate::atomic_file::stop_requested);
    for t in sim.finish_frames(ctx).context("the last frames")? {
        report(out, t)?;
    }
    print_summary(out, sim, &timings)?;
    if let Some([on, rebuilt]) = sim.contact_list_counters(ctx).context("the contact counters")? {
        // (a round a substep, or one an iteration: SimModel::contact_rounds)
        let rounds = model.contact_rounds() as u64;
        let total = sim.substeps_done() * rounds;
        let unit =
            if rounds > 1 { format!("contact rounds ({rounds} a substep)") } else { "substeps".into() };
        say!(
            out,
            "contact between objects: lists on in {on} of {total} {unit}, rebuilt in {rebuilt} of those"
        )?;
    }
    if let Some((r, file)) = recording {
        if let (Some(signal), Some(path)) = (interrupted, &args.record) {
            // (on standard error, with the stop itself: a user who pressed Ctrl-C looks there)
            let what = if file.is_some() {
                "writing them (another signal now discards the recording)"
            } else {
                "the recording keeps them"
            };
            eprintln!(
                "msdsim: {} after {} frames of {}: {what}",
                crate::atomic_file::Interrupted(signal),
                r.frames(),
                path.display()
            );
        }
        if let Some(file) = file {
            file.write_with(|w| r.write_to(w))?;
        }
        if let Some(path) = &args.record {
            say!(out, "{}", r.summary(path))?;
        }
    }
    if let Some(signal) = interrupted {
        // The state file is for a finished run: left as it was.
        return Err(crate::atomic_file::Interrupted(signal).into());
    }
    if let Some(warning) = sim.take_warning() {
        say!(out, "warning: {warning}")?;
    }

    if let Some(out_file) = out_file {
        let states = sim.read_states(ctx)?;
        let objects = model
            .objects
            .iter()
            .zip(&states)
            .map(|(o, s)| ObjectOut {
                kind: o.kind,
                name: &o.name,
                dims: o.dims,
                pinned: o.pinned.iter().enumerate().filter(|(_, p)| **p).map(|(i, _)| i).collect(),
                positions: s.particles.iter().map(|p| [p.pos[0], p.pos[1], p.pos[2]]).collect(),
                velocities: s.particles.iter().map(|p| [p.vel[0], p.vel[1], p.vel[2]]).collect(),
            })
            .collect();
        let file = StateFile {
            preset: args.preset.display().to_string(),
            device: ctx.info().name.clone(),
            time: sim.time(),
            frames: sim.frames(),
            substeps: sim.substeps_done(),
            substep_dt: model.dt(),
            objects,
        };
        out_file.write_json(&file)?;
    }
    Ok(())
}

fn print_summary(out: &mut Stdout, sim: &GpuSim, timings: &[FrameTiming]) -> Result<()> {
    say!(out, "simulated {:.4} s in {} frames ({} substeps)", sim.time(), sim.frames(), sim.substeps_done())?;
    if timings.is_empty() {
        return say!(out, "GPU timing: not available (the device has no timestamps)");
    }
    let stat = |f: fn(&FrameTiming) -> f64| {
        let mut v: Vec<f64> = timings.iter().map(f).collect();
        v.sort_by(|a, b| a.total_cmp(b));
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        (mean, v[v.len() / 2], v[0], v[v.len() - 1])
    };
    let (mean, median, min, max) = stat(|t| t.total_ms);
    say!(
        out,
        "GPU frame time: mean {mean:.3} ms, median {median:.3}, min {min:.3}, max {max:.3} ({:.0} frames/s)",
        1e3 / median.max(1e-9)
    )?;
    let (p, ..) = stat(|t| t.physics_ms);
    let (c, ..) = stat(|t| t.constraints_ms);
    let (s, ..) = stat(|t| t.surface_ms);
    // As the app's Stats: when every object is fused its substeps run in one pass, the stages
    // not separable.
    match timings[0].fused {
        Some(true) => say!(out, "GPU stage means: simulation (fused) {p:.3} ms, surface {s:.3} ms"),
        Some(false) => {
            say!(out, "GPU stage means: physics + fused objects {p:.3} ms, constraints {c:.3} ms, surface {s:.3} ms")
        }
        None => say!(out, "GPU stage means: physics {p:.3} ms, constraints {c:.3} ms, surface {s:.3} ms"),
    }
}

/// `n` and `noun`, plural unless n is 1 ("1 object", "2 colliders").
fn counted(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}
