//! Reading a triangle mesh from a file for a mesh collider: Wavefront OBJ through `tobj`, glTF
//! 2.0 (`.gltf` with its buffers beside it or embedded as base64, or `.glb`) through `gltf`.
//! Polygons are split into fans; a glTF scene's nodes place their meshes. The result is
//! checked (`ColliderMesh::check`), and every error is one line naming the file.

use crate::sim::collider_mesh::{ColliderMesh, MAX_TRIANGLES};
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
    built: std::sync::Mutex<Vec<(f64, f64, Arc<ColliderMesh>)>>,
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
    /// The collider of its triangles scaled by `scale`, found within `reach` of them: the same
    /// one while those stay (the last few kept: an edit and its undo, the scene before and
    /// after an edit that is refused).
    pub fn built(&self, scale: f64, reach: f64) -> Arc<ColliderMesh> {
        const KEPT: usize = 4;
        let mut built = self.built.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, _, mesh)) = built.iter().find(|(s, r, _)| (*s, *r) == (scale, reach)) {
            return mesh.clone();
        }
        let vertices = self.vertices.iter().map(|&p| p * scale).collect();
        let mesh = Arc::new(ColliderMesh::new(vertices, self.triangles.clone(), reach));
        if built.len() == KEPT {
            built.remove(0);
        }
        built.push((scale, reach, mesh.clone()));
        mesh
    }
}

/// Reads and checks the mesh at `path`.
pub fn read(path: &Path) -> Result<MeshFile, String> {
    let (vertices, triangles) = match extension(path)?.as_str() {
        "obj" => read_obj(path)?,
        _ => {
            let (vertices, triangles, _) = read_gltf(path)?;
            (vertices, triangles)
        }
    };
    ColliderMesh::check(&vertices, &triangles)?;
    Ok(MeshFile { path: path.to_path_buf(), vertices, triangles, built: Default::default() })
}

/// A mesh as read from its file for a mesh cloth: vertices in the file's units and frame,
/// faces as polygons (an OBJ file's quads kept), and each face corner's texture coordinates
/// in face order (empty where the file has none). Checked as a cloth when the scene builds.
#[derive(Debug)]
pub struct FaceFile {
    pub path: PathBuf,
    pub vertices: Vec<DVec3>,
    pub faces: Vec<Vec<u32>>,
    pub uvs: Vec<[f32; 2]>,
    built: std::sync::Mutex<Vec<(ClothKey, Arc<Placed>)>>,
}

/// What a mesh cloth's build depends on besides its file: centre, rotation, scale, weld, sew,
/// and its seams.
type ClothKey = ([f64; 9], Vec<Vec<[u32; 2]>>);
/// A mesh cloth as built: its particles placed and welded, and its topology.
pub type Placed = (Vec<DVec3>, Arc<crate::sim::cloth_mesh::ClothMesh>);

impl PartialEq for FaceFile {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
            || (self.path == other.path
                && self.vertices == other.vertices
                && self.faces == other.faces
                && self.uvs == other.uvs)
    }
}

impl FaceFile {
    /// The cloth `c` makes of its faces: placed by its `center`, `rotation` and `scale`,
    /// welded within its `weld`, with its seams and those its `sew` finds: the same one while
    /// those stay (the last few
    /// kept, as `MeshFile::built`'s), since the scene is built again on every edit.
    pub fn built(&self, c: &super::MeshCloth) -> Result<Arc<Placed>, String> {
        const KEPT: usize = 4;
        let (center, rotation, scale) = (c.center, c.rotation, c.scale);
        let seams = c.seam_pairs();
        let key = (
            [center[0], center[1], center[2], rotation[0], rotation[1], rotation[2], scale, c.weld, c.sew],
            seams,
        );
        let mut built = self.built.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, placed)) = built.iter().find(|(k, _)| *k == key) {
            return Ok(placed.clone());
        }
        let [x, y, z] = rotation.map(f64::to_radians);
        let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, x, y, z);
        let at = DVec3::from_array(center);
        let placed: Vec<DVec3> = self.vertices.iter().map(|&p| at + turn * (p * scale)).collect();
        let (positions, faces) = crate::sim::cloth_mesh::weld(&placed, &self.faces, c.weld);
        let mut seams = key.1.clone();
        if c.sew > 0.0 {
            seams.extend(crate::sim::cloth_mesh::found_seams(&positions, &faces, c.sew)?);
        }
        let mesh = crate::sim::cloth_mesh::ClothMesh::new(&positions, &faces, &self.uvs, &seams)?;
        let placed = Arc::new((positions, Arc::new(mesh)));
        if built.len() == KEPT {
            built.remove(0);
        }
        built.push((key, placed.clone()));
        Ok(placed)
    }
}

