//! The CPU twin of contact between objects (glsl/contact.comp). Every contact is a particle p
//! of one object against a piece of another's surface, the reach being the two objects'
//! contact radii added:
//! - a triangle t of a cloth (its triangles as the renderer draws them): p nearer than the
//!   reach to t's nearest point (weights b), and t's corner nearest to p nearer than the reach
//!   plus the cloth's corner reach (the GPU finds t through that corner);
//! - a segment of a rope (a chain of capsules; a lone node a segment of one point), p being a
//!   cloth's: the same with the segment's two ends (weights 1 - t and t at its point nearest
//!   to p), its end nearest to p within the reach plus the rope's corner reach;
//! - a rope's segment against an edge of another object (a rope's segment, or a cloth's row,
//!   column or diagonal: the nearest points of their axes, weights 1 - s, s and 1 - t, t), the
//!   ends nearest to those points within the reach plus both corner reaches; between two ropes
//!   once;
//! - two cloths' edges (rows, columns and diagonals), when either keeps its edges from edges
//!   (`SimModel::keeps_cloth_edges_apart`): the nearest points of the segments, taking part
//!   by `edge_fade` (near an end the vertex-triangle contacts hold), their nearest ends (of the
//!   four pairs of ends, one of each edge) within the reach plus both corner reaches and plus
//!   half of each edge's length (the GPU finds the pair through those ends); once.
//!
//! With n from the nearest point to p (turned back to the side where the pair began the
//! substep, if it crossed within it: `gap`), inverse masses w (0 pinned) and each particle's count
//! of contacts n_k (mass splitting, Tonge et al. 2012: a particle in several contacts takes
//! each as if its mass were shared among them), lambda = (reach - gap) / (n_p w_p + sum n_k w_k
//! b_k^2); p moves w_p lambda n, corner k -w_k b_k lambda n, so the contact keeps its momentum
//! (a segment pair likewise, with one segment's ends in p's place). Coulomb friction (mu the
//! mean of the two objects' `friction`): the contact's relative motion over the substep along
//! its tangent is undone whole when it is within mu times the normal correction (static), else
//! by that much (kinetic), with the same weights as the normal correction. Every pair is tested
//! here; the GPU finds the same through the scene's spatial hash.

use super::self_contact::{
    capsule_nearest, cloth_triangles, edge_fade, friction_correction, grid_edges, segment_nearest,
    triangle_nearest,
};
use crate::sim::model::SimModel;
use glam::DVec3;

/// One contact: its particles (object, particle, weight: the nearest points' difference is the
/// sum of weight x, positive on the side pushed along it) and its correction of that difference
/// (normal and friction).
struct Contact {
    corners: Vec<(usize, usize, f64)>,
    correction: DVec3,
}

