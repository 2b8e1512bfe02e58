//! The runtime neighbourhood of the correction (Lefebvre & Hoppe 2006, §4): the appearance
//! vectors at the 4 diagonal neighbours only, each predicted from 3 synthesized pixels.
//!
//! For a diagonal `Δ` the synthesized pixels `p + Δ`, `p + (Δx, 0)` and `p + (0, Δy)` (three
//! different parity classes) each predict the exemplar coordinate at `p + Δ`:
//! `S[p + Δ]`, `S[p + (Δx, 0)] + h·(0, Δy)` and `S[p + (0, Δy)] + h·(Δx, 0)`. The synthesized
//! neighbourhood is the *sum* of the three predicted appearance vectors per diagonal (32
//! integers); the exemplar neighbourhood of a candidate `u` is `3 · A[u + h·Δ]`, so the
//! comparison is the paper's average without a division. Averaging over three classes keeps
//! the Gauss–Seidel subpasses converging although the 4 diagonals share one class.
//!
//! The exemplar side is precomputed per pixel and level ([`exemplar_neighbourhoods`]): one
//! contiguous 32-byte record per candidate instead of 8 scattered appearance fetches, which is
//! what makes a candidate cheap on a GPU (and on lavapipe, where every per-lane load costs).

use super::appearance::APPEARANCE_DIMS;
use super::coords::{pack, unpack};

/// The 4 diagonal offsets, in the order of the neighbourhood's components.
pub const DIAGONALS: [(i32, i32); 4] = [(-1, -1), (1, -1), (-1, 1), (1, 1)];

/// Integers of one neighbourhood: 4 diagonals of [`APPEARANCE_DIMS`] components.
pub const NEIGHBOURHOOD_DIMS: usize = DIAGONALS.len() * APPEARANCE_DIMS;

/// Predictions averaged per diagonal.
pub const PREDICTIONS: i32 = 3;

/// `(c + d) mod n` for `c < n` and `|d| <= n`.
pub(crate) fn wrap(c: u32, d: i32, n: u32) -> u32 {
    (c as i32 + d + n as i32) as u32 % n
}

/// Packed coordinate `c` moved by `spacing · (dx, dy)` on the `w`×`h` torus.
pub(crate) fn shifted(c: u32, dx: i32, dy: i32, spacing: i32, w: u32, h: u32) -> u32 {
    let (x, y) = unpack(c);
    pack(wrap(x, dx * spacing, w), wrap(y, dy * spacing, h))
}

/// The exemplar neighbourhood of every pixel of a level: `A[u + h·Δ]` for the 4 diagonals,
/// row-major, from the level's appearance vectors.
pub fn exemplar_neighbourhoods(
    appearance: &[[i8; APPEARANCE_DIMS]],
    w: u32,
    h: u32,
    spacing: u32,
) -> Vec<[i8; NEIGHBOURHOOD_DIMS]> {
    let s = spacing as i32;
    (0..w * h)
        .map(|i| {
            let u = pack(i % w, i / w);
            let mut n = [0i8; NEIGHBOURHOOD_DIMS];
            for (j, &(dx, dy)) in DIAGONALS.iter().enumerate() {
                let (x, y) = unpack(shifted(u, dx, dy, s, w, h));
                n[j * APPEARANCE_DIMS..][..APPEARANCE_DIMS]
                    .copy_from_slice(&appearance[(y * w + x) as usize]);
            }
            n
        })
        .collect()
}

/// The synthesized neighbourhood from the 3×3 coordinates around a pixel (row by row, index
/// 4 the centre, which is not read): per diagonal the sum of the three predicted appearance
/// vectors.
pub fn synthesized_neighbourhood(
    around: &[u32; 9],
    appearance: impl Fn(u32) -> [i8; APPEARANCE_DIMS],
    spacing: i32,
    w: u32,
    h: u32,
) -> [i16; NEIGHBOURHOOD_DIMS] {
    let at = |dx: i32, dy: i32| around[((dy + 1) * 3 + dx + 1) as usize];
    let mut n = [0i16; NEIGHBOURHOOD_DIMS];
    for (j, &(dx, dy)) in DIAGONALS.iter().enumerate() {
        let predictions = [
            at(dx, dy),
            shifted(at(dx, 0), 0, dy, spacing, w, h),
            shifted(at(0, dy), dx, 0, spacing, w, h),
        ];
        for c in predictions {
            for (sum, v) in n[j * APPEARANCE_DIMS..].iter_mut().zip(appearance(c)) {
                *sum += i16::from(v);
            }
        }
    }
    n
}

