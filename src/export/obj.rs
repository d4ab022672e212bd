//! `.obj`: a Wavefront OBJ file a frame, and the materials (`.mtl`) they and the point caches'
//! meshes name.

use super::*;

impl Recording {
    /// The file of OBJ frame `n` (its time code).
    pub fn obj_path(&self, n: u64) -> PathBuf {
        let mut name = self.stem.clone().into_os_string();
        name.push(format!("_{n:05}.obj"));
        PathBuf::from(name)
    }

    /// The materials an OBJ sequence's frames or a point cache's meshes name: `{stem}.mtl`.
    pub(super) fn mtl_path(&self) -> PathBuf {
        self.stem.with_extension("mtl")
    }

    /// The materials as MTL text: one for each object, named as its group, with its colour as
    /// the diffuse colour `Kd`, and a grey one the colliders share. Kd is linear, as Blender's
    /// importer puts it into its (linear) base colour; the vertex colours stay sRGB (`obj`).
    pub(super) fn mtl(&self) -> String {
        let mut out = String::from("# msdsim materials\n");
        let grey = [COLLIDER_GREY; 3];
        let materials = self.tracks.iter().map(|t| (t.name.as_str(), t.color));
        for (name, [r, g, b]) in materials.chain(std::iter::once((COLLIDER_MATERIAL, grey))) {
            let _ = writeln!(out, "\nnewmtl {name}\nKd {r} {g} {b}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1");
        }
        out
    }

    /// One frame as OBJ text, at simulated time `time`: every object an `o` group of vertices
    /// (with the object's colour), normals and triangles, then every collider one (grey) where
    /// it is at that time.
    pub(super) fn obj(&self, states: &[ObjectState], time: f64) -> String {
        let mut out = format!("# msdsim frame {} ({} frames/s)\n", self.last_code(), self.fps);
        let mtl = self.mtl_path();
        let _ = writeln!(out, "mtllib {}", mtl.file_name().unwrap_or_default().to_string_lossy());
        let (mut base, mut st_base) = (1usize, 1usize);
        for (t, s) in self.tracks.iter().zip(states) {
            let _ = writeln!(out, "o {}\nusemtl {}", t.name, t.name);
            // OBJ readers (Blender, MeshLab) take vertex colours as sRGB; the scene's are linear.
            let [r, g, b] = t.color.map(srgb);
            let (points, normals) = t.frame(s);
            for [x, y, z] in &points {
                let _ = writeln!(out, "v {x} {y} {z} {r} {g} {b}");
            }
            for [x, y, z] in &normals {
                let _ = writeln!(out, "vn {x} {y} {z}");
            }
            for [u, v] in &t.st {
                let _ = writeln!(out, "vt {u} {v}");
            }
            for (tri, uv) in t.indices.chunks_exact(3).zip(t.st_indices.chunks_exact(3)) {
                let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize + base);
                let [ta, tb, tc] = [uv[0], uv[1], uv[2]].map(|i| i as usize + st_base);
                let _ = writeln!(out, "f {a}/{ta}/{a} {b}/{tb}/{b} {c}/{tc}/{c}");
            }
            base += points.len();
            st_base += t.st.len();
        }
        let grey = srgb(COLLIDER_GREY);
        for (c, name) in self.colliders.iter().zip(&self.collider_names) {
            let _ = writeln!(out, "o {name}\nusemtl {COLLIDER_MATERIAL}");
            let (points, normals, triangles) = collider_mesh(c, time);
            for p in &points {
                let _ = writeln!(out, "v {} {} {} {grey} {grey} {grey}", p.x, p.y, p.z);
            }
            for n in &normals {
                let _ = writeln!(out, "vn {} {} {}", n.x, n.y, n.z);
            }
            for tri in &triangles {
                let [a, b, c] = tri.map(|i| i as usize + base);
                let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
            }
            base += points.len();
        }
        out
    }
}

/// Removes the frames an earlier OBJ recording under the same name left (regular files named
/// `{stem}_NNNNN.obj`, five digits or more), so that a shorter recording leaves no stale
/// higher-numbered frames for an importer to pick up.
pub(super) fn remove_old_frames(path: &Path) -> Result<()> {
    let stem = path.with_extension("");
    let (Some(folder), Some(name)) = (stem.parent(), stem.file_name()) else { return Ok(()) };
    let folder = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
    let prefix = format!("{}_", name.to_string_lossy());
    for entry in std::fs::read_dir(folder)?.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let number = file.strip_prefix(&prefix).and_then(|rest| rest.strip_suffix(".obj"));
        let regular = entry.file_type().is_ok_and(|t| t.is_file());
        if regular && number.is_some_and(|n| n.len() >= 5 && n.bytes().all(|b| b.is_ascii_digit())) {
            std::fs::remove_file(entry.path())
                .map_err(|e| anyhow::anyhow!("removing the earlier frame {}: {e}", entry.path().display()))?;
        }
    }
    Ok(())
}

/// A linear colour channel in sRGB's transfer curve, to 4 decimals.
pub(super) fn srgb(linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 1e4).round() / 1e4
}
