//! A triangle mesh collider's geometry: its triangles in the collider's own frame (the file's
//! origin, scaled) and a uniform grid over them, built once on the host, which both the CPU twin and
//! the GPU (`mesh_distance` in glsl/include/colliders.glsl, from the words `pack` writes) walk.
//! Each cell lists every triangle within `reach` of some point of the cell, so a query visits
//! one cell and finds every triangle within `reach` of the point. The signed distance is to the
//! nearest triangle, negative on the side its winding faces away from (inside a closed mesh
//! whose triangles wind counter-clockwise seen from outside; behind an open one). Where two
//! triangles are equally near (an edge or a corner) the one the point lies most squarely in
//! front of or behind decides the side, which is right at convex and concave edges alike
//! (distances within a few f32 steps of the point's coordinates count as equal).

use glam::DVec3;

/// Cells along the grid's longest side at most (its starts stay within about a MiB).
const MAX_CELLS_ALONG: f64 = 64.0;
/// The vec4s a mesh collider may take on the GPU: the record's offsets are float values,
/// exact below 2^24.
pub const MAX_WORDS: u64 = 1 << 24;
/// Triangles a mesh collider may have (a query walks one cell's list; the whole mesh goes
/// into the GPU's collider buffer).
pub const MAX_TRIANGLES: usize = 1 << 20;

/// A mesh collider's triangles and their grid.
#[derive(Debug, Clone, PartialEq)]
pub struct ColliderMesh {
    /// Vertices in the collider's frame [m].
    pub vertices: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    /// Whether every edge is shared by exactly two triangles (a closed surface).
    pub closed: bool,
    /// How far from a cell its triangles are listed [m].
    pub reach: f64,
    grid: Grid,
}

#[derive(Debug, Clone, PartialEq)]
struct Grid {
    origin: DVec3,
    cell: f64,
    dims: [u32; 3],
    /// Per cell, its first entry in `items`; one more at the end.
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl ColliderMesh {
    /// Checks a mesh read from a file before it is built: triangles to take, vertices finite,
    /// every triangle naming vertices it has and with an area (the scene checks how far its
    /// vertices reach once scaled). The error names the first bad triangle or vertex.
    pub fn check(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), String> {
        if triangles.is_empty() {
            return Err("it has no triangles".into());
        }
        if triangles.len() > MAX_TRIANGLES {
            return Err(format!(
                "it has {} triangles; a mesh collider takes at most {MAX_TRIANGLES}",
                triangles.len()
            ));
        }
        if let Some(i) = vertices.iter().position(|v| !v.is_finite()) {
            return Err(format!("vertex {i} is at {:?}: not a finite coordinate", vertices[i]));
        }
        for (i, t) in triangles.iter().enumerate() {
            if let Some(&k) = t.iter().find(|&&k| k as usize >= vertices.len()) {
                return Err(format!("triangle {i} names vertex {k}, past its {} vertices", vertices.len()));
            }
            let [a, b, c] = t.map(|k| vertices[k as usize]);
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            let area = 0.5 * (b - a).cross(c - a).length();
            if area.is_nan() || area <= 1e-12 * longest * longest {
                return Err(format!("triangle {i} (vertices {} {} {}) has no area", t[0], t[1], t[2]));
            }
        }
        Ok(())
    }

    /// The mesh of `vertices` (in the collider's frame) and `triangles` (which passed `check`),
    /// its triangles listed in the cells within `reach` of them (more than the contact distance
    /// of any object that may touch it).
    pub fn new(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>, reach: f64) -> Self {
        debug_assert!(Self::check(&vertices, &triangles).is_ok());
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let mut edge_sum = 0.0;
        for t in &triangles {
            let [a, b, c] = t.map(|k| vertices[k as usize]);
            edge_sum += (b - a).length().max((c - b).length()).max((a - c).length());
            for p in [a, b, c] {
                (lo, hi) = (lo.min(p), hi.max(p));
            }
        }
        let closed = every_edge_twice(&triangles);
        let reach = reach.max(1e-6);
        let (lo, hi) = (lo - DVec3::splat(reach), hi + DVec3::splat(reach));
        let extent = (hi - lo).max_element();
        // Half the mean longest edge (shorter lists: each particle walks one), at least the
        // reach, so that a triangle is listed in a few cells around it (its box grown by the
        // reach), and no more than MAX_CELLS_ALONG along a side.
        let cell = (0.5 * edge_sum / triangles.len() as f64).max(extent / MAX_CELLS_ALONG).max(reach);
        let dims = ((hi - lo) / cell).ceil().max(DVec3::ONE).as_uvec3().to_array();
        let mut lists = vec![Vec::new(); (dims[0] * dims[1] * dims[2]) as usize];
        for (i, t) in triangles.iter().enumerate() {
            let p = t.map(|k| vertices[k as usize]);
            let (tlo, thi) = (p[0].min(p[1]).min(p[2]) - reach, p[0].max(p[1]).max(p[2]) + reach);
            let (c0, c1) = (cell_of(lo, cell, dims, tlo), cell_of(lo, cell, dims, thi));
            for z in c0[2]..=c1[2] {
                for y in c0[1]..=c1[1] {
                    for x in c0[0]..=c1[0] {
                        let centre = lo + (DVec3::new(x as f64, y as f64, z as f64) + 0.5) * cell;
                        // The triangle within reach of some point of the cell: its distance
                        // from the centre within reach plus the cell's half diagonal.
                        if distance_to(centre, p).0 <= reach + 0.87 * cell {
                            lists[(x + dims[0] * (y + dims[1] * z)) as usize].push(i as u32);
                        }
                    }
                }
            }
        }
        let mut starts = Vec::with_capacity(lists.len() + 1);
        let mut items = Vec::new();
        for l in &lists {
            starts.push(items.len() as u32);
            items.extend_from_slice(l);
        }
        starts.push(items.len() as u32);
        let grid = Grid { origin: lo, cell, dims, starts, items };
        Self { vertices, triangles, closed, reach, grid }
    }

    /// The same mesh with every number rounded to f32, as the GPU has it.
    pub fn rounded_to_f32(&self) -> Self {
        let mut m = self.clone();
        for v in &mut m.vertices {
            *v = v.as_vec3().as_dvec3();
        }
        m.grid.origin = m.grid.origin.as_vec3().as_dvec3();
        m.grid.cell = m.grid.cell as f32 as f64;
        m.reach = m.reach as f32 as f64;
        m
    }

    /// Its vertices' bounds in its frame.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        bounds(&self.vertices)
    }

