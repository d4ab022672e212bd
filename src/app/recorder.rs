//! The app's Record button (F9): the animated surfaces of every simulated frame into the file
//! named in the Simulation panel, USD (`.usda`, written when the recording stops), an OBJ
//! sequence (`.obj`, a file a frame as they come), glTF (`.glb`) or PC2 point caches (`.pc2`),
//! as `simulate --record` writes them. Each
//! recorded frame is read back from the GPU, so the app runs slower while it records.

use super::sim_host::SimHost;
use crate::export::{self as record, Format, Recording};
use crate::vk::GpuContext;
use anyhow::Result;
use std::path::{Path, PathBuf};

/// Frames from which stopping a recording is announced before it writes (`long_write`): where
/// the write starts to show as a stall (its rate: docs/guide/app.md, "Record (F9)").
const LONG_WRITE: u64 = 500;

#[derive(Default)]
pub struct AppRecorder {
    active: Option<(Recording, PathBuf)>,
}

impl AppRecorder {
    /// Frames recorded so far, while recording.
    pub fn frames(&self) -> Option<u64> {
        self.active.as_ref().map(|(r, _)| r.frames())
    }

    /// While recording into a file written when the recording stops (USD, glTF) with at least
    /// `LONG_WRITE` frames: how many, and the file. Stopping it writes them all at once, seconds
    /// for a long one, so the app says so a frame before (`edits_wait`).
    pub fn long_write(&self) -> Option<(u64, PathBuf)> {
        let (recording, path) = self.active.as_ref()?;
        (recording.format().keeps_frames() && recording.frames() >= LONG_WRITE)
            .then(|| (recording.frames(), path.clone()))
    }

    /// Frames recorded so far and the file's name, while recording.
    pub fn status(&self) -> Option<(u64, String)> {
        let name =
            |p: &Path| p.file_name().map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into());
        self.active.as_ref().map(|(r, path)| (r.frames(), name(path)))
    }

    /// Starts recording the scene of `host` into `path`; refused for an unknown extension, a
    /// missing folder, or a recording that would replace or remove the preset file `preset`
    /// (the file the editor opens and saves).
    pub fn start(&mut self, host: &SimHost, path: &Path, preset: &Path) -> Result<String> {
        if Format::of(path).is_ok_and(|f| f.endangers(path, preset)) {
            anyhow::bail!(
                "not recording: {} would replace or remove the preset {} (a file it writes or cleans up beside it); record under another name",
                path.display(),
                preset.display()
            );
        }
        let recording = Recording::new(host.model(), &record::colors(host.scene()), path, None)?;
        let what = match recording.format() {
            f if f.keeps_frames() => format!("recording to {} (written when you stop)", path.display()),
            Format::PointCache => {
                format!("recording to {} and its point caches", recording.base_path().display())
            }
            _ => format!("recording to {} ...", recording.obj_path(1).display()),
        };
        self.active = Some((recording, path.to_path_buf()));
        Ok(what)
    }

    /// Adds the frame just submitted (waits for it). A failure stops the recording, keeping
    /// what was recorded.
    pub fn capture(&mut self, ctx: &GpuContext, host: &mut SimHost) -> Result<(), String> {
        let Some((recording, _)) = self.active.as_mut() else { return Ok(()) };
        let added = if recording.matches(host.model()) {
            let time = host.sim_mut().time();
            host.sim_mut().read_states(ctx).and_then(|states| recording.add(&states, time))
        } else {
            Err(anyhow::anyhow!(
                "the scene's objects or frame rate changed (a recording keeps one set of meshes)"
            ))
        };
        added.map_err(|e| match self.stop() {
            Ok(saved) => format!("recording stopped: {e:#}; {saved}"),
            Err(also) => format!("recording stopped: {e:#}; {also:#}"),
        })
    }

    /// Stops recording and writes a USD or glTF file (the others are written as frames come);
    /// says what was written.
    pub fn stop(&mut self) -> Result<String> {
        let Some((recording, path)) = self.active.take() else { return Ok("not recording".into()) };
        if recording.format().keeps_frames() {
            crate::atomic_file::replace_with(&path, false, |w| recording.write_to(w))
                .map_err(|e| anyhow::anyhow!("writing {}: {e}", path.display()))?;
        }
        Ok(recording.summary(&path))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A recording written when it stops is announced before it writes from `LONG_WRITE`
    /// frames on, one written as it goes never.
    #[test]
    fn long_recordings_are_announced_before_they_write() {
        let scene =
            crate::scene::parse(include_str!("../../presets/curtain.toml"), "curtain.toml", &[]).unwrap();
        let model = crate::scene::to_model(&scene);
        let dir = tempfile::tempdir().unwrap();
        let states: Vec<crate::sim::gpu::ObjectState> = model
            .objects
            .iter()
            .map(|o| crate::sim::gpu::ObjectState {
                particles: vec![Default::default(); o.particle_count()],
                surface: vec![Default::default(); o.surface_count()],
            })
            .collect();
        for (name, announced) in [("a.usda", true), ("a.pc2", false)] {
            let path = dir.path().join(name);
            let recording = Recording::new(&model, &record::colors(&scene), &path, None).unwrap();
            let mut r = AppRecorder { active: Some((recording, path.clone())) };
            for f in 0..LONG_WRITE {
                assert!(r.long_write().is_none(), "{name}: announced at {f} frames");
                let (recording, _) = r.active.as_mut().unwrap();
                recording.add(&states, f as f64 / 60.0).unwrap();
            }
            assert_eq!(r.long_write().map(|(n, _)| n), announced.then_some(LONG_WRITE), "{name}");
        }
    }
}
