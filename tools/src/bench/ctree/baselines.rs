//! Fixed-rate texture-compression baselines: BC1, BC4, BC7 and 2x2 vector quantisation.
//!
//! Each codec is exposed as an encode-then-decode round trip, because what a comparison needs
//! is the image a GPU would actually sample from the compressed texture, measured against the
//! original with [`psnr_rgb`]. BC1 and BC7 encoding use Intel's ISPC texture compressor
//! (`intel_tex_2`, prebuilt kernels) and decoding uses `bcdec_rs`, so the baselines are the
//! formats' real decoders rather than approximations of them. The VQ baseline is written here:
//! it is simple, and owning it keeps its output byte-identical across dependency updates.

use rayon::prelude::*;

// `intel_tex_2` bundles a C++ object (its ASTC encoder) whose unwind tables name libstdc++'s
// personality routine. Rust's default linker on x86_64 Linux (rust-lld, since 1.90) rejects that
// undefined symbol even though the code referencing it is never called, so libstdc++ is linked
// here. An empty block: nothing is declared or called through it.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[link(name = "stdc++")]
extern "C" {}

/// An RGBA8 image, row-major, 4 bytes per texel.
///
/// Plain public fields so callers can build one from any source without conversions; use
/// [`Rgba8::new`] where the buffer length should be checked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rgba8 {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<u8>,
}

impl Rgba8 {
    /// Builds an image, panicking on a buffer of the wrong length so that a bad size surfaces
    /// here rather than as an out-of-bounds access deep inside a codec.
    pub fn new(width: u32, height: u32, texels: Vec<u8>) -> Self {
        assert_eq!(
            texels.len(),
            texel_count(width, height) * 4,
            "RGBA8 buffer length does not match {width}x{height}"
        );
        Self {
            width,
            height,
            texels,
        }
    }

    /// Replicates a single-channel field into R, G and B (alpha opaque), which is how scalar
    /// fields are fed to the colour codecs here.
    pub fn from_gray(width: u32, height: u32, gray: &[u8]) -> Self {
        assert_eq!(
            gray.len(),
            texel_count(width, height),
            "grey buffer length does not match {width}x{height}"
        );
        let texels = gray.iter().flat_map(|&g| [g, g, g, 255]).collect();
        Self {
            width,
            height,
            texels,
        }
    }

    /// Reads a single-channel field back as the rounded mean of R, G and B: after BC1's 5:6:5
    /// quantisation the three channels of a grey texel no longer agree, and their mean is a
    /// better estimate of the original value than any one of them.
    pub fn to_gray(&self) -> Vec<u8> {
        self.texels
            .chunks_exact(4)
            .map(|t| {
                let sum = u32::from(t[0]) + u32::from(t[1]) + u32::from(t[2]);
                // Values fit in u8: at most (765 + 1) / 3 = 255.
                ((sum + 1) / 3) as u8
            })
            .collect()
    }

    fn is_empty(&self) -> bool {
        self.width == 0 || self.height == 0
    }
}

fn texel_count(width: u32, height: u32) -> usize {
    width as usize * height as usize
}

/// A copy of `img` grown to multiples of `multiple` by repeating the last column and row, so that
/// the padding adds no new colours for an encoder to spend precision on.
fn pad_to_multiple(img: &Rgba8, multiple: u32) -> Rgba8 {
    let width = img.width.div_ceil(multiple) * multiple;
    let height = img.height.div_ceil(multiple) * multiple;
    if width == img.width && height == img.height {
        return img.clone();
    }
    let src_stride = img.width as usize * 4;
    let mut texels = Vec::with_capacity(texel_count(width, height) * 4);
    for y in 0..height {
        let sy = y.min(img.height - 1) as usize;
        let row = &img.texels[sy * src_stride..(sy + 1) * src_stride];
        texels.extend_from_slice(row);
        let last = &row[src_stride - 4..];
        for _ in img.width..width {
            texels.extend_from_slice(last);
        }
    }
    Rgba8 {
        width,
        height,
        texels,
    }
}

