//! Screenshots: the F12 key's and `--screenshot`'s, read back from the frame and written as PNG.

use super::Viewer;
use crate::vk::Swapchain;
use anyhow::{Context as _, Result};
use std::path::PathBuf;

impl Viewer {
    pub(super) fn screenshot_due(&self) -> bool {
        self.args.screenshot.is_some() && self.args.frames.is_none_or(|n| self.frame + 1 >= n)
    }

    pub(super) fn write_screenshot(
        &self,
        path: &std::path::Path,
        extent: [u32; 2],
        bgra: bool,
    ) -> Result<()> {
        let Some(buffer) = &self.screenshot else { return Ok(()) };
        let mut pixels: Vec<u8> = buffer.read::<u8>((extent[0] * extent[1] * 4) as usize)?;
        for px in pixels.chunks_exact_mut(4) {
            if bgra {
                px.swap(0, 2);
            }
            px[3] = 255;
        }
        write_png(path, extent, &pixels)
    }
}

/// The F12 screenshot's file: `msdsim-<seconds since 1970>-<milliseconds>.png` in the current
/// folder.
pub(super) fn screenshot_name() -> PathBuf {
    let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default();
    PathBuf::from(format!("msdsim-{}-{:03}.png", now.as_secs(), now.subsec_millis()))
}

pub(super) fn swapchain_is_bgra(s: Option<&Swapchain>) -> bool {
    s.is_some_and(|s| s.format() == crate::vk::Format::Bgra8Unorm)
}

/// Writes RGBA8 pixels as a PNG.
pub fn write_png(path: &std::path::Path, extent: [u32; 2], rgba: &[u8]) -> Result<()> {
    let file = std::fs::File::create(path).map_err(|e| {
        crate::error::UserError(format!("--screenshot {}: cannot write: {e}", path.display()))
    })?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), extent[0], extent[1]);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().context("writing the PNG header")?;
    writer.write_image_data(rgba).context("writing the PNG")?;
    Ok(())
}
