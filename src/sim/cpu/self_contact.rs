//! The CPU twin of a cloth's contact with itself (glsl/include/self_contact.glsl): particles
//! against triangles and, with edge contact (`ObjectModel::edge_contact`), edges against edges;
//! and of a rope's, its segments against its segments as edge pairs that count wherever their
//! nearest points lie (`ObjectModel::has_segment_pairs`).
//! Every pair (particle p, triangle t) not left out (a vertex of t in p's one-ring, or t nearer
//! than h to p at rest) and every pair of grid edges not left out (sharing a vertex, or nearer
//! than EDGE_REST_MARGIN h at rest, a rope's SEGMENT_REST_MARGIN h), one of them creased (`crease_sag`), whose nearest points
//! lie inside both edges, nearer than the self-collision distance h, is a contact. Its offset from side b's nearest point to side a's is sum c_k x_k over its
//! particles (p and t's vertices: 1 and minus the barycentric weights of t's point nearest p;
//! edges (p, a) and (j, b): 1 - s, s, u - 1, -u at their nearest points' parameters s and u);
//! with n its unit vector, particle k moves by w_k c_k lambda n,
//! lambda = c (h - d) min(RELAXATION / sum n_k w_k c_k^2, 1 / sum w_k c_k^2) (w: the inverse
//! mass over the object's `mass`, 0 pinned, 1 free on a grid; n: each particle's count of
//! contacts, at least 1, a contact counting by its weight c, fully once its overlap reaches
//! h / 10; its mass split among them, the share over-relaxed
//! with edge contact but never past the contact's whole, RELAXATION 1 without), so every contact conserves momentum. The part of the
//! overlap the substep's approach made moves the velocity too, the rest the position only.
//! Coulomb friction (mu: the cloth's `friction`) undoes the relative motion over the substep of
//! the two nearest points along the tangent at the contact's share, its weight c over
//! sum w_k c_k^2 max(n_k, c) (its counts n floored at c, not at 1, so that a lone resting
//! contact of small overlap still holds), over-relaxed like lambda's and at most
//! 1 / sum w_k c_k^2, while within mu times the normal impulse the contact applies (lambda's
//! factor times the approach), else that much of it, with the same weights. Every pair is tested here; the GPU finds the
//! same through its spatial hash or contact lists (and keeps at most 16 contacts a particle
//! in a substep; an edge pair belongs to the lower-indexed of its nearest ends).

use crate::sim::model::ObjectModel;
use glam::{DVec2, DVec3, DVec4};

/// Contacts the GPU keeps for a particle in a substep; a particle that finds more (as the
/// particle of its pairs) takes part in the substep's first pass only (`self_reapply`).
pub const PAIR_MAX: usize = 16;

/// How far each contact's share of its correction is over-relaxed with edge contact, never
/// past the contact's whole (`pair_relaxation` in the shaders, which say why); 1 without.
pub const RELAXATION: f64 = 1.5;

/// With a cloth's edge pairs, the gap (a fraction of h) that the two sides of a contact keep
/// at least from the planes between them (`TRUNCATION_GAP` in the shaders, which say why).
pub const TRUNCATION_GAP: f64 = 0.5;

/// With a cloth's edge pairs, the most a particle moves in a substep, in h (`TRUNCATION_MOVE`
/// in the shaders, which say why).
pub const TRUNCATION_MOVE: f64 = 0.5;

/// A cloth's edge pairs nearer than this many times h at rest are left out (`EDGE_REST_MARGIN`
/// in the shaders, which say why).
pub const EDGE_REST_MARGIN: f64 = 1.33;

/// A rope's segment pairs nearer than this many times h at rest are left out
/// (`SEGMENT_REST_MARGIN` in the shaders).
pub const SEGMENT_REST_MARGIN: f64 = 1.5;

/// The grid's ring around a vertex, in order (`VERTEX_RING` in glsl/include/triangle.glsl):
/// an edge pair names each edge by an end and the ring vertex of its other end.
const VERTEX_RING: [(i64, i64); 6] = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)];

