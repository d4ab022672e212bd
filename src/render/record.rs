//! Recordings of the animated surfaces (`simulate --record`, the app's Record button), one mesh
//! per object (a cloth's grid, a rope's tube), in the format the file name's extension picks:
//! - `.usda`: USD (ASCII) with points, normals and extents time-sampled at every frame (and the
//!   frame rate as framesPerSecond), so Blender, Houdini, usdview and Omniverse play it back;
//!   prims are named after the objects, made unique; each mesh and shape has a UsdPreviewSurface
//!   material bound, and the colliders are shapes. USD's text groups each attribute's samples,
//!   so it is written when the recording ends (`write_to`, by the caller, through a temporary
//!   file: an interrupted run leaves no partial file); until then the frames go to a spool file
//!   beside it, unlinked from the start, so memory stays at a frame however long the recording.
//! - `.glb`: glTF 2.0 binary (`super::gltf`), frames kept in memory (up to `MAX_BYTES`), each a
//!   morph target, written at the end as USD is.
//! - `.pc2`: a PC2 point cache a mesh, streamed, with the meshes in an OBJ file.
//! - `.obj`: a sequence of Wavefront OBJ files, `NAME_00001.obj`, `NAME_00002.obj`, ... one per
//!   frame, written as the frames come (every object and then every collider an `o` group with
//!   vertex colours and normals; Blender imports a sequence with its "Stop-motion OBJ" add-on,
//!   MeshLab and most tools read single frames).

use crate::render::mesh;
use crate::sim::collider::{ColliderModel, Shape};
use crate::sim::gpu::ObjectState;
use crate::sim::gpu_types::ROPE_RING;
use crate::sim::model::{ObjectKind, SimModel};
use anyhow::Result;
use glam::{DQuat, DVec3};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Half the side of the square that stands for the ground in a USD recording [m].
const GROUND_HALF_SIZE: f64 = 20.0;

/// Each object's front and back colours (the cloths', then the ropes', whose back is their
/// front), as the recordings write them.
pub fn colors(scene: &crate::scene::Scene) -> Vec<[[f32; 3]; 2]> {
    let cloths = scene.cloths.iter().map(|c| [c.color, c.back_color]);
    let ropes = scene.ropes.iter().map(|r| [r.color, r.color]);
    cloths.chain(ropes).map(|c| c.map(|c| c.map(|x| x as f32))).collect()
}

/// The scopes a USD recording keeps under /scene beside the objects' meshes: the colliders'
/// shapes and the materials.
const USD_SCOPES: [&str; 2] = ["colliders", "materials"];

/// The colour colliders are recorded in (linear).
const COLLIDER_GREY: f32 = 0.5;
/// The material the colliders share in an OBJ recording's MTL file (an object named so has
/// its group renamed apart, `unique_name`).
const COLLIDER_MATERIAL: &str = "collider";

/// The recording formats, by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Usd,
    ObjSequence,
    /// glTF 2.0 binary: each mesh's frames as morph targets, played by one animation.
    Gltf,
    /// PC2 point caches (one a mesh) with the meshes' first frame as OBJ, for Blender's Mesh
    /// Cache modifier: streamed, so memory stays at one frame.
    PointCache,
}

impl Format {
    /// Whether the file is written when the recording ends (USD from its spool, glTF from the
    /// frames kept in memory), not as the frames come.
    pub fn keeps_frames(self) -> bool {
        matches!(self, Format::Usd | Format::Gltf)
    }

    /// Whether a recording of this format into `record` writes `other` besides `record`: an OBJ
    /// sequence its frames `{stem}_NNNNN.obj` (`Recording::obj_path`), a point cache its meshes
    /// `{stem}.obj` and caches `{stem}_{name}.pc2` (`base_path`, `cache_path`), both their
    /// materials `{stem}.mtl` (`mtl_path`), in `record`'s folder.
    pub fn writes(self, record: &Path, other: &Path) -> bool {
        // (folders compared as the file system resolves them: a link or `..` is the same folder)
        let folder = |p: &Path| {
            let parent = std::path::absolute(p).ok()?.parent()?.to_path_buf();
            Some(parent.canonicalize().unwrap_or(parent))
        };
        let (Some(stem), Some(name)) = (record.file_stem().and_then(|s| s.to_str()), other.file_name())
        else {
            return false;
        };
        if folder(record) != folder(other) {
            return false;
        }
        let name = name.to_string_lossy();
        let after = name.strip_prefix(stem);
        match self {
            Format::ObjSequence => {
                after == Some(".mtl")
                    || after
                        .and_then(|a| a.strip_prefix('_'))
                        .and_then(|a| a.strip_suffix(".obj"))
                        .is_some_and(|n| n.len() >= 5 && n.bytes().all(|b| b.is_ascii_digit()))
            }
            Format::PointCache => after
                .is_some_and(|a| a == ".obj" || a == ".mtl" || (a.starts_with('_') && a.ends_with(".pc2"))),
            Format::Usd | Format::Gltf => false,
        }
    }

    /// Whether a recording of this format into `record` would replace or remove `file`: the
    /// recording itself, a file it writes beside it, or an earlier frame it cleans up.
    pub fn endangers(self, record: &Path, file: &Path) -> bool {
        same_file(record, file) || self.writes(record, file)
    }

    /// The format of `path`, from its extension (`usda` or `obj`), or a message naming the
    /// supported ones.
    pub fn of(path: &Path) -> Result<Self, String> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("usda") => Ok(Format::Usd),
            Some("obj") => Ok(Format::ObjSequence),
            Some("pc2") => Ok(Format::PointCache),
            Some("glb") => Ok(Format::Gltf),
            _ => Err(format!(
                "{}: the recording format follows the extension: .usda (USD ASCII, one file), .obj (a numbered sequence of OBJ files), .glb (glTF 2.0 binary) or .pc2 (a PC2 point cache a mesh, with the meshes as OBJ)",
                path.display()
            )),
        }
    }
}

/// Whether `a` and `b` name the same file: the same file when both exist, else the same
/// absolute path.
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => std::path::absolute(a).ok().zip(std::path::absolute(b).ok()).is_some_and(|(a, b)| a == b),
    }
}

/// The bytes of a PC2 header: "POINTCACHE2\0", version, points, start frame, sample rate,
/// samples (the last, updated as frames come).
const PC2_HEADER: u64 = 32;

/// What a USD or glTF recording keeps of a vertex a frame: its point, normal and velocity
/// [bytes] (USD in its spool, glTF in memory).
const BYTES_PER_VERTEX: u64 = 36;

/// The most memory a glTF recording may take: the frames it keeps and the file built from them
/// at the end.
const MAX_BYTES: u64 = 2 << 30;

