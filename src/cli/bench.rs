//! `msdsim bench`: times the benchmark matrix and writes the reports.

use super::stdout::{say, Stdout};
use crate::app::offscreen;
use crate::bench::{self, cases, report};
use crate::shaders::ShaderSet;
use crate::sim::model::Integrator;
use crate::vk::{ContextOptions, GpuContext};
use anyhow::{Context as _, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct BenchArgs {
    /// Frames measured per case (after the warm-up); at least 100.
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u64).range(100..=100_000))]
    pub frames: u64,
    /// Frames run before measuring.
    #[arg(long, default_value_t = 20)]
    pub warmup: u64,
    /// Only the smallest sizes (for a CPU device such as lavapipe).
    #[arg(long, conflicts_with_all = ["cloth_sizes", "rope_sizes"])]
    pub quick: bool,
    /// Cloth sizes (particles per side) of the matrix [default: 50,128,256,512,1024].
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(2..=4096))]
    pub cloth_sizes: Option<Vec<u32>>,
    /// Rope sizes (nodes) of the matrix [default: 256,1024,4096,16384,65536].
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(2..=16_777_216))]
    pub rope_sizes: Option<Vec<u32>>,
    /// Only cases whose name contains this text.
    #[arg(long)]
    pub filter: Option<String>,
    /// Run every object per stage (a dispatch per stage and substep), not fused in one
    /// workgroup where its layout fits: the reference path, for comparison.
    #[arg(long, conflicts_with = "fused_slots")]
    pub per_stage: bool,
    /// Fuse objects of up to this many particles per thread of a 1024-thread workgroup (1 to 4;
    /// default 1, and 4 for objects that self-collide through the hash or, on a GPU, that `xpbd`
    /// (spring classes), VBD or the implicit method solve; `xpbd_jacobi` keeps 1, see
    /// docs/PERFORMANCE.md), where they fit the shared memory.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4))]
    pub fused_slots: Option<u32>,
    /// Integrator of every case (the paper's by default).
    #[arg(long, value_enum, default_value_t = Integrator::SymplecticEuler)]
    pub integrator: Integrator,
    /// Solver iterations per substep (the iterative integrators).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub iterations: u32,
    /// Passes over a cloth's contacts with its own triangles a substep (`sim.contact_iterations`;
    /// the cases with triangle self-contact).
    #[arg(long, default_value_t = crate::sim::model::DEFAULT_CONTACT_ITERATIONS, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub contact_iterations: u32,
    /// Run each case as the app does instead (simulation and drawing into an offscreen target,
    /// two frames in flight), timed by the wall clock next to its GPU time and its GPU-only
    /// figure: the paper's cases unless --filter picks others. Writes end-to-end.md and .csv.
    #[arg(long)]
    pub end_to_end: bool,
    /// The offscreen target of --end-to-end, WIDTHxHEIGHT pixels.
    #[arg(long, default_value = "1920x1080", value_parser = parse_extent, requires = "end_to_end")]
    pub resolution: [u32; 2],
    /// Compile the shaders from this GLSL folder (with DIR/include for headers) instead of
    /// using the ones built into the binary: to measure an edited shader without rebuilding.
    #[arg(long, value_name = "DIR")]
    pub shaders: Option<PathBuf>,
    /// Folder for bench.md and bench.csv.
    #[arg(long, default_value = "bench-results")]
    pub out: PathBuf,
}