/// The grid's triangles as the renderer draws them, each with its number t = 2 a + k (a the
/// cell's first corner): (a, a + cols, a + 1) for k = 0, (a + 1, a + cols, a + cols + 1) for 1.
pub fn cloth_triangles(cols: usize, rows: usize) -> Vec<(usize, [usize; 3])> {
    let mut out = Vec::with_capacity(2 * cols.saturating_sub(1) * rows.saturating_sub(1));
    for r in 0..rows.saturating_sub(1) {
        for c in 0..cols.saturating_sub(1) {
            let a = c + r * cols;
            out.push((2 * a, [a, a + cols, a + 1]));
            out.push((2 * a + 1, [a + 1, a + cols, a + cols + 1]));
        }
    }
    out
}

/// The barycentric weights of the point of triangle (a, b, c) nearest to p (Ericson,
/// Real-Time Collision Detection, 5.1.5; `triangle_nearest` in the shaders).
pub fn triangle_nearest(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return DVec3::X;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return DVec3::Y;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        return DVec3::new(1.0 - t, t, 0.0);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return DVec3::Z;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        return DVec3::new(1.0 - t, 0.0, t);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return DVec3::new(0.0, 1.0 - t, t);
    }
    let sum = va + vb + vc;
    if sum > 0.0 {
        DVec3::new(va, vb, vc) / sum
    } else {
        DVec3::X // a degenerate triangle (or NaN): its first vertex
    }
}

