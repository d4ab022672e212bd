//! Shaders: the compile function shared with build.rs, the SPIR-V embedded at build time, and a
//! small SPIR-V reader for checking struct layouts against the Rust mirrors.

pub mod compile;
pub mod layout_check;
pub mod reflect;
mod set;

pub use set::{Changes, ShaderSet};

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));
}

use anyhow::{anyhow, Result};

/// SPIR-V words of an embedded shader by file name (e.g. `"physics.comp"`).
pub fn embedded(name: &str) -> Result<Vec<u32>> {
    let (_, bytes) = embedded::EMBEDDED
        .iter()
        .find(|(n, _)| *n == name)
        .ok_or_else(|| anyhow!("no embedded shader named {name}"))?;
    words(bytes)
}

/// Names of all embedded shaders.
pub fn embedded_names() -> impl Iterator<Item = &'static str> {
    embedded::EMBEDDED.iter().map(|(n, _)| *n)
}

/// Bytes to aligned SPIR-V words, checking the magic number.
pub fn words(bytes: &[u8]) -> Result<Vec<u32>> {
    if bytes.len() % 4 != 0 || bytes.len() < 20 {
        return Err(anyhow!("SPIR-V of {} bytes is not a whole module", bytes.len()));
    }
    let words: Vec<u32> =
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    if words[0] != 0x0723_0203 {
        return Err(anyhow!("not SPIR-V (bad magic number)"));
    }
    Ok(words)
}
