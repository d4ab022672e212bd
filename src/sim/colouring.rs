//! Vertex colourings of a mesh cloth's spring graph for VBD's Gauss-Seidel sweep: no spring
//! joins two particles of one colour, and each colour is a dependent pass of the sweep, so every
//! colour saved is a pass saved in each iteration of each substep.
//!
//! The fewer-coloured of DSatur's and greedy by degree's comes first (neither is best on every
//! mesh: a quad grid takes 5 by DSatur and 7 by greedy). Then one colour fewer is tried, again
//! while it succeeds: DSatur with the count fixed, where a particle whose neighbours hold every
//! colour is given one by a Kempe-chain interchange (two colours swapped over the connected part
//! of the graph they colour that touches the particle, which frees one of them), and the few
//! left without one after it by a tabu search (Hertz and de Werra's Tabucol) from the nearly
//! proper colouring. On a grid of triangles split along alternating diagonals, which 5 colours
//! suffice for, DSatur takes 7 and greedy 6; the interchanges at 5 leave a few particles, which a
//! few tabu moves place. Each try has a budget of work proportional to the particle count (the
//! chains' visits, the tabu search's evaluations of a move), so a mesh whose next count is out
//! of reach costs a bounded time and keeps the colouring it has.

use std::cmp::Reverse;
use std::collections::{BTreeSet, BinaryHeap, HashMap};

/// A graph in compressed rows: vertex `i`'s neighbours are `other[first[i]..first[i + 1]]`,
/// each pair listed from both ends, no vertex its own neighbour.
pub struct Graph<'a> {
    pub first: &'a [u32],
    pub other: &'a [u32],
}

impl Graph<'_> {
    fn len(&self) -> usize {
        self.first.len() - 1
    }

    fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        self.other[self.first[i] as usize..self.first[i + 1] as usize].iter().map(|&j| j as usize)
    }

    fn degree(&self, i: usize) -> usize {
        (self.first[i + 1] - self.first[i]) as usize
    }
}

/// Kempe-chain vertices a try at one colour fewer may visit, per vertex of the graph.
const CHAIN_VISITS_PER_VERTEX: usize = 64;
/// Tabu moves a try may make, per vertex left without a colour by the interchanges, and
/// evaluations of a vertex's move to another colour it may make, per vertex of the graph.
const TABU_MOVES_PER_LEFT: usize = 2_000;
const TABU_EVALUATIONS_PER_VERTEX: usize = 256;
/// A try whose interchanges leave more vertices than this (or 1 in 256 of them, if more)
/// without a colour is given up: the tabu search mends a nearly proper colouring, not a poor one.
const MOST_LEFT: usize = 16;
/// Colours are kept as bits of a word in the tries, so a colouring of more is kept as it is.
const MOST_COLOURS: usize = 64;

/// Each vertex's colour, from 0, as few as this module's search finds.
pub fn colour(g: &Graph) -> Vec<u32> {
    let count = |colour: &[u32]| colour.iter().max().map_or(0, |c| *c as usize + 1);
    let mut by_degree: Vec<usize> = (0..g.len()).collect();
    by_degree.sort_by_key(|&i| Reverse(g.degree(i)));
    let [saturated, greedy] = [dsatur(g), greedy(g, &by_degree)];
    let mut best = if count(&greedy) < count(&saturated) { greedy } else { saturated };
    while (2..=MOST_COLOURS).contains(&count(&best)) {
        match with_colours(g, count(&best) - 1) {
            Some(fewer) => best = fewer,
            None => break,
        }
    }
    best
}

/// DSatur (Brelaz 1979): each vertex's colour, given in turn to the vertex whose neighbours
/// already have the most distinct colours (ties: the most neighbours, then the lowest index),
/// the least colour they leave.
fn dsatur(g: &Graph) -> Vec<u32> {
    let n = g.len();
    let mut colour = vec![u32::MAX; n];
    let mut seen: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut queue: BinaryHeap<_> = (0..n).map(|i| (0u32, g.degree(i), Reverse(i))).collect();
    while let Some((saturation, _, Reverse(i))) = queue.pop() {
        if colour[i] != u32::MAX || saturation as usize != seen[i].len() {
            continue; // (coloured, or an older entry of a vertex seen since)
        }
        let c = (0..).find(|c| !seen[i].contains(c)).unwrap_or(0);
        colour[i] = c;
        for j in g.neighbours(i) {
            if colour[j] == u32::MAX && !seen[j].contains(&c) {
                seen[j].push(c);
                queue.push((seen[j].len() as u32, g.degree(j), Reverse(j)));
            }
        }
    }
    colour
}

/// Greedy colouring: the vertices in `order`, each the least colour its neighbours leave.
fn greedy(g: &Graph, order: &[usize]) -> Vec<u32> {
    let mut colour = vec![u32::MAX; order.len()];
    for &i in order {
        let taken: Vec<u32> = g.neighbours(i).map(|j| colour[j]).collect();
        colour[i] = (0..).find(|c| !taken.contains(c)).unwrap_or(0);
    }
    colour
}