/// The parameter t of the point a + t (b - a) of segment (a, b) nearest to p (a segment shrunk
/// to a point: its first end); `point_segment_nearest` in glsl/include/triangle.glsl.
pub fn point_segment_nearest(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.dot(ab);
    if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The parameters (s, t) of the nearest points p1 + s (q1 - p1) and p2 + t (q2 - p2) of two
/// segments (Ericson, Real-Time Collision Detection, 5.1.9); segments nearer parallel than a
/// relative 1e-5 take s = 0, as the GPU does (`segment_nearest` in the shaders).
pub fn segment_nearest(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (f64, f64) {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    if a <= 0.0 || e <= 0.0 {
        return (0.0, 0.0);
    }
    let (b, c) = (d1.dot(d2), d1.dot(r));
    let denom = a * e - b * b;
    let s = if denom > 1e-5 * a * e { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
    let t = (b * s + f) / e;
    if t < 0.0 {
        ((-c / a).clamp(0.0, 1.0), 0.0)
    } else if t > 1.0 {
        (((b - c) / a).clamp(0.0, 1.0), 1.0)
    } else {
        (s, t)
    }
}

/// The parameters (s, t) of the nearest points of two capsules' axes, segments p1 q1 and p2
/// q2 (either may be a point); nearly parallel axes take the middle of the part of p1 q1 that
/// p2 q2 overlaps (`capsule_nearest` in glsl/include/triangle.glsl).
pub fn capsule_nearest(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (f64, f64) {
    let (d1, d2) = (q1 - p1, q2 - p2);
    let (a, e) = (d1.dot(d1), d2.dot(d2));
    if a <= 0.0 {
        return (0.0, point_segment_nearest(p1, p2, q2));
    }
    if e <= 0.0 {
        return (point_segment_nearest(p2, p1, q1), 0.0);
    }
    let b = d1.dot(d2);
    if a * e - b * b > 1e-5 * a * e {
        return segment_nearest(p1, q1, p2, q2);
    }
    let (s0, s1) = ((p2 - p1).dot(d1) / a, (q2 - p1).dot(d1) / a);
    let s = 0.5 * (s0.min(s1).clamp(0.0, 1.0) + s0.max(s1).clamp(0.0, 1.0));
    (s, point_segment_nearest(p1 + s * d1, p2, q2))
}

/// How much of the relative motion `moved` over the substep friction undoes in a contact of
/// normal n whose normal correction is `normal`: all of its tangential part within the cone
/// (static), else mu times the normal correction of it (kinetic: Coulomb's bound on the
/// tangential impulse). `friction_correction` in glsl/include/triangle.glsl.
pub(super) fn friction_correction(moved: DVec3, n: DVec3, normal: f64, mu: f64) -> DVec3 {
    let slip = moved - moved.dot(n) * n;
    let (len, most) = (slip.length(), mu * normal);
    if len <= most {
        slip
    } else {
        slip * (most / len)
    }
}

/// Whether pair (particle p, triangle `tv`) of cloth `o` is left out: a vertex of the triangle
/// in p's one-ring, or the triangle nearer than h to p at rest.
fn left_out(o: &ObjectModel, h: f64, p: usize, tv: [usize; 3]) -> bool {
    if let Some(mesh) = &o.mesh {
        // (its thickness is below every rest distance outside the one-ring:
        // `ClothMesh::rest_clearance`)
        return tv.iter().any(|&k| mesh.linked(p, k));
    }
    let cols = o.dims[0] as usize;
    let cell = |k: usize| ((k % cols) as i64, (k / cols) as i64);
    let (pc, pr) = cell(p);
    tv.iter().any(|&k| (cell(k).0 - pc).abs() <= 1 && (cell(k).1 - pr).abs() <= 1)
        || near_at_rest(o, h, p, tv)
}

/// Whether triangle `tv` of grid cloth `o` is nearer than h to particle p at rest (possible
/// only for a thickness of 0.7 grid spacings or more: a cell's diagonal and the vertex next to
/// it are sx sy / |s| apart; past the one-ring, two spacings).
fn near_at_rest(o: &ObjectModel, h: f64, p: usize, tv: [usize; 3]) -> bool {
    let cols = o.dims[0] as usize;
    let cell = |k: usize| ((k % cols) as i64, (k / cols) as i64);
    let (pc, pr) = cell(p);
    if h < 0.7 * o.spacing[0].min(o.spacing[1]) {
        return false;
    }
    let rest = |k: usize| {
        let (c, r) = cell(k);
        DVec2::new((c - pc) as f64 * o.spacing[0], (r - pr) as f64 * o.spacing[1]).extend(0.0)
    };
    let w = triangle_nearest(DVec3::ZERO, rest(tv[0]), rest(tv[1]), rest(tv[2]));
    (rest(tv[0]) * w.x + rest(tv[1]) * w.y + rest(tv[2]) * w.z).length() < h
}

/// A contact's weight in its particles' counts: 1 once its overlap reaches a tenth of h, less
/// before, so that a contact that begins changes the others' shares gradually (a count is at
/// least 1).
fn count_weight(overlap: f64, h: f64) -> f64 {
    (overlap / (0.1 * h)).min(1.0)
}

/// One contact of a cloth with itself: its particles, the owner first (the particle against a
/// triangle's vertices, or edge (p, a) against edge (j, b) as [p, a, j, b]), the signed
/// weights c of its offset sum c_k x_k (from side b's nearest point to side a's) at the
/// positions it was found at, the unit normal along that offset, the overlap.
#[derive(Clone, Copy, Debug)]
pub struct Contact {
    pub particles: [usize; 4],
    pub edges: bool,
    /// A rope's segment pair (`ObjectModel::has_segment_pairs`): it counts wherever its
    /// nearest points lie (no `edge_fade`; a rope's edges are all on its border, creased).
    pub segments: bool,
    /// An edge pair's edges' opposite vertices (those of the two triangles on each edge, in
    /// the order of `particles`' edges; NONE on the border), and half a grid diagonal over h:
    /// what its crease weight is computed from.
    pub opposite: [usize; 4],
    pub chord: f64,
    pub weights: DVec4,
    pub normal: DVec3,
    pub overlap: f64,
}

impl Contact {
    /// The particle whose slots hold it on the GPU.
    pub fn owner(&self) -> usize {
        self.particles[0]
    }

    /// Its weights and offset at positions `x` (as the GPU's `pair_geometry` computes them).
    fn geometry(&self, x: &[DVec3]) -> (DVec4, DVec3) {
        let [p, a, j, b] = self.particles;
        if self.edges {
            let (s, u) = segment_nearest(x[p], x[a], x[j], x[b]);
            (DVec4::new(1.0 - s, s, u - 1.0, -u), x[p].lerp(x[a], s) - x[j].lerp(x[b], u))
        } else {
            let w = triangle_nearest(x[p], x[a], x[j], x[b]);
            (DVec4::new(1.0, -w.x, -w.y, -w.z), x[p] - (x[a] * w.x + x[j] * w.y + x[b] * w.z))
        }
    }

    /// How much it takes part at weights `w` and positions `x`: 1 against a triangle or as a
    /// rope's segment pair; an edge pair by `edge_fade` of its nearest points' parameters
    /// times the larger of its edges' crease weights.
    fn fade(&self, w: DVec4, x: &[DVec3]) -> f64 {
        if !self.edges || self.segments {
            return 1.0;
        }
        let [p, a, j, b] = self.particles;
        let [o1, o2, o3, o4] = self.opposite;
        let sag = |u: usize, v: usize, q1: usize, q2: usize| {
            if q1 == NONE || q2 == NONE {
                f64::INFINITY
            } else {
                crease_sag(x[u], x[v], x[q1], x[q2], self.chord)
            }
        };
        edge_fade(w.y, -w.w) * crease_weight(sag(p, a, o1, o2)).max(crease_weight(sag(j, b, o3, o4)))
    }

    /// The contact of `particles` (edge pair or not, a rope's segment pair or not; `opposite`
    /// and `chord` as the fields) at `x`, if they are nearer than h (and a cloth's edge pair's
    /// nearest points lie inside both edges and one of them is creased).
    fn at(
        particles: [usize; 4],
        (edges, segments): (bool, bool),
        opposite: [usize; 4],
        chord: f64,
        x: &[DVec3],
        h: f64,
    ) -> Option<Contact> {
        let mut c = Contact {
            particles,
            edges,
            segments,
            opposite,
            chord,
            weights: DVec4::ZERO,
            normal: DVec3::ZERO,
            overlap: 0.0,
        };
        let (weights, off) = c.geometry(x);
        let d = off.length();
        if d >= h || d <= 0.0 || c.fade(weights, x) <= 0.0 {
            return None;
        }
        c.weights = weights;
        c.normal = off / d;
        c.overlap = h - d;
        Some(c)
    }
}

/// No vertex (an edge on the border has one triangle).
const NONE: usize = usize::MAX;

/// Where an edge pair's crease weight starts and reaches 1, in sag over h (`CREASE_FROM`,
/// `CREASE_TO` in the shaders, which say why).
const CREASE_FROM: f64 = 0.1;
const CREASE_TO: f64 = 0.2;

/// The sag over h of a chord `chord` h long (half a grid diagonal) laid across edge (u, v)
/// between its triangles (u, v, o1) and (u, v, o2): chord tan(phi / 2), phi their dihedral
/// angle; infinite for a degenerate triangle (`crease_sag` in the shaders).
pub fn crease_sag(u: DVec3, v: DVec3, o1: DVec3, o2: DVec3, chord: f64) -> f64 {
    let e = v - u;
    let (n1, n2) = (e.cross(o1 - u), (o2 - u).cross(e));
    let l = n1.length() * n2.length();
    let flat = l + n1.dot(n2);
    // (NaN, from a degenerate triangle, counts as creased too)
    if l.is_nan() || flat.is_nan() || l <= 0.0 || flat <= 1e-12 * l {
        return f64::INFINITY;
    }
    chord * n1.cross(n2).length() / flat
}

/// An edge's crease weight at sag `sag`: 0 to CREASE_FROM, 1 from CREASE_TO.
pub fn crease_weight(sag: f64) -> f64 {
    ((sag - CREASE_FROM) / (CREASE_TO - CREASE_FROM)).clamp(0.0, 1.0)
}

/// The opposite vertices of grid edge (u, v) (v in u's one-ring) of cloth `o`: those of its
/// two triangles, NONE for a missing one.
fn edge_opposite(o: &ObjectModel, u: usize, v: usize) -> [usize; 2] {
    let (cu, cv) = (cell_of(o, u), cell_of(o, v));
    let Some(k) = VERTEX_RING.iter().position(|&(dc, dr)| (cu.0 + dc, cu.1 + dr) == cv) else {
        return [NONE; 2];
    };
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    [(k + 5) % 6, (k + 1) % 6].map(|r| {
        let (c, w) = (cu.0 + VERTEX_RING[r].0, cu.1 + VERTEX_RING[r].1);
        if (0..cols).contains(&c) && (0..rows).contains(&w) {
            (c + w * cols) as usize
        } else {
            NONE
        }
    })
}

/// How much an edge pair whose nearest points lie at s and u along its edges takes part: 1
/// where both lie inside by 0.05 of their edges or more, fading to 0 at an end (`edge_fade` in
/// the shaders, which say why).
pub fn edge_fade(s: f64, u: f64) -> f64 {
    (s.min(1.0 - s).min(u).min(1.0 - u) / 0.05).clamp(0.0, 1.0)
}

/// Grid vertex `k`'s cell (column, row) in cloth `o`.
fn cell_of(o: &ObjectModel, k: usize) -> (i64, i64) {
    let cols = o.dims[0] as usize;
    ((k % cols) as i64, (k / cols) as i64)
}

/// The grid's edges (rows, columns, the cells' diagonals; each once), as pairs of ends.
pub(super) fn grid_edges(o: &ObjectModel) -> Vec<[usize; 2]> {
    let (cols, rows) = (o.dims[0] as i64, o.dims[1] as i64);
    let mut out = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            for (dc, dr) in &VERTEX_RING[..3] {
                let (qc, qr) = (c + dc, r + dr);
                if (0..cols).contains(&qc) && (0..rows).contains(&qr) {
                    out.push([(c + r * cols) as usize, (qc + qr * cols) as usize]);
                }
            }
        }
    }
    out
}

/// Whether edge pair (e1, e2) of cloth or rope `o` is left out: they share a vertex, or are
/// nearer than EDGE_REST_MARGIN h (a rope's SEGMENT_REST_MARGIN h) at rest (possible from that
/// reaching 0.7 grid spacings: a cell's diagonal and the vertex next to it are sx sy / |s|
/// apart).
fn edges_left_out(o: &ObjectModel, h: f64, e1: [usize; 2], e2: [usize; 2]) -> bool {
    if e1.iter().any(|k| e2.contains(k)) {
        return true;
    }
    let margin = if o.has_segment_pairs() { SEGMENT_REST_MARGIN } else { EDGE_REST_MARGIN };
    let near = margin * h;
    if near < 0.7 * o.spacing[0].min(o.spacing[1]) {
        return false;
    }
    let rest = |k: usize| {
        let (c, r) = cell_of(o, k);
        DVec3::new(c as f64 * o.spacing[0], r as f64 * o.spacing[1], 0.0)
    };
    let (s, u) = segment_nearest(rest(e1[0]), rest(e1[1]), rest(e2[0]), rest(e2[1]));
    (rest(e1[0]).lerp(rest(e1[1]), s) - rest(e2[0]).lerp(rest(e2[1]), u)).length() < near
}

/// Whether the pair of ends a at squared distance da comes before b at db: the nearer, in
/// steps of h^2 / 1000, ties broken by the ends' indices (`ends_before` in the shaders, which
/// say why).
fn ends_before(h: f64, da: f64, a: (usize, usize), db: f64, b: (usize, usize)) -> bool {
    let step = 1000.0 / (h * h);
    let (qa, qb) = ((da * step).floor(), (db * step).floor());
    if qa != qb {
        return qa < qb;
    }
    (a.0.min(a.1), a.0.max(a.1)) < (b.0.min(b.1), b.0.max(b.1))
}

/// Edge pair (e1, e2) ordered as the GPU finds it: [p, a, j, b] with (p, j) its nearest ends
/// (`ends_before`) and p < j.
fn edge_pair_order(h: f64, x: &[DVec3], e1: [usize; 2], e2: [usize; 2]) -> [usize; 4] {
    let d2 = |(k1, k2): (usize, usize)| x[e1[k1]].distance_squared(x[e2[k2]]);
    let ends = |(k1, k2): (usize, usize)| (e1[k1], e2[k2]);
    let mut at = (0, 0);
    for k in [(0, 1), (1, 0), (1, 1)] {
        if ends_before(h, d2(k), ends(k), d2(at), ends(at)) {
            at = k;
        }
    }
    let (p, a, j, b) = (e1[at.0], e1[1 - at.0], e2[at.1], e2[1 - at.1]);
    if p < j {
        [p, a, j, b]
    } else {
        [j, b, p, a]
    }
}

/// Cloth `o`'s contacts with itself at positions `x` (none without triangle self-contact):
/// every particle-triangle pair and edge pair not left out, with a free particle, nearer than
/// h (an edge pair's nearest points inside both edges).
pub fn contacts(o: &ObjectModel, x: &[DVec3]) -> Vec<Contact> {
    let mut contacts = Vec::new();
    let Some(h) = o.self_distance.filter(|_| o.has_triangles()) else { return contacts };
    let pinned = |m: &[usize]| m.iter().all(|&k| o.pinned[k]);
    let triangles: Vec<[usize; 3]> = match &o.mesh {
        Some(mesh) => mesh.triangles.iter().map(|t| t.map(|k| k as usize)).collect(),
        None => {
            cloth_triangles(o.dims[0] as usize, o.dims[1] as usize).into_iter().map(|(_, tv)| tv).collect()
        }
    };
    for tv in triangles {
        let (lo, hi) = tv
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &k| (lo.min(x[k]), hi.max(x[k])));
        for (p, &xp) in x.iter().enumerate() {
            if xp.cmplt(lo - h).any() || xp.cmpgt(hi + h).any() || tv.contains(&p) {
                continue;
            }
            if o.pinned[p] && pinned(&tv) || left_out(o, h, p, tv) {
                continue;
            }
            contacts.extend(Contact::at([p, tv[0], tv[1], tv[2]], (false, false), [NONE; 4], 0.0, x, h));
        }
    }
    if !o.has_edge_pairs() {
        return contacts;
    }
    let chord = 0.5 * o.spacing[0].hypot(o.spacing[1]) / h;
    for (e1, e2) in edge_box_pairs(o, x, h) {
        let m = edge_pair_order(h, x, e1, e2);
        if pinned(&m) || edges_left_out(o, h, e1, e2) {
            continue;
        }
        let ([o1, o2], [o3, o4]) = (edge_opposite(o, m[0], m[1]), edge_opposite(o, m[2], m[3]));
        contacts.extend(Contact::at(m, (true, o.has_segment_pairs()), [o1, o2, o3, o4], chord, x, h));
    }
    contacts
}

/// The pairs of cloth `o`'s edges whose boxes at `x` come within `r` of each other, swept
/// along x: edges sorted by their boxes' low ends, each against those whose boxes begin
/// before its own (grown by r) ends.
fn edge_box_pairs(o: &ObjectModel, x: &[DVec3], r: f64) -> Vec<([usize; 2], [usize; 2])> {
    let mut edges: Vec<([usize; 2], DVec3, DVec3)> =
        grid_edges(o).into_iter().map(|e| (e, x[e[0]].min(x[e[1]]), x[e[0]].max(x[e[1]]))).collect();
    edges.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));
    let mut pairs = Vec::new();
    for (i, &(e1, lo1, hi1)) in edges.iter().enumerate() {
        for &(e2, lo2, hi2) in &edges[i + 1..] {
            if lo2.x > hi1.x + r {
                break;
            }
            if !((lo1 - r).cmpgt(hi2).any() || (lo2 - r).cmpgt(hi1).any()) {
                pairs.push((e1, e2));
            }
        }
    }
    pairs
}

