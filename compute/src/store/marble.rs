//! The procedural marble: veins from integer-hash value noise, computed entirely in integers
//! (16.16 fixed point) so that the GPU version (`glsl/include/store/marble.glsl`) gives the same
//! bytes. It is lazysolid's one procedural marble: stores are filled with it until synthesis
//! exists, and the renderer's `marble` solid texture evaluates it at hit points.

/// Lattice cells of the noise per unit of the unit cube at the first octave; a point given in
/// lattice cells ([`marble_band_at`]) is this many times the unit-cube point.
pub const MARBLE_BASE_FREQUENCY: u64 = 4;
/// The band's range: [`marble_band`] is in `0..=MARBLE_BAND_ONE`.
pub const MARBLE_BAND_ONE: i64 = 65536;
/// Octaves of the turbulence.
const OCTAVES: u32 = 3;
/// Vein colour and background colour (RGB) of [`marble_rgba8`].
const DARK: [i64; 3] = [60, 40, 30];
const LIGHT: [i64; 3] = [235, 225, 210];

fn hash3(x: u32, y: u32, z: u32, seed: u32) -> u32 {
    let mut h = seed
        ^ x.wrapping_mul(0x8da6_b343)
        ^ y.wrapping_mul(0xd816_3841)
        ^ z.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^ (h >> 16)
}

/// 3t² − 2t³ of a 16-bit fraction, in 16 bits.
fn smooth(f: i64) -> i64 {
    (f * f * (3 * 65536 - 2 * f)) >> 32
}

fn lerp(a: i64, b: i64, s: i64) -> i64 {
    a + (((b - a) * s) >> 16)
}

/// Value noise in 0..65536 at a 16.16 fixed-point point (any sign; cells wrap at 2^32).
fn value_noise(p: [i64; 3], seed: u32) -> i64 {
    let i = p.map(|c| (c >> 16) as u32);
    let s = p.map(|c| smooth(c & 0xffff));
    let corner = |o: u32| {
        (hash3(
            i[0].wrapping_add(o & 1),
            i[1].wrapping_add((o >> 1) & 1),
            i[2].wrapping_add(o >> 2),
            seed,
        ) >> 16) as i64
    };
    let x00 = lerp(corner(0), corner(1), s[0]);
    let x10 = lerp(corner(2), corner(3), s[0]);
    let x01 = lerp(corner(4), corner(5), s[0]);
    let x11 = lerp(corner(6), corner(7), s[0]);
    lerp(lerp(x00, x10, s[1]), lerp(x01, x11, s[1]), s[2])
}

/// The marble's band at the point `num / den` of unit-cube space (`den > 0`, `num` of any sign):
/// 0 in the middle of a vein, [`MARBLE_BAND_ONE`] between veins. Every fixed-point coordinate
/// is a floor division of `num`, so exact rationals (voxel centres) give exact bytes.
pub fn marble_band(num: [i64; 3], den: i64, seed: u32) -> i64 {
    let at = |c: i64, f: u64| (c * f as i64 * 65536).div_euclid(den);
    let mut turbulence = 0i64;
    for octave in 0..OCTAVES {
        let f = MARBLE_BASE_FREQUENCY << octave;
        let p = num.map(|c| at(c, f));
        turbulence += value_noise(p, seed.wrapping_add(octave)) >> (octave + 1);
    }
    let stripe = at(num[0], MARBLE_BASE_FREQUENCY);
    let phase = (stripe + 6 * turbulence) & 0x1ffff;
    if phase < 65536 {
        phase
    } else {
        131071 - phase
    }
}

/// The band at `p` given in lattice cells of the first octave (the renderer's texture space):
/// `p` is rounded down to 16.16 fixed point, the same way on the CPU and the GPU.
pub fn marble_band_at(p: [f32; 3], seed: u32) -> i64 {
    let num = p.map(|c| (c * 65536.0).floor() as i64);
    marble_band(num, MARBLE_BASE_FREQUENCY as i64 * 65536, seed)
}

/// The marble colour (RGBA8, red in the low byte, alpha 255) of the centre of `voxel` in a
/// `resolution`³ grid over the unit cube.
pub fn marble_rgba8(voxel: [u32; 3], resolution: u32, seed: u32) -> u32 {
    let band = marble_band(voxel.map(|c| 2 * c as i64 + 1), 2 * resolution as i64, seed);
    let mut rgba = 0xff00_0000u32;
    for (c, (d, l)) in DARK.iter().zip(LIGHT).enumerate() {
        rgba |= (lerp(*d, l, band) as u32) << (8 * c);
    }
    rgba
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marble_is_opaque_and_varies() {
        let a = marble_rgba8([3, 4, 5], 64, 1);
        assert_eq!(a >> 24, 255);
        let distinct: std::collections::HashSet<u32> =
            (0..64).map(|x| marble_rgba8([x, 10, 20], 64, 1)).collect();
        assert!(distinct.len() > 20, "{}", distinct.len());
        assert_ne!(marble_rgba8([3, 4, 5], 64, 2), a);
    }

    /// The voxel colours of the integer marble as first shipped (unsigned arithmetic, one
    /// formula): rewriting it over signed rational points changed no byte.
    #[test]
    fn voxel_colours_match_the_unsigned_formula() {
        fn unsigned(voxel: [u32; 3], resolution: u32, seed: u32) -> u32 {
            let r2 = 2 * resolution as u64;
            let mut turbulence = 0i64;
            for octave in 0..OCTAVES {
                let f = MARBLE_BASE_FREQUENCY << octave;
                let p = voxel.map(|c| ((2 * c as u64 + 1) * f * 65536) / r2);
                turbulence +=
                    value_noise(p.map(|c| c as i64), seed.wrapping_add(octave)) >> (octave + 1);
            }
            let stripe = ((2 * voxel[0] as u64 + 1) * MARBLE_BASE_FREQUENCY * 65536) / r2;
            let phase = (stripe as i64 + 6 * turbulence) & 0x1ffff;
            let band = if phase < 65536 { phase } else { 131071 - phase };
            let mut rgba = 0xff00_0000u32;
            for (c, (d, l)) in DARK.iter().zip(LIGHT).enumerate() {
                rgba |= (lerp(*d, l, band) as u32) << (8 * c);
            }
            rgba
        }
        for r in [1, 7, 64, 513] {
            for i in 0..200u32 {
                let v = [i * 7 % r, i * 13 % r, i * 29 % r];
                assert_eq!(marble_rgba8(v, r, i), unsigned(v, r, i), "{v:?} at {r}");
            }
        }
    }

    #[test]
    fn band_is_continuous_across_zero() {
        let a = marble_band_at([-1e-4, 0.3, 0.7], 0);
        let b = marble_band_at([1e-4, 0.3, 0.7], 0);
        assert!((a - b).abs() < 200, "{a} vs {b}");
        for x in -40..40 {
            let band = marble_band_at([x as f32 * 0.37, -2.5, 1.25], 3);
            assert!((0..=MARBLE_BAND_ONE).contains(&band), "{band}");
        }
    }
}