/// The top-left `width` x `height` texels of `padded`, undoing [`pad_to_multiple`].
fn crop(padded: &Rgba8, width: u32, height: u32) -> Rgba8 {
    if padded.width == width && padded.height == height {
        return padded.clone();
    }
    let src_stride = padded.width as usize * 4;
    let row_bytes = width as usize * 4;
    let texels = padded
        .texels
        .chunks_exact(src_stride)
        .take(height as usize)
        .flat_map(|row| &row[..row_bytes])
        .copied()
        .collect();
    Rgba8 {
        width,
        height,
        texels,
    }
}

/// Shared BCn round trip: pad to whole 4x4 blocks, encode and decode one row of blocks per rayon
/// task (the ISPC kernels themselves are single-threaded), then crop.
fn bc_roundtrip<E>(
    img: &Rgba8,
    block_bytes: usize,
    encode: E,
    decode: fn(&[u8], &mut [u8], usize),
) -> Rgba8
where
    E: Fn(&intel_tex_2::RgbaSurface, &mut [u8]) + Sync,
{
    if img.is_empty() {
        return img.clone();
    }
    let padded = pad_to_multiple(img, 4);
    let stride = padded.width as usize * 4;
    let blocks_per_row = padded.width as usize / 4;
    let strip_bytes = stride * 4;

    let mut blocks = vec![0u8; blocks_per_row * (padded.height as usize / 4) * block_bytes];
    blocks
        .par_chunks_mut(blocks_per_row * block_bytes)
        .zip(padded.texels.par_chunks(strip_bytes))
        .for_each(|(out, strip)| {
            let surface = intel_tex_2::RgbaSurface {
                data: strip,
                width: padded.width,
                height: 4,
                stride: stride as u32,
            };
            encode(&surface, out);
        });

    let mut decoded = vec![0u8; padded.texels.len()];
    decoded
        .par_chunks_mut(strip_bytes)
        .zip(blocks.par_chunks(blocks_per_row * block_bytes))
        .for_each(|(strip, row_blocks)| {
            for (bx, block) in row_blocks.chunks_exact(block_bytes).enumerate() {
                decode(block, &mut strip[bx * 16..], stride);
            }
        });

    crop(
        &Rgba8 {
            width: padded.width,
            height: padded.height,
            texels: decoded,
        },
        img.width,
        img.height,
    )
}

/// BC1 (DXT1, 4 bits per texel) encode then decode: what a GPU would sample.
///
/// The lowest-rate block format every desktop GPU samples natively, hence the floor any learned
/// or procedural representation has to beat. Alpha is not encoded (opaque BC1); the result's
/// alpha is whatever the decoder yields, normally 255.
pub fn bc1_roundtrip(img: &Rgba8) -> Rgba8 {
    bc_roundtrip(
        img,
        8,
        intel_tex_2::bc1::compress_blocks_into,
        bcdec_rs::bc1,
    )
}

/// BC7 (8 bits per texel) encode then decode.
///
/// The highest-quality fixed-rate RGBA8 block format, so it bounds what the hardware formats can
/// do at twice BC1's rate. Encoded with `intel_tex_2::bc7::opaque_basic_settings()` (all mode
/// groups enabled, two refinement iterations): the ISPC compressor's standard profile, which
/// on a noisy test image came within 0.11 dB of its slow profile at 0.36x the time. RGB only;
/// alpha is treated as opaque. The ISPC kernels pick an instruction set at run time, so the
/// exact bits may differ between CPUs.
pub fn bc7_roundtrip(img: &Rgba8) -> Rgba8 {
    let settings = intel_tex_2::bc7::opaque_basic_settings();
    bc_roundtrip(
        img,
        16,
        |surface, out| intel_tex_2::bc7::compress_blocks_into(&settings, surface, out),
        bcdec_rs::bc7,
    )
}