impl Format {
    /// The memory a recording in this format takes a vertex a frame at its end [bytes]: glTF's
    /// frames kept and its binary file built from them (24: a target's points and normals).
    /// USD spools its frames to disk and writes its text from there; the other formats write
    /// as the frames come: none.
    fn peak_bytes_per_vertex(self) -> u64 {
        match self {
            Format::Gltf => BYTES_PER_VERTEX + 24,
            Format::Usd | Format::ObjSequence | Format::PointCache => 0,
        }
    }
}

/// One object's mesh and its frames.
struct Track {
    /// The prim, group and cache name: letters, digits and underscores, unique.
    name: String,
    /// The object's own name, as glTF keeps it (UTF-8, any characters).
    label: String,
    /// The object's kind and grid: a recording keeps one set of meshes.
    shape: (ObjectKind, [u32; 2]),
    counts: usize,
    /// Surface vertices a frame (the simulation's; a rope's recording adds its two cap rings).
    vertices: usize,
    /// A rope's nodes: its caps get vertices of their own, with the rope's direction as normal.
    rope_nodes: Option<u32>,
    indices: Vec<u32>,
    /// Texture coordinates, and for each corner of `indices` the one it takes.
    st: Vec<[f32; 2]>,
    st_indices: Vec<u32>,
    color: [f32; 3],
    /// The colour of a cloth's back (a rope's is its front).
    back: [f32; 3],
    /// glTF's frames (USD's are in the spool).
    points: Vec<Vec<[f32; 3]>>,
    normals: Vec<Vec<[f32; 3]>>,
    /// Where the track's frame starts in a frame of the spool [bytes].
    spooled_at: u64,
}

/// A USD recording's frames on disk: frame f at `f * frame_bytes`; in it each track's points,
/// normals and velocities (a rope's tube vertex takes its node's, for motion blur), f32 x, y, z
/// a vertex, from the track's `spooled_at`.
struct Spool {
    file: std::fs::File,
    frame_bytes: u64,
}

pub struct Recording {
    tracks: Vec<Track>,
    /// The scene's colliders (USD writes them as shapes, moving ones with time-sampled
    /// placements).
    colliders: Vec<ColliderModel>,
    /// Each collider's group name in an OBJ frame.
    collider_names: Vec<String>,
    /// The simulated time of each frame added [s].
    times: Vec<f64>,
    /// The time code (and OBJ number) of the first frame: 0 when it is the initial state
    /// (time 0), else 1; the frames after it count on from there.
    first_code: u64,
    fps: f64,
    format: Format,
    /// `.obj`: the path without its extension; frame n goes to `{stem}_{n:05}.obj`.
    stem: PathBuf,
    frames: u64,
    /// `.pc2`: each mesh's point cache, once the first frame has come.
    caches: Vec<std::fs::File>,
    /// `.usda`: the frames so far.
    spool: Option<Spool>,
}

