//! Files replaced whole through a temporary file beside them, and the signals that must not
//! leave such a temporary behind.
//!
//! `replace` writes a new hidden file next to the target (created new, never through an
//! existing name), then renames it over the target, so a reader never sees half a file. While
//! the temporary exists its path sits in a fixed table that a handler for SIGINT, SIGTERM and
//! SIGHUP reads: the handler unlinks every path there, restores the signal's default action
//! and raises it again, so the process still ends as the signal says (the shell's 130 for
//! Ctrl-C). The table is plain bytes and atomics, so the handler only reads memory and calls
//! `unlink`, `signal` and `raise`, all async-signal-safe. A signal the process was started
//! with ignored (`nohup`, a background job) stays ignored.
//!
//! A command that can stop cleanly (a recording whose file is written at the end) holds a
//! `Graceful` while it runs: the first SIGINT, SIGTERM or SIGHUP (the terminal closed) then only
//! asks it to stop (`stop_requested`); it finishes what it has, and ends by the signal
//! (`end_by_signal`). A second signal ends the process at once, as above.
//!
//! This module and `vk` are the only places with `unsafe`.

use std::cell::UnsafeCell;
use std::os::unix::ffi::OsStrExt as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicI32, AtomicU8, AtomicUsize, Ordering};

/// Temporaries tracked at once (a run has one or two).
const SLOTS: usize = 8;
/// Longest path tracked, NUL included (Linux's PATH_MAX).
const PATH_BYTES: usize = 4096;

const FREE: u8 = 0;
const FILLING: u8 = 1;
const READY: u8 = 2;

struct Table {
    state: [AtomicU8; SLOTS],
    paths: [UnsafeCell<[u8; PATH_BYTES]>; SLOTS],
}

// SAFETY: a slot's bytes are written only by the thread that moved its state FREE -> FILLING,
// and read (by the handler) only while its state is READY.
unsafe impl Sync for Table {}

static TABLE: Table = Table {
    state: [const { AtomicU8::new(FREE) }; SLOTS],
    paths: [const { UnsafeCell::new([0; PATH_BYTES]) }; SLOTS],
};

/// A tracked temporary path; dropping it stops tracking (the file is not touched).
struct Tracked(Option<usize>);

impl Tracked {
    fn new(path: &Path) -> Self {
        install_handlers();
        let bytes = path.as_os_str().as_bytes();
        if bytes.len() >= PATH_BYTES || bytes.contains(&0) {
            return Self(None);
        }
        for (i, state) in TABLE.state.iter().enumerate() {
            if state.compare_exchange(FREE, FILLING, Ordering::AcqRel, Ordering::Acquire).is_ok() {
                // SAFETY: this thread owns the slot (FILLING); the handler does not read it.
                let slot = unsafe { &mut *TABLE.paths[i].get() };
                slot[..bytes.len()].copy_from_slice(bytes);
                slot[bytes.len()] = 0;
                state.store(READY, Ordering::Release);
                return Self(Some(i));
            }
        }
        Self(None) // every slot in use: left untracked
    }
}

impl Drop for Tracked {
    fn drop(&mut self) {
        if let Some(i) = self.0 {
            TABLE.state[i].store(FREE, Ordering::Release);
        }
    }
}

/// `Graceful` guards alive.
static GRACEFUL: AtomicUsize = AtomicUsize::new(0);
/// The signal that asked a graceful stop (0: none).
static STOP: AtomicI32 = AtomicI32::new(0);

/// While alive, the first SIGINT, SIGTERM or SIGHUP asks for a stop instead of ending the
/// process.
pub struct Graceful(());

impl Graceful {
    pub fn new() -> Self {
        install_handlers();
        GRACEFUL.fetch_add(1, Ordering::AcqRel);
        Self(())
    }
}

impl Default for Graceful {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for Graceful {
    fn drop(&mut self) {
        GRACEFUL.fetch_sub(1, Ordering::AcqRel);
    }
}

/// The signal that asked for a stop, if one did.
pub fn stop_requested() -> Option<i32> {
    Some(STOP.load(Ordering::Acquire)).filter(|s| *s != 0)
}

/// A stop asked by a signal, carried up as an error: `main` ends the process by the signal.
#[derive(Debug, thiserror::Error)]
#[error("stopped by {}", signal_name(*.0))]
pub struct Interrupted(pub i32);

impl Interrupted {
    /// The signal, when `e` is (or was caused by) a stop it asked for.
    pub fn signal_of(e: &anyhow::Error) -> Option<i32> {
        e.chain().find_map(|c| c.downcast_ref::<Interrupted>()).map(|i| i.0)
    }
}

fn signal_name(signal: i32) -> &'static str {
    match signal {
        libc::SIGINT => "SIGINT (Ctrl-C)",
        libc::SIGTERM => "SIGTERM",
        libc::SIGHUP => "SIGHUP",
        _ => "a signal",
    }
}