/// BC4 (one channel, 4 bits per texel) encode then decode of the red channel, replicated to
/// RGB: the block format a user picks for single-channel content (heights, distances, occlusion),
/// which BC1 codes with a colour endpoint pair it cannot use.
pub fn bc4_roundtrip(img: &Rgba8) -> Rgba8 {
    if img.is_empty() {
        return img.clone();
    }
    let padded = pad_to_multiple(img, 4);
    let width = padded.width as usize;
    let red: Vec<u8> = padded.texels.chunks_exact(4).map(|t| t[0]).collect();
    let blocks_per_row = width / 4;
    let mut blocks = vec![0u8; blocks_per_row * (padded.height as usize / 4) * 8];
    blocks
        .par_chunks_mut(blocks_per_row * 8)
        .zip(red.par_chunks(width * 4))
        .for_each(|(out, strip)| {
            let surface = intel_tex_2::RSurface {
                data: strip,
                width: padded.width,
                height: 4,
                stride: padded.width,
            };
            intel_tex_2::bc4::compress_blocks_into(&surface, out);
        });
    let mut decoded = vec![0u8; red.len()];
    decoded
        .par_chunks_mut(width * 4)
        .zip(blocks.par_chunks(blocks_per_row * 8))
        .for_each(|(strip, row_blocks)| {
            for (bx, block) in row_blocks.chunks_exact(8).enumerate() {
                bcdec_rs::bc4(block, &mut strip[bx * 4..], width, false);
            }
        });
    crop(
        &Rgba8 {
            width: padded.width,
            height: padded.height,
            texels: decoded.iter().flat_map(|&g| [g, g, g, 255]).collect(),
        },
        img.width,
        img.height,
    )
}

/// Codebook entries of the VQ baseline: one byte of index per 2x2 block, i.e. 2 bits per texel.
const VQ_CODEWORDS: usize = 256;
/// RGB of the four texels of a 2x2 block.
const VQ_DIM: usize = 12;
/// Lloyd iterations at most; k-means on this data has mostly settled well before.
const VQ_MAX_ITERATIONS: usize = 20;
/// Training uses at most this many blocks (every n-th one), which bounds the training cost of
/// large images while leaving a 512x512 image's 65,536 blocks all in.
const VQ_MAX_TRAINING_BLOCKS: usize = 1 << 16;
/// Fixed seed of the k-means++ initialisation, so the same image always gives the same codebook.
const VQ_SEED: u64 = 0x853c_49e6_748f_ea9b;

/// Uniform 2x2 block vector quantization with a 256-entry codebook (2 bits per texel plus the
/// codebook). Returns the decoded image and the codebook size in bytes (256 * 12).
///
/// A non-hardware baseline at a quarter of BC1's per-texel rate, showing what a learned codebook
/// alone buys. The codebook is trained by k-means (k-means++ seeded by a fixed-seed PCG, at most
/// 20 Lloyd iterations) on every block, or on a fixed-stride subsample of images above 65,536
/// blocks. All distances and sums are exact integers (held in `f32`/`u64` well below their exact
/// range) and ties go to the lowest index, so the output is byte-identical for the same input
/// whatever the thread count. Output alpha is 255: only RGB is coded.
pub fn vq2x2_roundtrip(img: &Rgba8) -> (Rgba8, usize) {
    let codebook_bytes = VQ_CODEWORDS * VQ_DIM;
    if img.is_empty() {
        return (img.clone(), codebook_bytes);
    }
    let padded = pad_to_multiple(img, 2);
    let blocks = gather_blocks(&padded);

    let stride = blocks.len().div_ceil(VQ_MAX_TRAINING_BLOCKS);
    let training: Vec<Block> = blocks.iter().step_by(stride).copied().collect();
    let codebook = train_codebook(&training);

    let indices: Vec<usize> = blocks.par_iter().map(|b| nearest(&codebook, b).0).collect();
    let decoded = scatter_blocks(&padded, &codebook, &indices);
    (crop(&decoded, img.width, img.height), codebook_bytes)
}

