//! The colour-state baseline of solid synthesis, after Kopf et al. 2007 ("Solid texture
//! synthesis from 2D exemplars"), scored by the same figures as `lazysolid solid`: what the
//! thesis' triples are measured against (docs/log/solid.md, "A colour optimizer measured").
//!
//! The volume holds colours. Each level alternates a search, which finds for every sparse
//! neighbourhood centre (every `spacing`-th pixel of every slice, in each of the three slice
//! families) the nearest 8×8 exemplar neighbourhood, and an optimization, which sets every
//! voxel to the weighted mean of the colours those neighbourhoods give it. The weights are
//! the robust ones, `d^(r − 2)` with `r = 0.8`, divided by `1 + h · excess`. `excess` sums
//! over the channels how far the solid's histogram exceeds the exemplar's at the colour's
//! bin, in units of a uniform bin's share; the histograms have 16 bins per channel over its
//! full range, or with `--bins exemplar` over the exemplar's range of it. The coarsest level
//! starts from random exemplar colours; a finer one from the coarser volume doubled.
//!
//! `--plane` runs the same optimizer on each z slice alone (the z family only): a 2D
//! synthesis of the same kind, to tell what the three families' agreement costs from what
//! the optimizer itself costs. `--search approx` replaces the exact search by candidates from
//! the previous matches, the neighbours' matches shifted, their nearest exemplar neighbours
//! and random samples (a PatchMatch-like search); it is much faster and much worse.
//!
//! ```text
//! cargo run --release -p lazysolid-tools --example kopf_solid -- EXEMPLAR --side 64 --seed 3 -o OUT
//! ```
//! prints the eight-slice SWD ratio, blockiness, histogram distance and band contrasts per
//! axis, and writes `OUT.png` (exemplar | mid slices x, y, z) and `OUT.txt` (the figures).

use anyhow::ensure;
use clap::{Parser, ValueEnum};
use lazysolid_synth::histogram_distance;
use lazysolid_synth::solid::{
    colour_slice, role_scorers, ImageScorer, SliceRatios, SolidExemplars, SolidRecipe,
    QUALITY_SLICES, ROLES, ROLE_AXES,
};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

type Rgb = [f32; 3];

