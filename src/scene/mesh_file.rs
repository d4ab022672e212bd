//! Reading a triangle mesh from a file for a mesh collider: Wavefront OBJ through `tobj`, glTF
//! 2.0 (`.gltf` with its buffers beside it or embedded as base64, or `.glb`) through `gltf`.
//! Polygons are split into fans; a glTF scene's nodes place their meshes. The result is
//! checked (`ColliderMesh::check`), and every error is one line naming the file.

use crate::sim::collider_mesh::ColliderMesh;
use glam::{DMat4, DVec3, Mat4};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The largest mesh file read [bytes].
pub const MAX_MESH_BYTES: u64 = 512 << 20;

/// A mesh as read from its file: vertices in the file's units and frame, triangles; and the
/// collider last built from it (`built`), kept so that a scene's colliders, taken every frame
/// for drawing, do not rebuild its grid.
#[derive(Debug)]
pub struct MeshFile {
    pub path: PathBuf,
    pub vertices: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    built: std::sync::Mutex<Option<(f64, f64, Arc<ColliderMesh>)>>,
}

impl PartialEq for MeshFile {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
            || (self.path == other.path
                && self.vertices == other.vertices
                && self.triangles == other.triangles)
    }
}

impl MeshFile {
    /// The collider of its triangles scaled by `scale`, found within `reach` of them.
    pub fn built(&self, scale: f64, reach: f64) -> Arc<ColliderMesh> {
        let mut built = self.built.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((s, r, mesh)) = built.as_ref() {
            if (*s, *r) == (scale, reach) {
                return mesh.clone();
            }
        }
        let vertices = self.vertices.iter().map(|&p| p * scale).collect();
        let mesh = Arc::new(ColliderMesh::new(vertices, self.triangles.clone(), reach));
        *built = Some((scale, reach, mesh.clone()));
        mesh
    }
}

/// Reads and checks the mesh at `path`.
pub fn read(path: &Path) -> Result<MeshFile, String> {
    let size = std::fs::metadata(path).map_err(|e| format!("cannot read the mesh: {e}"))?;
    if size.is_dir() {
        return Err("a folder, not a mesh".into());
    }
    if size.len() > MAX_MESH_BYTES {
        return Err(format!("larger than {} MiB", MAX_MESH_BYTES >> 20));
    }
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    let (vertices, triangles) = match ext.as_str() {
        "obj" => read_obj(path)?,
        "gltf" | "glb" => read_gltf(path)?,
        _ => return Err("not a mesh file msdsim reads (.obj, .gltf or .glb)".into()),
    };
    ColliderMesh::check(&vertices, &triangles)?;
    Ok(MeshFile { path: path.to_path_buf(), vertices, triangles, built: Default::default() })
}

fn read_obj(path: &Path) -> Result<(Vec<DVec3>, Vec<[u32; 3]>), String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let (models, _materials) =
        tobj::load_obj(path, &options).map_err(|e| format!("not a readable OBJ file: {e}"))?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for m in models {
        let base = vertices.len() as u32;
        vertices.extend(
            m.mesh.positions.chunks_exact(3).map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)),
        );
        triangles.extend(m.mesh.indices.chunks_exact(3).map(|t| [t[0] + base, t[1] + base, t[2] + base]));
    }
    Ok((vertices, triangles))
}

