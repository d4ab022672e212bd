//! `.pc2`: a PC2 point cache a mesh, streamed as the frames come.

use super::*;

impl Recording {
    /// The names of the meshes a point cache animates: every object's, then every moving
    /// collider's (a fixed one stays where the OBJ has it).
    pub(super) fn cached_names(&self) -> Vec<&str> {
        let moving = self.colliders.iter().zip(&self.collider_names).filter(|(c, _)| c.is_moving());
        self.tracks.iter().map(|t| t.name.as_str()).chain(moving.map(|(_, name)| name.as_str())).collect()
    }

    /// The file of cached mesh k's point cache (`cached_names`).
    pub fn cache_path(&self, k: usize) -> PathBuf {
        self.cache_file(self.cached_names()[k])
    }

    /// The point cache of the mesh named `name`: `{stem}_{name}.pc2`.
    pub(super) fn cache_file(&self, name: &str) -> PathBuf {
        let mut path = self.stem.clone().into_os_string();
        path.push(format!("_{name}.pc2"));
        PathBuf::from(path)
    }

    /// `.pc2`: appends a frame to each mesh's point cache, the objects' and the moving
    /// colliders' (the first frame also writes the meshes as OBJ and starts the caches), then
    /// counts it in their headers, so that a run stopped at any point leaves caches of the whole
    /// frames so far. A frame that cannot be written whole (a full disk) is taken back from
    /// every cache, each cut to the frames its header counts, so that the caches stay whole and
    /// agree with each other; the error then names the frame.
    pub(super) fn add_to_caches(&mut self, states: &[ObjectState], time: f64) -> Result<()> {
        let code = self.last_code();
        if self.caches.is_empty() {
            let base = self.base_path();
            write_whole(&base, self.obj(states, time).as_bytes())
                .map_err(|e| anyhow::anyhow!("recording the meshes to {}: {e}", base.display()))?;
        }
        let moving = self.colliders.iter().filter(|c| c.is_moving());
        let collider_points =
            moving.map(|c| collider_mesh(c, time).0.iter().map(|p| p.as_vec3().to_array()).collect());
        let frames: Vec<Vec<[f32; 3]>> = (self.tracks.iter().zip(states))
            .map(|(t, state)| t.frame(state).0)
            .chain(collider_points)
            .collect();
        for (k, points) in frames.iter().enumerate() {
            if let Err(e) = self.append_to_cache(k, points) {
                // (caches past k have not taken the frame; at the first frame none holds one)
                let kept = self.frames - 1;
                let cut = (0..self.caches.len().min(k + 1)).try_for_each(|j| {
                    if kept == 0 {
                        std::fs::remove_file(self.cache_path(j))
                    } else {
                        cut_cache(&mut self.caches[j], frames[j].len() as u64, kept)
                    }
                });
                let path = self.cache_path(k);
                return Err(match cut {
                    Ok(()) if kept == 0 => anyhow::anyhow!("recording frame {code} to {}: {e}", path.display()),
                    Ok(()) => anyhow::anyhow!(
                        "recording frame {code} to {}: {e} (the caches keep the {kept} whole frames before it)",
                        path.display()
                    ),
                    Err(cut) => anyhow::anyhow!(
                        "recording frame {code} to {}: {e}; cutting the caches back to {kept} whole frames failed too: {cut}",
                        path.display()
                    ),
                });
            }
        }
        Ok(())
    }

    /// Appends one frame of `points` to mesh k's point cache (starting it, with its header and no
    /// sample counted, at the first frame) and counts the frame in its header.
    pub(super) fn append_to_cache(&mut self, k: usize, points: &[[f32; 3]]) -> std::io::Result<()> {
        use std::io::{Seek, SeekFrom, Write};
        if k == self.caches.len() {
            let mut header = Vec::with_capacity(PC2_HEADER as usize);
            header.extend_from_slice(b"POINTCACHE2\0");
            header.extend_from_slice(&1i32.to_le_bytes()); // version
            header.extend_from_slice(&(points.len() as i32).to_le_bytes());
            header.extend_from_slice(&(self.first_code as f32).to_le_bytes()); // start frame
            header.extend_from_slice(&1f32.to_le_bytes()); // samples a frame
            header.extend_from_slice(&0i32.to_le_bytes()); // samples so far
            let mut file = std::fs::File::create(self.cache_path(k))?;
            self.caches.push(file.try_clone()?);
            file.write_all(&header)?;
        }
        let bytes: Vec<u8> = points.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let file = &mut self.caches[k];
        file.seek(SeekFrom::End(0))?;
        file.write_all(&bytes)?;
        count_samples(file, self.frames)
    }
}

/// Cuts a point cache of `points` points a sample back to its first `frames` samples, the
/// header counting them (a smaller file and a word rewritten in place: no new space is needed).
pub(super) fn cut_cache(file: &mut std::fs::File, points: u64, frames: u64) -> std::io::Result<()> {
    file.set_len(PC2_HEADER + frames * points * 12)?;
    count_samples(file, frames)
}

/// Writes a point cache's count of samples, the header's last word.
pub(super) fn count_samples(file: &mut std::fs::File, frames: u64) -> std::io::Result<()> {
    use std::io::{Seek, SeekFrom, Write};
    file.seek(SeekFrom::Start(PC2_HEADER - 4))?;
    file.write_all(&(frames as i32).to_le_bytes())
}