/// Neighbourhood side; offsets run from `-HALF` to `HALF - 1`.
const SIDE: i32 = 8;
const HALF: i32 = SIDE / 2;
const VALUES: usize = (SIDE * SIDE * 3) as usize;
/// Histogram bins per channel.
const BINS: usize = 16;
/// Marks a centre without a match yet.
const NONE: u32 = u32::MAX;

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Search {
    /// Every exemplar neighbourhood.
    Exact,
    /// Previous, propagated, nearest-neighbour and random candidates.
    Approx,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Range {
    /// 16 bins over each 8-bit channel's full range, as the paper's histograms.
    Full,
    /// 16 bins over the exemplar's range of each channel.
    Exemplar,
}

#[derive(Parser)]
struct Args {
    /// Exemplar image path, fitted as `lazysolid solid` fits it.
    exemplar: PathBuf,
    /// Exemplar side and volume side.
    #[arg(long, default_value_t = 64)]
    side: u32,
    #[arg(long, default_value_t = 3)]
    seed: u64,
    /// Pyramid levels.
    #[arg(long, default_value_t = 3)]
    levels: usize,
    /// Iterations per level, coarsest first.
    #[arg(long, value_delimiter = ',', default_values_t = [8, 6, 4])]
    iterations: Vec<usize>,
    /// Robust exponent r of the energy Σ‖s − e‖^r.
    #[arg(long, default_value_t = 0.8)]
    r: f32,
    /// Histogram weight h (0: no histogram matching).
    #[arg(long, default_value_t = 4.0)]
    histogram: f32,
    /// What the histogram's bins span.
    #[arg(long, value_enum, default_value_t = Range::Full)]
    bins: Range,
    /// Spacing of the neighbourhood centres in a slice.
    #[arg(long, default_value_t = 2)]
    spacing: i32,
    #[arg(long, value_enum, default_value_t = Search::Exact)]
    search: Search,
    /// Optimize each z slice alone (the z family only): a 2D synthesis by the same optimizer.
    #[arg(long)]
    plane: bool,
    /// Output prefix.
    #[arg(short, default_value = "kopf")]
    o: PathBuf,
}

/// One pyramid level of one role's exemplar.
struct Level {
    m: usize,
    px: Vec<Rgb>,
    /// For `--search approx`: each valid centre's nearest other centres (packed).
    nearest: Vec<Vec<u32>>,
}

fn pack(x: i32, y: i32) -> u32 {
    x as u32 | (y as u32) << 16
}

fn unpack(p: u32) -> (i32, i32) {
    ((p & 0xffff) as i32, (p >> 16) as i32)
}

impl Level {
    fn new(m: usize, px: Vec<Rgb>, search: Search) -> Level {
        let mut level = Level {
            m,
            px,
            nearest: Vec::new(),
        };
        if search == Search::Approx {
            level.nearest = level.nearest_centres(4);
        }
        level
    }

    fn at(&self, x: i32, y: i32) -> Rgb {
        self.px[y as usize * self.m + x as usize]
    }

    /// Centres whose neighbourhood lies inside the exemplar, per axis.
    fn centres(&self) -> std::ops::RangeInclusive<i32> {
        HALF..=self.m as i32 - HALF
    }

    fn valid(&self, x: i32, y: i32) -> bool {
        self.centres().contains(&x) && self.centres().contains(&y)
    }

    /// Squared distance of the neighbourhood at `c` to `q`, abandoned above `bound`.
    fn distance(&self, q: &[f32; VALUES], c: u32, bound: f32) -> f32 {
        let (cx, cy) = unpack(c);
        let mut d = 0.0;
        let mut k = 0;
        for dv in -HALF..HALF {
            for du in -HALF..HALF {
                let e = self.at(cx + du, cy + dv);
                for ch in 0..3 {
                    let t = q[k + ch] - e[ch];
                    d += t * t;
                }
                k += 3;
            }
            if d > bound {
                break;
            }
        }
        d
    }

    fn nearest_centres(&self, k: usize) -> Vec<Vec<u32>> {
        let centres: Vec<u32> = self
            .centres()
            .flat_map(|y| self.centres().map(move |x| pack(x, y)))
            .collect();
        let patch = |c: u32| {
            let (cx, cy) = unpack(c);
            let mut q = [0.0; VALUES];
            let mut i = 0;
            for dv in -HALF..HALF {
                for du in -HALF..HALF {
                    q[i..i + 3].copy_from_slice(&self.at(cx + du, cy + dv));
                    i += 3;
                }
            }
            q
        };
        let lists: Vec<Vec<u32>> = centres
            .par_iter()
            .map(|&c| {
                let q = patch(c);
                let (x, y) = unpack(c);
                let mut best: Vec<(f32, u32)> = Vec::with_capacity(k + 1);
                for &o in &centres {
                    let (ox, oy) = unpack(o);
                    if (ox - x).abs() < HALF && (oy - y).abs() < HALF {
                        continue;
                    }
                    let bound = if best.len() == k {
                        best[k - 1].0
                    } else {
                        f32::MAX
                    };
                    let d = self.distance(&q, o, bound);
                    if d < bound {
                        best.insert(best.partition_point(|e| e.0 < d), (d, o));
                        best.truncate(k);
                    }
                }
                best.into_iter().map(|(_, o)| o).collect()
            })
            .collect();
        let mut nearest = vec![Vec::new(); self.m * self.m];
        for (c, list) in centres.iter().zip(lists) {
            let (x, y) = unpack(*c);
            nearest[y as usize * self.m + x as usize] = list;
        }
        nearest
    }

    fn half(&self) -> Vec<Rgb> {
        let h = self.m / 2;
        (0..h * h)
            .map(|i| {
                let (x, y) = ((i % h) as i32 * 2, (i / h) as i32 * 2);
                let mut s = [0.0; 3];
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let c = self.at(x + dx, y + dy);
                    for ch in 0..3 {
                        s[ch] += c[ch] / 4.0;
                    }
                }
                s
            })
            .collect()
    }
}

/// Histogram bins per channel, over the full range or the exemplar's range of the channel (a
/// grey or narrow-ranged exemplar then gets as many occupied bins as a colourful one).
#[derive(Clone, Copy)]
struct Bins {
    low: Rgb,
    scale: Rgb,
}

impl Bins {
    fn new(exemplar: &[Rgb], range: Range) -> Bins {
        if range == Range::Full {
            return Bins {
                low: [0.0; 3],
                scale: [BINS as f32; 3],
            };
        }
        let mut low = [f32::MAX; 3];
        let mut high = [f32::MIN; 3];
        for c in exemplar {
            for ch in 0..3 {
                low[ch] = low[ch].min(c[ch]);
                high[ch] = high[ch].max(c[ch]);
            }
        }
        let scale = std::array::from_fn(|ch| BINS as f32 / (high[ch] - low[ch]).max(1e-3));
        Bins { low, scale }
    }