pub fn run(args: &BenchArgs, options: &ContextOptions) -> Result<()> {
    let mut out = Stdout::default();
    let (cloth, rope) = if args.quick {
        (vec![50], vec![256])
    } else {
        (
            args.cloth_sizes.clone().unwrap_or(cases::CLOTH_SIZES.to_vec()),
            args.rope_sizes.clone().unwrap_or(cases::ROPE_SIZES.to_vec()),
        )
    };
    let cases: Vec<_> = cases::matrix(&cloth, &rope)
        .into_iter()
        .filter(|c| match &args.filter {
            Some(f) => c.name.contains(f.as_str()),
            None => !args.end_to_end || c.group == "paper",
        })
        .map(|mut c| {
            c.scene.sim.integrator = crate::scene::IntegratorChoice::Method(args.integrator);
            c.scene.sim.iterations = args.iterations;
            c.scene.sim.contact_iterations = args.contact_iterations;
            c
        })
        .collect();
    if cases.is_empty() {
        let filter = args.filter.as_deref().unwrap_or_default();
        return Err(crate::error::UserError(format!(
            "--filter {filter:?} matches no case (names look like \"cloth 50x50, springs only\", \"rope 256, + wind\")"
        ))
        .into());
    }
    // The folder only once the cases are known (a filter that matches none leaves nothing).
    super::out_file::out_folder("--out", &args.out)?;
    let ctx = GpuContext::new(options)?;
    let info = ctx.info().clone();
    eprintln!("device: {info}");
    let fused_slots = if args.per_stage { Some(0) } else { args.fused_slots };
    let mut shaders = match &args.shaders {
        Some(dir) => ShaderSet::directory(dir)?.without_fallback(),
        None => ShaderSet::embedded(),
    };
    let bar = progress(cases.len() as u64 + 1);
    if args.end_to_end {
        return end_to_end(args, &ctx, &cases, fused_slots, &mut shaders, &bar, &mut out);
    }
    bar.set_message("copy bandwidth");
    let bandwidth = bench::bandwidth::measure(&ctx, 512 << 20, 21).context("measuring the copy bandwidth")?;
    if bar.is_hidden() {
        eprintln!("copy bandwidth: {:.0} GB/s", bandwidth.0 * 1e-9);
    }
    bar.inc(1);
    let mut rows = Vec::new();
    for case in &cases {
        bar.set_message(case.name.clone());
        let m = bench::measure(
            &ctx,
            case,
            args.warmup as usize,
            args.frames as usize,
            fused_slots,
            &mut shaders,
        )?;
        if bar.is_hidden() {
            // Not a terminal (a log): a line per case instead of the bar.
            eprintln!("[{}/{}] {}: {:.3} ms/frame", rows.len() + 1, cases.len(), case.name, m.total.median);
        }
        let hashed = case.scene.cloths.iter().any(|c| c.self_collision)
            || case.scene.ropes.iter().any(|r| r.self_collision);
        rows.push((m, hashed));
        bar.inc(1);
    }
    bar.finish_and_clear();
    let header = header(&ctx, Some(bandwidth));
    let md = report::markdown(&header, &rows);
    std::fs::write(args.out.join("bench.md"), &md).context("writing bench.md")?;
    std::fs::write(args.out.join("bench.csv"), report::csv(&header, &rows)).context("writing bench.csv")?;
    say!(out, "{md}")?;
    eprintln!("wrote {0}/bench.md and {0}/bench.csv", args.out.display());
    crate::cli::check_validation(&ctx)
}

/// `bench --end-to-end`: each case by the wall clock as the app runs it, and GPU-only.
fn end_to_end(
    args: &BenchArgs,
    ctx: &GpuContext,
    cases: &[cases::Case],
    fused_slots: Option<u32>,
    shaders: &mut ShaderSet,
    bar: &indicatif::ProgressBar,
    out: &mut Stdout,
) -> Result<()> {
    bar.set_length(cases.len() as u64);
    let options = offscreen::Options {
        extent: args.resolution,
        warmup: args.warmup as usize,
        frames: args.frames as usize,
        fused_slots,
        capture: false,
    };
    let mut rows = Vec::new();
    for case in cases {
        bar.set_message(case.name.clone());
        let gpu_only = bench::measure(ctx, case, options.warmup, options.frames, fused_slots, shaders)?;
        let mut e = offscreen::measure(ctx, &case.scene, options, shaders)
            .with_context(|| format!("{} end to end", case.name))?;
        e.case = case.name.clone();
        if bar.is_hidden() {
            eprintln!(
                "[{}/{}] {}: {:.0} frames/s end to end, GPU-only {:.3} ms/frame",
                rows.len() + 1,
                cases.len(),
                case.name,
                e.frames_per_second(),
                gpu_only.total.median
            );
        }
        rows.push((e, gpu_only));
        bar.inc(1);
    }
    bar.finish_and_clear();
    let header = header(ctx, None);
    let md = report::end_to_end_markdown(&header, args.resolution, &rows);
    std::fs::write(args.out.join("end-to-end.md"), &md).context("writing end-to-end.md")?;
    std::fs::write(args.out.join("end-to-end.csv"), report::end_to_end_csv(&header, args.resolution, &rows))
        .context("writing end-to-end.csv")?;
    say!(out, "{md}")?;
    eprintln!("wrote {0}/end-to-end.md and {0}/end-to-end.csv", args.out.display());
    crate::cli::check_validation(ctx)
}

fn progress(len: u64) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

fn header(ctx: &GpuContext, bandwidth: Option<(f64, u64)>) -> report::Header {
    let info = ctx.info();
    report::Header {
        device: info.name.clone(),
        driver: format!("{}, Vulkan {}", info.driver, info.api_version),
        command: std::env::args().collect::<Vec<_>>().join(" "),
        date: date(),
        bandwidth,
    }
}

/// `WIDTHxHEIGHT`, each 16 to 8192 pixels.
fn parse_extent(s: &str) -> Result<[u32; 2], String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("{s:?} is not WIDTHxHEIGHT"))?;
    let side = |v: &str| -> Result<u32, String> {
        let n: u32 = v.trim().parse().map_err(|_| format!("{v:?} is not a whole number of pixels"))?;
        if (16..=8192).contains(&n) {
            Ok(n)
        } else {
            Err(format!("{n} pixels is outside 16..=8192"))
        }
    };
    Ok([side(w)?, side(h)?])
}

/// UTC date and time of the run, from the system clock.
fn date() -> String {
    let secs =
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0);
    let (days, rem) = (secs / 86400, secs % 86400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + (m <= 2) as i64;
    format!("{y:04}-{m:02}-{d:02} {:02}:{:02} UTC", rem / 3600, rem % 3600 / 60)
}