impl Recording {
    /// A recording of `model` into `path` (its format from the extension), of `frames`
    /// frames when known: a USD recording that would not fit in memory is refused before any
    /// work; an OBJ sequence needs its folder to exist. `colors` is each object's front and back
    /// colour (`colors`).
    pub fn new(model: &SimModel, colors: &[[[f32; 3]; 2]], path: &Path, frames: Option<u64>) -> Result<Self> {
        let format = Format::of(path).map_err(crate::error::UserError)?;
        let vertices: u64 = model.objects.iter().map(|o| o.surface_count() as u64).sum();
        let bytes = vertices * format.peak_bytes_per_vertex() * frames.unwrap_or(0);
        if bytes > MAX_BYTES {
            return Err(crate::error::UserError(format!(
                "a glTF recording would take {:.1} GiB of memory for its frames and file (at most {} GiB): record fewer frames, or as .usda, a .pc2 point cache or an .obj sequence (kept on disk)",
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
        // The formats written as the frames come find a folder they cannot write in now, not at
        // the first frame after the run has begun (USD and glTF claim their file before).
        if !format.keeps_frames() {
            crate::atomic_file::probe_beside(path).map_err(|e| {
                crate::error::UserError(format!(
                    "{}: cannot write in the folder {} for the recording: {e}",
                    path.display(),
                    folder.display()
                ))
            })?;
        }
        if format == Format::ObjSequence {
            remove_old_frames(path)?;
        }
        // Objects are named apart from the scopes beside them under /scene in USD (a prim
        // path holds one prim), in every format so that the names agree.
        let mut taken: std::collections::HashSet<String> =
            USD_SCOPES.iter().chain([&COLLIDER_MATERIAL]).map(|s| s.to_string()).collect();
        let mut tracks: Vec<Track> = model
            .objects
            .iter()
            .zip(colors)
            .map(|(o, &[color, back])| {
                let (st, st_indices) = texture_coordinates(o.kind, o.dims);
                let (indices, rope_nodes) = match o.kind {
                    ObjectKind::Cloth => (mesh::cloth_indices(o.dims[0], o.dims[1]), None),
                    ObjectKind::Rope => {
                        // The caps on copies of the end rings after the tube's vertices.
                        let caps = o.surface_count() as u32;
                        let mut indices = mesh::rope_tube_indices(o.dims[0]);
                        indices.extend(mesh::rope_cap_indices(caps, caps + ROPE_RING as u32));
                        (indices, Some(o.dims[0]))
                    }
                };
                Track {
                    name: unique_name(&mut taken, usd_name(&o.name)),
                    label: o.name.clone(),
                    rope_nodes,
                    shape: (o.kind, o.dims),
                    counts: indices.len() / 3,
                    vertices: o.surface_count(),
                    indices,
                    st,
                    st_indices,
                    color,
                    back,
                    points: Vec::new(),
                    normals: Vec::new(),
                    spooled_at: 0,
                }
            })
            .collect();
        let mut spooled = 0;
        for t in &mut tracks {
            t.spooled_at = spooled;
            spooled += 3 * 12 * t.recorded_vertices() as u64;
        }
        let spool = match format {
            Format::Usd => Some(Spool {
                file: crate::atomic_file::anonymous_beside(path).map_err(|e| {
                    anyhow::anyhow!("{}: cannot make the recording's spool beside it: {e}", path.display())
                })?,
                frame_bytes: spooled,
            }),
            _ => None,
        };
        let collider_names = (model.colliders.iter().enumerate())
            .map(|(i, c)| unique_name(&mut taken, format!("collider_{}_{i}", c.shape.kind().label())))
            .collect();
        let recording = Self {
            tracks,
            colliders: model.colliders.clone(),
            collider_names,
            times: Vec::new(),
            first_code: 1,
            // Frames per second to the millisecond (a frame_dt of 0.016666667 s is 60).
            fps: (1e3 / model.frame_dt).round() / 1e3,
            format,
            stem: path.with_extension(""),
            frames: 0,
            caches: Vec::new(),
            spool,
        };
        if format == Format::PointCache {
            recording.remove_fixed_colliders_caches()?;
        }
        Ok(recording)
    }

    /// Removes the caches an earlier point-cache recording under the same name left for
    /// colliders that are fixed in this one (regular files `{stem}_{name}.pc2`), so that an
    /// importer that takes each mesh's cache where it finds one does not move them.
    fn remove_fixed_colliders_caches(&self) -> Result<()> {
        let fixed = self.colliders.iter().zip(&self.collider_names).filter(|(c, _)| !c.motion.is_moving());
        for (_, name) in fixed {
            let path = self.cache_file(name);
            if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
                std::fs::remove_file(&path)
                    .map_err(|e| anyhow::anyhow!("removing the earlier cache {}: {e}", path.display()))?;
            }
        }
        Ok(())
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

    /// The time code (the OBJ file's number) of the first frame added.
    pub fn first_code(&self) -> u64 {
        self.first_code
    }

    /// The time code (the OBJ file's number) of the last frame added.
    pub fn last_code(&self) -> u64 {
        (self.first_code + self.frames).saturating_sub(1)
    }

    /// The file of OBJ frame `n` (its time code).
    pub fn obj_path(&self, n: u64) -> PathBuf {
        let mut name = self.stem.clone().into_os_string();
        name.push(format!("_{n:05}.obj"));
        PathBuf::from(name)
    }

    /// Adds a frame, the state at simulated time `time`: each object's surface (a cloth's
    /// particles, a rope's tube vertices). USD keeps it (refused past `MAX_BYTES`); an OBJ
    /// sequence writes its file now.
    pub fn add(&mut self, states: &[ObjectState], time: f64) -> Result<()> {
        let same = states.len() == self.tracks.len()
            && self.tracks.iter().zip(states).all(|(t, s)| t.vertices == s.surface.len());
        if !same {
            return Err(crate::error::UserError(
                "the scene's objects changed while recording (a recording keeps one set of meshes)".into(),
            )
            .into());
        }
        // The guard checks the particles; the surface derived from them (normals, a rope's
        // tube) is checked here, so that no file holds a NaN or an infinity.
        for (t, s) in self.tracks.iter().zip(states) {
            let finite = |v: &[f32; 4]| v.iter().all(|c| c.is_finite());
            if let Some(k) = s.surface.iter().position(|v| !finite(&v.pos) || !finite(&v.normal)) {
                anyhow::bail!(
                    "the recording stopped at t = {time:.3} s: '{}' has a surface vertex ({k}) that is not a finite number, which no file format carries; the frames before it are whole",
                    t.name
                );
            }
        }
        if self.frames == 0 {
            self.first_code = if time == 0.0 { 0 } else { 1 };
            if matches!(self.format, Format::ObjSequence | Format::PointCache) {
                let path = self.mtl_path();
                write_whole(&path, self.mtl().as_bytes())
                    .map_err(|e| anyhow::anyhow!("recording the materials to {}: {e}", path.display()))?;
            }
        }
        self.frames += 1;
        if self.format == Format::ObjSequence {
            let code = self.last_code();
            let path = self.obj_path(code);
            return write_whole(&path, self.obj(states, time).as_bytes())
                .map_err(|e| anyhow::anyhow!("recording frame {code} to {}: {e}", path.display()));
        }
        if self.format == Format::PointCache {
            return self.add_to_caches(states, time);
        }
        let vertices: u64 = states.iter().map(|s| s.surface.len() as u64).sum();
        if vertices * self.format.peak_bytes_per_vertex() * self.frames > MAX_BYTES {
            self.frames -= 1;
            return Err(crate::error::UserError(format!(
                "the recording reached {} GiB of memory for its frames and file after {} frames: stop it, or record a .pc2 point cache or an .obj sequence (streamed)",
                MAX_BYTES >> 30,
                self.frames
            ))
            .into());
        }
        if let Some(spool) = &self.spool {
            use std::os::unix::fs::FileExt as _;
            let mut bytes = Vec::with_capacity(spool.frame_bytes as usize);
            for (t, s) in self.tracks.iter().zip(states) {
                let (points, normals) = t.frame(s);
                for v in points.iter().chain(&normals).chain(&t.velocities_of(s)) {
                    bytes.extend(v.iter().flat_map(|x| x.to_le_bytes()));
                }
            }
            let at = (self.frames - 1) * spool.frame_bytes;
            if let Err(e) = spool.file.write_all_at(&bytes, at) {
                self.frames -= 1;
                anyhow::bail!("recording frame {} to the spool beside the file: {e}", self.last_code() + 1);
            }
        } else {
            for (t, s) in self.tracks.iter_mut().zip(states) {
                let (points, normals) = t.frame(s);
                t.points.push(points);
                t.normals.push(normals);
            }
        }
        self.times.push(time);
        Ok(())
    }

    /// Writes the file of a format written when the recording ends (USD, glTF: `keeps_frames`);
    /// nothing for the others.
    pub fn write_to(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        match self.format {
            Format::Usd => self.write_usda(w),
            Format::Gltf => w.write_all(&self.glb().map_err(std::io::Error::other)?),
            Format::ObjSequence | Format::PointCache => Ok(()),
        }
    }

    /// The glTF binary (`super::gltf`): texture coordinates per vertex (a rope's tube, whose
    /// coordinates are face-varying at its seam and caps, with a vertex for each coordinate a
    /// point takes: `split_seams`), the colliders as meshes where the first frame had them.
    pub fn glb(&self) -> Result<Vec<u8>> {
        let split: Vec<Option<Seams>> =
            (self.tracks.iter()).map(|t| (t.st_indices != t.indices).then(|| split_seams(t))).collect();
        let meshes: Vec<super::gltf::MeshFrames> = (self.tracks.iter().zip(&split))
            .map(|(t, seams)| {
                let (indices, st, points, normals) = match seams {
                    None => (&t.indices, &t.st, &t.points, &t.normals),
                    Some(s) => (&s.indices, &s.st, &s.points, &s.normals),
                };
                super::gltf::MeshFrames {
                    name: &t.label,
                    indices,
                    st: Some(st.as_slice()),
                    color: t.color,
                    double_sided: t.shape.0 == ObjectKind::Cloth,
                    points,
                    normals,
                }
            })
            .collect();
        let first = self.times.first().copied().unwrap_or(0.0);
        let f32s = |v: DVec3| v.as_vec3().to_array();
        let colliders: Vec<super::gltf::ColliderMesh> = (self.colliders.iter().zip(&self.collider_names))
            .map(|(c, name)| {
                let (points, normals, triangles) = collider_mesh(c, first);
                let start = c.motion.offset(first);
                super::gltf::ColliderMesh {
                    name: name.clone(),
                    points: points.into_iter().map(f32s).collect(),
                    normals: normals.into_iter().map(f32s).collect(),
                    indices: triangles.into_iter().flatten().collect(),
                    offsets: c
                        .motion
                        .is_moving()
                        .then(|| self.times.iter().map(|&t| f32s(c.motion.offset(t) - start)).collect()),
                }
            })
            .collect();
        let times: Vec<f32> = self.times.iter().map(|&t| (t - first) as f32).collect();
        super::gltf::glb(&meshes, &colliders, &times)
    }

    /// The names of the meshes a point cache animates: every object's, then every moving
    /// collider's (a fixed one stays where the OBJ has it).
    fn cached_names(&self) -> Vec<&str> {
        let moving = self.colliders.iter().zip(&self.collider_names).filter(|(c, _)| c.motion.is_moving());
        self.tracks.iter().map(|t| t.name.as_str()).chain(moving.map(|(_, name)| name.as_str())).collect()
    }

    /// The file of cached mesh k's point cache (`cached_names`).
    pub fn cache_path(&self, k: usize) -> PathBuf {
        self.cache_file(self.cached_names()[k])
    }

    /// The point cache of the mesh named `name`: `{stem}_{name}.pc2`.
    fn cache_file(&self, name: &str) -> PathBuf {
        let mut path = self.stem.clone().into_os_string();
        path.push(format!("_{name}.pc2"));
        PathBuf::from(path)
    }

    /// The materials an OBJ sequence's frames or a point cache's meshes name: `{stem}.mtl`.
    fn mtl_path(&self) -> PathBuf {
        self.stem.with_extension("mtl")
    }

    /// The materials as MTL text: one for each object, named as its group, with its colour as
    /// the diffuse colour `Kd`, and a grey one the colliders share. Kd is linear, as Blender's
    /// importer puts it into its (linear) base colour; the vertex colours stay sRGB (`obj`).
    fn mtl(&self) -> String {
        let mut out = String::from("# msdsim materials\n");
        let grey = [COLLIDER_GREY; 3];
        let materials = self.tracks.iter().map(|t| (t.name.as_str(), t.color));
        for (name, [r, g, b]) in materials.chain(std::iter::once((COLLIDER_MATERIAL, grey))) {
            let _ = writeln!(out, "\nnewmtl {name}\nKd {r} {g} {b}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1");
        }
        out
    }

    /// The OBJ file with the meshes a point cache animates: `{stem}.obj`.
    pub fn base_path(&self) -> PathBuf {
        self.stem.with_extension("obj")
    }

    /// What a finished recording into `path` wrote (a USD file: once the caller has written it).
    pub fn summary(&self, path: &Path) -> String {
        let n = self.frames;
        match self.format {
            _ if n == 0 => "recorded no frames".into(),
            Format::Usd | Format::Gltf => format!("recorded {n} frames to {}", path.display()),
            Format::ObjSequence => format!(
                "recorded {n} frames to {} ... {}",
                self.obj_path(self.first_code).display(),
                self.obj_path(self.last_code()).display()
            ),
            Format::PointCache => {
                let caches: Vec<String> = self
                    .cached_names()
                    .iter()
                    .map(|&name| self.cache_file(name).display().to_string())
                    .collect();
                format!(
                    "recorded {n} frames to {} (the meshes in {})",
                    caches.join(", "),
                    self.base_path().display()
                )
            }
        }
    }

    /// `.pc2`: appends a frame to each mesh's point cache, the objects' and the moving
    /// colliders' (the first frame also writes the meshes as OBJ and starts the caches), then
    /// counts it in their headers, so that a run stopped at any point leaves caches of the whole
    /// frames so far. A frame that cannot be written whole (a full disk) is taken back from
    /// every cache, each cut to the frames its header counts, so that the caches stay whole and
    /// agree with each other; the error then names the frame.
    fn add_to_caches(&mut self, states: &[ObjectState], time: f64) -> Result<()> {
        let code = self.last_code();
        if self.caches.is_empty() {
            let base = self.base_path();
            write_whole(&base, self.obj(states, time).as_bytes())
                .map_err(|e| anyhow::anyhow!("recording the meshes to {}: {e}", base.display()))?;
        }
        let moving = self.colliders.iter().filter(|c| c.motion.is_moving());
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
    fn append_to_cache(&mut self, k: usize, points: &[[f32; 3]]) -> std::io::Result<()> {
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

    /// One frame as OBJ text, at simulated time `time`: every object an `o` group of vertices
    /// (with the object's colour), normals and triangles, then every collider one (grey) where
    /// it is at that time.
    fn obj(&self, states: &[ObjectState], time: f64) -> String {
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

    /// Writes the USD ASCII text: time codes `first_code()..=last_code()` at the simulation's
    /// frame rate; the meshes' time samples from the spool, a frame at a time.
    fn write_usda(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "#usda 1.0\n(\n    defaultPrim = \"scene\"\n    metersPerUnit = 1\n    upAxis = \"Y\""
        );
        let _ = writeln!(
            out,
            "    startTimeCode = {}\n    endTimeCode = {}\n    timeCodesPerSecond = {}\n    framesPerSecond = {}\n)\n",
            self.first_code,
            self.last_code().max(self.first_code),
            self.fps,
            self.fps
        );
        let _ = writeln!(out, "def Xform \"scene\"\n{{");
        for t in &self.tracks {
            let _ = writeln!(
                out,
                "    def Mesh \"{}\" (\n        prepend apiSchemas = [\"MaterialBindingAPI\"]\n    )\n    {{",
                t.name
            );
            let _ = writeln!(out, "        rel material:binding = </scene/materials/{}>", t.name);
            let _ = writeln!(out, "        uniform token subdivisionScheme = \"none\"");
            let _ = writeln!(out, "        uniform bool doubleSided = 1");
            let _ = writeln!(out, "        int[] faceVertexCounts = [{}]", vec!["3"; t.counts].join(", "));
            let indices: Vec<String> = t.indices.iter().map(u32::to_string).collect();
            let _ = writeln!(out, "        int[] faceVertexIndices = [{}]", indices.join(", "));
            let [r, g, b] = t.color;
            let _ = writeln!(out, "        color3f[] primvars:displayColor = [({r}, {g}, {b})]");
            // UsdPreviewSurface has one colour for both sides: a cloth's back goes in a primvar.
            let [r, g, b] = t.back;
            let _ = writeln!(out, "        color3f primvars:msdsim:backColor = ({r}, {g}, {b}) (\n            interpolation = \"constant\"\n        )");
            let st: Vec<String> = t.st.iter().map(|[u, v]| format!("({u}, {v})")).collect();
            let _ = writeln!(
                out,
                "        texCoord2f[] primvars:st = [{}] (\n            interpolation = \"faceVarying\"\n        )",
                st.join(", ")
            );
            let st_indices: Vec<String> = t.st_indices.iter().map(u32::to_string).collect();
            let _ = writeln!(out, "        int[] primvars:st:indices = [{}]", st_indices.join(", "));
            w.write_all(out.as_bytes())?;
            out.clear();
            let spooled = |k: u64| move |f: u64, values: &mut Vec<[f32; 3]>| self.spooled(t, k, f, values);
            samples(w, self.first_code, self.frames, "point3f[] points", spooled(0))?;
            let _ = writeln!(
                out,
                "        normal3f[] normals (\n            interpolation = \"vertex\"\n        )"
            );
            w.write_all(out.as_bytes())?;
            out.clear();
            samples(w, self.first_code, self.frames, "normal3f[] normals", spooled(1))?;
            samples(w, self.first_code, self.frames, "vector3f[] velocities", spooled(2))?;
            let extents = |f: u64, values: &mut Vec<[f32; 3]>| {
                self.spooled(t, 0, f, values)?;
                *values = extent(values).to_vec();
                Ok(())
            };
            samples(w, self.first_code, self.frames, "float3[] extent", extents)?;
            let _ = writeln!(out, "    }}");
        }
        self.usda_colliders(&mut out);
        self.usda_materials(&mut out);
        let _ = writeln!(out, "}}");
        w.write_all(out.as_bytes())
    }

    /// Track `t`'s attribute k (0 points, 1 normals, 2 velocities) in frame f, from the spool.
    fn spooled(&self, t: &Track, k: u64, f: u64, values: &mut Vec<[f32; 3]>) -> std::io::Result<()> {
        use std::os::unix::fs::FileExt as _;
        let spool =
            self.spool.as_ref().ok_or_else(|| std::io::Error::other("a USD recording has a spool"))?;
        let n = t.recorded_vertices() as u64;
        let mut bytes = vec![0u8; 12 * n as usize];
        spool.file.read_exact_at(&mut bytes, f * spool.frame_bytes + t.spooled_at + k * 12 * n)?;
        values.clear();
        values.extend(bytes.chunks_exact(12).map(|c| {
            std::array::from_fn(|i| f32::from_le_bytes([c[4 * i], c[4 * i + 1], c[4 * i + 2], c[4 * i + 3]]))
        }));
        Ok(())
    }

    /// The name of the colliders' material: `colliders`, made unique against the objects'.
    fn collider_material(&self) -> String {
        let mut taken = self.tracks.iter().map(|t| t.name.clone()).collect();
        unique_name(&mut taken, "colliders".into())
    }

    /// A `UsdPreviewSurface` material for each object (its front colour) and one for the
    /// colliders (grey), in a scope `materials`; the meshes and shapes bind them.
    fn usda_materials(&self, out: &mut String) {
        let _ = writeln!(out, "    def Scope \"materials\"\n    {{");
        let grey = [COLLIDER_GREY; 3];
        let shared = self.collider_material();
        let colliders = (!self.colliders.is_empty()).then_some((shared.as_str(), &grey));
        for (name, [r, g, b]) in self.tracks.iter().map(|t| (t.name.as_str(), &t.color)).chain(colliders) {
            let _ = writeln!(out, "        def Material \"{name}\"\n        {{");
            let _ = writeln!(
                out,
                "            token outputs:surface.connect = </scene/materials/{name}/surface.outputs:surface>"
            );
            let _ = writeln!(out, "            def Shader \"surface\"\n            {{");
            let _ = writeln!(out, "                uniform token info:id = \"UsdPreviewSurface\"");
            let _ = writeln!(out, "                color3f inputs:diffuseColor = ({r}, {g}, {b})");
            let _ = writeln!(out, "                float inputs:roughness = 0.8");
            let _ = writeln!(out, "                token outputs:surface");
            let _ = writeln!(out, "            }}\n        }}");
        }
        let _ = writeln!(out, "    }}");
    }

    /// The colliders as USD shapes in a scope `colliders` (grey): a sphere as a Sphere, a
    /// capsule as a Capsule along its local z, a box as a Cube of size 2 scaled by its half
    /// extents and turned by its rotation, the ground as a 40 m square Mesh facing up at its
    /// height. A moving collider's translation is time-sampled at every frame, a fixed one's
    /// constant.
    fn usda_colliders(&self, out: &mut String) {
        if self.colliders.is_empty() {
            return;
        }
        let _ = writeln!(out, "    def Scope \"colliders\"\n    {{");
        let material = self.collider_material();
        for (i, c) in self.colliders.iter().enumerate() {
            let kind = c.shape.kind().label();
            let (prim, place, rotation): (&str, DVec3, Option<DQuat>) = match c.shape {
                Shape::Sphere { center, .. } => ("Sphere", center, None),
                Shape::Capsule { a, b, .. } => (
                    "Capsule",
                    (a + b) / 2.0,
                    Some(DQuat::from_rotation_arc(DVec3::Z, (b - a).normalize_or(DVec3::Z))),
                ),
                Shape::Box { center, rotation, .. } => ("Cube", center, Some(rotation)),
                Shape::Ground { height } => ("Mesh", DVec3::new(0.0, height, 0.0), None),
            };
            let _ = writeln!(out, "        def {prim} \"{kind}_{i}\" (\n            prepend apiSchemas = [\"MaterialBindingAPI\"]\n        )\n        {{");
            let _ = writeln!(out, "            rel material:binding = </scene/materials/{material}>");
            match c.shape {
                Shape::Sphere { radius, .. } => {
                    let _ = writeln!(out, "            double radius = {radius}");
                }
                Shape::Capsule { a, b, radius } => {
                    let _ = writeln!(out, "            uniform token axis = \"Z\"\n            double height = {}\n            double radius = {radius}", a.distance(b));
                }
                Shape::Box { .. } => {
                    let _ = writeln!(out, "            double size = 2");
                }
                Shape::Ground { .. } => {
                    let h = GROUND_HALF_SIZE;
                    // (a flat quad, not a subdivision cage: as the objects' meshes say)
                    let _ = writeln!(out, "            uniform token subdivisionScheme = \"none\"");
                    let _ = writeln!(out, "            int[] faceVertexCounts = [4]\n            int[] faceVertexIndices = [0, 1, 2, 3]");
                    let _ = writeln!(out, "            point3f[] points = [(-{h}, 0, -{h}), (-{h}, 0, {h}), ({h}, 0, {h}), ({h}, 0, -{h})]");
                    let _ = writeln!(
                        out,
                        "            normal3f[] normals = [(0, 1, 0), (0, 1, 0), (0, 1, 0), (0, 1, 0)]"
                    );
                    let _ = writeln!(out, "            float3[] extent = [(-{h}, 0, -{h}), ({h}, 0, {h})]");
                }
            }
            let _ = writeln!(out, "            color3f[] primvars:displayColor = [({COLLIDER_GREY}, {COLLIDER_GREY}, {COLLIDER_GREY})]");
            let mut order = vec!["\"xformOp:translate\""];
            if c.motion.is_moving() {
                let _ = writeln!(out, "            double3 xformOp:translate.timeSamples = {{");
                for (f, &t) in self.times.iter().enumerate() {
                    let p = place + c.motion.offset(t);
                    let _ = writeln!(
                        out,
                        "                {}: ({}, {}, {}),",
                        self.first_code + f as u64,
                        p.x,
                        p.y,
                        p.z
                    );
                }
                let _ = writeln!(out, "            }}");
            } else {
                let _ = writeln!(
                    out,
                    "            double3 xformOp:translate = ({}, {}, {})",
                    place.x, place.y, place.z
                );
            }
            if let Some(q) = rotation {
                let _ =
                    writeln!(out, "            quatd xformOp:orient = ({}, {}, {}, {})", q.w, q.x, q.y, q.z);
                order.push("\"xformOp:orient\"");
            }
            if let Shape::Box { half_extents: e, .. } = c.shape {
                let _ = writeln!(out, "            double3 xformOp:scale = ({}, {}, {})", e.x, e.y, e.z);
                order.push("\"xformOp:scale\"");
            }
            let _ = writeln!(out, "            uniform token[] xformOpOrder = [{}]", order.join(", "));
            let _ = writeln!(out, "        }}");
        }
        let _ = writeln!(out, "    }}");
    }
}

/// Collider `c` where it is at simulated time `t` as a triangle mesh for formats without
/// shapes (OBJ): points, outward unit normals, and triangles wound counter-clockwise seen from
/// outside (the renderer's unit meshes, placed as the app draws them; the ground a
/// `GROUND_HALF_SIZE` square facing up). Triangles of no area (a sphere's poles) are left out.
fn collider_mesh(c: &ColliderModel, t: f64) -> (Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>) {
    let shape = c.shape.translated(c.motion.offset(t));
    if let Shape::Ground { height } = shape {
        let h = GROUND_HALF_SIZE;
        let points = [(-h, -h), (-h, h), (h, h), (h, -h)].map(|(x, z)| DVec3::new(x, height, z));
        return (points.to_vec(), vec![DVec3::Y; 4], vec![[0, 1, 2], [0, 2, 3]]);
    }
    let (mut points, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    for item in super::view::collider_items(&shape) {
        let unit = match item.shape {
            super::Shape::Sphere => mesh::sphere(12, 16),
            super::Shape::Tube => mesh::tube(16),
            super::Shape::Cube => mesh::cube(),
            _ => continue,
        };
        let model = item.model.as_dmat4();
        let normal_matrix = glam::DMat3::from_mat4(model).inverse().transpose();
        // The unit meshes repeat vertices along a sphere's seam and at its poles (apart by f32
        // rounding): one vertex for each position and normal, so that the mesh is closed.
        let mut at = std::collections::HashMap::new();
        let index: Vec<usize> = (unit.vertices.iter())
            .map(|v| {
                let key = |a: [f32; 4]| a.map(|x| (f64::from(x) * 1e5).round() as i64);
                *at.entry((key(v.pos), key(v.normal))).or_insert_with(|| {
                    let [x, y, z, _] = v.pos.map(f64::from);
                    let [nx, ny, nz, _] = v.normal.map(f64::from);
                    points.push(model.transform_point3(DVec3::new(x, y, z)));
                    normals.push((normal_matrix * DVec3::new(nx, ny, nz)).normalize_or_zero());
                    points.len() - 1
                })
            })
            .collect();
        for tri in unit.indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| index[i as usize]);
            if a == b || b == c || a == c {
                continue;
            }
            let area = (points[b] - points[a]).cross(points[c] - points[a]);
            if area.length_squared() <= 1e-24 {
                continue;
            }
            // The unit meshes' windings differ (the renderer draws both sides): wind each
            // triangle to agree with its vertices' outward normals.
            let outward = area.dot(normals[a] + normals[b] + normals[c]) > 0.0;
            let [a, b, c] = [a, b, c].map(|i| i as u32);
            triangles.push(if outward { [a, b, c] } else { [a, c, b] });
        }
    }
    (points, normals, triangles)
}

/// Removes the frames an earlier OBJ recording under the same name left (regular files named
/// `{stem}_NNNNN.obj`, five digits or more), so that a shorter recording leaves no stale
/// higher-numbered frames for an importer to pick up.
fn remove_old_frames(path: &Path) -> Result<()> {
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

/// A track's mesh with a vertex for each point and texture coordinate its corners pair (glTF's
/// attributes are per vertex): its points and normals at every frame, coordinates, triangles.
struct Seams {
    points: Vec<Vec<[f32; 3]>>,
    normals: Vec<Vec<[f32; 3]>>,
    st: Vec<[f32; 2]>,
    indices: Vec<u32>,
}

/// `t`'s mesh split along its seams (`Seams`): vertex v keeps its index with the coordinate of
/// its first corner; a corner with another coordinate gets a copy of v after the others.
fn split_seams(t: &Track) -> Seams {
    let vertices = t.recorded_vertices();
    let mut first_st: Vec<Option<u32>> = vec![None; vertices];
    let mut copies = std::collections::HashMap::new();
    let mut source: Vec<u32> = (0..vertices as u32).collect();
    let mut indices = Vec::with_capacity(t.indices.len());
    for (&v, &uv) in t.indices.iter().zip(&t.st_indices) {
        let at = first_st[v as usize].get_or_insert(uv);
        if *at == uv {
            indices.push(v);
        } else {
            let copy = *copies.entry((v, uv)).or_insert_with(|| {
                source.push(v);
                source.len() as u32 - 1
            });
            indices.push(copy);
        }
    }
    let mut st: Vec<[f32; 2]> = first_st.iter().map(|uv| uv.map_or([0.0; 2], |k| t.st[k as usize])).collect();
    let mut extra: Vec<(u32, u32)> = copies.into_iter().map(|((_, uv), copy)| (copy, uv)).collect();
    extra.sort_unstable();
    st.extend(extra.iter().map(|&(_, uv)| t.st[uv as usize]));
    let remap = |frames: &[Vec<[f32; 3]>]| -> Vec<Vec<[f32; 3]>> {
        frames.iter().map(|f| source.iter().map(|&v| f[v as usize]).collect()).collect()
    };
    Seams { points: remap(&t.points), normals: remap(&t.normals), st, indices }
}

/// Writes `bytes` to `path` so that no reader (and no interrupted run) sees part of it: a
/// regular file, or a new one, through a temporary file beside it renamed over it (at a
/// symbolic link's target: the link stays); anything else (/dev/null, a device) in place. A
/// failed write, or a signal during it, removes its temporary file.
fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let target = if path.is_symlink() { path.canonicalize()? } else { path.to_path_buf() };
    if target.exists() && !target.is_file() {
        return std::fs::write(&target, bytes);
    }
    crate::atomic_file::replace(&target, bytes, false)
}

/// Cuts a point cache of `points` points a sample back to its first `frames` samples, the
/// header counting them (a smaller file and a word rewritten in place: no new space is needed).
fn cut_cache(file: &mut std::fs::File, points: u64, frames: u64) -> std::io::Result<()> {
    file.set_len(PC2_HEADER + frames * points * 12)?;
    count_samples(file, frames)
}

/// Writes a point cache's count of samples, the header's last word.
fn count_samples(file: &mut std::fs::File, frames: u64) -> std::io::Result<()> {
    use std::io::{Seek, SeekFrom, Write};
    file.seek(SeekFrom::Start(PC2_HEADER - 4))?;
    file.write_all(&(frames as i32).to_le_bytes())
}

impl Track {
    /// Vertices a frame of the recorded mesh has: the surface's, and a rope's two cap rings.
    fn recorded_vertices(&self) -> usize {
        self.vertices + if self.rope_nodes.is_some() { 2 * ROPE_RING } else { 0 }
    }

    /// A frame's vertex velocities [m/s]: a cloth's particles', a rope's tube vertices (and cap
    /// copies) their node's.
    fn velocities_of(&self, s: &ObjectState) -> Vec<[f32; 3]> {
        let v = |p: &crate::sim::gpu_types::Particle| [p.vel[0], p.vel[1], p.vel[2]];
        match self.rope_nodes {
            None => s.particles.iter().map(v).collect(),
            Some(nodes) => {
                let last = nodes as usize - 1;
                let tube =
                    (0..nodes as usize).flat_map(|n| std::iter::repeat_n(v(&s.particles[n]), ROPE_RING));
                let caps =
                    [0, last].into_iter().flat_map(|n| std::iter::repeat_n(v(&s.particles[n]), ROPE_RING));
                tube.chain(caps).collect()
            }
        }
    }

    /// A frame's points and normals from the object's surface: a rope's with copies of its
    /// first and last rings, whose normals point back and forward along the rope (its caps).
    fn frame(&self, s: &ObjectState) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
        let mut points: Vec<[f32; 3]> = s.surface.iter().map(|v| [v.pos[0], v.pos[1], v.pos[2]]).collect();
        let mut normals: Vec<[f32; 3]> =
            s.surface.iter().map(|v| [v.normal[0], v.normal[1], v.normal[2]]).collect();
        if let Some(nodes) = self.rope_nodes {
            let ring = ROPE_RING;
            let centre = |n: usize| -> glam::Vec3 {
                points[n * ring..(n + 1) * ring].iter().map(|&p| glam::Vec3::from(p)).sum::<glam::Vec3>()
                    / ring as f32
            };
            let last = nodes as usize - 1;
            let along = |a: usize, b: usize| (centre(b) - centre(a)).normalize_or(glam::Vec3::X);
            let (back, forward) = if last > 0 {
                (-along(0, 1), along(last - 1, last))
            } else {
                (-glam::Vec3::X, glam::Vec3::X)
            };
            for (n, normal) in [(0, back), (last, forward)] {
                for k in 0..ring {
                    points.push(points[n * ring + k]);
                    normals.push(normal.to_array());
                }
            }
        }
        (points, normals)
    }
}

/// A linear colour channel in sRGB's transfer curve, to 4 decimals.
fn srgb(linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 1e4).round() / 1e4
}

/// Texture coordinates of an object's recorded mesh, and the one each triangle corner takes
/// (in the order of its indices). A cloth: its grid stretched over the unit square, row 0 at
/// v = 1. A rope: the tube unrolled, u around (0 to 1, the seam given both) and v along; each
/// cap a disc of radius 1/2 about (1/2, 1/2).
fn texture_coordinates(kind: ObjectKind, [cols, rows]: [u32; 2]) -> (Vec<[f32; 2]>, Vec<u32>) {
    match kind {
        ObjectKind::Cloth => {
            let span = |n: u32| (n.max(2) - 1) as f32;
            let st = (0..cols * rows)
                .map(|i| [(i % cols) as f32 / span(cols), 1.0 - (i / cols) as f32 / span(rows)]);
            (st.collect(), mesh::cloth_indices(cols, rows))
        }
        ObjectKind::Rope => {
            let (ring, nodes) = (ROPE_RING as u32, cols);
            let mut st: Vec<[f32; 2]> = (0..nodes)
                .flat_map(|n| {
                    (0..=ring).map(move |k| [k as f32 / ring as f32, n as f32 / (nodes.max(2) - 1) as f32])
                })
                .collect();
            let mut st_indices = mesh::rope_tube_uv_indices(nodes);
            let disc = st.len() as u32;
            st.extend((0..ring).map(|k| {
                let a = std::f32::consts::TAU * k as f32 / ring as f32;
                [0.5 + 0.5 * a.cos(), 0.5 + 0.5 * a.sin()]
            }));
            // Both caps' corners take the disc (their vertices are ring copies 0..ring).
            st_indices.extend(mesh::rope_cap_indices(0, 0).into_iter().map(|k| disc + k));
            (st, st_indices)
        }
    }
}

/// The bounding box of `points`: [min, max].
fn extent(points: &[[f32; 3]]) -> [[f32; 3]; 2] {
    let lo = points.iter().fold([f32::MAX; 3], |m, p| std::array::from_fn(|i| m[i].min(p[i])));
    let hi = points.iter().fold([f32::MIN; 3], |m, p| std::array::from_fn(|i| m[i].max(p[i])));
    [lo, hi]
}

/// `name`, or with `_2`, `_3`, ... appended when an earlier object took it (names that differ
/// only in characters USD does not allow, "my cloth" and "my-cloth", would be one prim).
fn unique_name(taken: &mut std::collections::HashSet<String>, name: String) -> String {
    let mut candidate = name.clone();
    let mut n = 1;
    while !taken.insert(candidate.clone()) {
        n += 1;
        candidate = format!("{name}_{n}");
    }
    candidate
}

/// `name.timeSamples = { first: [(x, y, z), ...], ... }`, numbers in Rust's shortest exact
/// form, `frames` frames (each read by `frame`) at time codes from `first` on.
fn samples(
    w: &mut dyn std::io::Write,
    first: u64,
    frames: u64,
    name: &str,
    mut frame: impl FnMut(u64, &mut Vec<[f32; 3]>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    writeln!(w, "        {name}.timeSamples = {{")?;
    let mut values = Vec::new();
    for f in 0..frames {
        frame(f, &mut values)?;
        write!(w, "            {}: [", first + f)?;
        for (i, [x, y, z]) in values.iter().enumerate() {
            write!(w, "{}({x}, {y}, {z})", if i == 0 { "" } else { ", " })?;
        }
        writeln!(w, "],")?;
    }
    writeln!(w, "        }}")
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
    /// The files a recording writes besides its own name, which `--out` may not name.
    #[test]
    fn a_recording_knows_the_files_it_writes() {
        use super::Format;
        use std::path::Path;
        let p = Path::new;
        let obj = Format::ObjSequence;
        assert!(obj.writes(p("out/x.obj"), p("out/x_00002.obj")));
        assert!(obj.writes(p("out/x.obj"), p("out/x_123456.obj")), "past 99,999 frames");
        assert!(!obj.writes(p("out/x.obj"), p("out/x_2.obj")));
        assert!(!obj.writes(p("out/x.obj"), p("out/y_00002.obj")));
        assert!(!obj.writes(p("out/x.obj"), p("elsewhere/x_00002.obj")));
        assert!(!obj.writes(p("out/x.obj"), p("out/x_00002.json")));
        let pc2 = Format::PointCache;
        assert!(pc2.writes(p("x.pc2"), p("x.obj")));
        assert!(pc2.writes(p("x.pc2"), p("x_curtain.pc2")));
        assert!(pc2.writes(p("x.pc2"), p("x_collider_box_1.pc2")));
        assert!(!pc2.writes(p("x.pc2"), p("x.json")));
        assert!(pc2.writes(p("x.pc2"), p("x.mtl")));
        assert!(obj.writes(p("out/x.obj"), p("out/x.mtl")));
        assert!(!Format::Usd.writes(p("x.usda"), p("x.obj")));
    }

    #[test]
    fn prim_names_are_valid() {
        assert_eq!(super::usd_name("my cloth-1"), "my_cloth_1");
        assert_eq!(super::usd_name("3d"), "_3d");
        assert_eq!(super::usd_name(""), "_");
    }

    #[test]
    fn prim_names_are_unique() {
        let mut taken = std::collections::HashSet::new();
        let names: Vec<String> = ["my cloth", "my-cloth", "my_cloth_2", "my.cloth"]
            .iter()
            .map(|n| super::unique_name(&mut taken, super::usd_name(n)))
            .collect();
        assert_eq!(names, ["my_cloth", "my_cloth_2", "my_cloth_2_2", "my_cloth_3"]);
    }

    /// A scene from preset text, and its model.
    fn parsed(text: &str) -> (crate::scene::Scene, crate::sim::model::SimModel) {
        let scene = crate::scene::parse(text, "t.toml", &[]).unwrap();
        let model = crate::scene::to_model(&scene);
        (scene, model)
    }

    /// A rope's glTF mesh has a vertex for each point and coordinate its corners pair: every
    /// corner keeps its point (at every frame) and its face-varying coordinate, the seam's and
    /// caps' points are copied, the others are not.
    #[test]
    fn a_rope_splits_along_its_seams_for_gltf() {
        use crate::sim::gpu::ObjectState;
        use crate::sim::gpu_types::{Particle, SurfaceVertex};
        let text = "[[rope]]\nname = \"r\"\nnodes = 5\nstart = [0.0, 1.0, 0.0]\nend = [1.0, 1.0, 0.0]\nmass = 0.1\nstiffness = 1.0\nradius = 0.02\n";
        let (scene, model) = parsed(text);
        let dir = tempfile::tempdir().unwrap();
        let mut rec =
            super::Recording::new(&model, &super::colors(&scene), &dir.path().join("r.glb"), Some(2))
                .unwrap();
        let n = model.objects[0].surface_count();
        for f in 0..2 {
            let surface = (0..n)
                .map(|k| SurfaceVertex { pos: [k as f32, f as f32, 0.0, 1.0], normal: [0.0, 1.0, 0.0, 0.0] })
                .collect();
            let state = ObjectState { particles: vec![Particle::default(); 5], surface };
            rec.add(&[state], f as f64 / 60.0).unwrap();
        }
        let t = &rec.tracks[0];
        let seams = super::split_seams(t);
        assert_eq!(seams.indices.len(), t.indices.len());
        for (c, (&v, &uv)) in t.indices.iter().zip(&t.st_indices).enumerate() {
            let w = seams.indices[c] as usize;
            assert_eq!(seams.st[w], t.st[uv as usize], "corner {c}");
            for f in 0..2 {
                assert_eq!(seams.points[f][w], t.points[f][v as usize], "corner {c}, frame {f}");
            }
        }
        let vertices = t.points[0].len();
        let copies = seams.points[0].len() - vertices;
        // The seam: a copy of each ring's first vertex (5 rings); the caps' ring copies take
        // the disc's coordinates at their first corner, so they need none.
        assert_eq!(copies, 5, "{copies} copies of {vertices} vertices");
        let bytes = rec.glb().unwrap();
        let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
        let attributes = &doc["meshes"][0]["primitives"][0]["attributes"];
        assert!(attributes.get("TEXCOORD_0").is_some(), "{attributes}");
    }

    /// A surface vertex that is not finite stops the recording with a line naming the object,
    /// in every format, and is never written (issue 30, item 7: the guard checks only the
    /// particles, and a USD with a NaN does not parse).
    #[test]
    fn a_non_finite_surface_is_refused() {
        use crate::sim::gpu::ObjectState;
        use crate::sim::gpu_types::{Particle, SurfaceVertex};
        let text = "[[cloth]]\nname = \"c\"\nresolution = [2, 2]\nsize = [1.0, 1.0]\norigin = [0.0, 1.0, 0.0]\nmass = 0.1\nstiffness = { structural = 1.0, shear = 1.0, bending = 1.0 }\n";
        let (scene, model) = parsed(text);
        let dir = tempfile::tempdir().unwrap();
        for name in ["r.usda", "r.obj", "r.pc2", "r.glb"] {
            let path = dir.path().join(name);
            let mut rec = super::Recording::new(&model, &super::colors(&scene), &path, Some(2)).unwrap();
            let vertex = SurfaceVertex { pos: [0.0, 1.0, 0.0, 1.0], normal: [0.0, 0.0, 1.0, 0.0] };
            let mut state = ObjectState { particles: vec![Particle::default(); 4], surface: vec![vertex; 4] };
            rec.add(std::slice::from_ref(&state), 0.0).unwrap();
            state.surface[3].normal[1] = f32::NAN;
            let err = format!("{:#}", rec.add(std::slice::from_ref(&state), 1.0 / 60.0).unwrap_err());
            assert!(err.contains("'c'") && err.contains("not a finite number"), "{name}: {err}");
        }
    }
}