    fn of(&self, v: f32, ch: usize) -> usize {
        (((v - self.low[ch]) * self.scale[ch]).max(0.0) as usize).min(BINS - 1)
    }

    /// Per-channel histogram in units of a uniform bin's share.
    fn histogram(&self, px: &[Rgb]) -> [Rgb; BINS] {
        let mut h = [[0.0; 3]; BINS];
        for c in px {
            for ch in 0..3 {
                h[self.of(c[ch], ch)][ch] += 1.0;
            }
        }
        let scale = BINS as f32 / px.len() as f32;
        h.map(|b| b.map(|v| v * scale))
    }
}

/// The volume's voxel at `p` (toroidal), `n` a side.
fn voxel(p: [i32; 3], n: usize) -> usize {
    let w = |v: i32| v.rem_euclid(n as i32) as usize;
    (w(p[2]) * n + w(p[1])) * n + w(p[0])
}

/// Matches and weights of one slice family's sparse centres, indexed (slice, v, u).
struct Family {
    matches: Vec<u32>,
    weights: Vec<f32>,
}

struct Solver<'a> {
    args: &'a Args,
    n: usize,
    /// Centres per slice axis.
    ns: usize,
    levels: [&'a Level; ROLES],
    roles: Vec<usize>,
}

impl Solver<'_> {
    fn centre(&self, ci: usize) -> (usize, i32, i32) {
        let sp = self.args.spacing;
        let (ns, s) = (self.ns, ci / (self.ns * self.ns));
        (s, ((ci / ns) % ns) as i32 * sp, (ci % ns) as i32 * sp)
    }

    /// The nearest exemplar neighbourhood of every centre of role `r`: (match, weight, r-energy).
    fn search(&self, vol: &[Rgb], r: usize, prev: &[u32], pass: u64) -> Vec<(u32, f32, f64)> {
        let [a, b] = ROLE_AXES[r];
        let level = self.levels[r];
        let (n, ns, sp) = (self.n, self.ns, self.args.spacing);
        (0..n * ns * ns)
            .into_par_iter()
            .map(|ci| {
                let (s, v, u) = self.centre(ci);
                let mut q = [0.0; VALUES];
                let mut k = 0;
                for dv in -HALF..HALF {
                    for du in -HALF..HALF {
                        let mut p = [0; 3];
                        p[r] = s as i32;
                        p[a] = u + du;
                        p[b] = v + dv;
                        q[k..k + 3].copy_from_slice(&vol[voxel(p, n)]);
                        k += 3;
                    }
                }
                let (mut best, mut bd) = (NONE, f32::MAX);
                let mut consider = |c: u32| {
                    if c != NONE {
                        let d = level.distance(&q, c, bd);
                        if d < bd {
                            (best, bd) = (c, d);
                        }
                    }
                };
                match self.args.search {
                    Search::Exact => {
                        for y in level.centres() {
                            for x in level.centres() {
                                consider(pack(x, y));
                            }
                        }
                    }
                    Search::Approx => {
                        let mut rng =
                            Pcg64::seed_from_u64(pass << 40 ^ (r as u64) << 36 ^ ci as u64);
                        let mut seeds = vec![prev[ci]];
                        for (du, dv) in [(-1, 0), (1, 0), (0, -1), (0, 1)] {
                            let uu = (u / sp + du).rem_euclid(ns as i32) as usize;
                            let vv = (v / sp + dv).rem_euclid(ns as i32) as usize;
                            let m = prev[(s * ns + vv) * ns + uu];
                            if m != NONE {
                                let (x, y) = unpack(m);
                                if level.valid(x - du * sp, y - dv * sp) {
                                    seeds.push(pack(x - du * sp, y - dv * sp));
                                }
                            }
                        }
                        for &c in &seeds {
                            consider(c);
                            if c != NONE {
                                let (x, y) = unpack(c);
                                for &o in &level.nearest[y as usize * level.m + x as usize] {
                                    consider(o);
                                }
                            }
                        }
                        for _ in 0..4 {
                            let x = rng.random_range(level.centres());
                            let y = rng.random_range(level.centres());
                            consider(pack(x, y));
                        }
                    }
                }
                let weight = (bd + 1e-3).powf((self.args.r - 2.0) / 2.0);
                (
                    best,
                    weight,
                    f64::from(bd).powf(f64::from(self.args.r) / 2.0),
                )
            })
            .collect()
    }

    /// Every voxel set to the weighted mean of what the neighbourhoods covering it give it.
    fn optimize(
        &self,
        vol: &[Rgb],
        families: &[Family; ROLES],
        exemplar: &[Rgb; BINS],
        bins: Bins,
    ) -> Vec<Rgb> {
        let (n, ns, sp) = (self.n, self.ns, self.args.spacing);
        let solid = bins.histogram(vol);
        let excess = |c: &Rgb| -> f32 {
            (0..3)
                .map(|ch| {
                    let b = bins.of(c[ch], ch);
                    (solid[b][ch] - exemplar[b][ch]).max(0.0)
                })
                .sum()
        };
        (0..n * n * n)
            .into_par_iter()
            .map(|i| {
                let p = [i % n, (i / n) % n, i / (n * n)];
                let (mut sum, mut total) = ([0.0f32; 3], 0.0f32);
                for &r in &self.roles {
                    let [a, b] = ROLE_AXES[r];
                    let f = &families[r];
                    for du in -HALF..HALF {
                        let u0 = p[a] as i32 - du;
                        if u0.rem_euclid(sp) != 0 {
                            continue;
                        }
                        for dv in -HALF..HALF {
                            let v0 = p[b] as i32 - dv;
                            if v0.rem_euclid(sp) != 0 {
                                continue;
                            }
                            let uu = (u0.rem_euclid(n as i32) / sp) as usize;
                            let vv = (v0.rem_euclid(n as i32) / sp) as usize;
                            let ci = (p[r] * ns + vv) * ns + uu;
                            let (mx, my) = unpack(f.matches[ci]);
                            let c = self.levels[r].at(mx + du, my + dv);
                            let w = f.weights[ci] / (1.0 + self.args.histogram * excess(&c));
                            for ch in 0..3 {
                                sum[ch] += w * c[ch];
                            }
                            total += w;
                        }
                    }
                }
                sum.map(|v| v / total)
            })
            .collect()
    }
}

