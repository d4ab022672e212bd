//! A cloth made from a mesh (`[[mesh_cloth]]`): its springs, triangles and vertex colouring,
//! built once on the host from the mesh's faces (triangles, quads and polygons, the last split
//! into fans). The springs follow the mesh as a grid's follow its cells, so that a grid written
//! as a quad mesh makes the grid's springs:
//! - structural: one along each edge;
//! - shear: a quad's two diagonals (a triangle's shear is its edges');
//! - bending: across each edge that two faces share, from each end's neighbour in one face
//!   to its neighbour in the other (for two triangles the two opposite vertices; for two quads
//!   the springs that skip a vertex, as a grid's bending springs do). An edge of three or more
//!   faces (non-manifold) has no bending spring across it (`unbent_edges` counts them).
//!
//! - across a seam (`[[mesh_cloth.seam]]`, or those `sew` finds: `found_seams`) as across a
//!   shared edge, where two of its pairs in a row sew a border edge to a border edge, at the
//!   length the pair has with the seam flat.
//!
//! A pair joined twice keeps its first kind in that order. Both simulators read a particle's
//! springs as a list (`springs_of`); the GPU reads the same lists from the words `pack` writes
//! after the object's parameters (glsl/include/mesh_springs.glsl).

use glam::DVec3;
use std::collections::HashMap;

/// Vertices a mesh cloth may have (a particle's index and its spring's kind share a word).
pub const MAX_VERTICES: usize = 1 << 22;
/// Faces a mesh cloth may have.
pub const MAX_FACES: usize = 1 << 23;

/// The integrators a mesh cloth runs with: every one (the place a method added later says
/// whether it does; scene validation and the advice read it).
pub const METHODS: [crate::sim::model::Integrator; 6] = {
    use crate::sim::model::Integrator::*;
    [SymplecticEuler, Verlet, Xpbd, Implicit, Vbd, XpbdJacobi]
};

/// Whether both simulators run object `o` of `model` as it asks: a mesh cloth with one of
/// `METHODS`, without contact between objects, and with self-contact, if
/// any, of its particles against its triangles (what scene validation keeps a preset to,
/// checked again for a model built otherwise; validation also checks the thickness against
/// the rest shape, `thin_enough`, which a model's current positions need not be). The error
/// names the object and what it lacks.
pub fn check_model(
    o: &crate::sim::model::ObjectModel,
    model: &crate::sim::model::SimModel,
) -> Result<(), String> {
    if o.mesh.is_none() {
        return Ok(());
    }
    let lacks = if !METHODS.contains(&model.integrator) {
        format!("the integrator \"{}\"", model.integrator.label())
    } else if model.inter_object_contact() {
        "contact between objects".into()
    } else if o.self_distance.is_some() && !o.has_triangles() {
        "self-collision of particles against particles".into()
    } else if o.has_edge_pairs() {
        "self-collision of edges against edges".into()
    } else {
        return Ok(());
    };
    Err(format!("mesh cloth '{}' does not run with {lacks} yet", o.name))
}

/// Whether a mesh cloth at `rest` can keep its particles `h` from its triangles: no vertex is
/// nearer than that to a triangle outside its one-ring at rest (those pairs would push apart
/// from the start). The error says which and how near.
pub fn thin_enough(mesh: &ClothMesh, rest: &[DVec3], h: f64) -> Result<(), String> {
    match mesh.rest_clearance(rest, h) {
        None => Ok(()),
        Some((d, v, t)) => Err(format!(
            "its self-collision distance {h} m is more than the mesh allows: vertex {v} is {d:.3e} m from \
             triangle {t} at rest, outside its one-ring; set self_collision_distance below that"
        )),
    }
}

/// What a user should know of `model`'s mesh cloths that is not an error: edges shared by
/// three or more faces (allowed; no bending spring crosses them), a line each.
pub fn notes(model: &crate::sim::model::SimModel) -> Vec<String> {
    let meshes = model.objects.iter().filter_map(|o| Some((&o.name, o.mesh.as_ref()?)));
    meshes
        .filter(|(_, m)| m.unbent_edges > 0)
        .map(|(name, m)| {
            format!(
                "mesh cloth '{name}': {} edge{} shared by three or more faces (non-manifold): no bending spring crosses {}",
                m.unbent_edges,
                if m.unbent_edges == 1 { " is" } else { "s are" },
                if m.unbent_edges == 1 { "it" } else { "them" }
            )
        })
        .collect()
}

/// The kind of a seam's spring: rest length zero, the object's seam stiffness.
pub const SEAM: u8 = 3;

/// A spring of a mesh cloth, seen from one end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSpring {
    /// The particle at the other end.
    pub other: u32,
    /// 0 structural, 1 shear, 2 bending (the grid's spring types), 3 a seam (`SEAM`).
    pub kind: u8,
    /// Its rest length in the mesh as placed, before the object's `rest_scale` [m].
    pub rest: f64,
}

impl MeshSpring {
    /// Its rest length with the object's `rest_scale` of its kind (a seam's, zero, unscaled)
    /// [m]: what both simulators and the energy take.
    pub fn scaled_rest(&self, rest_scale: [f64; 3]) -> f64 {
        self.rest * rest_scale.get(self.kind as usize).unwrap_or(&1.0)
    }
}

/// A mesh cloth's topology and what both simulators walk.
#[derive(Debug, Clone, PartialEq)]
pub struct ClothMesh {
    /// Faces as triangles (quads split along their first diagonal, polygons into fans),
    /// counter-clockwise seen from the side the normals point to.
    pub triangles: Vec<[u32; 3]>,
    /// The texture coordinates of each triangle's corners (empty where the file has none).
    pub corner_uvs: Vec<[f32; 2]>,
    /// Per particle, its first entry in `springs`; one more at the end.
    pub spring_first: Vec<u32>,
    pub springs: Vec<MeshSpring>,
    /// A colouring of the particles in which no spring joins two of one colour (the
    /// Gauss-Seidel sweeps'): the particles by colour, and each colour's first entry there,
    /// one more at the end.
    pub colour_order: Vec<u32>,
    pub colour_first: Vec<u32>,
    /// Per particle, its first entry in `ring` (its triangles); one more at the end.
    pub ring_first: Vec<u32>,
    pub ring: Vec<u32>,
    /// The mesh's area as placed [m^2].
    pub area: f64,
    /// Per particle, its mass over the mean particle's: an equal part of the area of each of
    /// its faces (a triangle's third, a quad's quarter: lumped), over the mean share area / n.
    /// On a mesh of triangles the lumped masses' centre is the area's centroid, whatever the
    /// triangles (a quad's corners, which the file may list from any of them, take equal parts
    /// rather than its fan's uneven thirds).
    pub mass_share: Vec<f64>,
    /// The mean length of its edges [m].
    pub mean_edge: f64,
    /// The longest of its structural and shear springs and its triangles' edges [m].
    pub longest: f64,
    /// Edges shared by three or more faces (no bending spring across them).
    pub unbent_edges: usize,
    /// `rest_clearance`'s nearest pair, once found.
    nearest_at_rest: Kept<Option<(f64, usize, usize)>>,
    /// XPBD's spring classes, in the order it sweeps them (`spring_classes`), made when first
    /// asked for (only XPBD by spring classes sweeps them): each spring as its lower end and
    /// its entry in that end's list, and each class's first there, one more at the end.
    classes: Kept<(Vec<[u32; 2]>, Vec<u32>)>,
}

