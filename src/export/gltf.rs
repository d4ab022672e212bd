//! glTF 2.0 binary (`.glb`) recordings, built with `gltf-json`: every object a mesh whose first
//! frame is its vertices and each later frame a morph target (its points' and normals' change
//! since the first), played by one animation that blends from each frame's target to the next's
//! (linear in time: the weights as sparse accessors, one 1.0 per keyframe, so the file grows
//! with the frames, not their square); colliders as meshes, a moving one's node translated over
//! time. Blender imports the targets as shape keys with their values animated. glTF is Y-up in
//! metres, as the simulation. Every mesh carries texture coordinates, per vertex (a rope's
//! tube comes split along its seam: `split_seams`).

use super::{collider_mesh, Recording, Track};
use crate::sim::model::ObjectKind;
use anyhow::Result;
use glam::DVec3;
use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;

/// One object's mesh and frames, as the recording keeps them.
pub struct MeshFrames<'a> {
    pub name: &'a str,
    pub indices: &'a [u32],
    /// Per-vertex texture coordinates, where every corner of a vertex takes the same.
    pub st: Option<&'a [[f32; 2]]>,
    pub color: [f32; 3],
    pub double_sided: bool,
    pub points: &'a [Vec<[f32; 3]>],
    pub normals: &'a [Vec<[f32; 3]>],
}

/// A collider's mesh where it is at the first frame (a turning one's about its centre there),
/// and its node's translation at each frame (None when it does not move: a turning one's is
/// where its centre is) and rotation (a unit quaternion, xyzw; None when it does not turn).
pub struct ColliderMesh {
    pub name: String,
    pub points: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
    pub offsets: Option<Vec<[f32; 3]>>,
    pub turns: Option<Vec<[f32; 4]>>,
}

/// The binary buffer and the document that describes it.
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
}