fn main() -> anyhow::Result<()> {
    let args = Args::parse();
    ensure!(
        args.iterations.len() == args.levels,
        "--iterations: one count per level ({} levels)",
        args.levels
    );
    ensure!(
        args.spacing >= 1 && args.spacing <= HALF,
        "--spacing: 1..={HALF}"
    );
    // The exemplar prepared as lazysolid's own synthesizer prepares it (fitted, oriented), so
    // the two methods start from the same images.
    let sources = SolidRecipe {
        exemplar_side: Some(args.side),
        ..SolidRecipe::new(&args.exemplar)
    }
    .load()?;
    let (exemplars, mirroring) = (sources.exemplars, sources.mirroring);
    let m = exemplars.side() as usize;
    ensure!(
        m >> (args.levels - 1) >= 2 * SIDE as usize,
        "--levels {}: the coarsest exemplar would be under {} pixels",
        args.levels,
        2 * SIDE
    );
    println!("orientation: {mirroring}");
    let started = Instant::now();
    // Pyramids per role, finest first.
    let pyramids: Vec<Vec<Level>> = (0..ROLES)
        .map(|r| {
            let mut px: Vec<Rgb> = exemplars
                .role(r)
                .rgb
                .iter()
                .map(|c| c.map(|v| f32::from(v) / 255.0))
                .collect();
            let mut levels = Vec::new();
            for l in 0..args.levels {
                let level = Level::new(m >> l, px, args.search);
                px = level.half();
                levels.push(level);
            }
            levels
        })
        .collect();
    let roles = if args.plane { vec![2] } else { vec![0, 1, 2] };
    let mut rng = Pcg64::seed_from_u64(args.seed);
    let coarsest = &pyramids[2][args.levels - 1];
    let mut n = coarsest.m;
    let mut vol: Vec<Rgb> = (0..n * n * n)
        .map(|_| coarsest.px[rng.random_range(0..coarsest.px.len())])
        .collect();
    let mut pass = 0u64;
    for l in (0..args.levels).rev() {
        if l + 1 < args.levels {
            let (coarse, c) = (vol, n);
            n *= 2;
            vol = (0..n * n * n)
                .map(|i| {
                    let (x, y, z) = (i % n / 2, i / n % n / 2, i / (n * n) / 2);
                    coarse[(z * c + y) * c + x]
                })
                .collect();
        }
        let levels: [&Level; ROLES] = std::array::from_fn(|r| &pyramids[r][l]);
        let solver = Solver {
            args: &args,
            n,
            ns: n / args.spacing as usize,
            levels,
            roles: roles.clone(),
        };
        let bins = Bins::new(&levels[2].px, args.bins);
        let exemplar_histogram = bins.histogram(&levels[2].px);
        let centres = n * solver.ns * solver.ns;
        let mut families: [Family; ROLES] = std::array::from_fn(|_| Family {
            matches: vec![NONE; centres],
            weights: vec![0.0; centres],
        });
        for it in 0..args.iterations[args.levels - 1 - l] {
            let t = Instant::now();
            let mut energy = 0.0;
            for &r in &roles {
                let found = solver.search(&vol, r, &families[r].matches, pass);
                pass += 1;
                let f = &mut families[r];
                for (ci, (mt, w, e)) in found.into_iter().enumerate() {
                    f.matches[ci] = mt;
                    f.weights[ci] = w;
                    energy += e;
                }
            }
            vol = solver.optimize(&vol, &families, &exemplar_histogram, bins);
            println!(
                "{n}³ iteration {it}: mean ‖s − e‖^r {:.4} ({:.1} s)",
                energy / (roles.len() * centres) as f64,
                t.elapsed().as_secs_f32()
            );
        }
    }
    println!("synthesis {:.1} s", started.elapsed().as_secs_f32());
    let colours: Vec<[u8; 3]> = vol
        .iter()
        .map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8))
        .collect();
    let figures = score(&exemplars, &colours, n, &roles);
    print!("{figures}");
    std::fs::write(args.o.with_extension("txt"), figures)?;
    panels(&exemplars, &colours, n, &args.o.with_extension("png"))
}

