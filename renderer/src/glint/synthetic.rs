//! A generated height field for glint examples: Gaussian bumps and straight scratches (a few
//! texels deep), like scratched leather, wrapped around the example's edges. The glint tests
//! and `lazysolid bench glints` draw their examples from it, so both see the same field for a
//! seed.

use rand::{Rng, SeedableRng};

/// How far each bump is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BumpExtent {
    /// At every texel (exact; the tests' field).
    Everywhere,
    /// Within 4 σ of its centre (for large examples, where evaluating every bump at every
    /// texel is quadratic).
    FourSigma,
}

/// The `size`² field for `seed`: `size / 2` bumps, then `size / 8` scratches.
pub fn bumps_and_scratches(size: usize, seed: u64, extent: BumpExtent) -> Vec<f32> {
    let mut r = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut h = vec![0.0f32; size * size];
    let s = size as f32;
    let wrap = |d: f32| d - s * (d / s).round();
    for _ in 0..size / 2 {
        let (cx, cy) = (r.random::<f32>() * s, r.random::<f32>() * s);
        let (radius, height) = (1.5 + 4.0 * r.random::<f32>(), r.random::<f32>() * 2.0 - 1.0);
        let bump = |x: f32, y: f32| {
            let (dx, dy) = (wrap(x - cx), wrap(y - cy));
            height * (-(dx * dx + dy * dy) / (2.0 * radius * radius)).exp()
        };
        match extent {
            BumpExtent::Everywhere => {
                for (i, v) in h.iter_mut().enumerate() {
                    *v += bump((i % size) as f32, (i / size) as f32);
                }
            }
            BumpExtent::FourSigma => {
                let reach = (4.0 * radius).ceil() as i64;
                for dy in -reach..=reach {
                    for dx in -reach..=reach {
                        let x = (cx.floor() as i64 + dx).rem_euclid(size as i64) as usize;
                        let y = (cy.floor() as i64 + dy).rem_euclid(size as i64) as usize;
                        h[y * size + x] += bump(x as f32, y as f32);
                    }
                }
            }
        }
    }
    for _ in 0..size / 8 {
        let (cx, cy) = (r.random::<f32>() * s, r.random::<f32>() * s);
        let angle = r.random::<f32>() * std::f32::consts::PI;
        let (nx, ny) = (-angle.sin(), angle.cos());
        for (i, v) in h.iter_mut().enumerate() {
            let d = wrap((i % size) as f32 - cx) * nx + wrap((i / size) as f32 - cy) * ny;
            *v -= 0.8 * (-d * d / 0.8).exp();
        }
    }
    h
}