/// A value computed once from what holds it: no part of what it is equal to.
#[derive(Debug, Clone, Default)]
struct Kept<T>(std::sync::OnceLock<T>);

impl<T> PartialEq for Kept<T> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl ClothMesh {
    /// The mesh of particles at `rest` (placed) and `faces` (each a polygon of vertex
    /// indices, counter-clockwise), with each face corner's texture coordinates (`uvs`, one
    /// per corner in face order, or empty), sewn by `seams` (each seam its pairs in order
    /// along it). The error names the first bad face, vertex or seam pair.
    pub fn new(
        rest: &[DVec3],
        faces: &[Vec<u32>],
        uvs: &[[f32; 2]],
        seams: &[Vec<[u32; 2]>],
    ) -> Result<Self, String> {
        check(rest, faces)?;
        let n = rest.len();
        for (s, seam) in seams.iter().enumerate() {
            for (k, &[a, b]) in seam.iter().enumerate() {
                if a as usize >= n || b as usize >= n || a == b {
                    return Err(format!(
                        "seam[{s}] pair {k} ({a}, {b}): a seam joins two different vertices of its {n}"
                    ));
                }
            }
        }
        let mut kinds: HashMap<(u32, u32), u8> = HashMap::new();
        // (a pair, its kind, and its rest length where it is not the pair's distance at rest)
        let mut order: Vec<(u32, u32, u8, Option<f64>)> = Vec::new();
        let mut join = |a: u32, b: u32, kind: u8, rest_length: Option<f64>| {
            let key = (a.min(b), a.max(b));
            if a != b && !kinds.contains_key(&key) {
                kinds.insert(key, kind);
                order.push((key.0, key.1, kind, rest_length));
            }
        };
        // Structural first, then shear, then bending: a pair keeps its first kind.
        for face in faces {
            for (k, &a) in face.iter().enumerate() {
                join(a, face[(k + 1) % face.len()], 0, None);
            }
        }
        let edge_faces = edge_faces(faces);
        for face in faces.iter().filter(|f| f.len() == 4) {
            join(face[0], face[2], 1, None);
            join(face[1], face[3], 1, None);
        }
        let mut unbent_edges = 0;
        let mut shared: Vec<_> = edge_faces.iter().filter(|(_, f)| f.len() >= 2).collect();
        shared.sort_unstable_by_key(|(e, _)| **e);
        for (&(a, b), fs) in shared {
            if fs.len() > 2 {
                unbent_edges += 1;
                continue;
            }
            let (f, g) = (&faces[fs[0]], &faces[fs[1]]);
            join(beside(f, a, b), beside(g, a, b), 2, None);
            join(beside(f, b, a), beside(g, b, a), 2, None);
        }
        // Seams last: a pair the mesh joins already keeps its spring.
        for &[a, b] in seams.iter().flatten() {
            join(a, b, SEAM, None);
        }
        // Bending across a seam as across an edge two faces share: where two pairs in a row
        // sew a border edge of one side to a border edge of the other, from each end's
        // neighbour in the one's face to its neighbour in the other's, at the length it has
        // with the seam sewn flat (so that the cloth beside a seam bends as elsewhere, not as
        // a hinge; an open seam's bending springs also pull it closed, at their stiffness).
        let border_face = |a: u32, b: u32| match edge_faces.get(&(a.min(b), a.max(b))) {
            Some(fs) if fs.len() == 1 => Some(&faces[fs[0]]),
            _ => None,
        };
        for w in seams.iter().flat_map(|seam| seam.windows(2)) {
            let ([a0, b0], [a1, b1]) = (w[0], w[1]);
            let (Some(f), Some(g)) = (border_face(a0, a1), border_face(b0, b1)) else { continue };
            for ((a, a_next), (b, b_next)) in [((a0, a1), (b0, b1)), ((a1, a0), (b1, b0))] {
                let (p, q) = (beside(f, a, a_next), beside(g, b, b_next));
                // Unfolded flat, p and q lie either side of the seam edge, at angles tp and tq
                // from it at its end a = b: |p - q|^2 = lp^2 + lq^2 - 2 lp lq cos(tp + tq).
                let at = |v: u32| rest[v as usize];
                let (ep, eq) = (at(p) - at(a), at(q) - at(b));
                let angle = ep.angle_between(at(a_next) - at(a)) + eq.angle_between(at(b_next) - at(b));
                let (lp, lq) = (ep.length(), eq.length());
                let flat = (lp * lp + lq * lq - 2.0 * lp * lq * angle.cos()).max(0.0).sqrt();
                join(p, q, 2, Some(flat));
            }
        }
        let mut lists: Vec<Vec<MeshSpring>> = vec![Vec::new(); n];
        for (a, b, kind, given) in order {
            let rest_length = match given {
                Some(length) => length,
                None if kind == SEAM => 0.0,
                None => (rest[a as usize] - rest[b as usize]).length(),
            };
            lists[a as usize].push(MeshSpring { other: b, kind, rest: rest_length });
            lists[b as usize].push(MeshSpring { other: a, kind, rest: rest_length });
        }
        let mut spring_first = Vec::with_capacity(n + 1);
        let mut springs = Vec::new();
        for list in &mut lists {
            spring_first.push(springs.len() as u32);
            list.sort_by_key(|s| (s.kind, s.other));
            springs.append(list);
        }
        spring_first.push(springs.len() as u32);
        let mut triangles = Vec::new();
        let mut corner_uvs = Vec::new();
        let mut corner = 0;
        for face in faces {
            for k in 1..face.len() - 1 {
                triangles.push([face[0], face[k], face[k + 1]]);
                if !uvs.is_empty() {
                    corner_uvs.extend([uvs[corner], uvs[corner + k], uvs[corner + k + 1]]);
                }
            }
            corner += face.len();
        }
        // Each face's area from its fan's triangles (each face has some, `check`).
        let face_areas: Vec<f64> = faces
            .iter()
            .map(|face| {
                let at = |k: usize| rest[face[k] as usize];
                (1..face.len() - 1).map(|k| 0.5 * (at(k) - at(0)).cross(at(k + 1) - at(0)).length()).sum()
            })
            .collect();
        let area: f64 = face_areas.iter().sum();
        let mut mass_share = vec![0.0; n];
        for (face, face_area) in faces.iter().zip(&face_areas) {
            let part = face_area / face.len() as f64 * n as f64 / area;
            face.iter().for_each(|&k| mass_share[k as usize] += part);
        }
        let edges: Vec<f64> = springs.iter().filter(|s| s.kind == 0).map(|s| s.rest).collect();
        let mean_edge = edges.iter().sum::<f64>() / edges.len().max(1) as f64;
        // (a polygon's fan diagonals are no springs, but its triangles reach that far)
        let fan = triangles.iter().flat_map(|t| {
            let [a, b, c] = t.map(|k| rest[k as usize]);
            [(a - b).length(), (b - c).length(), (c - a).length()]
        });
        let longest = springs.iter().filter(|s| s.kind < 2).map(|s| s.rest).chain(fan).fold(0.0, f64::max);
        let (colour_order, colour_first) = colouring(&spring_first, &springs);
        let mut rings: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (t, tri) in triangles.iter().enumerate() {
            tri.iter().for_each(|&k| rings[k as usize].push(t as u32));
        }
        let ring_first = std::iter::once(0)
            .chain(rings.iter().scan(0u32, |at, r| {
                *at += r.len() as u32;
                Some(*at)
            }))
            .collect();
        Ok(Self {
            ring_first,
            ring: rings.into_iter().flatten().collect(),
            triangles,
            corner_uvs,
            spring_first,
            springs,
            colour_order,
            colour_first,
            area,
            mass_share,
            mean_edge,
            longest,
            unbent_edges,
            nearest_at_rest: Kept::default(),
            classes: Kept::default(),
        })
    }