/// A 2x2 block's RGB as exact small integers; `f32` because it vectorises well on baseline
/// x86_64 and is exact for every squared distance here (at most 12 * 255^2 < 2^24).
type Block = [f32; VQ_DIM];

fn gather_blocks(padded: &Rgba8) -> Vec<Block> {
    let stride = padded.width as usize * 4;
    let (bw, bh) = (padded.width as usize / 2, padded.height as usize / 2);
    let mut blocks = Vec::with_capacity(bw * bh);
    for by in 0..bh {
        for bx in 0..bw {
            let mut block = [0.0; VQ_DIM];
            for (t, texel) in block.chunks_exact_mut(3).enumerate() {
                let offset = (by * 2 + t / 2) * stride + (bx * 2 + t % 2) * 4;
                for (c, v) in texel.iter_mut().enumerate() {
                    *v = f32::from(padded.texels[offset + c]);
                }
            }
            blocks.push(block);
        }
    }
    blocks
}

fn scatter_blocks(padded: &Rgba8, codebook: &[Block], indices: &[usize]) -> Rgba8 {
    let stride = padded.width as usize * 4;
    let bw = padded.width as usize / 2;
    let mut texels = vec![255u8; padded.texels.len()];
    for (i, &index) in indices.iter().enumerate() {
        let (bx, by) = (i % bw, i / bw);
        for (t, texel) in codebook[index].chunks_exact(3).enumerate() {
            let offset = (by * 2 + t / 2) * stride + (bx * 2 + t % 2) * 4;
            for (c, &v) in texel.iter().enumerate() {
                // Codewords are integers in 0..=255 by construction.
                texels[offset + c] = v as u8;
            }
        }
    }
    Rgba8 {
        width: padded.width,
        height: padded.height,
        texels,
    }
}

fn distance(a: &Block, b: &Block) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Index of and distance to the closest codeword, the lowest index on ties.
fn nearest(codebook: &[Block], block: &Block) -> (usize, f32) {
    let mut best = (0, f32::INFINITY);
    for (i, codeword) in codebook.iter().enumerate() {
        let d = distance(codeword, block);
        if d < best.1 {
            best = (i, d);
        }
    }
    best
}

/// k-means++ initialisation followed by Lloyd iterations, with codewords rounded to integers
/// after every update so the trained codebook is exactly the one that would be stored.
fn train_codebook(training: &[Block]) -> Vec<Block> {
    let mut codebook = kmeans_plus_plus(training);
    let mut assignment = vec![usize::MAX; training.len()];
    for _ in 0..VQ_MAX_ITERATIONS {
        let nearest_now: Vec<(usize, f32)> =
            training.par_iter().map(|b| nearest(&codebook, b)).collect();
        let changed = nearest_now
            .iter()
            .zip(&assignment)
            .any(|(&(new, _), &old)| new != old);
        if !changed {
            break;
        }
        for (slot, &(index, _)) in assignment.iter_mut().zip(&nearest_now) {
            *slot = index;
        }

        let mut sums = vec![[0u64; VQ_DIM]; VQ_CODEWORDS];
        let mut counts = vec![0u64; VQ_CODEWORDS];
        for (block, &index) in training.iter().zip(&assignment) {
            counts[index] += 1;
            for (s, &v) in sums[index].iter_mut().zip(block) {
                *s += v as u64;
            }
        }

        // Empty cells take the worst-fitted blocks, each block used once, so no codeword is
        // wasted while the data has more distinct blocks than there are codewords.
        let mut errors: Vec<f32> = nearest_now.iter().map(|&(_, d)| d).collect();
        for (k, codeword) in codebook.iter_mut().enumerate() {
            match counts[k] {
                0 => {
                    if let Some(worst) = argmax(&errors).filter(|&i| errors[i] > 0.0) {
                        *codeword = training[worst];
                        errors[worst] = 0.0;
                    }
                }
                n => {
                    for (c, &s) in codeword.iter_mut().zip(&sums[k]) {
                        *c = ((s + n / 2) / n) as f32;
                    }
                }
            }
        }
    }
    codebook
}

