//! The CPU twin of a cloth's contact with its own triangles (glsl/include/self_contact.glsl):
//! every pair (particle p, triangle t) not left out (a vertex of t in p's one-ring, or t nearer
//! than h to p at rest) and nearer than the self-collision distance h is a contact. With the barycentric weights b of t's point
//! nearest p and n the unit vector from it to p, p moves by w_p lambda n and vertex k by
//! -w_k b_k lambda n, lambda = c (h - d) / (n_p w_p + sum n_k w_k b_k^2) (w: 1 free, 0 pinned;
//! n: each particle's count of contacts, at least 1, a contact counting by its weight c, fully
//! once its overlap reaches h / 10; its mass split among them), so every contact conserves
//! momentum. The part of the overlap the substep's approach made moves the velocity too, the
//! rest the position only. Coulomb friction (mu: the cloth's `friction`) adds the relative
//! motion over the substep of p and t's nearest point along the tangent, undone whole while
//! within mu times the approach, else that much of it, with the same weights. Every pair is tested here;
//! the GPU finds the same through its spatial hash or contact lists (and keeps at most 16
//! contacts a particle in a substep).

use crate::sim::model::ObjectModel;
use glam::{DVec2, DVec3};

/// Contacts the GPU keeps for a particle in a substep; a particle that finds more (as the
/// particle of its pairs) takes part in the substep's first pass only (`self_reapply`).
pub const PAIR_MAX: usize = 16;

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
    let cols = o.dims[0] as usize;
    let cell = |k: usize| ((k % cols) as i64, (k / cols) as i64);
    let (pc, pr) = cell(p);
    if tv.iter().any(|&k| (cell(k).0 - pc).abs() <= 1 && (cell(k).1 - pr).abs() <= 1) {
        return true;
    }
    if h < 1.99 * o.spacing[0].min(o.spacing[1]) {
        return false; // no triangle without a vertex in the one-ring is nearer at rest
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

/// One contact of a cloth with its own triangles: particle p, the triangle's vertices, the
/// barycentric weights of its point nearest p, the unit normal from there to p, the overlap.
pub type Contact = (usize, [usize; 3], DVec3, DVec3, f64);

/// Cloth `o`'s contacts with its own triangles at positions `x` (none without triangle
/// self-contact): every pair not left out, with a free particle, nearer than h.
pub fn contacts(o: &ObjectModel, x: &[DVec3]) -> Vec<Contact> {
    let mut contacts = Vec::new();
    let Some(h) = o.self_distance.filter(|_| o.has_triangles()) else { return contacts };
    for (_, tv) in cloth_triangles(o.dims[0] as usize, o.dims[1] as usize) {
        let (lo, hi) = tv
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &k| (lo.min(x[k]), hi.max(x[k])));
        for (p, &xp) in x.iter().enumerate() {
            if xp.cmplt(lo - h).any() || xp.cmpgt(hi + h).any() || tv.contains(&p) {
                continue;
            }
            if o.pinned[p] && tv.iter().all(|&k| o.pinned[k]) || left_out(o, h, p, tv) {
                continue;
            }
            let w = triangle_nearest(xp, x[tv[0]], x[tv[1]], x[tv[2]]);
            let off = xp - (x[tv[0]] * w.x + x[tv[1]] * w.y + x[tv[2]] * w.z);
            let d = off.length();
            if d < h && d > 0.0 {
                contacts.push((p, tv, w, off / d, h - d));
            }
        }
    }
    contacts
}