    /// Particle i's springs.
    pub fn springs_of(&self, i: usize) -> &[MeshSpring] {
        &self.springs[self.spring_first[i] as usize..self.spring_first[i + 1] as usize]
    }

    /// The most structural and shear springs (those the stretch limit limits) a particle has.
    pub fn most_limited_springs(&self) -> usize {
        let limited = |i: usize| self.springs_of(i).iter().filter(|s| s.kind < 2).count();
        (0..self.spring_first.len() - 1).map(limited).max().unwrap_or(0)
    }

    /// Whether vertex j is particle p or joined to it by a structural, shear or seam spring:
    /// p's one-ring, as a grid's eight neighbours are (self-contact leaves out the triangles it
    /// touches; `mesh_linked` in glsl/include/mesh_springs.glsl).
    /// Vertices a seam sews together count as one: the one-ring of either is both's.
    pub fn linked(&self, p: usize, j: usize) -> bool {
        let direct = |u: usize, w: usize| {
            u == w || self.springs_of(u).iter().any(|s| s.other as usize == w && s.kind != 2)
        };
        let sewn = |u: usize| self.springs_of(u).iter().filter(|s| s.kind == SEAM).map(|s| s.other as usize);
        direct(p, j)
            || sewn(p).any(|u| direct(u, j) || sewn(j).any(|w| direct(u, w)))
            || sewn(j).any(|w| direct(p, w))
    }

    /// A vertex nearer than `within` at `rest` (the positions it was built at) to a triangle
    /// outside its one-ring (`linked`), as (the distance, the vertex, the triangle): self-contact
    /// of that thickness would push them apart from the start, so a mesh cloth's thickness must
    /// stay below the distance. The nearest such pair within the longest edge is found once and
    /// kept (validation asks again at every edit); a thickness past that edge searches again,
    /// for the first vertex in index order with a pair within it.
    pub fn rest_clearance(&self, rest: &[DVec3], within: f64) -> Option<(f64, usize, usize)> {
        if within > self.longest {
            return self.nearest_pair(rest, within, true);
        }
        let nearest = *self.nearest_at_rest.0.get_or_init(|| self.nearest_pair(rest, self.longest, false));
        nearest.filter(|n| n.0 < within)
    }

