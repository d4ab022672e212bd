//! `simulate --out FILE`: where the final state goes. The path is claimed before the run, so a
//! path that cannot be written fails at once (exit 2) and no simulation is lost; the file is
//! written at the end:
//! - a regular file, or a new one: through a temporary file beside it (created new, never
//!   through an existing name), renamed over it, so a reader never sees half a file; the
//!   temporary exists only while it is written (a run stopped by Ctrl-C or SIGTERM, even
//!   during the write, leaves nothing behind: `crate::temporary`), and takes the replaced
//!   file's permissions;
//! - a symbolic link: the same at the file it points to; the link stays a link;
//! - anything else (/dev/null, a FIFO): written through in place, never replaced; a FIFO is
//!   opened only at the end (opening it waits for a reader);
//! - a regular file reached through /dev or /proc (/dev/stdout redirected to a log): appended
//!   to, as the shell's own writes to it are, never replaced or emptied;
//! - a file of the kernel (/proc/version, /sys/...): refused.
//!
//! A replaced file is a new file: other hard links to the old one keep the old contents.

use crate::error::UserError;
use anyhow::{Context as _, Result};
use std::io::Write as _;
use std::os::unix::fs::FileTypeExt as _;
use std::path::{Path, PathBuf};

pub struct OutFile {
    /// The file written (a symbolic link's target).
    target: PathBuf,
    mode: Mode,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Through a temporary file renamed over the target.
    Replace,
    /// Opened and written where it is (created if missing, emptied first).
    InPlace,
    /// A regular file reached through a descriptor (/dev/stdout): appended to, as the shell's
    /// own writes to it are.
    Append,
}

/// Whether `path`, or a symbolic link on the way from it to its file, is under /dev or /proc:
/// a stand-in for a file descriptor or a device, to be written in place.
fn through_devices(path: &Path) -> bool {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        if p.starts_with("/dev") || p.starts_with("/proc") {
            return true;
        }
        match std::fs::read_link(&p) {
            Ok(next) => p = p.parent().map(|d| d.join(&next)).unwrap_or(next),
            Err(_) => return false,
        }
    }
    false
}

impl OutFile {
    /// Checks that `path`, given to `option` (`--out`, `--record`), can be written and how,
    /// without writing it; a refusal names the option.
    pub fn claim(option: &str, path: &Path) -> Result<Self> {
        let refuse = |why: String| UserError(format!("{option} {}: {why}", path.display()));
        let writable = |p: &Path| {
            std::fs::OpenOptions::new()
                .write(true)
                .open(p)
                .map(drop)
                .map_err(|e| refuse(format!("cannot write: {e}")))
        };
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => Err(refuse("is a directory; name a file".into()).into()),
            Ok(m) if m.is_file() => {
                let target =
                    std::fs::canonicalize(path).map_err(|e| refuse(format!("cannot resolve: {e}")))?;
                if target.starts_with("/proc") || target.starts_with("/sys") {
                    return Err(refuse(
                        "is a file of the kernel (/proc, /sys), not a place for output".into(),
                    )
                    .into());
                }
                writable(&target)?;
                if through_devices(path) {
                    return Ok(Self { target: path.to_path_buf(), mode: Mode::Append });
                }
                let out = Self { target, mode: Mode::Replace };
                out.probe_temporary().map_err(|e| {
                    refuse(format!(
                        "cannot create the temporary file beside it through which it is replaced whole: {e}"
                    ))
                })?;
                Ok(out)
            }
            Ok(m) => {
                if !m.file_type().is_fifo() {
                    writable(path)?;
                }
                Ok(Self { target: path.to_path_buf(), mode: Mode::InPlace })
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                if std::fs::symlink_metadata(path).is_ok() {
                    // A link to a file not there yet: created through the link, in a folder
                    // that must exist.
                    let link =
                        std::fs::read_link(path).map_err(|e| refuse(format!("cannot resolve: {e}")))?;
                    let target = path.parent().map(|d| d.join(&link)).unwrap_or(link);
                    if !target.parent().is_some_and(|d| d.as_os_str().is_empty() || d.is_dir()) {
                        return Err(refuse(format!(
                            "links to {}, in a folder that does not exist",
                            target.display()
                        ))
                        .into());
                    }
                    return Ok(Self { target: path.to_path_buf(), mode: Mode::InPlace });
                }
                let out = Self { target: path.to_path_buf(), mode: Mode::Replace };
                out.probe_temporary().map_err(|e| refuse(format!("cannot write: {e}")))?;
                Ok(out)
            }
            Err(e) => Err(refuse(format!("cannot write: {e}")).into()),
        }
    }

    /// Creates and removes a temporary file: the folder takes it.
    fn probe_temporary(&self) -> std::io::Result<()> {
        crate::atomic_file::probe_beside(&self.target)
    }

    /// Writes `bytes` (a whole file).
    pub fn write_bytes(self, bytes: &[u8]) -> Result<()> {
        self.write_with(|w| w.write_all(bytes))
    }

    /// Writes what `write` writes (buffered), so that a large file need not be in memory.
    pub fn write_with(
        self,
        write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
    ) -> Result<()> {
        self.write(write).with_context(|| format!("writing {}", self.target.display()))
    }

    /// Writes `value` as JSON.
    pub fn write_json(self, value: &impl serde::Serialize) -> Result<()> {
        let json = serde_json::to_vec(value).context("serialising the state")?;
        self.write_bytes(&json)
    }

    fn write(
        &self,
        write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        if self.mode != Mode::Replace {
            let mut options = std::fs::OpenOptions::new();
            match self.mode {
                Mode::Append => options.append(true),
                _ => options.write(true).create(true).truncate(true),
            };
            let mut file = std::io::BufWriter::with_capacity(1 << 20, options.open(&self.target)?);
            write(&mut file)?;
            return file.flush();
        }
        crate::atomic_file::replace_with(&self.target, true, write)
    }
}

/// Makes the folder `dir` given to `option` (`bench`, `chart` and `stability --out`,
/// `app --record-frames`) with its parents; an existing file there is refused by name (the
/// results are several files), not with the system's "File exists".
pub fn out_folder(option: &str, dir: &Path) -> Result<(), UserError> {
    if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
        return Err(UserError(format!(
            "{option} {}: a file, not a folder (the results are several files: name a folder, new or existing)",
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir).map_err(|e| UserError(format!("{option} {}: {e}", dir.display())))
}