/// Each particle's summed moves from cloth `o`'s contacts with its own triangles (positions
/// `x`, the physics output; `start`, where each began the substep), and the parts of them
/// that move the position only (undoing overlaps from earlier substeps); zero for pinned
/// particles. The contacts are those at `x`; `iterations` passes apply them, each from the
/// positions the passes before moved (a pair separated by then takes no part; the contacts of
/// a particle that found more than PAIR_MAX, the first pass only). Returns the
/// positions after all passes but the last, and the last pass's moves (the constraint stage
/// adds those, as the GPU's takes the last pass's sums).
pub(super) fn self_contact(
    o: &ObjectModel,
    x: &[DVec3],
    start: &[DVec3],
    iterations: u32,
) -> (Vec<DVec3>, Vec<DVec3>, Vec<DVec3>, Vec<DVec3>) {
    let mut xk = x.to_vec();
    let mut vk_shift = vec![DVec3::ZERO; x.len()];
    let Some(h) = o.self_distance.filter(|_| o.has_triangles()) else {
        let zero = vec![DVec3::ZERO; x.len()];
        return (xk, vk_shift, zero.clone(), zero);
    };
    let found = contacts(o, x);
    let mut count = vec![0.0; x.len()];
    for &(p, tv, _, _, overlap) in &found {
        for k in std::iter::once(p).chain(tv).filter(|&k| !o.pinned[k]) {
            count[k] += count_weight(overlap, h);
        }
    }
    let mut found_by = vec![0; x.len()];
    for c in &found {
        found_by[c.0] += 1;
    }
    let again: Vec<Contact> = found.iter().filter(|c| found_by[c.0] <= PAIR_MAX).copied().collect();
    let mut last = apply(o, h, &found, &count, x, start);
    for _ in 1..iterations {
        for i in 0..x.len() {
            xk[i] += last.0[i];
            vk_shift[i] += last.0[i] - last.1[i];
        }
        last = apply(o, h, &again, &count, &xk, start);
    }
    (xk, vk_shift, last.0, last.1)
}

/// One pass over cloth `o`'s contacts `found` (particles' counts `count`) at positions `x`:
/// each particle's summed moves and their position-only parts.
fn apply(
    o: &ObjectModel,
    h: f64,
    found: &[Contact],
    count: &[f64],
    x: &[DVec3],
    start: &[DVec3],
) -> (Vec<DVec3>, Vec<DVec3>) {
    let mut moves = vec![DVec3::ZERO; x.len()];
    let mut rests = vec![DVec3::ZERO; x.len()];
    let free = |k: usize| if o.pinned[k] { 0.0 } else { 1.0 };
    for &(p, tv, ..) in found {
        // The pair again at these positions (as the GPU's apply_contact computes it).
        let w = triangle_nearest(x[p], x[tv[0]], x[tv[1]], x[tv[2]]);
        let off = x[p] - (x[tv[0]] * w.x + x[tv[1]] * w.y + x[tv[2]] * w.z);
        let d = off.length();
        if d >= h || d == 0.0 {
            continue;
        }
        let (n, overlap) = (off / d, h - d);
        // Each free particle's mass split among its contacts.
        let split = |k: usize| free(k) * f64::max(1.0, count[k]);
        let weights = DVec3::from_array(tv.map(free));
        // The overlap this substep's approach made is undone with its velocity, the rest in
        // position only; friction within mu times the approach (the normal impulse).
        let moved = |k: usize| x[k] - start[k];
        let slip = moved(p) - (0..3).map(|k| moved(tv[k]) * w[k]).sum::<DVec3>();
        let approach = (-slip.dot(n)).clamp(0.0, overlap);
        let correction = n * overlap - friction_correction(slip, n, approach, o.friction);
        // A contact that begins takes part by its count weight (see the GPU's apply_contact).
        let k = count_weight(overlap, h) / (split(p) + (w * w).dot(DVec3::from_array(tv.map(split))));
        let (push, rest) = (correction * k, n * ((overlap - approach) * k));
        moves[p] += push * free(p);
        rests[p] += rest * free(p);
        for (j, &v) in tv.iter().enumerate() {
            moves[v] -= push * (w[j] * weights[j]);
            rests[v] -= rest * (w[j] * weights[j]);
        }
    }
    (moves, rests)
}
