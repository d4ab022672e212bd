//! Errors the user can fix: bad presets, bad arguments, scenes too large for the device.
//! The binary maps these to exit code 2 with a one-line message.

/// A problem with the user's input, stated in one line that names the file and the key.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct UserError(pub String);

/// Exit codes of the binary.
pub mod exit {
    /// Bad input: preset, arguments, sizes.
    pub const BAD_INPUT: i32 = 2;
    /// Anything else: no device, device lost, I/O failure.
    pub const FAILURE: i32 = 1;
    /// The runtime guard stopped an unstable simulation.
    pub const UNSTABLE: i32 = 3;
}
