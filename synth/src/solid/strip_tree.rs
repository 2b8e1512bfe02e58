//! An exact k-nearest-neighbour search over integer strips: a k-d tree built in the principal
//! axes of the target strips, whose pruning only skips what cannot enter the result.
//!
//! Strips of neighbouring samples are strongly correlated, so in their principal axes most of
//! the spread lies along a few coordinates, where the tree splits. A query descends to its
//! leaf first and visits a far child only while the squared distance from the query to that
//! child's cell (accumulated per axis, Arya & Mount's incremental distance) does not exceed the
//! current k-th distance. Distances of the strips themselves are computed exactly in integers,
//! and a cell is skipped only when its bound exceeds the k-th distance by more than any
//! rounding of the rotation, so the result — ranked by (distance, index) — is the brute
//! force's, ties included.
//!
//! Identical strips are one point of the tree holding all their pixels (in increasing order):
//! at the coarsest levels of a Gaussian stack most strips are the same few colours, every
//! distance ties, and without this the search degenerates to the brute force.

use nalgebra::{DMatrix, SymmetricEigen};
use rayon::prelude::*;
use std::collections::BinaryHeap;

/// Most strips in a leaf.
const LEAF: usize = 12;

enum Node {
    Leaf {
        start: u32,
        end: u32,
    },
    Split {
        dim: u16,
        value: f64,
        left: u32,
        right: u32,
    },
}

/// A k-d tree over `dims`-value integer strips.
pub(crate) struct StripTree {
    /// The distinct strips, padded (`padded`), in the order of `order`: the strips of one
    /// leaf lie together in memory (in their own order a leaf's strips are scattered over
    /// megabytes, and loading them was most of a search's time).
    strips: Vec<f32>,
    /// Pixels of the distinct strip at tree position `at` (`order[at]`):
    /// `members[first[at]..first[at + 1]]`, increasing.
    members: Vec<u32>,
    first: Vec<u32>,
    /// Tree position of every target pixel's strip.
    position: Vec<u32>,
    dims: usize,
    /// Row-major rotation into the principal axes (largest variance first).
    rotation: Vec<f64>,
    /// Rotated coordinates of every strip.
    rotated: Vec<f64>,
    order: Vec<u32>,
    nodes: Vec<Node>,
}

/// Values per lane group of a padded strip: the distance loop runs over fixed groups of this
/// many independent accumulators, which the compiler turns into SIMD on any x86-64 or ARM
/// baseline (integer lanes would need SSE4.1's 32-bit multiply).
pub(crate) const LANES: usize = 8;

/// `dims` rounded up to whole lane groups.
pub(crate) fn padded_len(dims: usize) -> usize {
    dims.div_ceil(LANES) * LANES
}

/// Strips of `dims` integers as zero-padded `f32` rows of [`padded_len`] values, the layout
/// [`ssd`] reads.
pub(crate) fn padded(all: &[i32], dims: usize) -> Vec<f32> {
    let stride = padded_len(dims);
    let mut out = vec![0.0f32; all.len() / dims.max(1) * stride];
    for (row, v) in out.chunks_exact_mut(stride).zip(all.chunks_exact(dims)) {
        row.iter_mut().zip(v).for_each(|(o, &x)| *o = x as f32);
    }
    out
}

/// Squared distance of two padded strips, exact: every value is an integer, every product at
/// most 255² and every sum at most 3 · 11 · 255² < 2²⁴, all represented exactly in `f32`
/// whatever the order of the additions.
#[inline(always)]
pub(crate) fn ssd(a: &[f32], b: &[f32]) -> u32 {
    const _: () = assert!(3 * super::strips::MAX_STRIP as usize * 255 * 255 < 1 << 24);
    let mut acc = [0.0f32; LANES];
    for (x, y) in a.chunks_exact(LANES).zip(b.chunks_exact(LANES)) {
        for k in 0..LANES {
            let d = x[k] - y[k];
            acc[k] += d * d;
        }
    }
    acc.iter().sum::<f32>() as u32
}

/// Whether a cell at squared distance `bound` can no longer hold a strip that enters a list
/// whose worst distance is `worst` (a margin far above f64 rounding keeps ties in).
fn ruled_out(bound: f64, worst: u32) -> bool {
    bound > f64::from(worst) * (1.0 + 1e-9) + 1e-6
}