/// Reads the mesh at `path` for a mesh cloth, its faces and texture coordinates.
pub fn read_faces(path: &Path) -> Result<FaceFile, String> {
    let (vertices, faces, uvs) = match extension(path)?.as_str() {
        "obj" => read_obj_faces(path)?,
        _ => {
            let (vertices, triangles, vertex_uvs) = read_gltf(path)?;
            let uvs = match vertex_uvs.is_empty() {
                true => Vec::new(),
                false => triangles
                    .iter()
                    .flatten()
                    .map(|&k| vertex_uvs.get(k as usize).copied().unwrap_or_default())
                    .collect(),
            };
            (vertices, triangles.iter().map(|t| t.to_vec()).collect(), uvs)
        }
    };
    if faces.len() > crate::sim::cloth_mesh::MAX_FACES {
        return Err(format!("more than {} faces", crate::sim::cloth_mesh::MAX_FACES));
    }
    Ok(FaceFile { path: path.to_path_buf(), vertices, faces, uvs, built: Default::default() })
}

/// The file's size checked and its kind by extension: "obj", "gltf" or "glb".
fn extension(path: &Path) -> Result<String, String> {
    let size = std::fs::metadata(path).map_err(|e| format!("cannot read the mesh: {e}"))?;
    if size.is_dir() {
        return Err("a folder, not a mesh".into());
    }
    if size.len() > MAX_MESH_BYTES {
        return Err(format!("larger than {} MiB", MAX_MESH_BYTES >> 20));
    }
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    match ext.as_str() {
        "obj" | "gltf" | "glb" => Ok(ext),
        _ => Err("not a mesh file msdsim reads (.obj, .gltf or .glb)".into()),
    }
}

type Faces = (Vec<DVec3>, Vec<Vec<u32>>, Vec<[f32; 2]>);
type Triangles = (Vec<DVec3>, Vec<[u32; 3]>, Vec<[f32; 2]>);

fn read_obj_faces(path: &Path) -> Result<Faces, String> {
    let options = tobj::LoadOptions { ignore_points: true, ignore_lines: true, ..Default::default() };
    let (models, _materials) =
        tobj::load_obj(path, &options).map_err(|e| format!("not a readable OBJ file: {e}"))?;
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    let mut uvs = Vec::new();
    let with_uvs = models.iter().all(|m| m.mesh.texcoord_indices.len() == m.mesh.indices.len());
    for m in models {
        let mesh = &m.mesh;
        let base = vertices.len() as u32;
        vertices.extend(mesh.positions.chunks_exact(3).map(|p| DVec3::new(p[0], p[1], p[2])));
        let arities: Vec<u32> = match mesh.face_arities.is_empty() {
            true => vec![3; mesh.indices.len() / 3],
            false => mesh.face_arities.clone(),
        };
        let mut corner = 0;
        for arity in arities {
            let range = corner..corner + arity as usize;
            let face = mesh.indices.get(range.clone()).ok_or("a face past its indices")?;
            faces.push(face.iter().map(|k| k + base).collect());
            if with_uvs {
                for &t in &mesh.texcoord_indices[range] {
                    let uv = mesh
                        .texcoords
                        .get(2 * t as usize..2 * t as usize + 2)
                        .ok_or("a texture coordinate past its list")?;
                    uvs.push([uv[0] as f32, uv[1] as f32]);
                }
            }
            corner += arity as usize;
        }
    }
    let (vertices, faces) = in_file_order(path, vertices, faces)?;
    Ok((vertices, faces, uvs))
}