    /// Signed distance from `p` (in its frame) to the nearest triangle within `reach` and the
    /// unit normal away from it (see the top). Where none is that near: a lower bound of the
    /// distance, at least `reach` (its distance to the grid's box), which a ray can march by.
    pub fn distance(&self, p: DVec3) -> (f64, DVec3) {
        self.distance_placed(p, DVec3::ZERO)
    }

    /// `distance` for the mesh placed at `centre` (whose size adds to the rounding that
    /// decides ties).
    pub fn distance_placed(&self, p: DVec3, centre: DVec3) -> (f64, DVec3) {
        let g = &self.grid;
        let q = (p - g.origin) / g.cell;
        let hi = DVec3::new(g.dims[0] as f64, g.dims[1] as f64, g.dims[2] as f64);
        // (written so that a NaN is outside, as on the GPU)
        let within = (0..3).all(|k| q[k] >= 0.0 && q[k] < hi[k]);
        if !within {
            let out = (g.origin - p).max(p - (g.origin + hi * g.cell)).max(DVec3::ZERO);
            return (out.length().max(self.reach), DVec3::Y);
        }
        let c = q.as_uvec3();
        let cell = (c.x + g.dims[0] * (c.y + g.dims[1] * c.z)) as usize;
        let (mut best, mut best_d, mut best_sq) = ((self.reach, DVec3::Y), f64::INFINITY, 0.0);
        // Distances within a few f32 steps of p count as equal (the GPU's rounding would
        // otherwise pick a triangle p is edge-on to, whose side is noise).
        let tie = crate::sim::collider::position_slack(p) + crate::sim::collider::position_slack(centre);
        for &t in &g.items[g.starts[cell] as usize..g.starts[cell + 1] as usize] {
            let tri = self.triangles[t as usize].map(|k| self.vertices[k as usize]);
            let (d, off, face) = distance_to(p, tri);
            if d > self.reach {
                continue;
            }
            // Squareness: how straight in front of (or behind) the triangle p is.
            let square = if d > 0.0 { (off.dot(face) / d).abs() } else { 1.0 };
            if d < best_d - tie || (d <= best_d + tie && square > best_sq) {
                // (the gradient of the signed distance: outwards)
                let side = if off.dot(face) >= 0.0 { 1.0 } else { -1.0 };
                let n = if d > 1e-12 { off / d * side } else { face };
                best = (side * d, n);
                (best_d, best_sq) = (d, square);
            }
        }
        best
    }