/// Index of the largest value, the lowest index on ties.
fn argmax(values: &[f32]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, &v) in values.iter().enumerate() {
        if best.is_none_or(|b| v > values[b]) {
            best = Some(i);
        }
    }
    best
}

/// k-means++ seeding: each further codeword is a block drawn with probability proportional to
/// its squared distance from the codewords so far. With fewer distinct blocks than codewords the
/// remaining entries repeat the first one, which changes nothing a decoder sees.
fn kmeans_plus_plus(training: &[Block]) -> Vec<Block> {
    let mut rng = Pcg32::new(VQ_SEED);
    let first = training[rng.below(training.len() as u64) as usize];
    let mut codebook = vec![first; VQ_CODEWORDS];
    let mut d2: Vec<u64> = training
        .par_iter()
        .map(|b| distance(b, &first) as u64)
        .collect();
    for slot in codebook.iter_mut().skip(1) {
        let total: u64 = d2.iter().sum();
        if total == 0 {
            break;
        }
        let mut target = rng.below(total);
        let mut chosen = 0;
        for (i, &d) in d2.iter().enumerate() {
            if target < d {
                chosen = i;
                break;
            }
            target -= d;
        }
        let pick = training[chosen];
        *slot = pick;
        d2.par_iter_mut()
            .zip(training.par_iter())
            .for_each(|(d, b)| *d = (*d).min(distance(b, &pick) as u64));
    }
    codebook
}

/// PCG32 (XSH-RR, O'Neill 2014): a few lines here rather than a crate so the VQ codebook never
/// changes because a random-number crate changed its sampling algorithms.
struct Pcg32 {
    state: u64,
}

impl Pcg32 {
    const MULTIPLIER: u64 = 6_364_136_223_846_793_005;
    const INCREMENT: u64 = 1_442_695_040_888_963_407;