    /// The nearest pair of `rest_clearance` within `within`, or with `first` the first vertex's.
    fn nearest_pair(&self, rest: &[DVec3], within: f64, first: bool) -> Option<(f64, usize, usize)> {
        // Triangles by the cells (as wide as `within` or the longest edge) their boxes touch:
        // a triangle within `within` of a vertex touches one of the 27 cells about it.
        let cell = within.max(self.longest).max(f64::MIN_POSITIVE);
        let key = |x: DVec3| (x / cell).floor().as_i64vec3().to_array();
        let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        for (t, tri) in self.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|k| rest[k as usize]);
            let (lo, hi) = (key(a.min(b).min(c)), key(a.max(b).max(c)));
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        cells.entry([x, y, z]).or_default().push(t as u32);
                    }
                }
            }
        }
        let mut nearest: Option<(f64, usize, usize)> = None;
        for (p, &x) in rest.iter().enumerate() {
            let at = key(x);
            let near =
                (-1..=1).flat_map(|dx| (-1..=1).flat_map(move |dy| (-1..=1).map(move |dz| [dx, dy, dz])));
            for d in near {
                let c = [0, 1, 2].map(|k| at[k].saturating_add(d[k]));
                let Some(ts) = cells.get(&c) else { continue };
                for &t in ts {
                    let tri = self.triangles[t as usize];
                    if tri.iter().any(|&k| self.linked(p, k as usize)) {
                        continue;
                    }
                    let [a, b, c] = tri.map(|k| rest[k as usize]);
                    let w = crate::sim::cpu::self_contact::triangle_nearest(x, a, b, c);
                    let dist = (x - (a * w.x + b * w.y + c * w.z)).length();
                    if dist < within && nearest.is_none_or(|n| dist < n.0) {
                        nearest = Some((dist, p, t as usize));
                    }
                }
            }
            if first && nearest.is_some() {
                break;
            }
        }
        nearest
    }

    pub fn colour_count(&self) -> usize {
        self.colour_first.len() - 1
    }

    /// The triangles about particle i.
    pub fn ring_of(&self, i: usize) -> impl Iterator<Item = [u32; 3]> + '_ {
        let ring = &self.ring[self.ring_first[i] as usize..self.ring_first[i + 1] as usize];
        ring.iter().map(|&t| self.triangles[t as usize])
    }

    /// XPBD's spring classes: the springs class by class and the classes' firsts.
    fn classes(&self) -> &(Vec<[u32; 2]>, Vec<u32>) {
        self.classes.0.get_or_init(|| spring_classes(&self.spring_first, &self.springs))
    }

    /// XPBD's spring classes: how many.
    pub fn class_count(&self) -> usize {
        self.classes().1.len() - 1
    }

    /// Class c's springs, each its lower end and its entry in that end's list.
    pub fn class(&self, c: usize) -> &[[u32; 2]] {
        let (springs, first) = self.classes();
        &springs[first[c] as usize..first[c + 1] as usize]
    }

    /// The particles of colour c.
    pub fn colour(&self, c: usize) -> &[u32] {
        &self.colour_order[self.colour_first[c] as usize..self.colour_first[c + 1] as usize]
    }

    /// How many words `pack` writes (`classes`: with XPBD's spring classes).
    pub fn word_count(&self, classes: bool) -> u64 {
        let n = self.spring_first.len() as u64 - 1;
        let lists =
            2 * self.springs.len() + self.colour_first.len() + 3 * self.triangles.len() + self.ring.len();
        let classes = match classes {
            true => self.classes().1.len() + 2 * self.classes().0.len(),
            false => 0,
        };
        // (header, spring firsts, colour count, colour order, ring firsts, mass shares, class
        // count; then the lists)
        6 + (n + 1) + 1 + n + (n + 1) + n + 1 + (lists + classes) as u64
    }

    /// The words the GPU reads after the object's parameters (glsl/include/mesh_springs.glsl):
    /// a header of where the spring entries, colours, triangles, rings, mass shares and spring
    /// classes start;
    /// the n + 1 spring firsts; a spring as two words (other end | kind << 30, its rest length
    /// scaled by `rest_scale` as f32 bits); the colour count C, the C + 1 colour firsts and the
    /// particles by colour; the triangles' corners; each particle's n + 1 ring firsts and
    /// then its triangles; each particle's `mass_share` as f32 bits; with `classes` (XPBD by
    /// spring classes; else none) the class count C, the C + 1 class firsts and each spring of
    /// the classes as its lower end and its entry.
    pub fn pack(&self, rest_scale: [f64; 3], classes: bool) -> Vec<u32> {
        let mut w = vec![0u32; 6];
        w.extend(&self.spring_first);
        w[0] = w.len() as u32;
        for s in &self.springs {
            w.push(s.other | (s.kind as u32) << 30);
            w.push((s.scaled_rest(rest_scale) as f32).to_bits());
        }
        w[1] = w.len() as u32;
        w.push(self.colour_count() as u32);
        w.extend(&self.colour_first);
        w.extend(&self.colour_order);
        w[2] = w.len() as u32;
        w.extend(self.triangles.iter().flatten());
        w[3] = w.len() as u32;
        w.extend(&self.ring_first);
        w.extend(&self.ring);
        w[4] = w.len() as u32;
        w.extend(self.mass_share.iter().map(|&m| (m as f32).to_bits()));
        w[5] = w.len() as u32;
        match classes {
            true => {
                let (springs, first) = self.classes();
                w.push(self.class_count() as u32);
                w.extend(first);
                w.extend(springs.iter().flatten());
            }
            false => w.push(0),
        }
        w
    }
}

/// Each edge of `faces` (its ends, lower first) and the faces it borders.
fn edge_faces(faces: &[Vec<u32>]) -> HashMap<(u32, u32), Vec<usize>> {
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        for (k, &a) in face.iter().enumerate() {
            let b = face[(k + 1) % face.len()];
            edge_faces.entry((a.min(b), a.max(b))).or_default().push(f);
        }
    }
    edge_faces
}

/// The cell of `p` in a spatial grid of cells `size` wide.
fn cell_of(p: DVec3, size: f64) -> [i64; 3] {
    (p / size).floor().as_i64vec3().to_array()
}

/// Cell `c` and the 26 around it: where a search within one cell's width of a point in `c`
/// looks.
fn cells_around(c: [i64; 3]) -> impl Iterator<Item = [i64; 3]> {
    (0..27).map(move |n| [c[0] + n % 3 - 1, c[1] + n / 3 % 3 - 1, c[2] + n / 9 - 1])
}

/// The vertices of `faces` with those within `tolerance` of an earlier one merged into it
/// (0: those at the very same place), renumbered in order of their first appearance.
pub fn weld(vertices: &[DVec3], faces: &[Vec<u32>], tolerance: f64) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let cell = |p: DVec3| match tolerance > 0.0 {
        true => cell_of(p, tolerance),
        false => p.to_array().map(|c| (c + 0.0).to_bits() as i64),
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut kept: Vec<DVec3> = Vec::new();
    let mut to: Vec<u32> = Vec::with_capacity(vertices.len());
    for &p in vertices {
        let c = cell(p);
        let near = |c: [i64; 3]| {
            grid.get(&c).into_iter().flatten().copied().find(|&k| kept[k as usize].distance(p) <= tolerance)
        };
        let found = match tolerance > 0.0 {
            true => cells_around(c).find_map(near),
            false => near(c),
        };
        to.push(found.unwrap_or_else(|| {
            grid.entry(c).or_default().push(kept.len() as u32);
            kept.push(p);
            kept.len() as u32 - 1
        }));
    }
    let faces =
        faces.iter().map(|f| f.iter().map(|&k| to.get(k as usize).copied().unwrap_or(k)).collect()).collect();
    (kept, faces)
}