    /// The words (vec4s) the GPU reads for it (`mesh_distance` in colliders.glsl): a header
    /// (the grid's origin and cell; its dims and the reach), the cell starts (one more than the
    /// cells), the items, and each triangle's three vertices, a vec4 each. `layout` gives the
    /// offsets of the three lists.
    pub fn pack(&self) -> Vec<[f32; 4]> {
        let g = &self.grid;
        let u = f32::from_bits;
        let mut words = vec![
            [g.origin.x as f32, g.origin.y as f32, g.origin.z as f32, g.cell as f32],
            [g.dims[0] as f32, g.dims[1] as f32, g.dims[2] as f32, self.reach as f32],
        ];
        for list in [&g.starts, &g.items] {
            for chunk in list.chunks(4) {
                let mut w = [0.0f32; 4];
                for (k, &x) in chunk.iter().enumerate() {
                    w[k] = u(x);
                }
                words.push(w);
            }
        }
        debug_assert_eq!(words.len() as u32, self.layout()[2]);
        for t in &self.triangles {
            for k in t {
                let v = self.vertices[*k as usize];
                words.push([v.x as f32, v.y as f32, v.z as f32, 0.0]);
            }
        }
        words
    }

    /// Its words in all (`pack`'s length).
    pub fn words(&self) -> u32 {
        self.layout()[2] + 3 * self.triangles.len() as u32
    }

    /// Offsets from the header, in vec4s, of the cell starts, the items and the triangles'
    /// vertices as `pack` lays them out.
    pub fn layout(&self) -> [u32; 3] {
        let starts = 2u32;
        let items = starts + self.grid.starts.len().div_ceil(4) as u32;
        let triangles = items + self.grid.items.len().div_ceil(4) as u32;
        [starts, items, triangles]
    }
}

/// The corners (least, greatest) of the box around `points`.
pub fn bounds(points: &[DVec3]) -> (DVec3, DVec3) {
    points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
}

fn cell_of(origin: DVec3, cell: f64, dims: [u32; 3], p: DVec3) -> [u32; 3] {
    let q = ((p - origin) / cell).floor().max(DVec3::ZERO);
    [0, 1, 2].map(|k| (q[k] as u32).min(dims[k] - 1))
}

/// Whether every edge of `triangles` is shared by exactly two of them.
fn every_edge_twice(triangles: &[[u32; 3]]) -> bool {
    let mut edges: Vec<(u32, u32)> = triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.chunk_by(|a, b| a == b).all(|run| run.len() == 2)
}

