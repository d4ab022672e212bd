//! Command-line interface.

mod simulate;

use crate::vk::{ContextOptions, GpuContext};
use anyhow::Result;
use clap::{Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "msdsim",
    version,
    about = "GPU mass-spring-damper simulator for cloth and ropes (Vulkan compute)"
)]
pub struct Cli {
    /// Enable the Vulkan validation layer with synchronization validation; any validation
    /// message makes the command fail.
    #[arg(long, global = true, env = "MSDSIM_VALIDATION")]
    pub validation: bool,
    /// GPU to use: an index from `msdsim devices` or part of its name (default: discrete >
    /// integrated > CPU).
    #[arg(long, global = true, env = "MSDSIM_DEVICE")]
    pub device: Option<String>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a preset headless, print per-frame GPU time and a summary, optionally save the state.
    Simulate(simulate::SimulateArgs),
    /// List the Vulkan devices and which one would be chosen.
    Devices,
}

impl Cli {
    fn context_options(&self) -> ContextOptions {
        ContextOptions { validation: self.validation, device: self.device.clone() }
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    let options = cli.context_options();
    match cli.command {
        Command::Simulate(args) => simulate::run(&args, &options),
        Command::Devices => {
            let ctx = GpuContext::new(&options)?;
            let (devices, skipped) = ctx.devices()?;
            for (i, d) in devices.iter().enumerate() {
                let mark = if d.name == ctx.info().name { "*" } else { " " };
                println!("{mark} [{i}] {d}");
            }
            for s in skipped {
                println!("  (skipped) {s}");
            }
            println!("* = chosen (select another with --device INDEX|NAME or MSDSIM_DEVICE)");
            check_validation(&ctx)
        }
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