/// Ends the process as `signal` would have (the shell then reports 128 + signal).
pub fn end_by_signal(signal: i32) -> ! {
    raise_default(signal);
    std::process::exit(128 + signal)
}

/// Restores `signal`'s default action and raises it (async-signal-safe). Inside its own
/// handler the signal is blocked, so it is delivered when the handler returns.
fn raise_default(signal: i32) {
    // SAFETY: plain libc calls, async-signal-safe; the default action of these signals ends
    // the process.
    unsafe {
        libc::signal(signal, libc::SIG_DFL);
        libc::raise(signal);
    }
}

extern "C" fn on_signal(signal: libc::c_int) {
    if GRACEFUL.load(Ordering::Acquire) > 0
        && STOP.compare_exchange(0, signal, Ordering::AcqRel, Ordering::Acquire).is_ok()
    {
        return; // the command stops at its next check
    }
    for (state, path) in TABLE.state.iter().zip(&TABLE.paths) {
        if state.load(Ordering::Acquire) == READY {
            // SAFETY: a READY slot holds a NUL-terminated path that no one writes.
            unsafe { libc::unlink(path.get().cast::<libc::c_char>()) };
        }
    }
    raise_default(signal);
}

fn install_handlers() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            // SAFETY: sigaction with valid pointers; the handler is async-signal-safe (above).
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                if libc::sigaction(signal, std::ptr::null(), &mut old) != 0
                    || old.sa_sigaction == libc::SIG_IGN
                {
                    continue;
                }
                let mut action: libc::sigaction = std::mem::zeroed();
                action.sa_sigaction = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
                // A stop request returns from the handler: calls it interrupted go on.
                action.sa_flags = libc::SA_RESTART;
                libc::sigemptyset(&mut action.sa_mask);
                libc::sigaction(signal, &action, std::ptr::null_mut());
            }
        }
    });
}

/// Creates a new temporary file beside `target` (a name not taken yet), tracked.
fn create_beside(target: &Path) -> std::io::Result<(PathBuf, Tracked, std::fs::File)> {
    let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let mut last = None;
    for attempt in 0..100 {
        let tmp = target.with_file_name(format!(".{name}.{}-{attempt}.partial", std::process::id()));
        // Tracked before it exists, so a signal between creating and tracking cannot miss it.
        let tracked = Tracked::new(&tmp);
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(file) => return Ok((tmp, tracked, file)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no free temporary name")))
}

/// A new file beside `target` for reading and writing, already unlinked: it takes disk space
/// only while open, and nothing is left behind however the process ends.
pub fn anonymous_beside(target: &Path) -> std::io::Result<std::fs::File> {
    let (tmp, _tracked, file) = create_beside(target)?;
    drop(file);
    let file = std::fs::OpenOptions::new().read(true).write(true).open(&tmp);
    std::fs::remove_file(&tmp)?;
    file
}

/// Whether a temporary file can be created beside `target` (creates and removes one).
pub fn probe_beside(target: &Path) -> std::io::Result<()> {
    let (tmp, _tracked, _) = create_beside(target)?;
    std::fs::remove_file(&tmp)
}

/// Writes `bytes` as the whole new content of `target` (a regular file, or a new one): through
/// a temporary file beside it, renamed over it. The temporary takes a replaced file's
/// permissions; `durable` also flushes it to the disk before the rename. A failed write, or a
/// signal during it, removes the temporary.
pub fn replace(target: &Path, bytes: &[u8], durable: bool) -> std::io::Result<()> {
    replace_with(target, durable, |w| w.write_all(bytes))
}

/// Like `replace`, with the content written by `write` (buffered), so that a large file need
/// not be in memory whole.
pub fn replace_with(
    target: &Path,
    durable: bool,
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let (tmp, _tracked, file) = create_beside(target)?;
    let written = (|| {
        let mut buffered = std::io::BufWriter::with_capacity(1 << 20, file);
        write(&mut buffered)?;
        let file = buffered.into_inner().map_err(std::io::IntoInnerError::into_error)?;
        hold_for_tests();
        if let Ok(old) = std::fs::metadata(target) {
            file.set_permissions(old.permissions())?;
        }
        if durable {
            file.sync_all()?;
        }
        std::fs::rename(&tmp, target)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// For the tests that send a signal while a temporary exists: `MSDSIM_TEST_HOLD_PARTIAL=SECONDS`
/// keeps each temporary, written, that long before it is renamed.
fn hold_for_tests() {
    if let Some(s) =
        std::env::var_os("MSDSIM_TEST_HOLD_PARTIAL").and_then(|s| s.to_str()?.parse::<f64>().ok())
    {
        if s.is_finite() && s > 0.0 {
            std::thread::sleep(std::time::Duration::from_secs_f64(s.min(60.0)));
        }
    }
}