/// The seams a mesh cloth's `sew` finds (`within` > 0): each border vertex (on an edge of one
/// face) sewn to the nearest border vertex within `within` that is not on its faces nor on
/// theirs' (two faces away), as
/// Marvelous Designer's panels laid round a body are sewn where their edges meet. Given as
/// runs of two pairs where a border edge is sewn to a border edge (what `ClothMesh::new`
/// bends across), then the other pairs alone. The error says where `within` reaches a
/// vertex's own border (a border edge no longer than it: it would sew a border to itself), or
/// that it sews nothing.
pub fn found_seams(rest: &[DVec3], faces: &[Vec<u32>], within: f64) -> Result<Vec<Vec<[u32; 2]>>, String> {
    let edge_faces = edge_faces(faces);
    let on_one = |e: &(u32, u32)| edge_faces.get(e).is_some_and(|f| f.len() == 1);
    let mut border: Vec<(u32, u32)> = edge_faces.keys().copied().filter(on_one).collect();
    border.sort_unstable();
    let length = |(a, b): (u32, u32)| rest[a as usize].distance(rest[b as usize]);
    if let Some(&e) = border.iter().find(|&&e| length(e) <= within) {
        return Err(format!(
            "sew = {within} m reaches along its own border: border edge ({}, {}) is {:.4} m long; \
             sew less than its border's edges",
            e.0,
            e.1,
            length(e)
        ));
    }
    let mut on_border = vec![false; rest.len()];
    border.iter().for_each(|&(a, b)| (on_border[a as usize], on_border[b as usize]) = (true, true));
    // Each border vertex's near vertices: those of its faces and of their faces (two faces
    // away: at a sharp corner of its border the vertex two edges along can come within reach
    // of it, and sewing them would pucker the corner).
    let mut vertex_faces: Vec<Vec<u32>> = vec![Vec::new(); rest.len()];
    for (f, face) in faces.iter().enumerate() {
        face.iter().for_each(|&v| vertex_faces[v as usize].push(f as u32));
    }
    let ring = |v: u32| vertex_faces[v as usize].iter().flat_map(|&f| faces[f as usize].iter().copied());
    let mut face_mates: HashMap<u32, Vec<u32>> = HashMap::new();
    for a in (0..rest.len() as u32).filter(|&a| on_border[a as usize]) {
        let mut near: Vec<u32> = ring(a).flat_map(ring).collect();
        near.sort_unstable();
        near.dedup();
        face_mates.insert(a, near);
    }
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (i, _) in on_border.iter().enumerate().filter(|(_, &b)| b) {
        grid.entry(cell_of(rest[i], within)).or_default().push(i as u32);
    }
    let partner: Vec<Option<u32>> = (0..rest.len() as u32)
        .map(|a| {
            let p = rest[a as usize];
            let mates = face_mates.get(&a)?;
            cells_around(cell_of(p, within))
                .flat_map(|c| grid.get(&c))
                .flatten()
                .filter(|&&b| mates.binary_search(&b).is_err() && rest[b as usize].distance(p) <= within)
                .min_by(|&&b, &&d| {
                    rest[b as usize].distance(p).total_cmp(&rest[d as usize].distance(p)).then(b.cmp(&d))
                })
                .copied()
        })
        .collect();
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut seams = Vec::new();
    let mut sewn = std::collections::HashSet::new();
    for &(a0, a1) in &border {
        let (Some(b0), Some(b1)) = (partner[a0 as usize], partner[a1 as usize]) else { continue };
        // (found from both sides: one run of the two)
        let (p, q) = (key(a0, b0), key(a1, b1));
        if b0 != b1 && on_one(&key(b0, b1)) && sewn.insert((p.min(q), p.max(q))) {
            seams.push(vec![[a0, b0], [a1, b1]]);
        }
    }
    let mut paired: std::collections::HashSet<(u32, u32)> =
        seams.iter().flatten().map(|&[a, b]| key(a, b)).collect();
    for (a, b) in partner.iter().enumerate().filter_map(|(a, b)| Some((a as u32, (*b)?))) {
        if paired.insert(key(a, b)) {
            seams.push(vec![[a, b]]);
        }
    }
    if seams.is_empty() {
        return Err(format!("sew = {within} m finds no border vertex that near another's"));
    }
    Ok(seams)
}

/// The vertex of `face` next to `a` that is not `b` (`a` and `b` an edge of it).
fn beside(face: &[u32], a: u32, b: u32) -> u32 {
    let k = face.iter().position(|&v| v == a).expect("an edge's end is in its face");
    let (prev, next) = (face[(k + face.len() - 1) % face.len()], face[(k + 1) % face.len()]);
    if next == b {
        prev
    } else {
        next
    }
}

/// Checks a mesh before its springs are built: faces to take, vertices finite and used, every
/// face of three or more distinct vertices it has, with an area.
fn check(rest: &[DVec3], faces: &[Vec<u32>]) -> Result<(), String> {
    if faces.is_empty() {
        return Err("it has no faces".into());
    }
    if faces.len() > MAX_FACES || rest.len() > MAX_VERTICES {
        return Err(format!(
            "it has {} vertices and {} faces; a mesh cloth takes at most {MAX_VERTICES} and {MAX_FACES}",
            rest.len(),
            faces.len()
        ));
    }
    if let Some(i) = rest.iter().position(|v| !v.is_finite()) {
        return Err(format!("vertex {i} is at {:?}: not a finite coordinate", rest[i]));
    }
    let mut used = vec![false; rest.len()];
    for (i, f) in faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(format!("face {i} has {} vertices; a face has three or more", f.len()));
        }
        if let Some(&k) = f.iter().find(|&&k| k as usize >= rest.len()) {
            return Err(format!("face {i} names vertex {k}, past its {} vertices", rest.len()));
        }
        let mut distinct = f.clone();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() < f.len() {
            return Err(format!("face {i} names a vertex twice {f:?} (welded together?)"));
        }
        let p: Vec<DVec3> = f.iter().map(|&k| rest[k as usize]).collect();
        let longest = (0..p.len()).map(|k| (p[(k + 1) % p.len()] - p[k]).length()).fold(0.0, f64::max);
        let normal = (1..p.len() - 1).fold(DVec3::ZERO, |s, k| s + (p[k] - p[0]).cross(p[k + 1] - p[0]));
        let area = 0.5 * normal.length();
        if area.is_nan() || area <= 1e-12 * longest * longest {
            return Err(format!("face {i} (vertices {f:?}) has no area"));
        }
        f.iter().for_each(|&k| used[k as usize] = true);
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(format!("vertex {i} belongs to no face (it would fall on its own)"));
    }
    Ok(())
}

/// XPBD's spring classes (Gauss-Seidel over the springs, as a grid's `SPRING_CLASSES`): a
/// greedy colouring of the springs in which no two of a class share a particle, the bending
/// springs' classes first, then the shear springs', then the structural and seam springs'
/// (the structural last, as on a grid: `sim::integrator::xpbd_class_order` says why). Each
/// spring is its lower end and its entry in that end's list; returns them class by class and
/// each class's first, one more at the end.
fn spring_classes(first: &[u32], springs: &[MeshSpring]) -> (Vec<[u32; 2]>, Vec<u32>) {
    let n = first.len() - 1;
    let (mut order, mut class_first) = (Vec::new(), vec![0u32]);
    for kinds in [&[2u8][..], &[1], &[0, SEAM]] {
        // (each particle's classes taken so far, as bits of the group's classes in use)
        let mut taken: Vec<Vec<u64>> = vec![Vec::new(); n];
        let mut classes: Vec<Vec<[u32; 2]>> = Vec::new();
        for a in 0..n {
            for e in first[a]..first[a + 1] {
                let s = &springs[e as usize];
                let b = s.other as usize;
                if b < a || !kinds.contains(&s.kind) {
                    continue;
                }
                let used = |v: &[u64], c: usize| v.get(c / 64).is_some_and(|w| w >> (c % 64) & 1 == 1);
                let c = (0..).find(|&c| !used(&taken[a], c) && !used(&taken[b], c)).expect("a free class");
                for v in [a, b] {
                    if taken[v].len() <= c / 64 {
                        taken[v].resize(c / 64 + 1, 0);
                    }
                    taken[v][c / 64] |= 1 << (c % 64);
                }
                if classes.len() <= c {
                    classes.resize(c + 1, Vec::new());
                }
                classes[c].push([a as u32, e]);
            }
        }
        for class in classes {
            order.extend(class);
            class_first.push(order.len() as u32);
        }
    }
    (order, class_first)
}

