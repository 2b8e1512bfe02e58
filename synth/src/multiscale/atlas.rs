//! A depth set packed for the GPU's correction passes: every member's texels laid end to end
//! in one index space (the packed superexemplar of P:200), so that a pixel's working state is
//! one texel index plus its transfer, and everything the correction reads of a neighbour is
//! one load away: the appearance at its coordinate and at its four spacing-shifted
//! neighbours, the texel its patch continues to for each of the 8 directions, its
//! neighbourhood record and its candidates (as texel indices). The 2D kernel computes the
//! same shifts with arithmetic on one exemplar; here each member has its own size and
//! spacing, and precomputing them removes the per-neighbour member lookups that made the
//! multiscale kernel 4× slower than the 2D one.
//!
//! Members are laid out in increasing `meta` and texels row-major, so comparing texel
//! indices compares `(meta, coordinate)` — the CPU reference's tie order.

use super::analysis::{DepthSetAnalysis, MultiscaleAnalysis};
use super::cpu::{meta, MAX_TRANSFER};
use crate::coords::pack;
use crate::cpu::offsets;
use crate::error::{SynthError, SynthResult};
use crate::neighbourhood::{pack_i8_words, wrap};
use crate::period::period_reach;
use crate::shader_constants;

/// Lookup slots per exemplar (levels `0..=L`, `L ≤ 8`).
pub(crate) const LEVEL_SLOTS: usize = shader_constants::MULTISCALE_LEVEL_SLOTS as usize;

/// Texel index of a pixel whose stack level is not in the depth set.
pub(crate) const ABSENT: u32 = shader_constants::MULTISCALE_ABSENT;

/// Flag of a texel index whose pixel is not corrected (magnified past its leaf's finest
/// level): it predicts its texel's appearance without shift and offers no candidates.
pub(crate) const FIXED: u32 = shader_constants::MULTISCALE_FIXED;

/// Flag of a candidate texel index whose level offers candidates that can be period-penalized
/// (see [`DepthAtlas::candidate_texels`]); of a texel's `meta` word, the same bit 16 up.
pub(crate) const OFFERS_PERIOD: u32 = shader_constants::MULTISCALE_OFFERS_PERIOD;

/// Shifts of the stored appearance, in units of the member's spacing: the texel itself,
/// then −x, +x, −y, +y (what the 4-diagonal neighbourhood reads of edge neighbours).
pub(crate) const APPEARANCE_SHIFTS: [(i32, i32); 5] = [(0, 0), (-1, 0), (1, 0), (0, -1), (0, 1)];

/// One depth set in the packed layout, as `u32` words ready for upload.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct DepthAtlas {
    /// First texel index of each stack level (| [`OFFERS_PERIOD`]): `exemplar · LEVEL_SLOTS +
    /// level`, or [`ABSENT`].
    pub lookup: Vec<u32>,
    /// Per texel: packed coordinate, `meta` | 1 << 16 where its level offers candidates that
    /// can be period-penalized.
    pub texels: Vec<u32>,
    /// Per texel, for the 8 neighbours `n ≠ 4` in row order: the texel index of the
    /// coordinate moved back by the neighbour's offset times the spacing (the texel that
    /// continues the neighbour's patch at the centre).
    pub continued: Vec<u32>,
    /// Per texel, 5 appearance vectors (2 words each) at [`APPEARANCE_SHIFTS`]; then the
    /// zero texel (index `texel_count`), which pixels whose level is not in the set predict.
    pub appearance: Vec<u32>,
    /// Per texel, the 4-diagonal neighbourhood record (8 words).
    pub records: Vec<u32>,
    /// Per texel, `k` candidate texel indices, [`OFFERS_PERIOD`] set where the candidate's level
    /// offers candidates that can be period-penalized: a pixel moving there makes the period
    /// test needed from the next subpass on (the GPU switches kernels on it).
    pub candidate_texels: Vec<u32>,
    /// Per texel, `k` × 2 words: the candidate's transfer r | g << 16 and b (16-bit two's
    /// complement each).
    pub candidate_extras: Vec<u32>,
    /// Per texel, `k` × 2 words for the period test: the candidate's coordinate x | y << 8
    /// and `meta` << 16; its exemplar's (width − 1) | (height − 1) << 8 and its level's
    /// period reach x << 16 | y << 20.
    pub candidate_periods: Vec<u32>,
    /// Texels in all.
    pub texel_count: u32,
    /// Whether some candidate's level spans at most 2 of its pixels (a period penalty can
    /// apply): without one the correction skips the period test altogether.
    pub has_reach: bool,
    /// Whether some candidate has a transfer other than zero.
    pub has_transfer: bool,
}