/// `vertices` (as `tobj` numbers them: in order of first use by the faces) renumbered in the
/// file's order, the order its `v` lines give and a user's tool shows (where two lines give
/// the same place, the first's: welding joins them anyway), so that pins by vertex index
/// name the vertices the user sees. The faces follow.
fn in_file_order(
    path: &Path,
    vertices: Vec<DVec3>,
    faces: Vec<Vec<u32>>,
) -> Result<(Vec<DVec3>, Vec<Vec<u32>>), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read the mesh: {e}"))?;
    let key = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut line_of: std::collections::HashMap<[u64; 3], usize> = std::collections::HashMap::new();
    let lines = text
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("v ").or_else(|| l.trim_start().strip_prefix("v\t")));
    for (k, rest) in lines.enumerate() {
        let c: Vec<f64> = rest.split_whitespace().take(3).filter_map(|w| w.parse().ok()).collect();
        if let [x, y, z] = c[..] {
            line_of.entry(key(DVec3::new(x, y, z))).or_insert(k);
        }
    }
    // (a place no line gives, which should not be, keeps tobj's order after the others)
    let rank: Vec<usize> = vertices
        .iter()
        .enumerate()
        .map(|(i, &p)| line_of.get(&key(p)).copied().unwrap_or(usize::MAX - vertices.len() + i))
        .collect();
    let mut order: Vec<usize> = (0..vertices.len()).collect();
    order.sort_by_key(|&i| rank[i]);
    let mut to = vec![0u32; vertices.len()];
    for (new, &old) in order.iter().enumerate() {
        to[old] = new as u32;
    }
    let faces = faces
        .into_iter()
        .map(|f| f.into_iter().map(|k| to.get(k as usize).copied().unwrap_or(k)).collect())
        .collect();
    Ok((order.iter().map(|&i| vertices[i]).collect(), faces))
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
        vertices.extend(m.mesh.positions.chunks_exact(3).map(|p| DVec3::new(p[0], p[1], p[2])));
        triangles.extend(m.mesh.indices.chunks_exact(3).map(|t| [t[0] + base, t[1] + base, t[2] + base]));
    }
    Ok((vertices, triangles))
}

/// A glTF file's triangles, and each vertex's texture coordinates (empty unless every
/// primitive has them).
fn read_gltf(path: &Path) -> Result<Triangles, String> {
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
    let mut uvs = Vec::new();
    let mut all_uvs = true;
    // The scene's nodes, or without one every node that is no node's child.
    let roots: Vec<gltf::Node> = match gltf.document.default_scene().or_else(|| gltf.document.scenes().next())
    {
        Some(s) => s.nodes().collect(),
        None => {
            let children: std::collections::HashSet<usize> = gltf
                .document
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()).collect::<Vec<_>>())
                .collect();
            gltf.document.nodes().filter(|n| !children.contains(&n.index())).collect()
        }
    };
    // Depth first, the path from the root kept: a node that is its own ancestor is a cycle.
    let mut stack: Vec<(gltf::Node, DMat4, Vec<usize>)> =
        roots.into_iter().map(|n| (n, DMat4::IDENTITY, Vec::new())).collect();
    while let Some((node, parent, mut path)) = stack.pop() {
        if path.contains(&node.index()) {
            return Err(format!("node {} is its own ancestor (a cycle)", node.index()));
        }
        path.push(node.index());
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
                let positions = p
                    .get(&gltf::Semantic::Positions)
                    .ok_or(format!("mesh {} has no positions", mesh.index()))?;
                for a in std::iter::once(&positions).chain(p.indices().as_ref()) {
                    accessor_fits(a, &buffers)?;
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
                // (read only where the accessor fits its buffer and is of a kind the reader
                // takes, two floats or normalised unsigned integers: it assumes so)
                let texcoords = p.get(&gltf::Semantic::TexCoords(0)).filter(|a| {
                    use gltf::accessor::{DataType, Dimensions};
                    accessor_fits(a, &buffers).is_ok()
                        && a.dimensions() == Dimensions::Vec2
                        && matches!(a.data_type(), DataType::F32 | DataType::U8 | DataType::U16)
                });
                match texcoords.and_then(|_| reader.read_tex_coords(0)) {
                    Some(t) if all_uvs => {
                        uvs.extend(t.into_f32().take(count as usize));
                        all_uvs = uvs.len() == vertices.len();
                    }
                    _ => all_uvs = false,
                }
                let indices: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..count).collect(),
                };
                if let Some(k) = indices.iter().find(|&&k| k >= count) {
                    return Err(format!("mesh {} names vertex {k}, past its {count} vertices", mesh.index()));
                }
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
                if triangles.len() > MAX_TRIANGLES || vertices.len() > 3 * MAX_TRIANGLES {
                    return Err(format!("more than {MAX_TRIANGLES} triangles"));
                }
            }
        }
        stack.extend(node.children().map(|c| (c, world, path.clone())));
    }
    if !all_uvs {
        uvs.clear();
    }
    Ok((vertices, triangles, uvs))
}

