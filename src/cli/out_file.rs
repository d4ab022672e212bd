//! `simulate --out FILE`: where the final state goes. The path is claimed before the run, so a
//! path that cannot be written fails at once (exit 2) and no simulation is lost; the file is
//! written at the end:
//! - a regular file, or a new one: through a temporary file beside it, renamed over it, so a
//!   reader never sees half a file; the temporary exists only while it is written (a run stopped
//!   by Ctrl-C leaves nothing behind);
//! - a symbolic link: the same at the file it points to; the link stays a link;
//! - anything else (a device such as /dev/null, a FIFO, a file of /proc): written through in
//!   place, never replaced. A FIFO is opened only at the end (opening it waits for a reader).

use crate::error::UserError;
use anyhow::{Context as _, Result};
use std::io::Write as _;
use std::os::unix::fs::FileTypeExt as _;
use std::path::{Path, PathBuf};

pub struct OutFile {
    /// The file written (a symbolic link's target).
    target: PathBuf,
    /// Written in place (not a regular file), else replaced through a temporary file.
    in_place: bool,
}

impl OutFile {
    /// Checks that `path` can be written and how, without writing it.
    pub fn claim(path: &Path) -> Result<Self> {
        let refuse = |why: String| UserError(format!("--out {}: {why}", path.display()));
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => Err(refuse("is a directory; name a file".into()).into()),
            Ok(m) if m.is_file() => {
                let target =
                    std::fs::canonicalize(path).map_err(|e| refuse(format!("cannot resolve: {e}")))?;
                std::fs::OpenOptions::new()
                    .write(true)
                    .open(&target)
                    .map_err(|e| refuse(format!("cannot write: {e}")))?;
                let out = Self { target, in_place: false };
                out.probe_temporary().map_err(|e| {
                    refuse(format!(
                        "cannot create the temporary file beside it through which it is replaced whole: {e}"
                    ))
                })?;
                Ok(out)
            }
            Ok(m) => {
                if !m.file_type().is_fifo() {
                    std::fs::OpenOptions::new()
                        .write(true)
                        .open(path)
                        .map_err(|e| refuse(format!("cannot write: {e}")))?;
                }
                Ok(Self { target: path.to_path_buf(), in_place: true })
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                if std::fs::symlink_metadata(path).is_ok() {
                    // A link to a file not there yet: create it through the link.
                    return Ok(Self { target: path.to_path_buf(), in_place: true });
                }
                let out = Self { target: path.to_path_buf(), in_place: false };
                out.probe_temporary().map_err(|e| refuse(format!("cannot write: {e}")))?;
                Ok(out)
            }
            Err(e) => Err(refuse(format!("cannot write: {e}")).into()),
        }
    }

    /// The temporary file beside the target.
    fn temporary(&self) -> PathBuf {
        let name = self.target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        self.target.with_file_name(format!(".{name}.{}.partial", std::process::id()))
    }

    /// Creates and removes the temporary file: the folder takes it.
    fn probe_temporary(&self) -> std::io::Result<()> {
        let tmp = self.temporary();
        std::fs::File::create(&tmp)?;
        std::fs::remove_file(&tmp)
    }

    /// Writes `value` as JSON.
    pub fn write_json(self, value: &impl serde::Serialize) -> Result<()> {
        let json = serde_json::to_vec(value).context("serialising the state")?;
        self.write(&json).with_context(|| format!("writing {}", self.target.display()))
    }

    fn write(&self, bytes: &[u8]) -> std::io::Result<()> {
        if self.in_place {
            let mut file =
                std::fs::OpenOptions::new().write(true).create(true).truncate(true).open(&self.target)?;
            return file.write_all(bytes).and_then(|_| file.flush());
        }
        let tmp = self.temporary();
        let written = (|| {
            let mut file = std::fs::File::create(&tmp)?;
            file.write_all(bytes)?;
            file.sync_all()?;
            std::fs::rename(&tmp, &self.target)
        })();
        if written.is_err() {
            let _ = std::fs::remove_file(&tmp);
        }
        written
    }
}
