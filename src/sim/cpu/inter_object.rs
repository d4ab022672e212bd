//! The CPU twin of contact between objects (glsl/contact.comp). Two kinds of contact, the
//! reach being the two objects' contact radii added:
//! - particle p of one object against triangle t of another that is a cloth (its triangles as
//!   the renderer draws them): p nearer than the reach to t's nearest point (weights b), and
//!   t's corner nearest to p nearer than the reach plus the cloth's corner reach (the GPU
//!   finds t through that corner). With n from that point to p and inverse masses w (0 pinned),
//!   lambda = (reach - d) / (w_p + sum w_k b_k^2); p moves w_p lambda n, corner k
//!   -w_k b_k lambda n, so the contact keeps its momentum;
//! - particle against particle between two objects that are not cloths (ropes): each moves
//!   away from the other by its share of the overlap (the other's mass over both, all of it
//!   when the other is pinned).
//!
//! Both kinds have Coulomb friction (mu the mean of the two objects' `friction`): the
//! contact's relative motion over the substep along its tangent is undone whole when it is
//! within mu times the normal correction (static), else by that much (kinetic), with the same
//! weights as the normal correction. Every contact's moves are divided by the largest count of
//! contacts among its free particles (the same for all: equal and opposite momenta). Every pair is tested here; the GPU finds
//! the same through the scene's spatial hash.

use super::self_contact::{cloth_triangles, friction_correction, triangle_nearest};
use crate::sim::model::SimModel;
use glam::DVec3;

/// The particles of one contact, each as (object, particle, its move before the split).
type Contact = Vec<(usize, usize, DVec3)>;

/// Whether objects a and b (positions x) are near enough to touch: their bounding boxes
/// within `gap` of each other.
fn near(x: &[&[DVec3]], a: usize, b: usize, gap: f64) -> bool {
    let bounds = |p: &[DVec3]| p.iter().fold((DVec3::MAX, DVec3::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let ((la, ha), (lb, hb)) = (bounds(x[a]), bounds(x[b]));
    (la - hb).max(lb - ha).max_element() < gap
}

/// Every contact between the objects at positions `x` (`x0` where they began the substep).
fn contacts(m: &SimModel, x: &[&[DVec3]], x0: &[&[DVec3]]) -> Vec<Contact> {
    let inverse_mass =
        |o: usize, i: usize| if m.objects[o].pinned[i] { 0.0 } else { 1.0 / m.objects[o].mass };
    let mut found = Vec::new();
    for (a, o) in m.objects.iter().enumerate() {
        for (b, other) in m.objects.iter().enumerate().filter(|&(b, _)| b != a) {
            let reach = o.contact_radius() + other.contact_radius();
            let mu = 0.5 * (o.friction + other.friction);
            if !near(x, a, b, reach + other.corner_reach().max(o.corner_reach())) {
                continue;
            }
            if other.contact_triangles() {
                let triangles = cloth_triangles(other.dims[0] as usize, other.dims[1] as usize);
                let sight = reach + other.corner_reach();
                for (i, &p) in x[a].iter().enumerate() {
                    for &(_, tv) in &triangles {
                        let corners = tv.map(|k| x[b][k]);
                        let nearest =
                            corners.iter().map(|c| (*c - p).length_squared()).fold(f64::MAX, f64::min);
                        if nearest >= sight * sight {
                            continue;
                        }
                        let w = triangle_nearest(p, corners[0], corners[1], corners[2]);
                        let off = p - (w.x * corners[0] + w.y * corners[1] + w.z * corners[2]);
                        let d = off.length();
                        if !(d > 0.0 && d < reach) {
                            continue;
                        }
                        let n = off / d;
                        let (wp, wk) = (inverse_mass(a, i), tv.map(|k| inverse_mass(b, k)));
                        let denom = wp + (0..3).map(|k| wk[k] * w[k] * w[k]).sum::<f64>();
                        let began = |o: usize, k: usize| x[o][k] - x0[o][k];
                        let moved = began(a, i) - (0..3).map(|k| w[k] * began(b, tv[k])).sum::<DVec3>();
                        let correction = n * (reach - d) - friction_correction(moved, n, reach - d, mu);
                        let push = if denom > 0.0 { correction / denom } else { DVec3::ZERO };
                        let mut contact = vec![(a, i, wp * push)];
                        contact.extend((0..3).map(|k| (b, tv[k], -wk[k] * w[k] * push)));
                        found.push(contact);
                    }
                }
            } else if !o.contact_triangles() && a < b {
                for (i, &p) in x[a].iter().enumerate() {
                    for (j, &q) in x[b].iter().enumerate() {
                        let d = (q - p).length();
                        if !(d > 0.0 && d < reach) {
                            continue;
                        }
                        let n = (p - q) / d;
                        let share = |pinned_other: bool, mine: f64, theirs: f64| {
                            if pinned_other {
                                1.0
                            } else {
                                theirs / (mine + theirs)
                            }
                        };
                        let moved = (p - x0[a][i]) - (q - x0[b][j]);
                        let correction = n * (reach - d) - friction_correction(moved, n, reach - d, mu);
                        let move_p = correction * share(other.pinned[j], o.mass, other.mass);
                        let move_q = -correction * share(o.pinned[i], other.mass, o.mass);
                        let keep = |pinned: bool, v: DVec3| if pinned { DVec3::ZERO } else { v };
                        found.push(vec![
                            (a, i, keep(o.pinned[i], move_p)),
                            (b, j, keep(other.pinned[j], move_q)),
                        ]);
                    }
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
    for &(o, i, _) in found.iter().flatten() {
        touches[o][i] += 1;
    }
    let mut moves: Vec<Vec<DVec3>> = x.iter().map(|x| vec![DVec3::ZERO; x.len()]).collect();
    for contact in &found {
        // Pinned particles take no share, so their counts do not dilute the others'.
        let free = contact.iter().filter(|&&(o, i, _)| !m.objects[o].pinned[i]);
        let split = free.map(|&(o, i, _)| touches[o][i]).max().unwrap_or(1).max(1) as f64;
        for &(o, i, v) in contact {
            moves[o][i] += v / split;
        }
    }
    moves
}
