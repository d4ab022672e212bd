//! The `msdsim` binary: parses the command line, runs it, and turns errors into a one-line
//! message and an exit code (2: bad input, 3: the runtime guard stopped an unstable
//! simulation, 1: other failures). No panic reaches the user.

use clap::Parser;
use msdsim::error::{exit, UserError};
use std::io::Write as _;

fn main() {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn,msdsim=warn"))
        .format_timestamp(None)
        .init();
    // Standard error may be closed too: the messages are dropped then, never a second panic.
    std::panic::set_hook(Box::new(|info| {
        let _ = writeln!(std::io::stderr(), "msdsim: internal error (a bug; please report it): {info}");
    }));
    let cli = msdsim::cli::Cli::parse();
    let code = match std::panic::catch_unwind(|| msdsim::cli::run(cli)) {
        Ok(Ok(())) => 0,
        Ok(Err(e)) => {
            let line = format!("{e:#}").replace('\n', " ");
            let _ = writeln!(std::io::stderr(), "msdsim: error: {line}");
            if e.chain().any(|c| c.is::<msdsim::sim::stability::GuardTrip>()) {
                exit::UNSTABLE
            } else if e.chain().any(|c| c.is::<UserError>() || is_selector_error(c)) {
                exit::BAD_INPUT
            } else {
                exit::FAILURE
            }
        }
        Err(_) => exit::FAILURE,
    };
    std::process::exit(code);
}

fn is_selector_error(e: &(dyn std::error::Error + 'static)) -> bool {
    matches!(e.downcast_ref::<msdsim::vk::VkError>(), Some(msdsim::vk::VkError::DeviceSelector(_)))
}