/// Whether objects a and b (positions x) are near enough to touch: their bounding boxes
/// within `gap` of each other.
fn near(x: &[&[DVec3]], a: usize, b: usize, gap: f64) -> bool {
    let bounds = |p: &[DVec3]| p.iter().fold((DVec3::MAX, DVec3::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let ((la, ha), (lb, hb)) = (bounds(x[a]), bounds(x[b]));
    (la - hb).max(lb - ha).max_element() < gap
}

/// The pieces of object `o`'s surface that other objects' particles touch, by their corners:
/// a cloth's triangles, else its segments in index order (a rope; a lone particle is one
/// segment of one point, listed once).
fn pieces(o: &crate::sim::model::ObjectModel) -> Vec<Vec<usize>> {
    if o.contact_triangles() {
        return cloth_triangles(o.dims[0] as usize, o.dims[1] as usize)
            .into_iter()
            .map(|(_, t)| t.to_vec())
            .collect();
    }
    let n = o.particle_count();
    if n == 1 {
        return vec![vec![0]];
    }
    (0..n - 1).map(|k| vec![k, k + 1]).collect()
}

/// The weights of the point of a triangle (corners `c`) nearest to p.
fn nearest_weights(p: DVec3, c: &[DVec3]) -> Vec<f64> {
    match c {
        [a, b, c] => triangle_nearest(p, *a, *b, *c).to_array().to_vec(),
        _ => vec![1.0],
    }
}

/// A segment's ends (a lone node's twice).
fn ends(x: &[DVec3], piece: &[usize]) -> (DVec3, DVec3) {
    (x[piece[0]], x[piece[piece.len() - 1]])
}

/// The gap of a contact at distance d (within the reach) between its nearest points, whose
/// offset is `off` now and `began` at the substep's start (the same weights): negative where
/// the two sides crossed within the substep, so that the pair is pushed back to the side it
/// began on rather than on through the piece (at a relative speed of more than the reach a
/// substep a pair can cross within one).
fn gap(off: DVec3, d: f64, began: DVec3) -> f64 {
    if off.dot(began) < 0.0 {
        -d
    } else {
        d
    }
}

/// Every contact between the objects at positions `x` (`x0` where they began the substep).
fn contacts(m: &SimModel, x: &[&[DVec3]], x0: &[&[DVec3]]) -> Vec<Contact> {
    // The contact of `corners` (see `Contact`), if within `reach`, its correction taken by
    // `part`.
    let contact = |corners: Vec<(usize, usize, f64)>, reach: f64, mu: f64, part: f64| -> Option<Contact> {
        let off = corners.iter().map(|&(o, i, w)| w * x[o][i]).sum::<DVec3>();
        let began = corners.iter().map(|&(o, i, w)| w * x0[o][i]).sum::<DVec3>();
        let d = off.length();
        if !(d > 0.0 && d < reach && part > 0.0) {
            return None;
        }
        let gap = gap(off, d, began);
        let n = off * (gap / (d * d));
        let moved = off - began;
        let correction = (n * (reach - gap) - friction_correction(moved, n, reach - gap, mu)) * part;
        Some(Contact { corners, correction })
    };
    let mut found = Vec::new();
    for (a, o) in m.objects.iter().enumerate() {
        for (b, other) in m.objects.iter().enumerate().filter(|&(b, _)| b != a) {
            let reach = o.contact_radius() + other.contact_radius();
            let mu = 0.5 * (o.friction + other.friction);
            let (rope, cloth) = (!o.contact_triangles(), other.contact_triangles());
            let sight = reach + other.corner_reach();
            let edge_sight = reach + 2.0 * (o.corner_reach() + other.corner_reach());
            // A cloth's particles look only for triangles; two ropes meet once.
            if (!cloth && (!rope || b < a)) || !near(x, a, b, edge_sight) {
                continue;
            }
            let theirs = pieces(other);
            if rope {
                let edges: Vec<Vec<usize>> = if cloth {
                    let vertices = (0..other.particle_count()).map(|k| vec![k]);
                    grid_edges(other).iter().map(|e| e.to_vec()).chain(vertices).collect()
                } else {
                    theirs.clone()
                };
                for sa in pieces(o) {
                    let (a0, a1) = ends(x[a], &sa);
                    for sb in &edges {
                        let (b0, b1) = ends(x[b], sb);
                        if (a0 - b0).length_squared() >= edge_sight * edge_sight {
                            continue;
                        }
                        let (s, t) = capsule_nearest(a0, a1, b0, b1);
                        let mut corners = vec![(a, sa[0], 1.0 - s), (b, sb[0], t - 1.0)];
                        if sa.len() > 1 {
                            corners.push((a, sa[1], s));
                        }
                        if sb.len() > 1 {
                            corners.push((b, sb[1], -t));
                        }
                        found.extend(contact(corners, reach, mu, 1.0));
                    }
                }
                if !cloth {
                    continue;
                }
            }
            if a < b && m.keeps_cloth_edges_apart(o, other) {
                let theirs = grid_edges(other);
                let ends_sight = reach + o.corner_reach() + other.corner_reach();
                for e in grid_edges(o) {
                    for f in &theirs {
                        let ends = e.iter().flat_map(|&i| f.iter().map(move |&j| x[a][i].distance(x[b][j])));
                        let nearest = ends.fold(f64::MAX, f64::min);
                        let half = 0.5 * (x[a][e[0]].distance(x[a][e[1]]) + x[b][f[0]].distance(x[b][f[1]]));
                        if nearest >= ends_sight.min(reach + half) {
                            continue;
                        }
                        let (s, t) = segment_nearest(x[a][e[0]], x[a][e[1]], x[b][f[0]], x[b][f[1]]);
                        let corners =
                            vec![(a, e[0], 1.0 - s), (a, e[1], s), (b, f[0], t - 1.0), (b, f[1], -t)];
                        found.extend(contact(corners, reach, mu, edge_fade(s, t)));
                    }
                }
            }
            for (i, &p) in x[a].iter().enumerate() {
                for piece in &theirs {
                    let c: Vec<DVec3> = piece.iter().map(|&k| x[b][k]).collect();
                    let nearest = c.iter().map(|c| (*c - p).length_squared()).fold(f64::MAX, f64::min);
                    if nearest >= sight * sight {
                        continue;
                    }
                    let w = nearest_weights(p, &c);
                    let corners =
                        std::iter::once((a, i, 1.0)).chain(piece.iter().zip(&w).map(|(&k, w)| (b, k, -w)));
                    found.extend(contact(corners.collect(), reach, mu, 1.0));
                }
            }
        }
    }
    found
}

/// Each object's corrections from the contacts between the objects at positions `x` (`x0`
/// where they began the substep).
pub(super) fn inter_object(m: &SimModel, x: &[&[DVec3]], x0: &[&[DVec3]]) -> Vec<Vec<DVec3>> {
    let found = contacts(m, x, x0);
    let mut touches: Vec<Vec<u32>> = x.iter().map(|x| vec![0; x.len()]).collect();
    for &(o, i, _) in found.iter().flat_map(|c| &c.corners) {
        touches[o][i] += 1;
    }
    let inverse_mass =
        |o: usize, i: usize| if m.objects[o].pinned[i] { 0.0 } else { 1.0 / m.objects[o].mass };
    let mut moves: Vec<Vec<DVec3>> = x.iter().map(|x| vec![DVec3::ZERO; x.len()]).collect();
    for contact in &found {
        // Mass splitting: each particle as if its mass were shared among its contacts.
        let denom = contact
            .corners
            .iter()
            .map(|&(o, i, w)| touches[o][i] as f64 * inverse_mass(o, i) * w * w)
            .sum::<f64>();
        if denom > 0.0 {
            for &(o, i, w) in &contact.corners {
                moves[o][i] += contact.correction * (inverse_mass(o, i) * w / denom);
            }
        }
    }
    moves
}