/// Whether accessor `a` (positions as three f32s, or indices) lies within its buffer view and
/// that within its buffer, and holds something: the reader assumes so.
fn accessor_fits(a: &gltf::Accessor, buffers: &[Vec<u8>]) -> Result<(), String> {
    let bad = |why: &str| Err(format!("accessor {} {why}", a.index()));
    if a.count() == 0 {
        return bad("is empty");
    }
    let Some(view) = a.view() else { return bad("has no buffer view (sparse accessors are not read)") };
    let size = a.size();
    let stride = view.stride().unwrap_or(size);
    let need = a.offset() + stride * (a.count() - 1) + size;
    if need > view.length() {
        return bad("reaches past its buffer view");
    }
    let have = buffers.get(view.buffer().index()).map_or(0, Vec::len);
    if view.offset() + view.length() > have {
        return bad("'s buffer view reaches past its buffer");
    }
    Ok(())
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
    /// A glTF with an embedded buffer reads as its triangle, moved by its node's translation
    /// (a child under it, mirrored, wound back); a node cycle, an empty accessor and one
    /// reaching past its buffer are named, not followed or read.
    #[test]
    fn gltf_nodes_place_their_meshes_and_bad_files_are_named() {
        use base64::Engine as _;
        let floats: Vec<u8> =
            [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|f| f.to_le_bytes()).collect();
        let data = base64::engine::general_purpose::STANDARD.encode(&floats);
        let gltf = |nodes: &str, count: usize, length: usize| {
            format!(
                r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"scene":0,"nodes":{nodes},
                "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
                "accessors":[{{"bufferView":0,"componentType":5126,"count":{count},"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
                "bufferViews":[{{"buffer":0,"byteLength":{length}}}],
                "buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{data}"}}]}}"#
            )
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gltf");
        let nodes = r#"[{"mesh":0,"translation":[0,2,0],"children":[1]},{"mesh":0,"scale":[-1,1,1]}]"#;
        std::fs::write(&path, gltf(nodes, 3, 36)).unwrap();
        let m = read(&path).unwrap();
        assert_eq!(m.triangles, vec![[3, 5, 4], [0, 1, 2]].into_iter().rev().collect::<Vec<_>>());
        assert_eq!(m.vertices[1], DVec3::new(1.0, 2.0, 0.0));
        assert_eq!(m.vertices[4], DVec3::new(-1.0, 2.0, 0.0));
        let cycle = r#"[{"mesh":0,"children":[1]},{"children":[0]}]"#;
        std::fs::write(&path, gltf(cycle, 3, 36)).unwrap();
        assert!(read(&path).unwrap_err().contains("ancestor"), "{:?}", read(&path));
        std::fs::write(&path, gltf(r#"[{"mesh":0}]"#, 0, 36)).unwrap();
        assert!(read(&path).is_err());
        std::fs::write(&path, gltf(r#"[{"mesh":0}]"#, 3, 24)).unwrap();
        assert!(read(&path).is_err());
    }
}