impl Builder {
    /// Appends `bytes` (4-byte aligned) as a buffer view.
    fn view(
        &mut self,
        bytes: &[u8],
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::buffer::View> {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: target.map(Valid),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// An accessor of `count` elements of `kind` (f32 components) over `view`, with its bounds
    /// when given.
    fn accessor(
        &mut self,
        view: Option<json::Index<json::buffer::View>>,
        count: usize,
        kind: json::accessor::Type,
        bounds: Option<(Vec<f32>, Vec<f32>)>,
    ) -> json::Index<json::Accessor> {
        self.root.push(json::Accessor {
            buffer_view: view,
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(json::accessor::ComponentType::F32)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(kind),
            min: bounds.as_ref().map(|(lo, _)| json::Value::from(lo.clone())),
            max: bounds.map(|(_, hi)| json::Value::from(hi)),
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// A VEC3 accessor of `values` (with bounds: positions need them).
    fn vec3(
        &mut self,
        values: &[[f32; 3]],
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::Accessor> {
        let lo = (0..3).map(|k| values.iter().map(|v| v[k]).fold(f32::INFINITY, f32::min)).collect();
        let hi = (0..3).map(|k| values.iter().map(|v| v[k]).fold(f32::NEG_INFINITY, f32::max)).collect();
        let view = self.view(bytemuck::cast_slice(values), target);
        self.accessor(Some(view), values.len(), json::accessor::Type::Vec3, Some((lo, hi)))
    }

    /// An animation sampler's output of unit quaternions.
    fn quaternions(&mut self, values: &[[f32; 4]]) -> json::Index<json::Accessor> {
        let view = self.view(bytemuck::cast_slice(values), None);
        self.accessor(Some(view), values.len(), json::accessor::Type::Vec4, None)
    }

    fn indices(&mut self, indices: &[u32]) -> json::Index<json::Accessor> {
        let view = self.view(bytemuck::cast_slice(indices), Some(json::buffer::Target::ElementArrayBuffer));
        let accessor = self.accessor(Some(view), indices.len(), json::accessor::Type::Scalar, None);
        self.root.accessors[accessor.value()].component_type =
            Valid(json::accessor::GenericComponentType(json::accessor::ComponentType::U32));
        accessor
    }

    fn material(&mut self, name: &str, color: [f32; 3], double_sided: bool) -> json::Index<json::Material> {
        self.root.push(json::Material {
            name: Some(name.to_string()),
            double_sided,
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_factor: json::material::PbrBaseColorFactor([color[0], color[1], color[2], 1.0]),
                metallic_factor: json::material::StrengthFactor(0.0),
                roughness_factor: json::material::StrengthFactor(0.8),
                ..Default::default()
            },
            ..Default::default()
        })
    }

    /// A mesh of one triangle primitive, and the node that places it.
    fn mesh(
        &mut self,
        name: &str,
        attributes: Vec<(json::mesh::Semantic, json::Index<json::Accessor>)>,
        indices: json::Index<json::Accessor>,
        material: json::Index<json::Material>,
        targets: Option<Vec<json::mesh::MorphTarget>>,
    ) -> json::Index<json::Node> {
        let weights = targets.as_ref().map(|t| vec![0.0; t.len()]);
        let mesh = self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.to_string()),
            primitives: vec![json::mesh::Primitive {
                attributes: attributes.into_iter().map(|(s, a)| (Valid(s), a)).collect(),
                extensions: None,
                extras: Default::default(),
                indices: Some(indices),
                material: Some(material),
                mode: Valid(json::mesh::Mode::Triangles),
                targets,
            }],
            weights,
        });
        self.root.push(json::Node { mesh: Some(mesh), name: Some(name.to_string()), ..Default::default() })
    }
}

/// The `.glb` bytes of objects `meshes` and `colliders` at frame times `times` [s from the
/// first frame].
pub fn glb(meshes: &[MeshFrames], colliders: &[ColliderMesh], times: &[f32]) -> anyhow::Result<Vec<u8>> {
    let mut b = Builder { root: json::Root::default(), bin: Vec::new() };
    b.root.asset = json::Asset {
        generator: Some(format!("msdsim {}", env!("CARGO_PKG_VERSION"))),
        version: "2.0".into(),
        copyright: None,
        extensions: None,
        extras: Default::default(),
        min_version: None,
    };
    let frames = times.len();
    let (mut nodes, mut channels, mut samplers) = (Vec::new(), Vec::new(), Vec::new());
    for m in meshes {
        let (Some(first), Some(first_normals)) = (m.points.first(), m.normals.first()) else { continue };
        let position = b.vec3(first, Some(json::buffer::Target::ArrayBuffer));
        let normal = b.vec3(first_normals, Some(json::buffer::Target::ArrayBuffer));
        let mut attributes =
            vec![(json::mesh::Semantic::Positions, position), (json::mesh::Semantic::Normals, normal)];
        if let Some(st) = m.st {
            let view = b.view(bytemuck::cast_slice(st), Some(json::buffer::Target::ArrayBuffer));
            let uv = b.accessor(Some(view), st.len(), json::accessor::Type::Vec2, None);
            attributes.push((json::mesh::Semantic::TexCoords(0), uv));
        }
        let indices = b.indices(m.indices);
        let material = b.material(m.name, m.color, m.double_sided);
        let change = |later: &[[f32; 3]], first: &[[f32; 3]]| -> Vec<[f32; 3]> {
            later.iter().zip(first).map(|(p, q)| [p[0] - q[0], p[1] - q[1], p[2] - q[2]]).collect()
        };
        let targets: Vec<json::mesh::MorphTarget> = (1..frames)
            .map(|f| json::mesh::MorphTarget {
                positions: Some(b.vec3(&change(&m.points[f], first), None)),
                normals: Some(b.vec3(&change(&m.normals[f], first_normals), None)),
                tangents: None,
            })
            .collect();
        let animated = !targets.is_empty();
        let node = b.mesh(m.name, attributes, indices, material, animated.then_some(targets));
        nodes.push(node);
        if animated {
            // Keyframe f (after the first) weighs target f - 1 fully, the others not at all.
            let targets = frames - 1;
            let at: Vec<u32> = (1..frames).map(|f| (f * targets + f - 1) as u32).collect();
            let ones = vec![1.0f32; targets];
            let at_view = b.view(bytemuck::cast_slice(&at), None);
            let ones_view = b.view(bytemuck::cast_slice(&ones), None);
            let output = b.accessor(None, frames * targets, json::accessor::Type::Scalar, None);
            b.root.accessors[output.value()].sparse = Some(json::accessor::sparse::Sparse {
                count: USize64::from(targets),
                indices: json::accessor::sparse::Indices {
                    buffer_view: at_view,
                    byte_offset: USize64(0),
                    component_type: Valid(json::accessor::IndexComponentType(
                        json::accessor::ComponentType::U32,
                    )),
                    extensions: None,
                    extras: Default::default(),
                },
                values: json::accessor::sparse::Values {
                    buffer_view: ones_view,
                    byte_offset: USize64(0),
                    extensions: None,
                    extras: Default::default(),
                },
                extensions: None,
                extras: Default::default(),
            });
            channels.push((node, json::animation::Property::MorphTargetWeights, samplers.len()));
            samplers.push(output);
        }
    }
    if !colliders.is_empty() {
        let material = b.material("colliders", [0.5; 3], false);
        for c in colliders {
            let position = b.vec3(&c.points, Some(json::buffer::Target::ArrayBuffer));
            let normal = b.vec3(&c.normals, Some(json::buffer::Target::ArrayBuffer));
            let indices = b.indices(&c.indices);
            let attributes =
                vec![(json::mesh::Semantic::Positions, position), (json::mesh::Semantic::Normals, normal)];
            let node = b.mesh(&c.name, attributes, indices, material, None);
            nodes.push(node);
            if let Some(offsets) = c.offsets.as_ref().filter(|o| frames > 1 && o.len() == frames) {
                let output = b.vec3(offsets, None);
                channels.push((node, json::animation::Property::Translation, samplers.len()));
                samplers.push(output);
            }
            if let Some(turns) = c.turns.as_ref().filter(|o| frames > 1 && o.len() == frames) {
                let output = b.quaternions(turns);
                channels.push((node, json::animation::Property::Rotation, samplers.len()));
                samplers.push(output);
            }
        }
    }
    if !channels.is_empty() {
        // The keyframes' times (an accessor must hold at least one element: only with frames).
        let time_view = b.view(bytemuck::cast_slice(times), None);
        let bounds = (vec![times[0]], vec![times[frames - 1]]);
        let input = b.accessor(Some(time_view), frames, json::accessor::Type::Scalar, Some(bounds));
        b.root.push(json::Animation {
            extensions: None,
            extras: Default::default(),
            name: Some("simulation".into()),
            channels: channels
                .into_iter()
                .map(|(node, path, sampler)| json::animation::Channel {
                    sampler: json::Index::new(sampler as u32),
                    target: json::animation::Target {
                        extensions: None,
                        extras: Default::default(),
                        node,
                        path: Valid(path),
                    },
                    extensions: None,
                    extras: Default::default(),
                })
                .collect(),
            samplers: samplers
                .into_iter()
                .map(|output| json::animation::Sampler {
                    extensions: None,
                    extras: Default::default(),
                    input,
                    interpolation: Valid(json::animation::Interpolation::Linear),
                    output,
                })
                .collect(),
        });
    }
    let scene = b.root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some("scene".into()),
        nodes,
    });
    b.root.scene = Some(scene);
    b.root.push(json::Buffer {
        byte_length: USize64::from(b.bin.len()),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let mut text = b.root.to_vec()?;
    text.resize(text.len().next_multiple_of(4), b' ');
    let length = 12 + 8 + text.len() + 8 + b.bin.len();
    let mut out = Vec::with_capacity(length);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&u32::try_from(length)?.to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(b.bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b.bin);
    Ok(out)
}

impl Recording {
    /// The glTF binary (`glb`, below): texture coordinates per vertex (a rope's tube, whose
    /// coordinates are face-varying at its seam and caps, with a vertex for each coordinate a
    /// point takes: `split_seams`), the colliders as meshes where the first frame had them.
    pub fn glb(&self) -> Result<Vec<u8>> {
        let split: Vec<Option<Seams>> =
            (self.tracks.iter()).map(|t| (t.st_indices != t.indices).then(|| split_seams(t))).collect();
        let meshes: Vec<MeshFrames> = (self.tracks.iter().zip(&split))
            .map(|(t, seams)| {
                let (indices, st, points, normals) = match seams {
                    None => (&t.indices, &t.st, &t.points, &t.normals),
                    Some(s) => (&s.indices, &s.st, &s.points, &s.normals),
                };
                MeshFrames {
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
        let colliders: Vec<ColliderMesh> = (self.colliders.iter().zip(&self.collider_names))
            .map(|(c, name)| {
                let (points, normals, triangles) = collider_mesh(c, first);
                // A turning one's mesh is placed about its centre at the first frame, and its
                // node at the centre: the turn is then about the node's origin, and a viewer's
                // interpolation between frames keeps the centre on its (linear) path.
                let start = c.motion.offset(first);
                let centre = if c.turns() { c.shape_at(first).reference_point() } else { DVec3::ZERO };
                let turn = |t: f64| c.turn_at(t) * c.turn_at(first).inverse();
                let offset = |t: f64| c.motion.offset(t) - start + centre;
                ColliderMesh {
                    name: name.clone(),
                    points: points.into_iter().map(|p| f32s(p - centre)).collect(),
                    normals: normals.into_iter().map(f32s).collect(),
                    indices: triangles.into_iter().flatten().collect(),
                    offsets: c.is_moving().then(|| self.times.iter().map(|&t| f32s(offset(t))).collect()),
                    turns: c.turns().then(|| {
                        self.times.iter().map(|&t| turn(t).as_quat().normalize().to_array()).collect()
                    }),
                }
            })
            .collect();
        let times: Vec<f32> = self.times.iter().map(|&t| (t - first) as f32).collect();
        glb(&meshes, &colliders, &times)
    }
}

/// A track's mesh with a vertex for each point and texture coordinate its corners pair (glTF's
/// attributes are per vertex): its points and normals at every frame, coordinates, triangles.
pub(super) struct Seams {
    pub(super) points: Vec<Vec<[f32; 3]>>,
    pub(super) normals: Vec<Vec<[f32; 3]>>,
    pub(super) st: Vec<[f32; 2]>,
    pub(super) indices: Vec<u32>,
}

/// `t`'s mesh split along its seams (`Seams`): vertex v keeps its index with the coordinate of
/// its first corner; a corner with another coordinate gets a copy of v after the others.
pub(super) fn split_seams(t: &Track) -> Seams {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A recording stopped after its first frame (or before any: the app's Record pressed
    /// twice) is still valid glTF: no animation and no accessor without elements (glTF needs
    /// at least one), the meshes and colliders still there.
    #[test]
    fn no_accessor_is_empty_with_one_frame_or_none() {
        let triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let up = [[0.0, 0.0, 1.0]; 3];
        for frames in [0, 1] {
            let (points, normals) = (vec![triangle.to_vec(); frames], vec![up.to_vec(); frames]);
            let mesh = MeshFrames {
                name: "c",
                indices: &[0, 1, 2],
                st: None,
                color: [0.5; 3],
                double_sided: true,
                points: &points,
                normals: &normals,
            };
            let collider = ColliderMesh {
                name: "box".into(),
                points: triangle.to_vec(),
                normals: up.to_vec(),
                indices: vec![0, 1, 2],
                offsets: Some(vec![[0.0; 3]; frames]),
                turns: Some(vec![[0.0, 0.0, 0.0, 1.0]; frames]),
            };
            let bytes = glb(&[mesh], &[collider], &vec![0.0; frames]).unwrap();
            let text = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
            let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + text]).unwrap();
            let accessors = doc["accessors"].as_array().unwrap();
            assert!(accessors.iter().all(|a| a["count"].as_u64() > Some(0)), "{frames} frames: {doc}");
            assert!(doc.get("animations").is_none(), "{frames} frames: {doc}");
            assert_eq!(doc["meshes"].as_array().unwrap().len(), frames + 1, "{frames} frames: {doc}");
        }
    }
}
