//! The commands' standard output. A reader that closes the pipe early (`msdsim simulate ... |
//! head -1`) has what it wanted: the rest of the output is dropped and the command finishes
//! its work (an `--out` file is still written) and exits as it would have. Any other failure to
//! write (a full disk, `> /dev/full`) is an error (exit 1) that names standard output. Rust
//! ignores SIGPIPE, so a closed pipe shows as a `BrokenPipe` write error, never a signal.

use anyhow::{anyhow, Result};
use std::io::Write as _;

/// Standard output, muted once its reader has gone.
#[derive(Debug, Default)]
pub struct Stdout {
    closed: bool,
}

impl Stdout {
    /// Writes one line (and flushes it, so a pipe sees each line as it is made).
    pub fn line(&mut self, args: std::fmt::Arguments<'_>) -> Result<()> {
        if self.closed {
            return Ok(());
        }
        let mut out = std::io::stdout().lock();
        let written = out.write_fmt(args).and_then(|_| out.write_all(b"\n")).and_then(|_| out.flush());
        match written {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(())
            }
            Err(e) => Err(anyhow!("writing to standard output: {e}")),
        }
    }
}

/// `println!` through a `Stdout`, returning its error: `say!(out, "frame {n}")?`.
macro_rules! say {
    ($out:expr, $($arg:tt)*) => {
        $out.line(format_args!($($arg)*))
    };
}
pub(crate) use say;