/// Each particle's summed moves from cloth `o`'s contacts with its own triangles (positions
/// `x`, the physics output; `start`, where each began the substep), and the parts of them
/// that move the position only (undoing overlaps from earlier substeps); zero for pinned
/// particles. The contacts are those at `x`; `iterations` passes apply them, each from the
/// positions the passes before moved (a pair separated by then takes no part; the contacts of
/// a particle that found more than PAIR_MAX, the first pass only). Returns the
/// positions after all passes but the last, and the last pass's moves (the constraint stage
/// adds those, as the GPU's takes the last pass's sums).
pub(super) fn self_contact(o: &ObjectModel, x: &[DVec3], start: &[DVec3], iterations: u32) -> SelfContact {
    let mut xk = x.to_vec();
    let mut vk_shift = vec![DVec3::ZERO; x.len()];
    let Some(h) = o.self_distance.filter(|_| o.has_triangles()) else {
        let zero = vec![DVec3::ZERO; x.len()];
        return SelfContact { moved: xk, shift: vk_shift, last: zero.clone(), last_rest: zero };
    };
    let found = contacts(o, x);
    let mut count = vec![0.0; x.len()];
    for c in &found {
        for (j, &k) in c.particles.iter().enumerate() {
            // (a particle-triangle pair counts in each of its four particles once)
            if !o.pinned[k] && !c.particles[..j].contains(&k) {
                count[k] += count_weight(c.overlap, h) * c.fade(c.weights, x);
            }
        }
    }
    let mut found_by = vec![0; x.len()];
    for c in &found {
        found_by[c.owner()] += 1;
    }
    let again: Vec<Contact> = found.iter().filter(|c| found_by[c.owner()] <= PAIR_MAX).copied().collect();
    let mut last = apply(o, h, &found, &count, (x, start));
    for _ in 1..iterations {
        for i in 0..x.len() {
            xk[i] += last.0[i];
            vk_shift[i] += last.0[i] - last.1[i];
        }
        last = apply(o, h, &again, &count, (&xk, start));
    }
    SelfContact { moved: xk, shift: vk_shift, last: last.0, last_rest: last.1 }
}