    fn new(seed: u64) -> Self {
        let mut rng = Self { state: 0 };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(Self::MULTIPLIER)
            .wrapping_add(Self::INCREMENT);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// A value in `0..bound` (`bound > 0`); the modulo bias is irrelevant for seeding.
    fn below(&mut self, bound: u64) -> u64 {
        let wide = (u64::from(self.next_u32()) << 32) | u64::from(self.next_u32());
        wide % bound
    }
}

/// PSNR in dB over the RGB channels (alpha ignored), 255 peak.
///
/// Alpha is left out because every baseline here codes colour only. Identical images give
/// infinity; images of different sizes panic, as comparing them is a caller bug.
pub fn psnr_rgb(a: &Rgba8, b: &Rgba8) -> f64 {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "PSNR of images of different sizes"
    );
    assert_eq!(a.texels.len(), b.texels.len(), "PSNR of malformed images");
    let samples = a.texels.len() / 4 * 3;
    if samples == 0 {
        return f64::INFINITY;
    }
    let squared_error: u64 = a
        .texels
        .chunks_exact(4)
        .zip(b.texels.chunks_exact(4))
        .map(|(p, q)| {
            (0..3)
                .map(|c| {
                    let d = i64::from(p[c]) - i64::from(q[c]);
                    (d * d) as u64
                })
                .sum::<u64>()
        })
        .sum();
    if squared_error == 0 {
        return f64::INFINITY;
    }
    let mse = squared_error as f64 / samples as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gradient(width: u32, height: u32) -> Rgba8 {
        let mut texels = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let fx = x as f32 / (width.max(2) - 1) as f32;
                let fy = y as f32 / (height.max(2) - 1) as f32;
                texels.extend_from_slice(&[
                    (fx * 255.0).round() as u8,
                    (fy * 255.0).round() as u8,
                    ((fx + fy) * 0.5 * 200.0 + 20.0).round() as u8,
                    255,
                ]);
            }
        }
        Rgba8::new(width, height, texels)
    }

    fn noise(width: u32, height: u32, seed: u64) -> Rgba8 {
        let mut rng = Pcg32::new(seed);
        let texels = (0..texel_count(width, height))
            .flat_map(|_| {
                let v = rng.next_u32().to_le_bytes();
                [v[0], v[1], v[2], 255]
            })
            .collect();
        Rgba8::new(width, height, texels)
    }

    /// Flat 4x4 tiles of colours exact in 5:6:5, distinct per tile: a BC1 round trip should be
    /// near lossless (the ISPC encoder lands within a step or so of a flat colour), and any
    /// mix-up of block order shows as gross error.
    fn tiles_565(width: u32, height: u32) -> Rgba8 {
        let mut texels = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let t = (y / 4) * 37 + (x / 4) * 11;
                let r5 = (t * 7) % 32;
                let g6 = (t * 13 + 5) % 64;
                let b5 = (t * 3 + 9) % 32;
                texels.extend_from_slice(&[
                    ((r5 << 3) | (r5 >> 2)) as u8,
                    ((g6 << 2) | (g6 >> 4)) as u8,
                    ((b5 << 3) | (b5 >> 2)) as u8,
                    255,
                ]);
            }
        }
        Rgba8::new(width, height, texels)
    }

    #[test]
    fn psnr_basics() {
        let a = gradient(8, 8);
        assert_eq!(psnr_rgb(&a, &a), f64::INFINITY);
        let mut b = a.clone();
        b.texels[0] = b.texels[0].wrapping_add(16);
        b.texels[3] = 0; // alpha: ignored
        let mse = 256.0 / (64.0 * 3.0);
        let expected = 10.0 * (255.0f64 * 255.0 / mse).log10();
        assert!((psnr_rgb(&a, &b) - expected).abs() < 1e-9);
    }

    #[test]
    fn padding_repeats_border_and_crop_restores() {
        let img = gradient(5, 3);
        let padded = pad_to_multiple(&img, 4);
        assert_eq!((padded.width, padded.height), (8, 4));
        let at = |im: &Rgba8, x: usize, y: usize| {
            let o = (y * im.width as usize + x) * 4;
            im.texels[o..o + 4].to_vec()
        };
        assert_eq!(at(&padded, 7, 3), at(&img, 4, 2));
        assert_eq!(at(&padded, 6, 1), at(&img, 4, 1));
        assert_eq!(at(&padded, 2, 3), at(&img, 2, 2));
        assert_eq!(crop(&padded, 5, 3), img);
    }

    #[test]
    fn gray_helpers_round_trip() {
        let gray: Vec<u8> = (0..=255).collect();
        let img = Rgba8::from_gray(16, 16, &gray);
        assert_eq!(img.to_gray(), gray);
        let decoded = bc1_roundtrip(&img).to_gray();
        let worst = gray
            .iter()
            .zip(&decoded)
            .map(|(&a, &b)| a.abs_diff(b))
            .max()
            .unwrap();
        assert!(worst <= 8, "grey ramp error {worst}");
    }

    #[test]
    fn bc1_flat_tiles_are_near_lossless() {
        for (w, h) in [(16, 8), (64, 64), (12, 8)] {
            let img = tiles_565(w, h);
            let p = psnr_rgb(&img, &bc1_roundtrip(&img));
            assert!(p > 50.0, "BC1 flat tiles {w}x{h}: {p:.2} dB");
        }
    }

    #[test]
    fn bc7_flat_tiles_are_near_lossless() {
        let img = tiles_565(64, 32);
        let p = psnr_rgb(&img, &bc7_roundtrip(&img));
        assert!(p > 45.0, "BC7 flat tiles {p:.2} dB");
    }

    #[test]
    fn codecs_on_gradient_and_noise() {
        let smooth = gradient(256, 256);
        let rough = noise(256, 256, 7);
        for (name, img) in [("gradient", &smooth), ("noise", &rough)] {
            let bc1 = psnr_rgb(img, &bc1_roundtrip(img));
            let bc7 = psnr_rgb(img, &bc7_roundtrip(img));
            let (vq_img, vq_bytes) = vq2x2_roundtrip(img);
            let vq = psnr_rgb(img, &vq_img);
            eprintln!("{name}: BC1 {bc1:.2} dB, BC7 {bc7:.2} dB, VQ2x2 {vq:.2} dB");
            assert_eq!(vq_bytes, 256 * 12);
            assert!(bc7 >= bc1, "{name}: BC7 {bc7} < BC1 {bc1}");
            if name == "gradient" {
                assert!(bc1 > 35.0, "BC1 gradient {bc1}");
                assert!(bc7 > 40.0, "BC7 gradient {bc7}");
                assert!(vq > 28.0, "VQ gradient {vq}");
            } else {
                // Uniform noise: error near the spread of the data, yet better than a flat grey.
                assert!((8.0..25.0).contains(&bc1), "BC1 noise {bc1}");
                assert!((8.0..25.0).contains(&bc7), "BC7 noise {bc7}");
                assert!((8.0..25.0).contains(&vq), "VQ noise {vq}");
            }
        }
    }

    #[test]
    fn vq_is_deterministic() {
        let img = noise(96, 80, 3);
        let (a, _) = vq2x2_roundtrip(&img);
        let (b, _) = vq2x2_roundtrip(&img);
        assert_eq!(a.texels, b.texels);
        let single = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let (c, _) = single.install(|| vq2x2_roundtrip(&img));
        assert_eq!(a.texels, c.texels);
    }

    #[test]
    fn vq_with_at_most_256_distinct_blocks_is_lossless() {
        // 32x32 texels = 256 flat 2x2 blocks, all distinct.
        let mut texels = Vec::new();
        for y in 0..32u32 {
            for x in 0..32u32 {
                let k = (y / 2) * 16 + x / 2;
                texels.extend_from_slice(&[k as u8, (k * 7) as u8, (255 - k) as u8, 255]);
            }
        }
        let img = Rgba8::new(32, 32, texels);
        let (out, _) = vq2x2_roundtrip(&img);
        assert_eq!(psnr_rgb(&img, &out), f64::INFINITY);
    }

    #[test]
    fn odd_sizes_work() {
        for (w, h) in [(13, 7), (1, 1), (3, 5), (2, 9)] {
            // Gentle slopes whatever the size, so the image stays smooth at 13x7 too.
            let img = crop(&gradient(64, 64), w, h);
            let results = [
                ("BC1", bc1_roundtrip(&img)),
                ("BC7", bc7_roundtrip(&img)),
                ("VQ", vq2x2_roundtrip(&img).0),
            ];
            for (name, out) in &results {
                assert_eq!((out.width, out.height), (w, h), "{name}");
                assert_eq!(out.texels.len(), img.texels.len(), "{name}");
                let p = psnr_rgb(&img, out);
                assert!(p > 30.0, "{name} {w}x{h}: {p:.2} dB");
            }
            // BC encoding is deterministic, so padding by hand must give the same texels.
            let padded = pad_to_multiple(&img, 4);
            assert_eq!(crop(&bc1_roundtrip(&padded), w, h), results[0].1);
            assert_eq!(crop(&bc7_roundtrip(&padded), w, h), results[1].1);
        }
        let empty = Rgba8::new(0, 4, Vec::new());
        assert_eq!(bc1_roundtrip(&empty), empty);
        assert_eq!(vq2x2_roundtrip(&empty).0, empty);
    }

    #[test]
    fn vq_512_is_fast_enough() {
        let img = noise(512, 512, 11);
        let start = std::time::Instant::now();
        let (out, _) = vq2x2_roundtrip(&img);
        let vq_time = start.elapsed();
        let start = std::time::Instant::now();
        let _ = bc7_roundtrip(&img);
        let bc7_time = start.elapsed();
        eprintln!(
            "512x512: VQ2x2 {vq_time:?} ({:.2} dB), BC7 {bc7_time:?}",
            psnr_rgb(&img, &out)
        );
    }
}