/// The particles by colour and the colours' firsts, from `sim::colouring`'s colouring of the
/// spring graph.
fn colouring(first: &[u32], springs: &[MeshSpring]) -> (Vec<u32>, Vec<u32>) {
    let n = first.len() - 1;
    let other: Vec<u32> = springs.iter().map(|s| s.other).collect();
    let colour = super::colouring::colour(&super::colouring::Graph { first, other: &other });
    let count = colour.iter().max().map_or(0, |c| *c as usize + 1);
    let mut colour_first = vec![0u32; count + 1];
    for &c in &colour {
        colour_first[c as usize + 1] += 1;
    }
    for c in 0..count {
        colour_first[c + 1] += colour_first[c];
    }
    let mut next = colour_first.clone();
    let mut colour_order = vec![0u32; n];
    for (i, &c) in colour.iter().enumerate() {
        colour_order[next[c as usize] as usize] = i as u32;
        next[c as usize] += 1;
    }
    (colour_order, colour_first)
}

/// A grid of `cols x rows` particles at `positions` as quads (column-major within a row as
/// the grid's particles are), for tests and the grid's export as a mesh.
pub fn grid_quads(cols: u32, rows: u32) -> Vec<Vec<u32>> {
    let mut faces = Vec::new();
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            let i = c + r * cols;
            faces.push(vec![i, i + 1, i + 1 + cols, i + cols]);
        }
    }
    faces
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat grid of `cols` x `rows` rest positions in the x-z plane, `dx` and `dz` apart,
    /// from x = `x0`, in grid_quads' order.
    fn flat_grid(cols: u32, rows: u32, x0: f64, dx: f64, dz: f64) -> Vec<DVec3> {
        (0..cols * rows)
            .map(|i| DVec3::new(x0 + (i % cols) as f64 * dx, 0.0, (i / cols) as f64 * dz))
            .collect()
    }

    /// Two 3 x 3 panels of quads sewn along a border (A's last column to B's first) bend across
    /// the seam as one grid of 5 columns does across its middle column: a bending spring from
    /// A's middle column to B's in every row, of two spacings (the seam sewn flat), though the
    /// panels lie apart; not where the pairs are seams of their own.
    #[test]
    fn a_seam_bends_as_the_grid_it_sews() {
        let s = 0.1;
        let mut rest = flat_grid(3, 3, 0.0, s, s);
        rest.extend(flat_grid(3, 3, 2.0 * s + 0.3, s, s));
        let mut faces = grid_quads(3, 3);
        faces.extend(grid_quads(3, 3).into_iter().map(|f| f.into_iter().map(|v| v + 9).collect()));
        let seams: [Vec<[u32; 2]>; 1] = [(0..3).map(|r| [3 * r + 2, 9 + 3 * r]).collect()];
        let m = ClothMesh::new(&rest, &faces, &[], &seams).unwrap();
        for r in 0..3u32 {
            let across: Vec<&MeshSpring> =
                m.springs_of((3 * r + 1) as usize).iter().filter(|s| s.other >= 9).collect();
            assert_eq!(across.len(), 1, "row {r}: {across:?}");
            assert_eq!((across[0].other, across[0].kind), (9 + 3 * r + 1, 2), "row {r}");
            assert!((across[0].rest - 2.0 * s).abs() < 1e-12, "row {r}: {}", across[0].rest);
        }
        // The same pairs as three seams of one pair each: no two pairs of one seam in a row,
        // so no bending spring crosses.
        let single: Vec<Vec<[u32; 2]>> = seams[0].iter().map(|&p| vec![p]).collect();
        let m = ClothMesh::new(&rest, &faces, &[], &single).unwrap();
        assert!((0..9).all(|p| m.springs_of(p).iter().all(|s| s.other < 9 || s.kind != 2)));
    }

    /// The same panels as triangles (each quad split along its first diagonal, so the seam's
    /// ends meet their faces at 45 and 90 degrees): every bending spring across the seam is as
    /// long as its ends are apart with the second panel moved flat onto the first (the seam
    /// sewn flat); and a seamed vertex's one-ring holds its partner's neighbours.
    #[test]
    fn a_seam_of_triangles_bends_at_its_flat_length() {
        let (s, gap) = (0.1, 0.3);
        let mut rest = flat_grid(3, 3, 0.0, s, s);
        rest.extend(flat_grid(3, 3, 2.0 * s + gap, s, s));
        let split = |q: Vec<u32>| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]];
        let mut faces: Vec<Vec<u32>> = grid_quads(3, 3).into_iter().flat_map(split).collect();
        let second = grid_quads(3, 3).into_iter().map(|f| f.into_iter().map(|v| v + 9).collect());
        faces.extend(second.flat_map(split));
        let seams: [Vec<[u32; 2]>; 1] = [(0..3).map(|r| [3 * r + 2, 9 + 3 * r]).collect()];
        let m = ClothMesh::new(&rest, &faces, &[], &seams).unwrap();
        let mut across = 0;
        for p in 0..9 {
            for sp in m.springs_of(p).iter().filter(|sp| sp.other >= 9 && sp.kind == 2) {
                let flat = (rest[p] - (rest[sp.other as usize] - DVec3::new(gap, 0.0, 0.0))).length();
                assert!((sp.rest - flat).abs() < 1e-12, "{p}-{}: {} against {flat}", sp.other, sp.rest);
                across += 1;
            }
        }
        assert!(across >= 2, "{across} bending springs across the seam");
        // Vertex 2 (sewn to 9) has 9's neighbours 10 and 12 in its one-ring, and they its.
        assert!(m.linked(2, 10) && m.linked(2, 12) && m.linked(10, 2) && !m.linked(2, 11));
    }

    /// `sew` on two 4 x 4 panels of triangles a gap apart (g = 0.04 m, spacings s = 0.1 m)
    /// finds the seam one would list, A's last column to B's first, row by row: 4 pairs, each
    /// g apart, and the same springs, bending ones across included, as that list given as a
    /// seam; reaching to g it finds nothing, and reaching a border edge's length it is refused
    /// (it would sew a border to itself). Rolled into a tube, one panel's sides sew to each
    /// other the same way.
    #[test]
    fn sewing_finds_the_seam_one_would_list() {
        let (s, g) = (0.1, 0.04);
        let mut rest = flat_grid(4, 4, 0.0, s, s);
        rest.extend(flat_grid(4, 4, 3.0 * s + g, s, s));
        let split = |q: Vec<u32>| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]];
        let mut faces: Vec<Vec<u32>> = grid_quads(4, 4).into_iter().flat_map(split).collect();
        let second = grid_quads(4, 4).into_iter().map(|f| f.into_iter().map(|v| v + 16).collect());
        faces.extend(second.flat_map(split));
        let listed: Vec<[u32; 2]> = (0..4).map(|r| [4 * r + 3, 16 + 4 * r]).collect();
        let found = found_seams(&rest, &faces, 1.5 * g).unwrap();
        let mut pairs: Vec<[u32; 2]> = found.iter().flatten().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
        pairs.sort_unstable();
        pairs.dedup();
        assert_eq!(pairs, listed, "{found:?}");
        assert_eq!(found.iter().filter(|run| run.len() == 2).count(), 3, "{found:?}");
        assert!(pairs.iter().all(|&[a, b]| (rest[a as usize].distance(rest[b as usize]) - g).abs() < 1e-12));
        let by_list = ClothMesh::new(&rest, &faces, &[], std::slice::from_ref(&listed)).unwrap();
        let by_sew = ClothMesh::new(&rest, &faces, &[], &found).unwrap();
        assert_eq!((&by_sew.spring_first, &by_sew.springs), (&by_list.spring_first, &by_list.springs));
        assert!(by_sew.springs.iter().any(|sp| sp.kind == 2 && sp.rest > 1.9 * s), "no bending across it");
        let err = found_seams(&rest, &faces, 0.99 * g).unwrap_err();
        assert!(err.contains("finds no border vertex"), "{err}");
        let err = found_seams(&rest, &faces, s).unwrap_err();
        assert!(err.contains("reaches along its own border"), "{err}");
        // One panel of 8 columns rolled round a 7-sided ring, less a gap between its sides.
        let turn = |c: u32| 2.0 * std::f64::consts::PI * (c as f64 - 0.5) / 7.2;
        let tube: Vec<DVec3> =
            (0..24).map(|i| DVec3::new(turn(i % 8).cos(), (i / 8) as f64, turn(i % 8).sin())).collect();
        let faces = grid_quads(8, 3);
        let found = found_seams(&tube, &faces, 0.2).unwrap();
        let mut pairs: Vec<[u32; 2]> = found.iter().flatten().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
        pairs.sort_unstable();
        pairs.dedup();
        assert_eq!(pairs, [[0, 7], [8, 15], [16, 23]], "{found:?}");
    }

    /// A flat grid of quads, whose one-rings are a grid's eight neighbours (a quad's diagonals
    /// are shear springs), has its nearest pair outside a one-ring two spacings apart at rest,
    /// as a grid has (a thickness below it passes, one above it is refused); a seam joins its
    /// two ends' rings; two squares 1 cm apart are 1 cm apart.
    #[test]
    fn the_rest_clearance_is_the_nearest_pair_outside_a_one_ring() {
        let (cols, rows) = (5u32, 4u32);
        let rest = flat_grid(cols, rows, 0.0, 0.1, 0.1);
        let m = ClothMesh::new(&rest, &grid_quads(cols, rows), &[], &[vec![[0, 4]]]).unwrap();
        let linked = [1, 5, 6, 4, 10, 2].map(|j| m.linked(0, j));
        assert_eq!(linked, [true, true, true, true, false, false]);
        assert_eq!(m.rest_clearance(&rest, 0.199), None);
        let (d, v, t) = m.rest_clearance(&rest, 0.25).unwrap();
        assert!((d - 0.2).abs() < 1e-12 && v == 0, "{d} {v} {t}");
        assert!(!m.triangles[t].iter().any(|&k| m.linked(v, k as usize)));
        let square = [rest[0], rest[1], rest[5], rest[6]];
        let mut two = square.to_vec();
        two.extend(square.iter().map(|p| *p + DVec3::new(0.0, 0.01, 0.0)));
        let m = ClothMesh::new(&two, &[vec![0, 1, 3, 2], vec![4, 5, 7, 6]], &[], &[]).unwrap();
        let (d, v, _) = m.rest_clearance(&two, 0.05).unwrap();
        assert!((d - 0.01).abs() < 1e-12 && v == 0, "{d} {v}");
    }

    /// A grid written as quads makes the grid's springs: each particle's springs are those
    /// of its 12 grid offsets inside the grid, of the same types; the colouring is proper.
    #[test]
    fn a_quad_grid_makes_the_grids_springs() {
        let (cols, rows) = (6u32, 5u32);
        let rest = flat_grid(cols, rows, 0.0, 0.1, 0.2);
        let m = ClothMesh::new(&rest, &grid_quads(cols, rows), &[], &[]).unwrap();
        let offsets: [(i64, i64, u8); 12] = [
            (1, 0, 0),
            (-1, 0, 0),
            (0, 1, 0),
            (0, -1, 0),
            (1, 1, 1),
            (-1, -1, 1),
            (1, -1, 1),
            (-1, 1, 1),
            (2, 0, 2),
            (-2, 0, 2),
            (0, 2, 2),
            (0, -2, 2),
        ];
        for i in 0..(cols * rows) as usize {
            let (c, r) = ((i as u32 % cols) as i64, (i as u32 / cols) as i64);
            let mut want: Vec<(u32, u8)> = offsets
                .iter()
                .filter(|(dc, dr, _)| {
                    (0..cols as i64).contains(&(c + dc)) && (0..rows as i64).contains(&(r + dr))
                })
                .map(|(dc, dr, k)| (((c + dc) + (r + dr) * cols as i64) as u32, *k))
                .collect();
            let mut got: Vec<(u32, u8)> = m.springs_of(i).iter().map(|s| (s.other, s.kind)).collect();
            want.sort_unstable();
            got.sort_unstable();
            assert_eq!(got, want, "particle {i}");
            for s in m.springs_of(i) {
                assert!((s.rest - (rest[s.other as usize] - rest[i]).length()).abs() < 1e-15);
            }
        }
        assert_eq!(m.triangles.len(), 2 * 5 * 4);
        for classes in [false, true] {
            assert_eq!(m.word_count(classes), m.pack([1.0; 3], classes).len() as u64);
        }
        assert!((m.area - 0.5 * 0.8).abs() < 1e-12);
        assert_eq!(m.colour_order.len(), 30);
        assert_proper(&m);
    }

    /// Masses lumped by area, closed forms: a unit square split into four uneven triangles
    /// about a vertex at (0.2, 0.3) gives the corner (0, 0) a third of its two triangles'
    /// areas (0.15 and 0.1) over the mean share (1/5); the shares sum to the particle count; and
    /// their centre is the square's centroid (each triangle's thirds at its corners weigh as
    /// its area at its centroid), where equal shares would put it at (0.44, 0.46). A quad of
    /// 2 x 1 and a triangle on its side share their corners' areas equally (2 / 4 and 1 / 3).
    #[test]
    fn masses_are_lumped_by_area_with_their_centre_at_the_centroid() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(0.2, 0.3, 0.0)];
        let faces = [vec![0, 1, 4], vec![1, 2, 4], vec![2, 3, 4], vec![3, 0, 4]];
        let m = ClothMesh::new(&p, &faces, &[], &[]).unwrap();
        assert!((m.mass_share[0] - 0.25 / 3.0 * 5.0).abs() < 1e-12, "{:?}", m.mass_share);
        assert!((m.mass_share.iter().sum::<f64>() - 5.0).abs() < 1e-12);
        let centre = p.iter().zip(&m.mass_share).map(|(x, s)| *x * *s).sum::<DVec3>() / 5.0;
        assert!(centre.distance(DVec3::new(0.5, 0.5, 0.0)) < 1e-12, "{centre}");
        let q = [DVec3::ZERO, 2.0 * DVec3::X, DVec3::new(2.0, 1.0, 0.0), DVec3::Y, DVec3::new(1.0, 2.0, 0.0)];
        let m = ClothMesh::new(&q, &[vec![0, 1, 2, 3], vec![3, 2, 4]], &[], &[]).unwrap();
        let want = [0.5, 0.5, 0.5 + 1.0 / 3.0, 0.5 + 1.0 / 3.0, 1.0 / 3.0].map(|a| a * 5.0 / 3.0);
        assert!(m.mass_share.iter().zip(want).all(|(s, w)| (s - w).abs() < 1e-12), "{:?}", m.mass_share);
    }

    /// No spring joins two particles of one colour; each particle has one colour.
    fn assert_proper(m: &ClothMesh) {
        let mut seen = vec![0; m.colour_order.len()];
        for c in 0..m.colour_count() {
            for &i in m.colour(c) {
                seen[i as usize] += 1;
                assert!(m.springs_of(i as usize).iter().all(|s| !m.colour(c).contains(&s.other)));
            }
        }
        assert!(seen.iter().all(|&k| k == 1), "a particle in no colour or in two");
        // XPBD's spring classes: each spring once, from its lower end; no two of a class share
        // a particle; the bending springs' classes first, the structural and seams' last.
        let mut sewn = vec![0; m.springs.len()];
        let mut last_group = 0;
        for c in 0..m.class_count() {
            let mut ends: Vec<u32> =
                m.class(c).iter().flat_map(|&[a, e]| [a, m.springs[e as usize].other]).collect();
            let count = ends.len();
            ends.sort_unstable();
            ends.dedup();
            assert_eq!(ends.len(), count, "class {c} has two springs at one particle");
            for &[a, e] in m.class(c) {
                let s = &m.springs[e as usize];
                assert!(e >= m.spring_first[a as usize] && e < m.spring_first[a as usize + 1] && s.other > a);
                sewn[e as usize] += 1;
                let group = match s.kind {
                    2 => 0,
                    1 => 1,
                    _ => 2,
                };
                assert!(group >= last_group, "class {c}: kinds out of order");
                last_group = group;
            }
        }
        for (i, list) in m.spring_first.windows(2).enumerate() {
            for e in list[0]..list[1] {
                let forward = m.springs[e as usize].other as usize > i;
                assert_eq!(sewn[e as usize], forward as u32, "entry {e} of particle {i}");
            }
        }
    }

    /// Grids of 64 x 64 as quads and as triangles split along alternating diagonals take 5
    /// colours, as the grid's formula (c + 2 r) mod 5 does (DSatur and greedy alone take 6 and 7
    /// for the triangles): each colour is a pass of VBD's sweep.
    #[test]
    fn a_grid_as_a_mesh_takes_the_grids_five_colours() {
        let (cols, rows) = (64u32, 64u32);
        let rest = flat_grid(cols, rows, 0.0, 0.1, 0.1);
        let quads = grid_quads(cols, rows);
        let split = |(k, q): (usize, &Vec<u32>)| {
            let (c, r) = (k as u32 % (cols - 1), k as u32 / (cols - 1));
            if (c + r) % 2 == 0 {
                [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]]
            } else {
                [vec![q[0], q[1], q[3]], vec![q[1], q[2], q[3]]]
            }
        };
        let triangles: Vec<Vec<u32>> = quads.iter().enumerate().flat_map(split).collect();
        for (faces, most) in [(&quads, 5), (&triangles, 5)] {
            let m = ClothMesh::new(&rest, faces, &[], &[]).unwrap();
            assert!(m.colour_count() <= most, "{} colours, not {most}", m.colour_count());
            assert_proper(&m);
        }
    }

    /// Two triangles make 5 structural springs and one bending spring between their opposite
    /// vertices; an edge of three triangles bends nothing and is counted; bad faces are named.
    #[test]
    fn triangles_bend_across_shared_edges_and_bad_faces_are_named() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 0.5, 1.0)];
        let m = ClothMesh::new(&p[..4], &[vec![0, 1, 2], vec![1, 3, 2]], &[], &[]).unwrap();
        let kinds: Vec<u8> = m.springs.iter().map(|s| s.kind).collect();
        assert_eq!(kinds.iter().filter(|&&k| k == 0).count(), 10);
        assert_eq!(m.springs_of(0).last().map(|s| (s.other, s.kind)), Some((3, 2)));
        let fan = ClothMesh::new(&p, &[vec![0, 1, 2], vec![1, 3, 2], vec![1, 4, 2]], &[], &[]).unwrap();
        assert_eq!((fan.unbent_edges, fan.springs.iter().filter(|s| s.kind == 2).count()), (1, 0));
        let err = |faces: &[Vec<u32>]| ClothMesh::new(&p, faces, &[], &[]).unwrap_err();
        assert!(err(&[vec![0, 1, 7]]).contains("past its"));
        assert!(err(&[vec![0, 1, 1]]).contains("twice"));
        assert!(err(&[vec![0, 1]]).contains("three or more"));
        assert!(err(&[vec![0, 1, 2]]).contains("belongs to no face"));
        let line = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
        assert!(ClothMesh::new(&line, &[vec![0, 1, 2]], &[], &[]).unwrap_err().contains("no area"));
    }
}