/// The distinct strips of `all` (`dims` values each) and, per distinct strip, its pixels in
/// increasing order (`members[first[u]..first[u + 1]]`).
pub(crate) fn distinct_strips(all: &[i32], dims: usize) -> (Vec<i32>, Vec<u32>, Vec<u32>) {
    let mut order: Vec<u32> = (0..(all.len() / dims) as u32).collect();
    let strip = |i: u32| &all[i as usize * dims..][..dims];
    order.sort_unstable_by(|&a, &b| strip(a).cmp(strip(b)).then(a.cmp(&b)));
    let (mut strips, mut first) = (Vec::new(), Vec::new());
    for (k, &i) in order.iter().enumerate() {
        if k == 0 || strip(order[k - 1]) != strip(i) {
            first.push(k as u32);
            strips.extend_from_slice(strip(i));
        }
    }
    first.push(order.len() as u32);
    (strips, order, first)
}

impl StripTree {
    /// Builds the tree over `all` (`dims` values per pixel).
    pub(crate) fn new(all: &[i32], dims: usize) -> StripTree {
        let (strips, members, first) = distinct_strips(all, dims);
        let n = strips.len() / dims;
        let mut mean = vec![0.0f64; dims];
        for v in strips.chunks_exact(dims) {
            mean.iter_mut()
                .zip(v)
                .for_each(|(m, &x)| *m += f64::from(x));
        }
        mean.iter_mut().for_each(|m| *m /= n.max(1) as f64);
        let mut cov = DMatrix::<f64>::zeros(dims, dims);
        for v in strips.chunks_exact(dims) {
            for a in 0..dims {
                let da = f64::from(v[a]) - mean[a];
                for b in 0..dims {
                    cov[(a, b)] += da * (f64::from(v[b]) - mean[b]);
                }
            }
        }
        let eigen = SymmetricEigen::new(cov);
        let mut axes: Vec<usize> = (0..dims).collect();
        axes.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
        let rotation: Vec<f64> = axes
            .iter()
            .flat_map(|&k| (0..dims).map(move |d| (k, d)))
            .map(|(k, d)| eigen.eigenvectors[(d, k)])
            .collect();
        let mut tree = StripTree {
            strips: Vec::new(),
            members,
            first,
            position: Vec::new(),
            dims,
            rotated: Vec::with_capacity(n * dims),
            rotation,
            order: (0..n as u32).collect(),
            nodes: Vec::new(),
        };
        for v in strips.chunks_exact(dims) {
            let r = tree.rotate(v);
            tree.rotated.extend(r);
        }
        tree.build(0, n);
        let padded = padded(&strips, dims);
        let stride = padded_len(dims);
        tree.strips = tree
            .order
            .iter()
            .flat_map(|&u| &padded[u as usize * stride..][..stride])
            .copied()
            .collect();
        // Pixels by tree position too.
        let (mut members, mut first) = (Vec::with_capacity(tree.members.len()), vec![0]);
        for &u in &tree.order {
            let (a, b) = (tree.first[u as usize], tree.first[u as usize + 1]);
            members.extend_from_slice(&tree.members[a as usize..b as usize]);
            first.push(members.len() as u32);
        }
        (tree.members, tree.first) = (members, first);
        tree.position = vec![0; tree.members.len()];
        for at in 0..n {
            for &pixel in &tree.members[tree.first[at] as usize..tree.first[at + 1] as usize] {
                tree.position[pixel as usize] = at as u32;
            }
        }
        tree
    }

    fn rotate(&self, v: &[i32]) -> Vec<f64> {
        self.rotation
            .chunks_exact(self.dims)
            .map(|axis| axis.iter().zip(v).map(|(a, &x)| a * f64::from(x)).sum())
            .collect()
    }

    fn coordinate(&self, i: u32, dim: usize) -> f64 {
        self.rotated[i as usize * self.dims + dim]
    }

