//! `simulate --record FILE.usda`: the animated surfaces as USD (ASCII), one mesh per object
//! (a cloth's grid, a rope's tube) with its points and normals time-sampled at every frame, so
//! Blender, Houdini, usdview and Omniverse play it back. Frames are kept in memory until the run
//! ends, then written through `OutFile` (a bad path fails before the run; an interrupted run
//! leaves no partial file).

use crate::render::mesh;
use crate::sim::gpu::ObjectState;
use crate::sim::model::{ObjectKind, SimModel};
use anyhow::Result;
use std::fmt::Write as _;

/// The most memory a recording may take (points and normals kept until the end).
const MAX_BYTES: u64 = 2 << 30;

/// One object's mesh and its frames.
struct Track {
    name: String,
    counts: usize,
    indices: Vec<u32>,
    color: [f32; 3],
    points: Vec<Vec<[f32; 3]>>,
    normals: Vec<Vec<[f32; 3]>>,
}

pub struct Recording {
    tracks: Vec<Track>,
    fps: f64,
}

impl Recording {
    /// A recording of `frames` frames of `model`; refused (before any work) when it would not
    /// fit in memory. `colors` is each object's display colour.
    pub fn new(model: &SimModel, colors: &[[f32; 3]], frames: u64) -> Result<Self> {
        let vertices: u64 = model.objects.iter().map(|o| o.surface_count() as u64).sum();
        let bytes = vertices * 24 * frames;
        if bytes > MAX_BYTES {
            return Err(crate::error::UserError(format!(
                "--record would keep {:.1} GiB of frames in memory (at most {} GiB): record fewer --frames",
                bytes as f64 / (1u64 << 30) as f64,
                MAX_BYTES >> 30
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
                    counts: indices.len() / 3,
                    indices,
                    color,
                    points: Vec::new(),
                    normals: Vec::new(),
                }
            })
            .collect();
        // Frames per second to the millisecond (a frame_dt of 0.016666667 s is 60).
        Ok(Self { tracks, fps: (1e3 / model.frame_dt).round() / 1e3 })
    }

    /// Adds a frame: each object's surface (a cloth's particles, a rope's tube vertices).
    pub fn add(&mut self, states: &[ObjectState]) {
        for (t, s) in self.tracks.iter_mut().zip(states) {
            t.points.push(s.surface.iter().map(|v| [v.pos[0], v.pos[1], v.pos[2]]).collect());
            t.normals.push(s.surface.iter().map(|v| [v.normal[0], v.normal[1], v.normal[2]]).collect());
        }
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
