//! Records the scene draws into a dynamic rendering: simulation surfaces (straight from their
//! compute buffers, after the simulation's compute -> vertex-input barrier), primitive meshes
//! for colliders and gizmos, the ground grid and, on the ground, the shadows the light casts of
//! the surfaces and colliders (planar projection from the point light, so contact with the
//! ground reads at a glance: `mesh.vert` flattens each shadow caster onto the ground plane and
//! draws it, without depth writes, in the floor's colour darkened, keeping the darker of it and
//! what is there: where layers of a caster overlap (a folded towel, a closed collider's near
//! and far sides) the ground darkens once, not once per layer. The grid is drawn after them,
//! so its lines show through.)
//!
//! Per frame slot it owns a camera uniform buffer, written by the host only after that slot's
//! fence, so no frame in flight reads a buffer being written.

use super::mesh::{self, MeshData};
use crate::shaders::ShaderSet;
use crate::sim::collider::ColliderModel;
use crate::sim::gpu::{GpuSim, FRAME_SLOTS};
use crate::sim::gpu_types::{Camera, Draw, SurfaceVertex};
use crate::sim::model::{ObjectKind, ObjectShape};
use crate::vk::{
    BindingKind, BindingSet, BindingSetLayout, Blend, Buffer, BufferUsage, DescriptorArena, Format,
    GpuContext, GraphicsDesc, GraphicsPipeline, MemoryKind, Recorder, Retired, Topology, VertexFormat,
    VertexLayout,
};
use anyhow::{Context as _, Result};
use glam::Mat4;

/// What to draw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Sphere,
    Cone,
    Cube,
    /// An open tube of radius 1 around z from -1 to 1.
    Tube,
    /// The surface of simulation object `i` (cloth mesh or rope tube).
    Surface(usize),
    /// A mesh collider's triangles (`set_objects`), by `collider_mesh_key` of its mesh.
    Mesh(usize),
}

