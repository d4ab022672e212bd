//! A report for a test binary that dies by a signal (SIGSEGV, SIGBUS, SIGILL, SIGFPE): which
//! test thread it was and its stack, on standard error, before the signal ends the process as
//! it would have. A crash inside the driver or the validation layer otherwise leaves only
//! "signal: 11" in the log. The handler calls only async-signal-safe functions (`write`,
//! `prctl`, `sigaction`, and glibc's `backtrace`, whose first call, the one that may load
//! libgcc, is made at installation), so it cannot hang where the fault interrupted `malloc`.

use std::sync::Once;

const SIGNALS: [libc::c_int; 4] = [libc::SIGSEGV, libc::SIGBUS, libc::SIGILL, libc::SIGFPE];

/// The actions installed before ours (Rust's own, which reports a stack overflow), put back
/// by the handler before the fault repeats.
static mut PREVIOUS: [Option<libc::sigaction>; 4] = [None; 4];

fn write_err(bytes: &[u8]) {
    // SAFETY: writing a live buffer to standard error.
    unsafe { libc::write(2, bytes.as_ptr().cast(), bytes.len()) };
}

extern "C" fn report(signal: libc::c_int, _info: *mut libc::siginfo_t, _context: *mut libc::c_void) {
    let mut name = [0u8; 17];
    // SAFETY: PR_GET_NAME writes at most 16 bytes, NUL-terminated, into `name`.
    unsafe { libc::prctl(libc::PR_GET_NAME, name.as_mut_ptr() as libc::c_ulong, 0, 0, 0) };
    let len = name.iter().position(|&b| b == 0).unwrap_or(16);
    let digits = [b'0' + (signal / 10) as u8, b'0' + (signal % 10) as u8];
    write_err(b"\n=== fatal signal ");
    write_err(&digits);
    write_err(b" in test thread '");
    write_err(&name[..len]);
    write_err(b"' (the name is cut at 15 characters); its stack:\n");
    let mut frames = [std::ptr::null_mut::<libc::c_void>(); 64];
    // SAFETY: `frames` holds 64 entries; backtrace_symbols_fd writes to fd 2 without allocating.
    unsafe {
        let n = libc::backtrace(frames.as_mut_ptr(), frames.len() as libc::c_int);
        libc::backtrace_symbols_fd(frames.as_ptr(), n, 2);
    }
    write_err(b"=== end of stack\n");
    // Put back the action before ours and return: the faulting instruction runs again and
    // the signal ends the process (or Rust's handler reports a stack overflow) as before.
    if let Some(k) = SIGNALS.iter().position(|&s| s == signal) {
        // SAFETY: PREVIOUS was written once, before the handlers were installed.
        let previous = unsafe { (*std::ptr::addr_of!(PREVIOUS))[k] };
        match previous {
            // SAFETY: restoring an action the kernel gave us.
            Some(action) => unsafe { libc::sigaction(signal, &action, std::ptr::null_mut()) },
            // SAFETY: the default action, from zeroed memory (SIG_DFL is 0).
            None => unsafe { libc::sigaction(signal, &std::mem::zeroed(), std::ptr::null_mut()) },
        };
    }
}

/// Installs the report once a process.
pub fn install() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let mut frames = [std::ptr::null_mut::<libc::c_void>(); 4];
        // SAFETY: a first call outside any handler (it may load libgcc's unwinder).
        unsafe { libc::backtrace(frames.as_mut_ptr(), frames.len() as libc::c_int) };
        for (k, &signal) in SIGNALS.iter().enumerate() {
            // SAFETY: a zeroed sigaction is valid; the handler has the SA_SIGINFO signature.
            unsafe {
                let mut action: libc::sigaction = std::mem::zeroed();
                action.sa_sigaction = report as *const () as usize;
                action.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK;
                libc::sigemptyset(&mut action.sa_mask);
                let mut previous: libc::sigaction = std::mem::zeroed();
                if libc::sigaction(signal, std::ptr::null(), &mut previous) == 0 {
                    (*std::ptr::addr_of_mut!(PREVIOUS))[k] = Some(previous);
                    libc::sigaction(signal, &action, std::ptr::null_mut());
                }
            }
        }
    });
}
