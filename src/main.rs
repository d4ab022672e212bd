//! The `msdsim` binary: parses the command line, runs it, and turns errors into a one-line
//! message and an exit code (2: bad input, 3: the runtime guard stopped an unstable
//! simulation, 1: other failures; a run stopped by SIGINT or SIGTERM ends by that signal). No
//! panic reaches the user.

use clap::Parser;
use msdsim::atomic_file::Interrupted;
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
    let cli = match msdsim::cli::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => exit_on_argument_error(e),
    };
    let code = match std::panic::catch_unwind(|| msdsim::cli::run(cli)) {
        Ok(Ok(())) => 0,
        Ok(Err(e)) => {
            if let Some(signal) = Interrupted::signal_of(&e) {
                let _ = writeln!(std::io::stderr(), "msdsim: {e:#}");
                let _ = std::io::stdout().flush();
                msdsim::atomic_file::end_by_signal(signal);
            }
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
    if msdsim::vk::any_device_stuck() {
        // The driver's exit handlers would wait for the work that never ends.
        let _ = std::io::stdout().flush();
        msdsim::vk::exit_without_teardown(code);
    }
    std::process::exit(code);
}

/// Help and version print as clap prints them; an argument error is one line, like every
/// other error, with exit code 2.
fn exit_on_argument_error(e: clap::Error) -> ! {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        e.exit();
    }
    // The message and what it lists (a missing argument, a tip), before the usage.
    let text = e.render().to_string();
    let lines: Vec<&str> = text
        .lines()
        .map(str::trim)
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .filter(|l| !l.is_empty())
        .collect();
    let message = lines.join(" ");
    let message = message.strip_prefix("error:").unwrap_or(&message).trim();
    let _ = writeln!(std::io::stderr(), "msdsim: error: {message} (msdsim --help lists the arguments)");
    std::process::exit(exit::BAD_INPUT);
}

fn is_selector_error(e: &(dyn std::error::Error + 'static)) -> bool {
    matches!(e.downcast_ref::<msdsim::vk::VkError>(), Some(msdsim::vk::VkError::DeviceSelector(_)))
}