fn read_gltf(path: &Path) -> Result<(Vec<DVec3>, Vec<[u32; 3]>), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read the mesh: {e}"))?;
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| format!("not a readable glTF file: {e}"))?;
    let folder = path.parent().unwrap_or(Path::new("."));
    let mut buffers = Vec::new();
    for b in gltf.document.buffers() {
        let data = match b.source() {
            gltf::buffer::Source::Bin => gltf.blob.clone().ok_or("its binary chunk is missing")?,
            gltf::buffer::Source::Uri(uri) => buffer_at(folder, uri)?,
        };
        if data.len() < b.length() {
            return Err(format!(
                "buffer {} holds {} bytes, less than its {}",
                b.index(),
                data.len(),
                b.length()
            ));
        }
        buffers.push(data);
    }
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let scene = gltf.document.default_scene().or_else(|| gltf.document.scenes().next());
    let roots: Vec<gltf::Node> = match scene {
        Some(s) => s.nodes().collect(),
        None => gltf.document.nodes().collect(),
    };
    let mut stack: Vec<(gltf::Node, DMat4)> = roots.into_iter().map(|n| (n, DMat4::IDENTITY)).collect();
    let mut visited = 0usize;
    while let Some((node, parent)) = stack.pop() {
        visited += 1;
        if visited > 1 << 20 {
            return Err("its nodes form a cycle".into());
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix()).as_dmat4();
        if let Some(mesh) = node.mesh() {
            for p in mesh.primitives() {
                if p.mode() != gltf::mesh::Mode::Triangles {
                    return Err(format!(
                        "mesh {} has {:?} primitives; only triangles are read",
                        mesh.index(),
                        p.mode()
                    ));
                }
                let reader = p.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
                let positions =
                    reader.read_positions().ok_or(format!("mesh {} has no positions", mesh.index()))?;
                let base = vertices.len() as u32;
                vertices.extend(
                    positions
                        .map(|q| world.transform_point3(DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64))),
                );
                let count = vertices.len() as u32 - base;
                let indices: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..count).collect(),
                };
                // A mirroring transform turns the winding over.
                let flip = world.determinant() < 0.0;
                triangles.extend(indices.chunks_exact(3).map(|t| {
                    let (a, b, c) = (t[0] + base, t[1] + base, t[2] + base);
                    if flip {
                        [a, c, b]
                    } else {
                        [a, b, c]
                    }
                }));
            }
        }
        stack.extend(node.children().map(|c| (c, world)));
    }
    Ok((vertices, triangles))
}

/// A glTF buffer's bytes from its URI: embedded base64 data, or a file beside the glTF.
fn buffer_at(folder: &Path, uri: &str) -> Result<Vec<u8>, String> {
    use base64::Engine as _;
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest.split_once(";base64,").ok_or("a data URI that is not base64")?;
        return base64::engine::general_purpose::STANDARD
            .decode(data)
            .map_err(|e| format!("its embedded buffer: {e}"));
    }
    let file = folder.join(uri.replace("%20", " "));
    let size = std::fs::metadata(&file).map_err(|e| format!("its buffer {}: {e}", file.display()))?.len();
    if size > MAX_MESH_BYTES {
        return Err(format!("its buffer {} is larger than {} MiB", file.display(), MAX_MESH_BYTES >> 20));
    }
    std::fs::read(&file).map_err(|e| format!("its buffer {}: {e}", file.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cube written as OBJ quads reads as 12 triangles wound as the quads; bad files are
    /// named in one line.
    #[test]
    fn obj_quads_become_triangles_and_bad_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("cube.obj");
        let v = "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n";
        let f = "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";
        std::fs::write(&obj, format!("{v}{f}")).unwrap();
        let m = read(&obj).unwrap();
        assert_eq!((m.vertices.len(), m.triangles.len()), (8, 12));
        let cm = ColliderMesh::new(m.vertices, m.triangles, 0.1);
        assert!(cm.closed);
        assert!((cm.distance(DVec3::new(0.0, 1.05, 0.0)).0 - 0.05).abs() < 1e-12);
        assert!((cm.distance(DVec3::new(0.0, 0.95, 0.0)).0 + 0.05).abs() < 1e-12);
        let bad = dir.path().join("bad.obj");
        std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").unwrap();
        assert!(read(&bad).unwrap_err().contains("no area"), "{:?}", read(&bad));
        std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
        assert!(read(&bad).is_err());
        std::fs::write(&bad, "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert!(read(&bad).is_err());
        assert!(read(&dir.path().join("missing.obj")).unwrap_err().contains("cannot read"));
        let stl = dir.path().join("x.stl");
        std::fs::write(&stl, "solid").unwrap();
        assert!(read(&stl).unwrap_err().contains(".obj, .gltf or .glb"));
        assert!(read(dir.path()).unwrap_err().contains("folder"));
    }
}