/// A colouring of `k` colours (k <= MOST_COLOURS), or None where the try's budget ran out first.
fn with_colours(g: &Graph, k: usize) -> Option<Vec<u32>> {
    let n = g.len();
    // Vertices not yet coloured hold `UNSET`; those the interchanges leave hold `k` until the
    // tabu search: neither counts as a colour a neighbour holds.
    const UNSET: u32 = u32::MAX;
    let held = |colour: &[u32], i: usize| {
        g.neighbours(i).filter(|&j| (colour[j] as usize) < k).fold(0u64, |m, j| m | 1 << colour[j])
    };
    let all = if k == 64 { u64::MAX } else { (1u64 << k) - 1 };
    let mut colour = vec![UNSET; n];
    let mut chains = Chains { visits_left: CHAIN_VISITS_PER_VERTEX * n, seen: vec![0; n], stamp: 0 };
    let mut left = Vec::new();
    let mut queue: BinaryHeap<_> = (0..n).map(|i| (0u32, g.degree(i), Reverse(i))).collect();
    while let Some((saturation, _, Reverse(i))) = queue.pop() {
        if colour[i] != UNSET {
            continue;
        }
        let seen = held(&colour, i);
        if seen.count_ones() != saturation {
            // (an interchange changed its neighbours' colours since this entry)
            queue.push((seen.count_ones(), g.degree(i), Reverse(i)));
            continue;
        }
        let free = all & !seen;
        let changed = if free != 0 {
            colour[i] = free.trailing_zeros();
            vec![i]
        } else if let Some((c, mut chain)) = chains.interchange(g, &mut colour, i, k)? {
            colour[i] = c;
            chain.push(i);
            chain
        } else {
            colour[i] = k as u32;
            left.push(i);
            if left.len() > MOST_LEFT.max(n / 256) {
                return None;
            }
            continue;
        };
        for u in changed {
            for j in g.neighbours(u).filter(|&j| colour[j] == UNSET) {
                queue.push((held(&colour, j).count_ones(), g.degree(j), Reverse(j)));
            }
        }
    }
    if left.is_empty() {
        return Some(colour);
    }
    tabu(g, colour, &left, k, (TABU_MOVES_PER_LEFT * left.len(), TABU_EVALUATIONS_PER_VERTEX * n))
}

/// The Kempe chains' walk: a stamp a walk marks its vertices with, so that no walk clears the
/// marks of the one before, and the visits the try has left.
struct Chains {
    visits_left: usize,
    seen: Vec<u32>,
    stamp: u32,
}

impl Chains {
    /// Frees a colour for vertex `v`, all of whose neighbours are coloured `0..k` and hold every
    /// colour: for colours a and b, the vertices coloured a or b connected to v's a-coloured
    /// neighbours through such vertices (v aside) swap a and b, if none is a b-coloured
    /// neighbour of v; then v may take a. Returns a and the swapped vertices; Ok(None) where
    /// no pair of colours can; None where the visits ran out.
    fn interchange(
        &mut self,
        g: &Graph,
        colour: &mut [u32],
        v: usize,
        k: usize,
    ) -> Option<Option<(u32, Vec<usize>)>> {
        for a in 0..k as u32 {
            'pair: for b in (0..k as u32).filter(|&b| b != a) {
                self.stamp += 1;
                let mut chain: Vec<usize> = g.neighbours(v).filter(|&j| colour[j] == a).collect();
                chain.iter().for_each(|&j| self.seen[j] = self.stamp);
                let mut at = 0;
                while let Some(&u) = chain.get(at) {
                    at += 1;
                    self.visits_left = self.visits_left.checked_sub(1)?;
                    for w in g.neighbours(u) {
                        if w == v || self.seen[w] == self.stamp || (colour[w] != a && colour[w] != b) {
                            continue;
                        }
                        if colour[w] == b && g.neighbours(v).any(|j| j == w) {
                            continue 'pair;
                        }
                        self.seen[w] = self.stamp;
                        chain.push(w);
                    }
                }
                for &u in &chain {
                    colour[u] = if colour[u] == a { b } else { a };
                }
                return Some(Some((a, chain)));
            }
        }
        Some(None)
    }
}

