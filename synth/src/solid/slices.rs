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
    let w = synthesis.window;
    let n = w.size[0] as usize;
    let triples = synthesis.window_triples();
    let [a, b] = super::roles::ROLE_AXES[axis];
    let mut rgb = Vec::with_capacity(n * n);
    let mut coords = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let mut p = [0usize; 3];
            p[axis] = at as usize;
            p[a] = i;
            p[b] = j;
            let idx = (p[2] * n + p[1]) * n + p[0];
            rgb.push(colours[idx]);
            coords.push(triples[idx][axis]);
        }
    }
    (rgb, coords)
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