/// What a cloth's contact with itself gives the constraint stage (`self_contact`).
pub(super) struct SelfContact {
    /// The positions after all passes but the last, and the velocity shift they made.
    pub moved: Vec<DVec3>,
    pub shift: Vec<DVec3>,
    /// The last pass's moves, and their position-only parts.
    pub last: Vec<DVec3>,
    pub last_rest: Vec<DVec3>,
}

/// With a cloth's edge pairs, each particle's fraction of its move over the substep (from
/// `start` to `x`, the constraint stage's result) that keeps it on its side of the plane
/// between the two sides of each pair nearer than h at the start (`near_pairs`;
/// `note_truncation` in glsl/include/self_contact.glsl, which says why), each move also held to
/// TRUNCATION_MOVE h unless longer than `runaway`: 1 where nothing truncates it.
pub(super) fn truncation(o: &ObjectModel, start: &[DVec3], x: &[DVec3], runaway: f64) -> Vec<f64> {
    let mut t = vec![1.0f64; x.len()];
    let Some(h) = o.self_distance else { return t };
    for (k, t) in t.iter_mut().enumerate() {
        let moved = (x[k] - start[k]).length();
        // (not a move past `runaway`, the guard's speed times the substep: a blow-up)
        if moved > TRUNCATION_MOVE * h && moved <= runaway && !o.pinned[k] {
            *t = TRUNCATION_MOVE * h / moved;
        }
    }
    for contact in near_pairs(o, start, h) {
        let (c, off) = contact.geometry(start);
        let d = off.length();
        let n = off / d;
        // Side a: the particle (against a triangle) or the first edge; the plane halfway.
        let a_side = if contact.edges { 2 } else { 1 };
        let m = contact.particles;
        let middle = (0..a_side).map(|q| start[m[q]] * c[q]).sum::<DVec3>() - off * 0.5;
        for (q, &k) in m.iter().enumerate() {
            if o.pinned[k] {
                continue;
            }
            let side = if q < a_side { 1.0 } else { -1.0 };
            let room = (side * n.dot(start[k] - middle) - 0.5 * TRUNCATION_GAP * h).max(0.0);
            let approach = -side * n.dot(x[k] - start[k]);
            if approach > room {
                t[k] = t[k].min(room / approach);
            }
        }
    }
    t
}