/// Distance from `p` to triangle `t`, the offset from its nearest point to `p` and its unit
/// face normal (by its winding).
fn distance_to(p: DVec3, t: [DVec3; 3]) -> (f64, DVec3, DVec3) {
    let w = crate::sim::cpu::self_contact::triangle_nearest(p, t[0], t[1], t[2]);
    let off = p - (t[0] * w.x + t[1] * w.y + t[2] * w.z);
    let face = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
    (off.length(), off, face)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A unit cube's 12 triangles, wound outwards.
    pub fn cube(h: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let v = (0..8)
            .map(|i| {
                DVec3::new(
                    if i & 1 == 0 { -h } else { h },
                    if i & 2 == 0 { -h } else { h },
                    if i & 4 == 0 { -h } else { h },
                )
            })
            .collect();
        let quads = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
        let t = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        (v, t)
    }

    /// Against a box's analytic distance wherever the box's nearest point is within reach,
    /// inside and outside, over faces, edges and corners.
    #[test]
    fn a_cube_mesh_measures_as_the_box() {
        let (v, t) = cube(0.5);
        let m = ColliderMesh::new(v, t, 0.1);
        assert!(m.closed);
        let b = crate::sim::collider::Shape::Box {
            center: DVec3::ZERO,
            half_extents: DVec3::splat(0.5),
            rotation: glam::DQuat::IDENTITY,
        };
        let mut checked = 0;
        for i in 0..21 {
            for j in 0..21 {
                for k in 0..21 {
                    let p = DVec3::new(i as f64, j as f64, k as f64) * 0.06 - 0.6;
                    let (exact, en) = b.distance(p);
                    if exact.abs() > 0.09 {
                        continue;
                    }
                    let (d, n) = m.distance(p);
                    assert!((d - exact).abs() < 1e-9, "{p}: {d} against {exact}");
                    // (inside, where two faces are as near, either's normal is right)
                    let q = p.abs() - 0.5;
                    let tie = [(0, 1), (1, 2), (0, 2)].iter().any(|&(a, b)| {
                        (q[a] - q[b]).abs() < 1e-6 && q[a].max(q[b]) >= q.max_element() - 1e-6
                    });
                    if exact.abs() > 1e-9 && (exact > 0.0 || !tie) {
                        assert!((n - en).length() < 1e-6, "{p}: normal {n} against {en}");
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 1000, "{checked}");
        assert_eq!(m.distance(DVec3::new(0.0, 0.7, 0.0)).0, 0.1);
        let far = m.distance(DVec3::new(0.0, 2.0, 0.0)).0;
        assert!((0.1..=1.4 + 1e-9).contains(&far), "{far}");
        assert_eq!(m.distance(DVec3::ZERO).0, 0.1);
    }

    #[test]
    fn bad_meshes_are_named() {
        let (v, mut t) = cube(0.5);
        t.push([0, 0, 1]);
        assert!(ColliderMesh::check(&v, &t).unwrap_err().contains("triangle 12"));
        assert!(ColliderMesh::check(&v, &[[0, 1, 9]]).unwrap_err().contains("vertex 9"));
        let mut far = v.clone();
        far[3].x = f64::NAN;
        assert!(ColliderMesh::check(&far, &cube(0.5).1).unwrap_err().contains("vertex 3"));
        assert!(ColliderMesh::check(&v, &[]).unwrap_err().contains("no triangles"));
        let (v, t) = cube(0.5);
        assert!(!ColliderMesh::new(v, t[..11].to_vec(), 0.1).closed);
    }
}

#[cfg(test)]
mod packing {
    use super::*;

    /// `mesh_distance` in colliders.glsl, step for step in f32 over `pack`'s words: the GPU's
    /// reading of the layout gives the mesh's own distances (to f32 rounding).
    #[test]
    fn the_shaders_reading_of_the_words_gives_the_distances() {
        let (v, t) = tests::cube(0.5);
        let m = ColliderMesh::new(v, t, 0.1);
        let words = m.pack();
        let [_, items, triangles] = m.layout();
        let word = |at: u32, k: u32| words[(at + k / 4) as usize][(k % 4) as usize].to_bits();
        let glsl = |p: glam::Vec3| -> f32 {
            let (h0, h1) = (words[0], words[1]);
            let dims = [h1[0] as u32, h1[1] as u32, h1[2] as u32];
            let q = (p - glam::Vec3::new(h0[0], h0[1], h0[2])) / h0[3];
            let c = q.as_uvec3();
            let cell = c.x + dims[0] * (c.y + dims[1] * c.z);
            let mut best = h1[3];
            let mut best_d = 1e30f32;
            for k in word(2, cell)..word(2, cell + 1) {
                let tri = triangles + 3 * word(items, k);
                let [a, b, c] = [0, 1, 2].map(|j| glam::Vec4::from(words[(tri + j) as usize]).truncate());
                let w = crate::sim::cpu::self_contact::triangle_nearest(
                    p.as_dvec3(),
                    a.as_dvec3(),
                    b.as_dvec3(),
                    c.as_dvec3(),
                );
                let off = p.as_dvec3() - (a.as_dvec3() * w.x + b.as_dvec3() * w.y + c.as_dvec3() * w.z);
                let d = off.length() as f32;
                if d < best_d && d <= h1[3] {
                    let face = (b - a).cross(c - a).normalize();
                    best = if off.as_vec3().dot(face) >= 0.0 { d } else { -d };
                    best_d = d;
                }
            }
            best
        };
        let mut checked = 0;
        for i in 0..41 {
            for j in 0..41 {
                for k in 0..9 {
                    let p = DVec3::new(i as f64 * 0.03 - 0.6, 0.45 + k as f64 * 0.01, j as f64 * 0.03 - 0.6);
                    let (exact, _) = m.distance(p);
                    let g = glsl(p.as_vec3()) as f64;
                    assert!((g - exact).abs() < 1e-6, "{p}: {g} against {exact}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 10_000);
    }
}
