//! Recordings of the animated surfaces (`simulate --record`, the app's Record button), one mesh
//! per object (a cloth's grid, a rope's tube), in the format the file name's extension picks:
//! - `.usda`: USD (ASCII) with points and normals time-sampled at every frame, so Blender,
//!   Houdini, usdview and Omniverse play it back. Frames are kept in memory (up to `MAX_BYTES`)
//!   and written at the end by the caller (`usda`), so an interrupted run leaves no partial file.
//! - `.obj`: a sequence of Wavefront OBJ files, `NAME_00001.obj`, `NAME_00002.obj`, ... one per
//!   frame, written as the frames come (every object an `o` group with vertex colours and
//!   normals; Blender imports a sequence with its "Stop-motion OBJ" add-on, MeshLab and most
//!   tools read single frames).

use crate::render::mesh;
use crate::sim::gpu::ObjectState;
use crate::sim::model::{ObjectKind, SimModel};
use anyhow::Result;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Each object's display colour (the cloths', then the ropes'), as the recordings write them.
pub fn colors(scene: &crate::scene::Scene) -> Vec<[f32; 3]> {
    let cloths = scene.cloths.iter().map(|c| c.color);
    cloths.chain(scene.ropes.iter().map(|r| r.color)).map(|c| c.map(|x| x as f32)).collect()
}

/// The recording formats, by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Usd,
    ObjSequence,
}

impl Format {
    /// The format of `path`, from its extension (`usda` or `obj`), or a message naming the
    /// supported ones.
    pub fn of(path: &Path) -> Result<Self, String> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("usda") => Ok(Format::Usd),
            Some("obj") => Ok(Format::ObjSequence),
            _ => Err(format!(
                "{}: the recording format follows the extension: .usda (USD ASCII, one file) or .obj (a numbered sequence of OBJ files)",
                path.display()
            )),
        }
    }
}

/// The most memory a recording may take (points and normals kept until the end).
const MAX_BYTES: u64 = 2 << 30;

/// One object's mesh and its frames.
struct Track {
    name: String,
    /// The object's kind and grid: a recording keeps one set of meshes.
    shape: (ObjectKind, [u32; 2]),
    counts: usize,
    /// Surface vertices a frame.
    vertices: usize,
    indices: Vec<u32>,
    color: [f32; 3],
    points: Vec<Vec<[f32; 3]>>,
    normals: Vec<Vec<[f32; 3]>>,
}

pub struct Recording {
    tracks: Vec<Track>,
    fps: f64,
    format: Format,
    /// `.obj`: the path without its extension; frame n goes to `{stem}_{n:05}.obj`.
    stem: PathBuf,
    frames: u64,
}

impl Recording {
    /// A recording of `model` into `path` (its format from the extension), of `frames`
    /// frames when known: a USD recording that would not fit in memory is refused before any
    /// work; an OBJ sequence needs its folder to exist. `colors` is each object's display colour.
    pub fn new(model: &SimModel, colors: &[[f32; 3]], path: &Path, frames: Option<u64>) -> Result<Self> {
        let format = Format::of(path).map_err(crate::error::UserError)?;
        let vertices: u64 = model.objects.iter().map(|o| o.surface_count() as u64).sum();
        let bytes = vertices * 24 * frames.unwrap_or(0);
        if format == Format::Usd && bytes > MAX_BYTES {
            return Err(crate::error::UserError(format!(
                "a USD recording would keep {:.1} GiB of frames in memory (at most {} GiB): record fewer frames, or an .obj sequence",
                bytes as f64 / (1u64 << 30) as f64,
                MAX_BYTES >> 30
            ))
            .into());
        }
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if !folder.is_dir() {
            return Err(crate::error::UserError(format!(
                "{}: the folder {} for the recording does not exist",
                path.display(),
                folder.display()
            ))
            .into());
        }
        let tracks = model
            .objects
            .iter()
            .zip(colors)
            .map(|(o, &color)| {
                let indices = match o.kind {
                    ObjectKind::Cloth => mesh::cloth_indices(o.dims[0], o.dims[1]),
                    ObjectKind::Rope => mesh::rope_indices(o.dims[0]),
                };
                Track {
                    name: usd_name(&o.name),
                    shape: (o.kind, o.dims),
                    counts: indices.len() / 3,
                    vertices: o.surface_count(),
                    indices,
                    color,
                    points: Vec::new(),
                    normals: Vec::new(),
                }
            })
            .collect();
        Ok(Self {
            tracks,
            // Frames per second to the millisecond (a frame_dt of 0.016666667 s is 60).
            fps: (1e3 / model.frame_dt).round() / 1e3,
            format,
            stem: path.with_extension(""),
            frames: 0,
        })
    }

    /// Whether `model` still has the objects and frame rate this recording began with (an
    /// edit that changes them cannot go into the same meshes).
    pub fn matches(&self, model: &SimModel) -> bool {
        (1e3 / model.frame_dt).round() / 1e3 == self.fps
            && model.objects.len() == self.tracks.len()
            && self.tracks.iter().zip(&model.objects).all(|(t, o)| t.shape == (o.kind, o.dims))
    }

    pub fn format(&self) -> Format {
        self.format
    }

    /// Frames added so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The file of OBJ frame `n` (1-based).
    pub fn obj_path(&self, n: u64) -> PathBuf {
        let mut name = self.stem.clone().into_os_string();
        name.push(format!("_{n:05}.obj"));
        PathBuf::from(name)
    }