/// The pairs of grid cloth `o` at positions `x` nearer than h that the truncation keeps apart
/// (`note_truncation` in glsl/include/self_contact.glsl): (particle p, triangle t) with p not
/// a vertex of t, a fold's pairs too, which the contacts leave out; and pairs of edges that
/// share no vertex, one of them creased (`crease_weight`), wherever their nearest points lie;
/// none near at rest. Found by sweeping boxes along x.
fn near_pairs(o: &ObjectModel, x: &[DVec3], h: f64) -> Vec<Contact> {
    let r = h;
    let boxed = |k: &[usize]| {
        k.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &q| (lo.min(x[q]), hi.max(x[q])))
    };
    let apart =
        |a: (DVec3, DVec3), b: (DVec3, DVec3)| (a.0 - r).cmpgt(b.1).any() || (b.0 - r).cmpgt(a.1).any();
    let mut out = Vec::new();
    let mut tris: Vec<([usize; 3], (DVec3, DVec3))> = cloth_triangles(o.dims[0] as usize, o.dims[1] as usize)
        .into_iter()
        .map(|(_, tv)| (tv, boxed(&tv)))
        .collect();
    tris.sort_by(|a, b| a.1 .0.x.total_cmp(&b.1 .0.x));
    let mut points: Vec<usize> = (0..x.len()).collect();
    points.sort_by(|&a, &b| x[a].x.total_cmp(&x[b].x));
    // (each triangle against the points from its box's low x less r to its high x plus r)
    for (tv, bx) in &tris {
        let from = points.partition_point(|&p| x[p].x < bx.0.x - r);
        for &p in points[from..].iter().take_while(|&&p| x[p].x <= bx.1.x + r) {
            if tv.contains(&p) || apart((x[p], x[p]), *bx) || near_at_rest(o, h, p, *tv) {
                continue;
            }
            out.extend(Contact::at([p, tv[0], tv[1], tv[2]], (false, false), [NONE; 4], 0.0, x, r));
        }
    }
    // (an edge's crease weight, 1 on the border: `crease_sag`)
    let chord = 0.5 * o.spacing[0].hypot(o.spacing[1]) / h;
    let creased = |e: [usize; 2]| match edge_opposite(o, e[0], e[1]) {
        [q1, q2] if q1 != NONE && q2 != NONE => {
            crease_weight(crease_sag(x[e[0]], x[e[1]], x[q1], x[q2], chord))
        }
        _ => 1.0,
    };
    for (e1, e2) in edge_box_pairs(o, x, r) {
        if edges_left_out(o, h, e1, e2) || creased(e1) <= 0.0 && creased(e2) <= 0.0 {
            continue;
        }
        out.extend(Contact::at([e1[0], e1[1], e2[0], e2[1]], (true, true), [NONE; 4], 0.0, x, r));
    }
    out
}

