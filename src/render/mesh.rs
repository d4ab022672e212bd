//! Meshes generated in code: unit sphere, cone, cube and tube for colliders and gizmos, the ground
//! grid, and the index buffers that turn cloth grids and rope rings into triangles.

use crate::sim::gpu_types::{SurfaceVertex, ROPE_RING};
use glam::Vec3;
use std::f32::consts::{PI, TAU};

/// Vertices (position, normal) and triangle (or line) indices.
#[derive(Debug, Clone, Default)]
pub struct MeshData {
    pub vertices: Vec<SurfaceVertex>,
    pub indices: Vec<u32>,
}

fn vertex(p: Vec3, n: Vec3) -> SurfaceVertex {
    SurfaceVertex { pos: [p.x, p.y, p.z, 1.0], normal: [n.x, n.y, n.z, 0.0] }
}

/// A unit sphere centred on the origin.
pub fn sphere(stacks: u32, slices: u32) -> MeshData {
    let mut m = MeshData::default();
    for i in 0..=stacks {
        let theta = PI * i as f32 / stacks as f32;
        for j in 0..=slices {
            let phi = TAU * j as f32 / slices as f32;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            m.vertices.push(vertex(n, n));
        }
    }
    for i in 0..stacks {
        for j in 0..slices {
            let a = i * (slices + 1) + j;
            let b = a + slices + 1;
            m.indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    m
}

/// A cone with its apex at the origin opening along +z to a unit circle at z = 1, with a cap.
pub fn cone(slices: u32) -> MeshData {
    let mut m = MeshData::default();
    let slant = Vec3::new(0.0, 0.0, -1.0); // outward normals tilt back towards the apex
    for j in 0..=slices {
        let phi = TAU * j as f32 / slices as f32;
        let rim = Vec3::new(phi.cos(), phi.sin(), 1.0);
        let n = (Vec3::new(phi.cos(), phi.sin(), 0.0) + slant).normalize();
        m.vertices.push(vertex(Vec3::ZERO, n));
        m.vertices.push(vertex(rim, n));
    }
    for j in 0..slices {
        let a = 2 * j;
        m.indices.extend_from_slice(&[a, a + 1, a + 3]);
    }
    let centre = m.vertices.len() as u32;
    m.vertices.push(vertex(Vec3::Z, Vec3::Z));
    for j in 0..=slices {
        let phi = TAU * j as f32 / slices as f32;
        m.vertices.push(vertex(Vec3::new(phi.cos(), phi.sin(), 1.0), Vec3::Z));
    }
    for j in 0..slices {
        m.indices.extend_from_slice(&[centre, centre + 1 + j, centre + 2 + j]);
    }
    m
}

/// An open tube of radius 1 around the z axis from z = -1 to 1 (a capsule's side).
pub fn tube(slices: u32) -> MeshData {
    let mut m = MeshData::default();
    for j in 0..=slices {
        let phi = TAU * j as f32 / slices as f32;
        let n = Vec3::new(phi.cos(), phi.sin(), 0.0);
        m.vertices.push(vertex(n - Vec3::Z, n));
        m.vertices.push(vertex(n + Vec3::Z, n));
    }
    for j in 0..slices {
        let a = 2 * j;
        m.indices.extend_from_slice(&[a, a + 2, a + 1, a + 1, a + 2, a + 3]);
    }
    m
}

/// A cube from -1 to 1 with flat faces.
pub fn cube() -> MeshData {
    let mut m = MeshData::default();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let (u, v) = (
                Vec3::from_array(std::array::from_fn(|k| (k == (axis + 1) % 3) as u8 as f32)),
                Vec3::from_array(std::array::from_fn(|k| (k == (axis + 2) % 3) as u8 as f32)),
            );
            let base = m.vertices.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                m.vertices.push(vertex(n + u * a + v * b, n));
            }
            m.indices.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        }
    }
    m
}

/// Lines of a square grid on y = 0 from -half to half, every `step`.
pub fn grid_lines(half: f32, step: f32) -> MeshData {
    let mut m = MeshData::default();
    let count = (half / step).round() as i32;
    for i in -count..=count {
        let t = i as f32 * step;
        for (a, b) in [
            (Vec3::new(t, 0.0, -half), Vec3::new(t, 0.0, half)),
            (Vec3::new(-half, 0.0, t), Vec3::new(half, 0.0, t)),
        ] {
            let base = m.vertices.len() as u32;
            m.vertices.push(vertex(a, Vec3::Y));
            m.vertices.push(vertex(b, Vec3::Y));
            m.indices.extend_from_slice(&[base, base + 1]);
        }
    }
    m
}