    /// Adds a frame: each object's surface (a cloth's particles, a rope's tube vertices). USD
    /// keeps it (refused past `MAX_BYTES`); an OBJ sequence writes its file now.
    pub fn add(&mut self, states: &[ObjectState]) -> Result<()> {
        let same = states.len() == self.tracks.len()
            && self.tracks.iter().zip(states).all(|(t, s)| t.vertices == s.surface.len());
        if !same {
            return Err(crate::error::UserError(
                "the scene's objects changed while recording (a recording keeps one set of meshes)".into(),
            )
            .into());
        }
        self.frames += 1;
        if self.format == Format::ObjSequence {
            let path = self.obj_path(self.frames);
            return std::fs::write(&path, self.obj(states)).map_err(|e| {
                crate::error::UserError(format!("recording frame {} to {}: {e}", self.frames, path.display()))
                    .into()
            });
        }
        let vertices: u64 = states.iter().map(|s| s.surface.len() as u64).sum();
        if vertices * 24 * self.frames > MAX_BYTES {
            self.frames -= 1;
            return Err(crate::error::UserError(format!(
                "the USD recording reached {} GiB of frames in memory after {} frames: stop it, or record an .obj sequence",
                MAX_BYTES >> 30,
                self.frames
            ))
            .into());
        }
        for (t, s) in self.tracks.iter_mut().zip(states) {
            t.points.push(s.surface.iter().map(|v| [v.pos[0], v.pos[1], v.pos[2]]).collect());
            t.normals.push(s.surface.iter().map(|v| [v.normal[0], v.normal[1], v.normal[2]]).collect());
        }
        Ok(())
    }

    /// One frame as OBJ text: every object an `o` group of vertices (with the object's colour),
    /// normals and triangles.
    fn obj(&self, states: &[ObjectState]) -> String {
        let mut out = format!("# msdsim frame {} ({} frames/s)\n", self.frames, self.fps);
        let mut base = 1usize;
        for (t, s) in self.tracks.iter().zip(states) {
            let _ = writeln!(out, "o {}", t.name);
            let [r, g, b] = t.color;
            for v in &s.surface {
                let _ = writeln!(out, "v {} {} {} {r} {g} {b}", v.pos[0], v.pos[1], v.pos[2]);
            }
            for v in &s.surface {
                let _ = writeln!(out, "vn {} {} {}", v.normal[0], v.normal[1], v.normal[2]);
            }
            for tri in t.indices.chunks_exact(3) {
                let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize + base);
                let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
            }
            base += s.surface.len();
        }
        out
    }

    /// The USD ASCII text: time codes 1..=frames at the simulation's frame rate.
    pub fn usda(&self) -> String {
        let frames = self.tracks.first().map(|t| t.points.len()).unwrap_or(0);
        let mut out = String::new();
        let _ = writeln!(
            out,
            "#usda 1.0\n(\n    defaultPrim = \"scene\"\n    metersPerUnit = 1\n    upAxis = \"Y\""
        );
        let _ = writeln!(
            out,
            "    startTimeCode = 1\n    endTimeCode = {}\n    timeCodesPerSecond = {}\n)\n",
            frames.max(1),
            self.fps
        );
        let _ = writeln!(out, "def Xform \"scene\"\n{{");
        for t in &self.tracks {
            let _ = writeln!(out, "    def Mesh \"{}\"\n    {{", t.name);
            let _ = writeln!(out, "        uniform token subdivisionScheme = \"none\"");
            let _ = writeln!(out, "        uniform bool doubleSided = 1");
            let _ = writeln!(out, "        int[] faceVertexCounts = [{}]", vec!["3"; t.counts].join(", "));
            let indices: Vec<String> = t.indices.iter().map(u32::to_string).collect();
            let _ = writeln!(out, "        int[] faceVertexIndices = [{}]", indices.join(", "));
            let [r, g, b] = t.color;
            let _ = writeln!(out, "        color3f[] primvars:displayColor = [({r}, {g}, {b})]");
            samples(&mut out, "point3f[] points", &t.points);
            let _ = writeln!(
                out,
                "        normal3f[] normals (\n            interpolation = \"vertex\"\n        )"
            );
            samples(&mut out, "normal3f[] normals", &t.normals);
            let _ = writeln!(out, "    }}");
        }
        let _ = writeln!(out, "}}");
        out
    }
}

/// `name.timeSamples = { 1: [(x, y, z), ...], ... }`, numbers in Rust's shortest exact form.
fn samples(out: &mut String, name: &str, frames: &[Vec<[f32; 3]>]) {
    let _ = writeln!(out, "        {name}.timeSamples = {{");
    for (f, values) in frames.iter().enumerate() {
        let items: Vec<String> = values.iter().map(|[x, y, z]| format!("({x}, {y}, {z})")).collect();
        let _ = writeln!(out, "            {}: [{}],", f + 1, items.join(", "));
    }
    let _ = writeln!(out, "        }}");
}

/// A valid USD prim name: letters, digits and underscores, not starting with a digit.
fn usd_name(name: &str) -> String {
    let mut s: String = name.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    s
}

#[cfg(test)]
mod tests {
    #[test]
    fn prim_names_are_valid() {
        assert_eq!(super::usd_name("my cloth-1"), "my_cloth_1");
        assert_eq!(super::usd_name("3d"), "_3d");
        assert_eq!(super::usd_name(""), "_");
    }
}