/// The key a mesh collider's triangles are drawn by: the address of its shared mesh.
pub fn collider_mesh_key(mesh: &std::sync::Arc<crate::sim::collider_mesh::ColliderMesh>) -> usize {
    std::sync::Arc::as_ptr(mesh) as usize
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawItem {
    pub shape: Shape,
    pub model: Mat4,
    pub front: [f32; 3],
    pub back: [f32; 3],
    pub lit: bool,
}

/// The floor's colour under the ground grid (the sky is darker, the grid lighter).
const FLOOR: [f32; 3] = [0.2, 0.21, 0.23];

/// Whether `item` casts a shadow on the ground: the simulated surfaces and the colliders (lit
/// solids), not the flat gizmos (wind cone, grab marker).
fn item_casts_shadow(item: &DrawItem) -> bool {
    item.lit && item.shape != Shape::Cone
}

impl DrawItem {
    /// One colour on both sides.
    pub fn solid(shape: Shape, model: Mat4, color: [f32; 3], lit: bool) -> Self {
        Self { shape, model, front: color, back: color, lit }
    }
}

/// A mesh in host-visible buffers (small, written once).
struct GpuMesh {
    vertices: Buffer,
    indices: Buffer,
    count: u32,
}

impl GpuMesh {
    fn new(ctx: &GpuContext, name: &str, data: &MeshData) -> Result<Self> {
        let mut vertices = Buffer::new(
            ctx,
            &format!("{name}.vertices"),
            std::mem::size_of_val(data.vertices.as_slice()) as u64,
            BufferUsage::VERTEX,
            MemoryKind::Upload,
        )?;
        let indices = Self::indices(ctx, name, &data.indices);
        let mut indices = match indices {
            Ok(i) => i,
            Err(e) => {
                vertices.destroy(ctx);
                return Err(e);
            }
        };
        vertices.write(0, &data.vertices)?;
        indices.write(0, &data.indices)?;
        Ok(Self { vertices, indices, count: data.indices.len() as u32 })
    }

    fn indices(ctx: &GpuContext, name: &str, indices: &[u32]) -> Result<Buffer> {
        Ok(Buffer::new(
            ctx,
            &format!("{name}.indices"),
            4 * indices.len() as u64,
            BufferUsage::INDEX,
            MemoryKind::Upload,
        )?)
    }

    fn destroy(self, ctx: &GpuContext) {
        self.vertices.destroy(ctx);
        self.indices.destroy(ctx);
    }
}

pub struct SceneRenderer {
    triangles: GraphicsPipeline,
    lines: GraphicsPipeline,
    shadows: GraphicsPipeline,
    color: Format,
    depth: Format,
    layout: BindingSetLayout,
    arena: DescriptorArena,
    cameras: Vec<Buffer>,
    sets: Vec<BindingSet>,
    sphere: GpuMesh,
    cone: GpuMesh,
    cube: GpuMesh,
    tube: GpuMesh,
    grid: GpuMesh,
    /// Index buffers of the simulation objects' surfaces, with their index counts.
    surfaces: Vec<(Buffer, u32)>,
    /// Mesh colliders' triangles, by `collider_mesh_key` (each mesh held, so that its address
    /// is not another's while it is drawn).
    meshes: Vec<(std::sync::Arc<crate::sim::collider_mesh::ColliderMesh>, GpuMesh)>,
}

impl SceneRenderer {
    pub fn new(ctx: &GpuContext, color: Format, depth: Format, shaders: &mut ShaderSet) -> Result<Self> {
        let layout = BindingSetLayout::new(ctx, &[BindingKind::GraphicsUniform])?;
        let vertex = shaders.load_or_embedded("mesh.vert")?;
        let fragment = shaders.load_or_embedded("mesh.frag")?;
        let [triangles, lines, shadows] = Self::pipelines(ctx, &layout, color, depth, &vertex, &fragment)?;
        let mut arena = DescriptorArena::new(ctx, FRAME_SLOTS as u32, 1)?;
        let mut cameras = Vec::new();
        let mut sets = Vec::new();
        for slot in 0..FRAME_SLOTS {
            let buffer = Buffer::new(
                ctx,
                &format!("camera[{slot}]"),
                std::mem::size_of::<Camera>() as u64,
                BufferUsage::UNIFORM,
                MemoryKind::Upload,
            )?;
            sets.push(arena.allocate(ctx, &layout, &[&buffer])?);
            cameras.push(buffer);
        }
        Ok(Self {
            color,
            depth,
            sphere: GpuMesh::new(ctx, "sphere", &mesh::sphere(24, 32))?,
            cone: GpuMesh::new(ctx, "cone", &mesh::cone(32))?,
            cube: GpuMesh::new(ctx, "cube", &mesh::cube())?,
            tube: GpuMesh::new(ctx, "tube", &mesh::tube(32))?,
            grid: GpuMesh::new(ctx, "grid", &mesh::grid_lines(5.0, 0.25))?,
            triangles,
            lines,
            shadows,
            layout,
            arena,
            cameras,
            sets,
            surfaces: Vec::new(),
            meshes: Vec::new(),
        })
    }

    fn pipelines(
        ctx: &GpuContext,
        layout: &BindingSetLayout,
        color: Format,
        depth: Format,
        vertex: &[u32],
        fragment: &[u32],
    ) -> Result<[GraphicsPipeline; 3]> {
        let stride = std::mem::size_of::<SurfaceVertex>() as u32;
        let attributes = [(0, VertexFormat::Float32x4, 0), (1, VertexFormat::Float32x4, 16)];
        let desc = |name, topology, blend: Blend| GraphicsDesc {
            name,
            vertex,
            fragment,
            vertices: VertexLayout { stride, attributes: &attributes },
            topology,
            color,
            depth,
            depth_write: blend == Blend::Opaque,
            blend,
            set_layout: layout,
            push_constant_bytes: std::mem::size_of::<Draw>() as u32,
        };
        let descs = [
            desc("scene triangles", Topology::Triangles, Blend::Opaque),
            desc("scene lines", Topology::Lines, Blend::Opaque),
            desc("scene shadows", Topology::Triangles, Blend::Darker),
        ];
        let mut made = Vec::new();
        for d in &descs {
            match GraphicsPipeline::new(ctx, d) {
                Ok(p) => made.push(p),
                Err(e) => {
                    made.into_iter().for_each(|p| p.destroy(ctx));
                    return Err(e.into());
                }
            }
        }
        Ok(made.try_into().unwrap_or_else(|_| unreachable!("three pipelines made")))
    }

    /// Rebuilds the scene pipelines when `changed` names one of their shaders and both
    /// compile; returns whether it did and the replaced pipelines (free them once the frames
    /// recorded before have completed).
    pub fn reload(
        &mut self,
        ctx: &GpuContext,
        shaders: &mut ShaderSet,
        changed: &[String],
    ) -> (bool, Vec<Retired>) {
        if !changed.iter().any(|n| n == "mesh.vert" || n == "mesh.frag") {
            return (false, Vec::new());
        }
        let (Ok(vertex), Ok(fragment)) = (shaders.load("mesh.vert"), shaders.load("mesh.frag")) else {
            return (false, Vec::new());
        };
        match Self::pipelines(ctx, &self.layout, self.color, self.depth, &vertex, &fragment) {
            Ok([triangles, lines, shadows]) => {
                let old = [
                    std::mem::replace(&mut self.triangles, triangles),
                    std::mem::replace(&mut self.lines, lines),
                    std::mem::replace(&mut self.shadows, shadows),
                ];
                (true, old.into_iter().map(Retired::Graphics).collect())
            }
            Err(e) => {
                log::error!("scene pipelines: {e:#}");
                (false, Vec::new())
            }
        }
    }

    /// Builds the index buffers for a simulation's objects (after it is created or rebuilt; the
    /// device must be idle).
    pub fn set_objects(
        &mut self,
        ctx: &GpuContext,
        shapes: &[ObjectShape],
        colliders: &[ColliderModel],
    ) -> Result<()> {
        for (b, _) in self.surfaces.drain(..) {
            b.destroy(ctx);
        }
        for (_, m) in self.meshes.drain(..) {
            m.destroy(ctx);
        }
        for c in colliders {
            if let crate::sim::collider::Shape::Mesh { mesh: ref m, .. } = c.shape {
                if !self.meshes.iter().any(|(k, _)| std::sync::Arc::ptr_eq(k, m)) {
                    self.meshes.push((m.clone(), GpuMesh::new(ctx, "mesh collider", &mesh::flat(m))?));
                }
            }
        }
        for s in shapes {
            let indices = match s.kind {
                ObjectKind::Cloth if s.mesh.is_some() => {
                    s.mesh.iter().flat_map(|m| m.triangles.iter().flatten().copied()).collect()
                }
                ObjectKind::Cloth => mesh::cloth_indices(s.dims[0], s.dims[1]),
                ObjectKind::Rope => mesh::rope_indices(s.dims[0]),
            };
            let mut buffer = GpuMesh::indices(ctx, &format!("{}.indices", s.name), &indices)
                .with_context(|| format!("index buffer of '{}'", s.name))?;
            buffer.write(0, &indices)?;
            self.surfaces.push((buffer, indices.len() as u32));
        }
        Ok(())
    }

    /// Writes the camera of frame `slot` (after that slot's fence).
    pub fn set_camera(&mut self, slot: usize, camera: &Camera) -> Result<()> {
        Ok(self.cameras[slot].write(0, std::slice::from_ref(camera))?)
    }

    /// Records `items` and, where the scene has a ground, its floor, grid and shadows into the
    /// current rendering.
    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        slot: usize,
        sim: &GpuSim,
        items: &[DrawItem],
        ground: Option<super::view::Ground>,
    ) {
        // params: x lit, y 1 for a shadow flattened onto the ground at height z.
        let push = |rec: &mut Recorder<'_>,
                    pipeline: &GraphicsPipeline,
                    item: &DrawItem,
                    shadow: Option<f32>| {
            // A shadow is drawn in the floor's colour (darkened by the shader).
            let front = if shadow.is_some() { FLOOR } else { item.front };
            let draw = Draw {
                model: item.model.to_cols_array_2d(),
                front: [front[0], front[1], front[2], 1.0],
                back: [item.back[0], item.back[1], item.back[2], 1.0],
                params: [item.lit as u32 as f32, shadow.is_some() as u32 as f32, shadow.unwrap_or(0.0), 0.0],
            };
            rec.push_constants(pipeline, bytemuck::bytes_of(&draw));
        };
        let mesh = |rec: &mut Recorder<'_>, shape: Shape| match shape {
            Shape::Sphere => {
                rec.draw_indexed(&self.sphere.vertices, &self.sphere.indices, self.sphere.count, 1)
            }
            Shape::Cone => rec.draw_indexed(&self.cone.vertices, &self.cone.indices, self.cone.count, 1),
            Shape::Cube => rec.draw_indexed(&self.cube.vertices, &self.cube.indices, self.cube.count, 1),
            Shape::Tube => rec.draw_indexed(&self.tube.vertices, &self.tube.indices, self.tube.count, 1),
            Shape::Mesh(key) => {
                if let Some((_, m)) = self.meshes.iter().find(|(k, _)| collider_mesh_key(k) == key) {
                    rec.draw_indexed(&m.vertices, &m.indices, m.count, 1);
                }
            }
            Shape::Surface(i) => {
                if let Some((indices, count)) = self.surfaces.get(i) {
                    if i < sim.object_count() {
                        rec.draw_indexed(sim.surface(i).0, indices, *count, 1);
                    }
                }
            }
        };
        if let Some(super::view::Ground { height, shadows }) = ground {
            // The floor: a flat slab under the grid, light enough for the shadows to show.
            rec.bind_graphics(&self.triangles, self.sets[slot]);
            let floor = DrawItem::solid(
                Shape::Cube,
                Mat4::from_scale_rotation_translation(
                    glam::Vec3::new(5.0, 0.001, 5.0),
                    glam::Quat::IDENTITY,
                    glam::Vec3::Y * (height - 0.004),
                ),
                FLOOR,
                false,
            );
            push(rec, &self.triangles, &floor, None);
            mesh(rec, Shape::Cube);
            // The shadows of what stands on the ground: surfaces and colliders, not gizmos.
            if shadows {
                rec.bind_graphics(&self.shadows, self.sets[slot]);
                for item in items.iter().filter(|i| item_casts_shadow(i)) {
                    push(rec, &self.shadows, item, Some(height));
                    mesh(rec, item.shape);
                }
            }
            // The grid after the shadows, so that its lines show through them.
            rec.bind_graphics(&self.lines, self.sets[slot]);
            let item = DrawItem {
                shape: Shape::Cube,
                model: Mat4::from_translation(glam::Vec3::Y * height),
                front: [0.42; 3],
                back: [0.42; 3],
                lit: false,
            };
            push(rec, &self.lines, &item, None);
            rec.draw_indexed(&self.grid.vertices, &self.grid.indices, self.grid.count, 1);
        }
        rec.bind_graphics(&self.triangles, self.sets[slot]);
        for item in items {
            push(rec, &self.triangles, item, None);
            mesh(rec, item.shape);
        }
    }

    /// Frees everything; the device must be idle.
    pub fn destroy(self, ctx: &GpuContext) {
        for (b, _) in self.surfaces {
            b.destroy(ctx);
        }
        for (_, m) in self.meshes {
            m.destroy(ctx);
        }
        for m in [self.sphere, self.cone, self.cube, self.tube, self.grid] {
            m.destroy(ctx);
        }
        for c in self.cameras {
            c.destroy(ctx);
        }
        self.arena.destroy(ctx);
        self.triangles.destroy(ctx);
        self.lines.destroy(ctx);
        self.shadows.destroy(ctx);
        self.layout.destroy(ctx);
    }
}