/// Tabucol (Hertz and de Werra 1987) from `colour`, where the vertices `left` hold `k`: each is
/// given the colour fewest of its neighbours hold, then, while any spring joins two vertices of
/// one colour, the move of one such vertex to another colour that leaves the fewest such
/// springs is made (a move back forbidden for a while, unless it would leave fewer than ever),
/// at most `moves` times and within `evaluations` of a vertex's move. The random choices are seeded, so that a mesh's colouring is the same
/// at every load.
fn tabu(
    g: &Graph,
    mut colour: Vec<u32>,
    left: &[usize],
    k: usize,
    (moves, mut evaluations): (usize, usize),
) -> Option<Vec<u32>> {
    let clashes = |colour: &[u32], v: usize, c: u32| g.neighbours(v).filter(|&j| colour[j] == c).count();
    for &v in left {
        colour[v] = (0..k as u32).min_by_key(|&c| clashes(&colour, v, c)).unwrap_or(0);
    }
    let clashing = |colour: &[u32], v: usize| clashes(colour, v, colour[v]) > 0;
    let mut clash: BTreeSet<usize> = left
        .iter()
        .flat_map(|&v| std::iter::once(v).chain(g.neighbours(v)))
        .filter(|&v| clashing(&colour, v))
        .collect();
    let mut total: usize = clash.iter().map(|&v| clashes(&colour, v, colour[v])).sum::<usize>() / 2;
    let mut fewest = total;
    let mut banned_until: HashMap<(usize, u32), usize> = HashMap::new();
    let mut random = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        random ^= random << 13;
        random ^= random >> 7;
        random ^= random << 17;
        random
    };
    for step in 1..=moves {
        if clash.is_empty() {
            return Some(colour);
        }
        // The best move, ties broken at random (reservoir sampling).
        let mut best: Option<(isize, usize, u32)> = None;
        let mut ties = 0u64;
        evaluations = evaluations.checked_sub(clash.len() * k)?;
        for &v in &clash {
            let here = clashes(&colour, v, colour[v]) as isize;
            for c in (0..k as u32).filter(|&c| c != colour[v]) {
                let d = clashes(&colour, v, c) as isize - here;
                let allowed = banned_until.get(&(v, c)).is_none_or(|&until| until < step)
                    || total as isize + d < fewest as isize;
                match best {
                    _ if !allowed => {}
                    Some((bd, ..)) if d > bd => {}
                    Some((bd, ..)) if d == bd => {
                        ties += 1;
                        if next() % ties == 0 {
                            best = Some((d, v, c));
                        }
                    }
                    _ => {
                        (best, ties) = (Some((d, v, c)), 1);
                    }
                }
            }
        }
        let Some((d, v, c)) = best else { continue };
        let was = colour[v];
        colour[v] = c;
        total = (total as isize + d) as usize;
        fewest = fewest.min(total);
        banned_until.insert((v, was), step + clash.len() * 3 / 5 + (next() % 10) as usize);
        for u in std::iter::once(v).chain(g.neighbours(v)) {
            if clashing(&colour, u) {
                clash.insert(u);
            } else {
                clash.remove(&u);
            }
        }
    }
    clash.is_empty().then_some(colour)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A graph from its pairs, each listed from both ends.
    fn graph(n: usize, pairs: &[(usize, usize)]) -> (Vec<u32>, Vec<u32>) {
        let mut lists = vec![Vec::new(); n];
        for &(a, b) in pairs {
            lists[a].push(b as u32);
            lists[b].push(a as u32);
        }
        let first = std::iter::once(0).chain(lists.iter().scan(0, |at, l| {
            *at += l.len() as u32;
            Some(*at)
        }));
        (first.collect(), lists.concat())
    }

    fn assert_proper(g: &Graph, colour: &[u32]) {
        for i in 0..g.len() {
            assert!(g.neighbours(i).all(|j| colour[j] != colour[i]), "{i} shares a colour");
        }
    }

    /// Closed forms: an odd cycle takes 3 colours, an even one 2, a complete graph of 6 takes 6,
    /// a wheel of 5 spokes 4 (its odd rim 3, the hub one more), a graph of no pairs 1.
    #[test]
    fn small_graphs_take_their_chromatic_numbers() {
        let cycle = |n: usize| (0..n).map(|i| (i, (i + 1) % n)).collect::<Vec<_>>();
        let complete: Vec<_> = (0..6).flat_map(|a| (a + 1..6).map(move |b| (a, b))).collect();
        let wheel: Vec<_> = cycle(5).into_iter().chain((0..5).map(|i| (i, 5))).collect();
        for (n, pairs, colours) in
            [(9, cycle(9), 3), (10, cycle(10), 2), (6, complete, 6), (6, wheel, 4), (3, vec![], 1)]
        {
            let (first, other) = graph(n, &pairs);
            let g = Graph { first: &first, other: &other };
            let colour = colour(&g);
            assert_proper(&g, &colour);
            assert_eq!(colour.iter().max().map(|c| c + 1), Some(colours), "{pairs:?}");
        }
    }

    /// Random sparse graphs (each vertex joined to 6 others on average): the colouring is
    /// proper, no worse than DSatur's, and the same at every call.
    #[test]
    fn random_graphs_colour_properly_and_repeatably() {
        let mut random = 12345u64;
        let mut next = |m: usize| {
            random = random.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (random >> 33) as usize % m
        };
        for n in [50, 500, 3000] {
            let mut pairs: Vec<(usize, usize)> =
                (0..3 * n).map(|_| (next(n), next(n))).filter(|(a, b)| a != b).collect();
            pairs.sort_unstable_by_key(|&(a, b)| (a.min(b), a.max(b)));
            pairs.dedup_by_key(|&mut (a, b)| (a.min(b), a.max(b)));
            let (first, other) = graph(n, &pairs);
            let g = Graph { first: &first, other: &other };
            let colour = colour(&g);
            assert_proper(&g, &colour);
            assert!(colour.iter().max() <= dsatur(&g).iter().max());
            assert_eq!(colour, super::colour(&g));
        }
    }
}
