//! Slices of a synthesized cube as images: what a person looks at and what the quality figures
//! score, the same pixels for both.

use super::volume::SolidSynthesis;

/// An axis-aligned slice of a synthesized cube of side `n`: perpendicular to world `axis` at
/// `at`, over that role's image axes; colours and the role's own coordinates.
pub fn slice(
    synthesis: &SolidSynthesis,
    colours: &[[u8; 3]],
    axis: usize,
    at: u32,
) -> (Vec<[u8; 3]>, Vec<u32>) {
    let n = synthesis.window.size[0] as usize;
    let triples = synthesis.window_triples();
    let coords = slice_indices(n, axis, at as usize)
        .map(|idx| triples[idx][axis])
        .collect();
    (colour_slice(colours, n, axis, at as usize), coords)
}

/// The colours of the same slice as [`slice()`] of any cube of side `n` stored x fastest, with
/// or without triples behind it (a colour-state synthesizer's volume, a decoded NRRD).
pub fn colour_slice(colours: &[[u8; 3]], n: usize, axis: usize, at: usize) -> Vec<[u8; 3]> {
    slice_indices(n, axis, at).map(|idx| colours[idx]).collect()
}

/// The voxel indices of the slice, row by row over the role's image axes.
fn slice_indices(n: usize, axis: usize, at: usize) -> impl Iterator<Item = usize> {
    let [a, b] = super::roles::ROLE_AXES[axis];
    (0..n * n).map(move |k| {
        let mut p = [0usize; 3];
        p[axis] = at;
        p[a] = k % n;
        p[b] = k / n;
        (p[2] * n + p[1]) * n + p[0]
    })
}

/// The diagonal plane `y + z = n − 1` of a cube of side `n` (a 45° cut about x), as an
/// `n`×`n` image (stretched by √2 along its second axis).
pub fn oblique(colours: &[[u8; 3]], n: usize) -> Vec<[u8; 3]> {
    (0..n * n)
        .map(|k| {
            let (x, y) = (k % n, k / n);
            let z = n - 1 - y;
            colours[(z * n + y) * n + x]
        })
        .collect()
}