/// Neighbours with a continued texel: all but the centre, row by row.
pub(crate) const CONTINUED_SLOTS: usize = 8;

impl DepthAtlas {
    /// Packs `set` (of `analysis`).
    ///
    /// # Errors
    /// [`SynthError::Parameter`] when the set has more texels than a texel index holds, or a
    /// candidate's transfer does not fit 16 bits.
    pub(crate) fn new(
        analysis: &MultiscaleAnalysis,
        set: &DepthSetAnalysis,
    ) -> SynthResult<DepthAtlas> {
        let k = analysis.k as usize;
        let mut order: Vec<usize> = (0..set.members.len()).collect();
        order.sort_by_key(|&m| meta(set.members[m].exemplar, set.members[m].level));
        let mut start = vec![0u64; set.members.len()];
        let mut total = 0u64;
        for &m in &order {
            start[m] = total;
            let e = &analysis.exemplars[set.members[m].exemplar];
            total += e.width as u64 * e.height as u64;
        }
        if total >= FIXED as u64 {
            return Err(SynthError::Parameter {
                name: "depth set texels",
                value: total.to_string(),
                limit: format!("must be below {FIXED}"),
            });
        }
        let texel_count = total as u32;
        // Each member's period reach, and whether its candidate lists hold one whose level
        // spans at most 2 of its pixels.
        let reaches: Vec<[u32; 2]> = set
            .members
            .iter()
            .map(|m| {
                let e = &analysis.exemplars[m.exemplar];
                period_reach(m.spacing, e.width, e.height)
            })
            .collect();
        let offers: Vec<bool> = set
            .members
            .iter()
            .map(|member| {
                member
                    .candidates
                    .iter()
                    .any(|c| reaches[c.member as usize] != [0, 0])
            })
            .collect();
        let start: Vec<u32> = start.into_iter().map(|s| s as u32).collect();
        let mut lookup = vec![ABSENT; analysis.exemplars.len() * LEVEL_SLOTS];
        let n = texel_count as usize;
        let mut atlas = DepthAtlas {
            lookup: Vec::new(),
            texels: Vec::with_capacity(2 * n),
            continued: Vec::with_capacity(CONTINUED_SLOTS * n),
            appearance: Vec::with_capacity(10 * n),
            records: Vec::with_capacity(8 * n),
            candidate_texels: Vec::with_capacity(k * n),
            candidate_extras: Vec::with_capacity(2 * k * n),
            candidate_periods: Vec::with_capacity(2 * k * n),
            texel_count,
            has_reach: false,
            has_transfer: false,
        };
        for &m in &order {
            let member = &set.members[m];
            let e = &analysis.exemplars[member.exemplar];
            let (w, h, sp) = (e.width, e.height, member.spacing as i32);
            lookup[member.exemplar * LEVEL_SLOTS + member.level as usize] =
                start[m] | if offers[m] { OFFERS_PERIOD } else { 0 };
            let index = |x: u32, y: u32| start[m] + y * w + x;
            for y in 0..h {
                for x in 0..w {
                    let t = (y * w + x) as usize;
                    atlas.texels.push(pack(x, y));
                    atlas
                        .texels
                        .push(meta(member.exemplar, member.level) | ((offers[m] as u32) << 16));
                    for (slot, (dx, dy)) in offsets().enumerate() {
                        if slot != 4 {
                            let c = index(wrap(x, -dx * sp, w), wrap(y, -dy * sp, h));
                            atlas.continued.push(c);
                        }
                    }
                    for (dx, dy) in APPEARANCE_SHIFTS {
                        let s = (wrap(y, dy * sp, h) * w + wrap(x, dx * sp, w)) as usize;
                        atlas
                            .appearance
                            .extend(pack_i8_words(&member.appearance[s]));
                    }
                    atlas
                        .records
                        .extend(pack_i8_words(&member.neighbourhoods[t]));
                    for c in &member.candidates[t * k..][..k] {
                        let cm = &set.members[c.member as usize];
                        let ce = &analysis.exemplars[cm.exemplar];
                        let (cx, cy) = crate::coords::unpack(c.coord);
                        let [tr, tg, tb] = c.transfer;
                        if let Some(&v) = c.transfer.iter().find(|v| v.abs() > MAX_TRANSFER) {
                            return Err(SynthError::Parameter {
                                name: "candidate transfer",
                                value: v.to_string(),
                                limit: format!("must be within ±{MAX_TRANSFER}"),
                            });
                        }
                        let reach = reaches[c.member as usize];
                        atlas.has_reach |= reach != [0, 0];
                        atlas.has_transfer |= c.transfer != [0; 3];
                        let flag = if offers[c.member as usize] {
                            OFFERS_PERIOD
                        } else {
                            0
                        };
                        atlas
                            .candidate_texels
                            .push((start[c.member as usize] + cy * ce.width + cx) | flag);
                        atlas.candidate_extras.extend_from_slice(&[
                            (tr as u32 & 0xffff) | ((tg as u32) << 16),
                            tb as u32 & 0xffff,
                        ]);
                        atlas.candidate_periods.extend_from_slice(&[
                            cx | (cy << 8) | (meta(cm.exemplar, cm.level) << 16),
                            (ce.width - 1)
                                | ((ce.height - 1) << 8)
                                | (reach[0] << 16)
                                | (reach[1] << 20),
                        ]);
                    }
                }
            }
        }
        atlas.appearance.extend([0; 10]);
        atlas.lookup = lookup;
        Ok(atlas)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coords::unpack;
    use crate::multiscale::{analyze_graph, ExemplarGraph};
    use crate::{AnalysisParams, Exemplar};

    fn noise(side: u32, seed: u32) -> Exemplar {
        let rgb = (0..side * side)
            .map(|i| {
                let h = crate::hash4(i, seed, 0, 0);
                [h as u8, (h >> 8) as u8, (h >> 16) as u8]
            })
            .collect();
        Exemplar::from_rgb("noise", side, side, rgb).unwrap()
    }

    #[test]
    fn texel_order_is_meta_then_coordinate_and_shifts_wrap_at_the_spacing() {
        let text = "root = \"a\"\n[[exemplar]]\nname = \"a\"\nimage = \"a\"\n\
                    [[exemplar]]\nname = \"b\"\nimage = \"b\"\n\
                    [[edge]]\nsource = \"a\"\ndestination = \"b\"\nr = 1\n";
        let graph = ExemplarGraph::parse(std::path::Path::new("g.toml"), text, &|name| {
            Ok(if name == "a" {
                noise(32, 1)
            } else {
                noise(32, 2)
            })
        })
        .unwrap();
        let params = AnalysisParams {
            k: 2,
            ..AnalysisParams::default()
        };
        let analysis = analyze_graph(&graph, &params).unwrap();
        for set in &analysis.sets {
            let atlas = DepthAtlas::new(&analysis, set).unwrap();
            let n = atlas.texel_count as usize;
            assert_eq!(atlas.texels.len(), 2 * n);
            assert_eq!(atlas.continued.len(), 8 * n);
            assert_eq!(atlas.appearance.len(), 10 * (n + 1));
            assert_eq!(atlas.records.len(), 8 * n);
            assert_eq!(atlas.candidate_texels.len(), 2 * n);
            assert_eq!(atlas.candidate_extras.len(), 2 * 2 * n);
            assert_eq!(atlas.candidate_periods.len(), 2 * 2 * n);
            let key = |i: usize| {
                (
                    atlas.texels[2 * i + 1] & 0xffff,
                    unpack(atlas.texels[2 * i]),
                )
            };
            for &c in &atlas.candidate_texels {
                let target = (c & !OFFERS_PERIOD) as usize;
                assert!(target < n);
                assert_eq!(c >> 31, (atlas.texels[2 * target + 1] >> 16) & 1);
            }
            for i in 1..n {
                let ((ma, (xa, ya)), (mb, (xb, yb))) = (key(i - 1), key(i));
                assert!((ma, ya, xa) < (mb, yb, xb), "texel {i} out of order");
            }
            for member in &set.members {
                let e = &analysis.exemplars[member.exemplar];
                let first = atlas.lookup[member.exemplar * LEVEL_SLOTS + member.level as usize]
                    & !OFFERS_PERIOD;
                assert_eq!(
                    atlas.texels[2 * first as usize + 1] & 0xffff,
                    meta(member.exemplar, member.level)
                );
                let sp = member.spacing as i32;
                // A texel near the corner, where every shift wraps.
                let (x, y) = (1, e.height - 1);
                let i = (first + y * e.width + x) as usize;
                let back = atlas.continued[8 * i]; // neighbour (-1, -1): moved by (+sp, +sp)
                assert_eq!(
                    unpack(atlas.texels[2 * back as usize]),
                    (wrap(x, sp, e.width), wrap(y, sp, e.height))
                );
                let up = (wrap(y, -sp, e.height) * e.width + x) as usize;
                assert_eq!(
                    atlas.appearance[10 * i + 6..10 * i + 8],
                    pack_i8_words(&member.appearance[up])[..]
                );
            }
        }
    }
}