    /// Builds the subtree over `order[start..end]` and returns its node index.
    fn build(&mut self, start: usize, end: usize) -> u32 {
        let id = self.nodes.len() as u32;
        if end - start <= LEAF {
            self.nodes.push(Node::Leaf {
                start: start as u32,
                end: end as u32,
            });
            return id;
        }
        // Split the widest axis at its median.
        let dim = (0..self.dims)
            .map(|d| {
                let (lo, hi) = self.order[start..end].iter().fold(
                    (f64::INFINITY, f64::NEG_INFINITY),
                    |(lo, hi), &i| {
                        let c = self.coordinate(i, d);
                        (lo.min(c), hi.max(c))
                    },
                );
                (hi - lo, d)
            })
            .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)))
            .expect("some axis")
            .1;
        let mid = (start + end) / 2;
        let rotated = &self.rotated;
        let dims = self.dims;
        self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            rotated[a as usize * dims + dim]
                .total_cmp(&rotated[b as usize * dims + dim])
                .then(a.cmp(&b))
        });
        let value = self.coordinate(self.order[mid], dim);
        self.nodes.push(Node::Leaf { start: 0, end: 0 });
        let left = self.build(start, mid);
        let right = self.build(mid, end);
        self.nodes[id as usize] = Node::Split {
            dim: dim as u16,
            value,
            left,
            right,
        };
        id
    }

    /// The `k` strips nearest to each of `queries` (`dims` values each), ranked by
    /// (distance, index), in the order of the queries.
    ///
    /// Queries are sorted by the leaf they descend to and answered in runs, each first offered the
    /// strips its predecessor in the run found: queries of one leaf share most of their
    /// nearest strips, so the k-th distance starts close to its final value and the descent
    /// skips far more cells. The seeds change only the order in which strips are offered,
    /// never which strips can enter, so the result is the brute force's.
    pub(crate) fn nearest_all(&self, queries: &[i32], k: usize) -> Vec<Vec<(u32, u32)>> {
        let dims = self.dims;
        let count = queries.len() / dims.max(1);
        // Each query rotated once: for its leaf here and for its descent below.
        let rotated: Vec<Vec<f64>> = queries
            .par_chunks_exact(dims)
            .map(|query| self.rotate(query))
            .collect();
        let leaves: Vec<u32> = rotated.iter().map(|q| self.leaf_of(q)).collect();
        let mut order: Vec<u32> = (0..count as u32).collect();
        order.sort_unstable_by_key(|&i| (leaves[i as usize], i));
        let scratch = || Seeds {
            seen: vec![false; self.first.len() - 1],
            last: Vec::new(),
        };
        let found: Vec<Vec<(u32, u32)>> = order
            .par_iter()
            .with_min_len(RUN)
            .map_init(scratch, |seeds, &i| {
                let i = i as usize;
                self.nearest_seeded(&queries[i * dims..][..dims], &rotated[i], k, seeds)
            })
            .collect();
        let mut out = vec![Vec::new(); count];
        for (&i, row) in order.iter().zip(found) {
            out[i as usize] = row;
        }
        out
    }

    /// The leaf a rotated query descends to (its near child at every split).
    fn leaf_of(&self, q: &[f64]) -> u32 {
        let mut node = 0u32;
        while let Node::Split {
            dim,
            value,
            left,
            right,
        } = self.nodes[node as usize]
        {
            node = if q[dim as usize] - value < 0.0 {
                left
            } else {
                right
            };
        }
        node
    }

    /// One query of [`nearest_all`](Self::nearest_all), the strips in `seeds.last` offered
    /// first (`q`: the query rotated); on return `seeds.last` holds this query's strips.
    fn nearest_seeded(
        &self,
        query: &[i32],
        q: &[f64],
        k: usize,
        seeds: &mut Seeds,
    ) -> Vec<(u32, u32)> {
        let query = padded(query, self.dims);
        let stride = query.len();
        let mut heap = BinaryHeap::with_capacity(k + 1);
        for &at in &seeds.last {
            let at = at as usize;
            self.offer(
                at,
                ssd(&query, &self.strips[at * stride..][..stride]),
                k,
                &mut heap,
            );
            seeds.seen[at] = true;
        }
        let mut offsets = vec![0.0f64; self.dims];
        let mut search = Search {
            query: &query,
            q,
            offsets: &mut offsets,
            k,
            heap: &mut heap,
            seen: &seeds.seen,
        };
        self.visit(0, 0.0, &mut search);
        for &at in &seeds.last {
            seeds.seen[at as usize] = false;
        }
        let found = heap.into_sorted_vec();
        seeds.last.clear();
        for &(_, pixel) in &found {
            let at = self.position[pixel as usize];
            if !seeds.seen[at as usize] {
                seeds.seen[at as usize] = true;
                seeds.last.push(at);
            }
        }
        for &at in &seeds.last {
            seeds.seen[at as usize] = false;
        }
        found
    }

    /// Offers the strip at tree position `at`, at distance `d`, to the `k` best.
    fn offer(&self, at: usize, d: u32, k: usize, heap: &mut BinaryHeap<(u32, u32)>) {
        // Every pixel of a strip farther than the worst kept ranks after it: skip the strip
        // without reading its pixels.
        if heap.len() == k && d > heap.peek().expect("full").0 {
            return;
        }
        let (a, b) = (self.first[at], self.first[at + 1]);
        for &pixel in &self.members[a as usize..b as usize] {
            if heap.len() < k {
                heap.push((d, pixel));
            } else if (d, pixel) < *heap.peek().expect("full") {
                // Replacing the top sifts down once (a pop and a push sift twice).
                *heap.peek_mut().expect("full") = (d, pixel);
            } else {
                // Later pixels of this strip rank after this one.
                break;
            }
        }
    }

    fn visit(&self, node: u32, bound: f64, search: &mut Search<'_>) {
        match self.nodes[node as usize] {
            Node::Leaf { start, end } => {
                let stride = search.query.len();
                for at in start as usize..end as usize {
                    if search.seen[at] {
                        continue;
                    }
                    let d = ssd(search.query, &self.strips[at * stride..][..stride]);
                    self.offer(at, d, search.k, search.heap);
                }
            }
            Node::Split {
                dim,
                value,
                left,
                right,
            } => {
                let dim = dim as usize;
                let diff = search.q[dim] - value;
                let (near, far) = if diff < 0.0 {
                    (left, right)
                } else {
                    (right, left)
                };
                self.visit(near, bound, search);
                let old = search.offsets[dim];
                let far_bound = bound - old * old + diff * diff;
                if search.heap.len() < search.k
                    || !ruled_out(far_bound, search.heap.peek().expect("full").0)
                {
                    search.offsets[dim] = diff;
                    self.visit(far, far_bound, search);
                    search.offsets[dim] = old;
                }
            }
        }
    }
}