/// Squared distance between a synthesized neighbourhood and `3 ×` an exemplar one (exact;
/// at most 32 · (2 · 3 · 128)² ≈ 1.9·10⁷).
///
/// Sums of three `i8` predictions and `3 ×` an `i8` both stay within ±384, so each difference
/// fits an `i16` and its square an `i32`: in 16-bit lanes the x86-64 baseline (SSE2) multiplies
/// and adds pairs in one instruction, while it cannot multiply 32-bit lanes. That matters
/// because the CPU correction spends most of its time here; the gain is in
/// `docs/log/solid.md` ("Open", "Candidate time at 128²").
///
/// The arithmetic wraps, as a release build's does: the bounds above make it exact for every
/// neighbourhood [`synthesized_neighbourhood`] builds, and without a debug build's overflow
/// check on each lane the test build can vectorize the loop too (`docs/testing.md`, "Where a
/// command-line test's time goes").
pub fn neighbourhood_distance(
    synthesized: &[i16; NEIGHBOURHOOD_DIMS],
    exemplar: &[i8; NEIGHBOURHOOD_DIMS],
) -> u32 {
    synthesized
        .iter()
        .zip(exemplar)
        .fold(0i32, |sum, (&s, &e)| {
            let d = i32::from(s.wrapping_sub((PREDICTIONS as i16).wrapping_mul(i16::from(e))));
            sum.wrapping_add(d.wrapping_mul(d))
        }) as u32
}

/// Packs records of `i8`s into little-endian `u32` words (4 components per word, the first in
/// the low byte), the layout the GLSL side unpacks with `bitfieldExtract`.
pub fn pack_i8_words(values: &[i8]) -> Vec<u32> {
    values
        .chunks(4)
        .map(|c| {
            c.iter()
                .enumerate()
                .fold(0u32, |w, (b, &v)| w | ((v as u8 as u32) << (8 * b)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coherent_neighbourhood_matches_its_exemplar_exactly() {
        // A 4×4 exemplar whose appearance encodes the position: in a coherent patch the
        // synthesized neighbourhood is 3× the exemplar's, at distance 0.
        let (w, h, s) = (4u32, 4u32, 1i32);
        let appearance: Vec<[i8; APPEARANCE_DIMS]> = (0..16)
            .map(|i| std::array::from_fn(|d| (i * 7 + d as i32 * 3 - 40) as i8))
            .collect();
        let neighbourhoods = exemplar_neighbourhoods(&appearance, w, h, s as u32);
        let centre = pack(0, 3);
        let around: [u32; 9] =
            std::array::from_fn(|n| shifted(centre, n as i32 % 3 - 1, n as i32 / 3 - 1, s, w, h));
        let syn = synthesized_neighbourhood(
            &around,
            |c| {
                let (x, y) = unpack(c);
                appearance[(y * w + x) as usize]
            },
            s,
            w,
            h,
        );
        assert_eq!(neighbourhood_distance(&syn, &neighbourhoods[12]), 0);
        assert!(neighbourhood_distance(&syn, &neighbourhoods[13]) > 0);
        // The record of pixel 12 = (0, 3): diagonal (−1, −1) is (3, 2) = pixel 11.
        assert_eq!(neighbourhoods[12][..APPEARANCE_DIMS], appearance[11]);
    }

    #[test]
    fn i8_words_are_little_endian_twos_complement() {
        assert_eq!(pack_i8_words(&[1, -1, 0, -128]), vec![0x80_00_ff_01]);
    }
}
