//! A procedural solid texture to fill stores with until synthesis exists: marble veins from
//! integer-hash value noise, computed entirely in integers (16.16 fixed point) so that the
//! GPU version (`glsl/include/store/marble.glsl`) gives the same bytes.

/// Lattice cells of the noise per unit of object space at the first octave.
const BASE_FREQUENCY: u64 = 4;
/// Octaves of the turbulence.
const OCTAVES: u32 = 3;
/// Vein colour and background colour (RGB).
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
fn smooth(f: u64) -> i64 {
    ((f * f * (3 * 65536 - 2 * f)) >> 32) as i64
}

fn lerp(a: i64, b: i64, s: i64) -> i64 {
    a + (((b - a) * s) >> 16)
}

/// Value noise in 0..65536 at a 16.16 fixed-point point.
fn value_noise(p: [u64; 3], seed: u32) -> i64 {
    let i = p.map(|c| (c >> 16) as u32);
    let s = p.map(|c| smooth(c & 0xffff));
    let corner =
        |o: u32| (hash3(i[0] + (o & 1), i[1] + ((o >> 1) & 1), i[2] + (o >> 2), seed) >> 16) as i64;
    let x00 = lerp(corner(0), corner(1), s[0]);
    let x10 = lerp(corner(2), corner(3), s[0]);
    let x01 = lerp(corner(4), corner(5), s[0]);
    let x11 = lerp(corner(6), corner(7), s[0]);
    lerp(lerp(x00, x10, s[1]), lerp(x01, x11, s[1]), s[2])
}

/// The marble colour (RGBA8, red in the low byte, alpha 255) of the centre of `voxel` in a
/// `resolution`³ grid over the unit cube.
pub fn marble_rgba8(voxel: [u32; 3], resolution: u32, seed: u32) -> u32 {
    let r2 = 2 * resolution as u64;
    let mut turbulence = 0i64;
    for octave in 0..OCTAVES {
        let f = BASE_FREQUENCY << octave;
        let p = voxel.map(|c| ((2 * c as u64 + 1) * f * 65536) / r2);
        turbulence += value_noise(p, seed.wrapping_add(octave)) >> (octave + 1);
    }
    let stripe = ((2 * voxel[0] as u64 + 1) * BASE_FREQUENCY * 65536) / r2;
    let phase = (stripe as i64 + 6 * turbulence) & 0x1ffff;
    let band = if phase < 65536 { phase } else { 131071 - phase };
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
}
