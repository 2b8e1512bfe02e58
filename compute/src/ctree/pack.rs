//! The compact topology (thesis §4.1.3): every internal node is a record of one byte of its own
//! code followed by one `PointerOrData` byte per child. A child that is a leaf keeps its 7-bit
//! code in that byte (high bit clear); an internal child is a 7-bit offset x (high bit set) to
//! its own record, y = s_l·x bytes after the end of the parent's record, s_l chosen per level.
//! Records are packed in preorder, fine to coarse: a node's block is its record followed by the
//! blocks of its internal children in slot order, each preceded by the padding that makes its
//! offset a multiple of s_l. s_l is searched exhaustively over ⌈y_max/127⌉ ..= y_max for the
//! least padding of the level, as the thesis does; levels are independent once the blocks below
//! are known, so every level's work is parallel over its nodes (and candidates).

use super::lattice::Lattice;
use super::residuals::{child_exists, Residuals};

pub use crate::shader_constants::CTREE_MAX_OFFSET as MAX_OFFSET;

/// The packing of one level's records.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LevelPacking {
    /// The scale s_l of the offsets from this level's records to their children's.
    pub scale: u32,
    /// Padding bytes inserted before this level's children's blocks.
    pub padding: u64,
    /// The largest unpadded offset, y_max.
    pub max_offset: u64,
    /// Scales tried by the search.
    pub candidates: u64,
}

/// Internal children's blocks of one record, with the record's size.
struct Record {
    size: u32,
    children: Vec<u64>,
}

/// Packed sizes of every level's blocks, bottom-up.
#[derive(Clone, Debug)]
pub struct Packing {
    /// Per level 0..L (the finest has no records): scale and padding.
    pub levels: Vec<LevelPacking>,
    /// Per level, the block size of each node (0 for nodes that are not internal), dense order.
    pub blocks: Vec<Vec<u64>>,
}

/// The records of level `l` (every node, internal or not), dense order.
fn records(res: &Residuals, l: u32, blocks_below: &[u64]) -> Vec<Option<Record>> {
    let lat = &res.lattice;
    let count = if l == 0 { 1 } else { lat.count(l) };
    (0..count)
        .map(|i| {
            if !res.internal[l as usize][i] {
                return None;
            }
            let q = if l == 0 { [0; 3] } else { lat.coords(l, i) };
            let open = lat.open_axes(l, q);
            let children = (0..lat.brood())
                .filter(|&c| child_exists(lat, open, c))
                .map(|c| blocks_below[lat.index(l + 1, lat.child(l, q, c))])
                .filter(|&b| b > 0)
                .collect();
            Some(Record {
                size: 1 + lat.child_count(open),
                children,
            })
        })
        .collect()
}

/// Offsets of the children's blocks after padding to multiples of `scale`, and the padding.
/// `None` when an offset exceeds 127·scale.
pub fn place(children: &[u64], scale: u64) -> Option<(Vec<u64>, u64)> {
    let mut offset = 0u64;
    let mut padding = 0u64;
    let mut offsets = Vec::with_capacity(children.len());
    for &b in children {
        let pad = (scale - offset % scale) % scale;
        offset += pad;
        padding += pad;
        if offset / scale > MAX_OFFSET as u64 {
            return None;
        }
        offsets.push(offset);
        offset += b;
    }
    Some((offsets, padding))
}

/// The least-padding scale of a level whose records have internal children of `children`
/// block sizes (the thesis' exhaustive search).
pub fn search_scale(children: &[&[u64]]) -> LevelPacking {
    let max_offset = children
        .iter()
        .map(|c| c.iter().rev().skip(1).sum::<u64>())
        .max()
        .unwrap_or(0);
    let first = max_offset.div_ceil(MAX_OFFSET as u64).max(1);
    let last = max_offset.max(1);
    let mut best: Option<(u64, u64)> = None;
    for scale in first..=last {
        let mut total = 0u64;
        let mut fits = true;
        for c in children {
            match place(c, scale) {
                Some((_, pad)) => total += pad,
                None => {
                    fits = false;
                    break;
                }
            }
            if best.is_some_and(|(_, b)| total >= b) {
                fits = false;
                break;
            }
        }
        if fits && best.is_none_or(|(_, b)| total < b) {
            best = Some((scale, total));
        }
        if best.is_some_and(|(_, b)| b == 0) {
            break;
        }
    }
    let (scale, padding) = best.expect("scale y_max always fits");
    LevelPacking {
        scale: scale as u32,
        padding,
        max_offset,
        candidates: last - first + 1,
    }
}

impl Packing {
    /// Packs every level of `res`, finest first.
    pub fn build(res: &Residuals) -> Packing {
        let lat: &Lattice = &res.lattice;
        let finest = lat.finest();
        let mut blocks: Vec<Vec<u64>> = vec![Vec::new(); finest as usize + 1];
        blocks[finest as usize] = vec![0; lat.count(finest)];
        let mut levels = vec![LevelPacking::default(); finest as usize];
        for l in (0..finest).rev() {
            let recs = records(res, l, &blocks[l as usize + 1]);
            let lists: Vec<&[u64]> = recs
                .iter()
                .flatten()
                .map(|r| r.children.as_slice())
                .collect();
            let packing = search_scale(&lists);
            let scale = packing.scale as u64;
            blocks[l as usize] = recs
                .iter()
                .map(|r| match r {
                    None => 0,
                    Some(r) => {
                        let (offsets, _) = place(&r.children, scale).expect("searched scale fits");
                        let end = offsets
                            .last()
                            .zip(r.children.last())
                            .map_or(0, |(o, b)| o + b);
                        r.size as u64 + end
                    }
                })
                .collect();
            levels[l as usize] = packing;
        }
        Packing { levels, blocks }
    }
}