/// A particle at `p` with velocity `vel` that began the substep at `start`, moved back towards
/// it by fraction `t` of its move, its velocity scaled as its move is; whether it moved it
/// (`truncate_move` in glsl/include/self_contact.glsl, which says why).
pub(super) fn truncate(p: &mut DVec3, vel: &mut DVec3, start: DVec3, t: f64) -> bool {
    if t >= 1.0 {
        return false;
    }
    *p = start + (*p - start) * t;
    *vel *= t;
    true
}

/// One pass over cloth `o`'s contacts `found` (particles' counts `count`) at positions `x`:
/// each particle's summed moves and their position-only parts.
fn apply(
    o: &ObjectModel,
    h: f64,
    found: &[Contact],
    count: &[f64],
    (x, start): (&[DVec3], &[DVec3]),
) -> (Vec<DVec3>, Vec<DVec3>) {
    let mut moves = vec![DVec3::ZERO; x.len()];
    let mut rests = vec![DVec3::ZERO; x.len()];
    // Each particle's inverse mass over the object's `mass`: 0 pinned.
    let free = |k: usize| if o.pinned[k] { 0.0 } else { o.mass / o.mass_of(k) };
    let relaxation = if o.has_edge_pairs() { RELAXATION } else { 1.0 };
    for contact in found {
        // The pair again at these positions (as the GPU's apply_contact computes it).
        let (c, off) = contact.geometry(x);
        let d = off.length();
        if d >= h || d == 0.0 {
            continue;
        }
        let (n, overlap) = (off / d, h - d);
        let m = contact.particles;
        let free_m = DVec4::from_array(m.map(free));
        // Each free particle's mass split among its contacts.
        let split_m = DVec4::from_array(m.map(|k| free(k) * f64::max(1.0, count[k])));
        // The overlap this substep's approach made is undone with its velocity, the rest in
        // position only.
        let slip = (0..4).map(|q| (x[m[q]] - start[m[q]]) * c[q]).sum::<DVec3>();
        let approach = (-slip.dot(n)).clamp(0.0, overlap);
        let (split, whole) = ((c * c).dot(split_m), (c * c).dot(free_m));
        if whole <= 0.0 {
            continue; // weights on pinned particles only
        }
        // A contact that begins takes part by its count weight (see the GPU's apply_contact);
        // its share over-relaxed, never past its whole.
        let weight = count_weight(overlap, h) * contact.fade(c, x);
        let k = weight * f64::min(relaxation / split, 1.0 / whole);
        // Friction at the contact's weight in its particles' counts (see the GPU's
        // apply_contact), within mu times its normal impulse (k times the approach).
        let counted = DVec4::from_array(m.map(|k| free(k) * count[k].max(weight)));
        let share = if weight > 0.0 {
            f64::min(relaxation * weight / (c * c).dot(counted), 1.0 / whole)
        } else {
            0.0
        };
        let friction = if share > 0.0 {
            friction_correction(slip, n, k * approach / share, o.friction) * share
        } else {
            DVec3::ZERO
        };
        let (push, rest) = (n * (overlap * k) - friction, n * ((overlap - approach) * k));
        for q in 0..4 {
            moves[m[q]] += push * (c[q] * free_m[q]);
            rests[m[q]] += rest * (c[q] * free_m[q]);
        }
    }
    (moves, rests)
}
