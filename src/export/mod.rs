//! Recordings of the animated surfaces (`simulate --record`, the app's Record button), one mesh
//! per object (a cloth's grid, a rope's tube), in the format the file name's extension picks
//! (a file a format: `usd`, `gltf`, `pc2`, `obj`; what they share is here):
//! - `.usda`: USD (ASCII) with points, normals and extents time-sampled at every frame (and the
//!   frame rate as framesPerSecond), so Blender, Houdini, usdview and Omniverse play it back;
//!   prims are named after the objects, made unique; each mesh and shape has a UsdPreviewSurface
//!   material bound, and the colliders are shapes. USD's text groups each attribute's samples,
//!   so it is written when the recording ends (`write_to`, by the caller, through a temporary
//!   file: an interrupted run leaves no partial file); until then the frames go to a spool file
//!   beside it, unlinked from the start, so memory stays at a frame however long the recording.
//! - `.glb`: glTF 2.0 binary (`gltf`), frames kept in memory (up to `MAX_BYTES`), each a
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

pub mod gltf;
mod obj;
mod pc2;
mod usd;

use obj::remove_old_frames;
use usd::usd_name;

/// Half the side of the square that stands for the ground in a USD recording [m].
const GROUND_HALF_SIZE: f64 = 20.0;

/// Each object's front and back colours (the cloths', the ropes', whose back is their front,
/// then the mesh cloths'), as the recordings write them.
pub fn colors(scene: &crate::scene::Scene) -> Vec<[[f32; 3]; 2]> {
    let cloths = scene.cloths.iter().map(|c| [c.color, c.back_color]);
    let ropes = scene.ropes.iter().map(|r| [r.color, r.color]);
    let meshes = scene.mesh_cloths.iter().map(|c| [c.color, c.back_color]);
    cloths.chain(ropes).chain(meshes).map(|c| c.map(|c| c.map(|x| x as f32))).collect()
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
    /// The object's kind and grid (and a mesh cloth's topology): a recording keeps one set of
    /// meshes.
    shape: (ObjectKind, [u32; 2], Option<std::sync::Arc<crate::sim::cloth_mesh::ClothMesh>>),
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
                let (st, st_indices) = match &o.mesh {
                    Some(m) => mesh_texture_coordinates(m),
                    None => texture_coordinates(o.kind, o.dims),
                };
                let (indices, rope_nodes) = match o.kind {
                    ObjectKind::Cloth if o.mesh.is_some() => {
                        (o.mesh.iter().flat_map(|m| m.triangles.iter().flatten().copied()).collect(), None)
                    }
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
                    shape: (o.kind, o.dims, o.mesh.clone()),
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
        let fixed = self.colliders.iter().zip(&self.collider_names).filter(|(c, _)| !c.is_moving());
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
            && (self.tracks.iter().zip(&model.objects))
                .all(|(t, o)| (t.shape.0, t.shape.1, &t.shape.2) == (o.kind, o.dims, &o.mesh))
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
}

/// Collider `c` where it is at simulated time `t` as a triangle mesh for formats without
/// shapes (OBJ): points, outward unit normals, and triangles wound counter-clockwise seen from
/// outside (the renderer's unit meshes, placed as the app draws them; the ground a
/// `GROUND_HALF_SIZE` square facing up). Triangles of no area (a sphere's poles) are left out.
fn collider_mesh(c: &ColliderModel, t: f64) -> (Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>) {
    let shape = c.shape_at(t);
    if let Shape::Ground { height } = shape {
        let h = GROUND_HALF_SIZE;
        let points = [(-h, -h), (-h, h), (h, h), (h, -h)].map(|(x, z)| DVec3::new(x, height, z));
        return (points.to_vec(), vec![DVec3::Y; 4], vec![[0, 1, 2], [0, 2, 3]]);
    }
    if let Some((points, triangles)) = shape.placed_mesh() {
        // Its own triangles, placed; each vertex's normal the mean of its triangles'.
        let mut normals = vec![DVec3::ZERO; points.len()];
        for t in triangles {
            let [a, b, c] = t.map(|k| points[k as usize]);
            let n = (b - a).cross(c - a);
            t.iter().for_each(|&k| normals[k as usize] += n);
        }
        let normals = normals.into_iter().map(|n| n.normalize_or(DVec3::Y)).collect();
        return (points, normals, triangles.to_vec());
    }
    let (mut points, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    for item in crate::render::view::collider_items(&shape) {
        let unit = match item.shape {
            crate::render::Shape::Sphere => mesh::sphere(12, 16),
            crate::render::Shape::Tube => mesh::tube(16),
            crate::render::Shape::Cube => mesh::cube(),
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

/// A mesh cloth's texture coordinates as its file gives them, each one once, and the one each
/// triangle corner takes (all at the origin where the file has none): a vertex whose corners
/// agree keeps one, so a glTF recording splits vertices along the texture's seams only.
fn mesh_texture_coordinates(m: &crate::sim::cloth_mesh::ClothMesh) -> (Vec<[f32; 2]>, Vec<u32>) {
    if m.corner_uvs.is_empty() {
        return (vec![[0.0; 2]], vec![0; 3 * m.triangles.len()]);
    }
    let mut index: std::collections::HashMap<[u32; 2], u32> = std::collections::HashMap::new();
    let mut st = Vec::new();
    let corners = (m.corner_uvs.iter())
        .map(|uv| {
            *index.entry(uv.map(f32::to_bits)).or_insert_with(|| {
                st.push(*uv);
                st.len() as u32 - 1
            })
        })
        .collect();
    (st, corners)
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
        assert_eq!(super::usd::usd_name("my cloth-1"), "my_cloth_1");
        assert_eq!(super::usd::usd_name("3d"), "_3d");
        assert_eq!(super::usd::usd_name(""), "_");
    }

    #[test]
    fn prim_names_are_unique() {
        let mut taken = std::collections::HashSet::new();
        let names: Vec<String> = ["my cloth", "my-cloth", "my_cloth_2", "my.cloth"]
            .iter()
            .map(|n| super::unique_name(&mut taken, super::usd::usd_name(n)))
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
        let seams = super::gltf::split_seams(t);
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