/// Queries a worker answers in a row, seeding each with its predecessor's strips.
const RUN: usize = 64;

/// A worker's seeds: the tree positions of the previous query's strips, and marks of the
/// strips already offered to the current one.
struct Seeds {
    seen: Vec<bool>,
    last: Vec<u32>,
}

/// One query's descent.
struct Search<'a> {
    query: &'a [f32],
    q: &'a [f64],
    /// Per rotated axis, the query's offset from the cell along it (Arya & Mount).
    offsets: &'a mut [f64],
    k: usize,
    heap: &'a mut BinaryHeap<(u32, u32)>,
    seen: &'a [bool],
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The k nearest by brute force, ranked by (distance, pixel).
    fn brute(targets: &[i32], query: &[i32], dims: usize, k: usize) -> Vec<(u32, u32)> {
        let (q, stride) = (padded(query, dims), padded_len(dims));
        let t = padded(targets, dims);
        let mut all: Vec<(u32, u32)> = (0..targets.len() / dims)
            .map(|p| (ssd(&q, &t[p * stride..][..stride]), p as u32))
            .collect();
        all.sort_unstable();
        all.truncate(k);
        all
    }

    #[test]
    fn seeded_runs_give_the_brute_force_ranking_ties_included() {
        // Few distinct values, so that many strips are identical and many distances tie:
        // the seeds' order of offering must not change which pixels win a tie.
        let dims = 9;
        let mut state = 12345u32;
        let mut next = |range: u32| {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state % range
        };
        for (points, range, k) in [(700, 4, 65), (900, 60, 65), (300, 3, 400), (50, 255, 7)] {
            let targets: Vec<i32> = (0..points * dims).map(|_| next(range) as i32).collect();
            let queries: Vec<i32> = (0..200 * dims).map(|_| next(range) as i32).collect();
            let tree = StripTree::new(&targets, dims);
            let found = tree.nearest_all(&queries, k);
            for (i, query) in queries.chunks_exact(dims).enumerate() {
                assert_eq!(
                    found[i],
                    brute(&targets, query, dims, k),
                    "query {i}, range {range}"
                );
            }
        }
    }
}
