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
    /// The distinct strips, padded (`padded`).
    strips: Vec<f32>,
    /// Pixels of distinct strip `u`: `members[first[u]..first[u + 1]]`, increasing.
    members: Vec<u32>,
    first: Vec<u32>,
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
        tree.strips = padded(&strips, dims);
        tree.build(0, n);
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

    /// The `k` strips nearest to `query`, ranked by (distance, index).
    pub(crate) fn nearest(&self, query: &[i32], k: usize) -> Vec<(u32, u32)> {
        let q = self.rotate(query);
        let query = padded(query, self.dims);
        let query = query.as_slice();
        let mut heap = BinaryHeap::with_capacity(k + 1);
        let mut offsets = vec![0.0f64; self.dims];
        self.visit(0, query, &q, &mut offsets, 0.0, k, &mut heap);
        heap.into_sorted_vec()
    }

    #[allow(clippy::too_many_arguments)]
    fn visit(
        &self,
        node: u32,
        query: &[f32],
        q: &[f64],
        offsets: &mut [f64],
        bound: f64,
        k: usize,
        heap: &mut BinaryHeap<(u32, u32)>,
    ) {
        match self.nodes[node as usize] {
            Node::Leaf { start, end } => {
                for &u in &self.order[start as usize..end as usize] {
                    let stride = query.len();
                    let d = ssd(query, &self.strips[u as usize * stride..][..stride]);
                    let (a, b) = (self.first[u as usize], self.first[u as usize + 1]);
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
            }
            Node::Split {
                dim,
                value,
                left,
                right,
            } => {
                let dim = dim as usize;
                let diff = q[dim] - value;
                let (near, far) = if diff < 0.0 {
                    (left, right)
                } else {
                    (right, left)
                };
                self.visit(near, query, q, offsets, bound, k, heap);
                let old = offsets[dim];
                let far_bound = bound - old * old + diff * diff;
                if heap.len() < k || !ruled_out(far_bound, heap.peek().expect("full").0) {
                    offsets[dim] = diff;
                    self.visit(far, query, q, offsets, far_bound, k, heap);
                    offsets[dim] = old;
                }
            }
        }
    }
}