fn score(exemplars: &SolidExemplars, colours: &[[u8; 3]], n: usize, roles: &[usize]) -> String {
    let scorers: [ImageScorer; ROLES] = role_scorers(exemplars);
    let q = QUALITY_SLICES as usize;
    let mut out = String::new();
    for &axis in roles {
        let figures: Vec<SliceRatios> = (0..q)
            .map(|k| {
                let s = colour_slice(colours, n, axis, n * (2 * k + 1) / (2 * q));
                scorers[axis].ratios(&s, n as u32, n as u32)
            })
            .collect();
        let mean = |f: &dyn Fn(&SliceRatios) -> f64| figures.iter().map(f).sum::<f64>() / q as f64;
        let histogram = histogram_distance(
            &colour_slice(colours, n, axis, n / 2),
            &exemplars.role(axis).rgb,
        );
        out += &format!(
            "axis {}: SWD ratio {:.2}, blockiness {:.2}, histogram {:.3}, band SWD fine/mid/coarse {:.2}/{:.2}/{:.2}, band contrast {:.2}/{:.2}/{:.2}\n",
            ["x", "y", "z"][axis],
            mean(&|f| f.swd),
            mean(&|f| f.blockiness),
            histogram,
            mean(&|f| f.bands[0]),
            mean(&|f| f.bands[1]),
            mean(&|f| f.bands[2]),
            mean(&|f| f.contrast[0]),
            mean(&|f| f.contrast[1]),
            mean(&|f| f.contrast[2]),
        );
    }
    out
}

/// Exemplar | mid slices x, y, z, 4 pixels apart.
fn panels(
    exemplars: &SolidExemplars,
    colours: &[[u8; 3]],
    n: usize,
    path: &std::path::Path,
) -> anyhow::Result<()> {
    let m = exemplars.side() as usize;
    let gap = 4;
    let mut image = image::RgbImage::new((m + 3 * (n + gap)) as u32, m.max(n) as u32);
    for (i, c) in exemplars.role(0).rgb.iter().enumerate() {
        image.put_pixel((i % m) as u32, (i / m) as u32, image::Rgb(*c));
    }
    for axis in 0..ROLES {
        let x0 = m + gap + axis * (n + gap);
        for (i, c) in colour_slice(colours, n, axis, n / 2).iter().enumerate() {
            image.put_pixel((x0 + i % n) as u32, (i / n) as u32, image::Rgb(*c));
        }
    }
    image.save(path)?;
    Ok(())
}