/// Two triangles per grid cell of a cloth of `cols x rows` particles.
pub fn cloth_indices(cols: u32, rows: u32) -> Vec<u32> {
    let mut out = Vec::with_capacity(((cols - 1) * (rows - 1) * 6) as usize);
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            let a = c + r * cols;
            let b = a + cols;
            out.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    out
}

/// A tube through the rings of `nodes` rope nodes (ROPE_RING vertices each), with the end rings
/// closed by fans; counter-clockwise seen from outside (the ring runs counter-clockwise about
/// the rope's direction, glsl/rope_vertices.comp).
pub fn rope_indices(nodes: u32) -> Vec<u32> {
    let mut out = rope_tube_indices(nodes);
    out.extend(rope_cap_indices(0, (nodes - 1) * ROPE_RING as u32));
    out
}

/// The tube of `rope_indices` alone.
pub fn rope_tube_indices(nodes: u32) -> Vec<u32> {
    let ring = ROPE_RING as u32;
    tube_indices(nodes, ring, |k| (k + 1) % ring)
}

/// The tube's triangles in the same order over a grid of `ROPE_RING + 1` texture coordinates a
/// node, whose last column repeats the first (the seam gets both sides).
pub fn rope_tube_uv_indices(nodes: u32) -> Vec<u32> {
    tube_indices(nodes, ROPE_RING as u32 + 1, |k| k + 1)
}

/// Two triangles for each of a ring's `ROPE_RING` sides between neighbouring nodes, over a grid
/// of `stride` entries a node; `next(k)` is the entry after k around the ring.
fn tube_indices(nodes: u32, stride: u32, next: impl Fn(u32) -> u32) -> Vec<u32> {
    let mut out = Vec::new();
    for n in 0..nodes.saturating_sub(1) {
        for k in 0..ROPE_RING as u32 {
            let (a, b) = (n * stride + k, n * stride + next(k));
            out.extend_from_slice(&[a, b, a + stride, b, b + stride, a + stride]);
        }
    }
    out
}

/// Fans closing a rope's first ring (its vertices from `first`, facing back along the rope)
/// and last ring (from `last`, facing forward).
pub fn rope_cap_indices(first: u32, last: u32) -> Vec<u32> {
    let ring = ROPE_RING as u32;
    let mut out = Vec::new();
    for k in 1..ring - 1 {
        out.extend_from_slice(&[first, first + k + 1, first + k]);
    }
    for k in 1..ring - 1 {
        out.extend_from_slice(&[last, last + k, last + k + 1]);
    }
    out
}

/// A mesh collider's triangles with flat normals (each triangle its own three vertices), in
/// the collider's frame.
pub fn flat(mesh: &crate::sim::collider_mesh::ColliderMesh) -> MeshData {
    let mut m = MeshData::default();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|k| mesh.vertices[k as usize].as_vec3());
        let n = (b - a).cross(c - a).normalize_or_zero();
        let base = m.vertices.len() as u32;
        m.vertices.extend([vertex(a, n), vertex(b, n), vertex(c, n)]);
        m.indices.extend_from_slice(&[base, base + 1, base + 2]);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_stay_in_range() {
        for (mesh, count) in
            [(sphere(8, 12), 9 * 13), (cone(12), 2 * 13 + 14), (cube(), 24), (grid_lines(1.0, 0.5), 20)]
        {
            assert_eq!(mesh.vertices.len(), count);
            assert!(mesh.indices.iter().all(|&i| (i as usize) < mesh.vertices.len()));
        }
        assert!(cloth_indices(13, 9).iter().all(|&i| i < 13 * 9));
        assert_eq!(cloth_indices(13, 9).len(), 12 * 8 * 6);
        assert!(rope_indices(40).iter().all(|&i| i < 40 * ROPE_RING as u32));
    }

    #[test]
    fn sphere_normals_point_outward() {
        for v in sphere(8, 12).vertices {
            let p = Vec3::new(v.pos[0], v.pos[1], v.pos[2]);
            let n = Vec3::new(v.normal[0], v.normal[1], v.normal[2]);
            assert!((p.length() - 1.0).abs() < 1e-5 && p.dot(n) > 0.99);
        }
    }
}
