//! Smooth fields lazysolid makes itself, for the trees' tests and benchmarks: a fractal terrain
//! height field and the distance field of a torus. Deterministic for a seed.

use super::field::ScalarField;

fn hash(x: i32, y: i32, z: i32, seed: u32) -> f32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ (z as u32).wrapping_mul(0xcb1a_b31f)
        ^ seed.wrapping_mul(0x9e37_79b9);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

fn smoothstep(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// Value noise in [0, 1) at (x, y) with lattice spacing 1.
fn value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let (xi, yi) = (x.floor() as i32, y.floor() as i32);
    let (tx, ty) = (smoothstep(x - xi as f32), smoothstep(y - yi as f32));
    let a = hash(xi, yi, 0, seed);
    let b = hash(xi + 1, yi, 0, seed);
    let c = hash(xi, yi + 1, 0, seed);
    let d = hash(xi + 1, yi + 1, 0, seed);
    let top = a + (b - a) * tx;
    let bottom = c + (d - c) * tx;
    top + (bottom - top) * ty
}

/// A fractal terrain of `width`×`height` samples in grey levels 0–255: five octaves of value
/// noise, the coarsest 4 features across, gains halving.
pub fn terrain(width: u32, height: u32, seed: u32) -> ScalarField {
    let mut values = Vec::with_capacity((width * height) as usize);
    let side = width.max(height) as f32;
    for y in 0..height {
        for x in 0..width {
            let (mut f, mut amp, mut sum, mut norm) = (4.0 / side, 1.0, 0.0, 0.0);
            for octave in 0..5 {
                sum += amp * value_noise(x as f32 * f, y as f32 * f, seed + octave);
                norm += amp;
                f *= 2.0;
                amp *= 0.5;
            }
            values.push(255.0 * sum / norm);
        }
    }
    ScalarField::new("terrain", 2, [width, height, 1], values).expect("a terrain is in range")
}

/// The signed distance to a torus in the unit cube (radii 0.3 and 0.1, tilted), sampled on
/// `side`³ points and mapped to grey levels: 128 on the surface, 255 per unit of distance,
/// clamped to 0–255.
pub fn torus_distance(side: u32) -> ScalarField {
    let mut values = Vec::with_capacity((side * side * side) as usize);
    for z in 0..side {
        for y in 0..side {
            for x in 0..side {
                let p = [x, y, z].map(|v| (v as f32 + 0.5) / side as f32 - 0.5);
                let (px, py, pz) = (p[0], 0.8 * p[1] + 0.6 * p[2], -0.6 * p[1] + 0.8 * p[2]);
                let ring = (px * px + py * py).sqrt() - 0.3;
                let d = (ring * ring + pz * pz).sqrt() - 0.1;
                values.push((128.0 + 255.0 * d).clamp(0.0, 255.0));
            }
        }
    }
    ScalarField::new("torus distance", 3, [side; 3], values).expect("a distance is in range")
}
