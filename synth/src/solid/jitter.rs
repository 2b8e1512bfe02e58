//! The 3D jitter: `J_l(p) = ⌊h_l · H(p) · r_l + ½⌋` per world axis, `H` an integer hash of the
//! absolute voxel position, the level, the axis and the seed into [−1, 1)³ (the 2D jitter of
//! `synth/jitter.rs` with a third coordinate), mirrored by `glsl/include/synth/solid.glsl`.
//! A voxel's triple moves by the projection of `J` into each role's image, which is the shift
//! of a coherent 3D block: the three coordinates stay in step.

use crate::hash4;

/// The jitter offset of absolute voxel `p` at `level` (each component in `-spacing..=spacing`).
pub fn jitter3(p: [i32; 3], level: u32, seed: u32, spacing: u32, strength: u32) -> [i32; 3] {
    let base = hash4(p[0] as u32, p[1] as u32, p[2] as u32, seed);
    [0u32, 1, 2].map(|axis| {
        let h = hash4(base, level | (axis << 8), 0x5011_d000, 0);
        let v = (h >> 16) as i64 - 32768;
        ((spacing as i64 * v * strength as i64 + (1 << 22)) >> 23) as i32
    })
}
