//! Rate–distortion of the compressed trees against the block codecs a user would pick instead,
//! on one test image: the tree at each step of a geometric ladder (bits per texel of the whole
//! structure against PSNR of the decoded 8-bit image), BC1 (4 bpp), BC7 (8 bpp) and 2×2 block VQ
//! with 256 codewords (2 bpp plus its codebook), BC4 too for grey images; where the tree first
//! matches BC1's PSNR, its Table 4.2 and topology bytes per node.

use super::baselines::{
    bc1_roundtrip, bc4_roundtrip, bc7_roundtrip, psnr_rgb, vq2x2_roundtrip, Rgba8,
};
use super::images::TestImage;
use lazysolid_compute::ctree::colour::{grey_of_fixed, ColourTrees};
use lazysolid_compute::ctree::topology::TopologyCosts;
use lazysolid_compute::ctree::{CompressedTree, CtreeOptions, ScalarField};
use serde::Serialize;

/// One point of a tree's rate–distortion curve.
#[derive(Clone, Debug, Serialize)]
pub struct TreePoint {
    /// The finest step, grey levels.
    pub step: f32,
    /// Bytes of every tree (three for colour).
    pub bytes: u64,
    /// Bits per texel.
    pub bpp: f64,
    /// PSNR of the decoded image, dB.
    pub psnr: f64,
    /// Topology bytes per node (over every tree).
    pub topology_per_node: f64,
    /// Nodes of every tree.
    pub nodes: u64,
    /// The forest level of each tree.
    pub forests: Vec<u32>,
}

/// A row of Table 4.2 (see `lazysolid_compute::ctree::LevelRow`).
#[derive(Clone, Debug, Serialize)]
pub struct TableRow {
    /// The level (0 = root).
    pub level: u32,
    /// Nodes kept.
    pub nodes: u64,
    /// Internal nodes (records).
    pub internal: u64,
    /// The offset scale.
    pub scale: u32,
    /// Padding bytes.
    pub padding: u64,
}

/// Topology bytes per node of the encodings (see `TopologyCosts`).
#[derive(Clone, Debug, Serialize)]
pub struct Costs {
    /// Pointer tree.
    pub pointer: f64,
    /// Sibling tree.
    pub sibling: f64,
    /// Autumnal tree.
    pub autumnal: f64,
    /// Compact, packed from the root.
    pub compact_rooted: f64,
    /// Compact with the forest.
    pub compact: f64,
}

/// One block codec's point.
#[derive(Clone, Debug, Serialize)]
pub struct CodecPoint {
    /// BC1, BC4, BC7 or VQ.
    pub codec: String,
    /// Bits per texel, the codebook included.
    pub bpp: f64,
    /// PSNR, dB.
    pub psnr: f64,
}

/// Everything measured on one image.
#[derive(Clone, Debug, Serialize)]
pub struct ImageRd {
    /// The image's short name.
    pub image: String,
    /// What it is.
    pub what: String,
    /// Size.
    pub width: u32,
    /// Size.
    pub height: u32,
    /// 1 or 3.
    pub channels: u32,
    /// The tree's curve, finest step first.
    pub tree: Vec<TreePoint>,
    /// The codecs.
    pub codecs: Vec<CodecPoint>,
    /// Where the tree first matches BC1's PSNR (from the coarse end of the ladder), if it does.
    pub matches_bc1: Option<TreePoint>,
    /// The first tree's Table 4.2 at that point (Y for colour).
    pub table: Vec<TableRow>,
    /// The topology encodings' costs at that point (the first tree).
    pub costs: Option<Costs>,
    /// The tree's PSNR at BC1's and BC7's rates, interpolated on its curve.
    pub tree_at_4bpp: Option<f64>,
    /// See `tree_at_4bpp`.
    pub tree_at_8bpp: Option<f64>,
}

/// PSNR of two 8-bit planes of the same size (any channel count), 255 peak.
pub fn psnr(a: &[u8], b: &[u8]) -> f64 {
    let se: f64 = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (x as f64 - y as f64).powi(2))
        .sum();
    let mse = se / a.len() as f64;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    }
}

/// The trees of `img` at `step`, and their decoded texels.
pub fn trees(img: &TestImage, step: f32) -> anyhow::Result<(Vec<CompressedTree>, Vec<u8>)> {
    let options = CtreeOptions {
        step,
        ..Default::default()
    };
    if img.channels == 1 {
        let values = img.texels.iter().map(|&g| g as f32).collect();
        let field = ScalarField::new(&img.name, 2, [img.width, img.height, 1], values)?;
        let tree = CompressedTree::build(&field, &options)?;
        let decoded = (0..img.height)
            .flat_map(|y| (0..img.width).map(move |x| (x, y)))
            .map(|(x, y)| grey_of_fixed(tree.texel_fixed([x, y, 0])))
            .collect();
        Ok((vec![tree], decoded))
    } else {
        let trees = ColourTrees::build(&img.name, &img.texels, img.width, img.height, &options)?;
        let decoded = trees.decode();
        Ok((trees.channels.to_vec(), decoded))
    }
}

/// The tree's point at `step`.
pub fn tree_point(img: &TestImage, step: f32) -> anyhow::Result<(TreePoint, Vec<CompressedTree>)> {
    let (trees, decoded) = trees(img, step)?;
    let bytes: u64 = trees.iter().map(CompressedTree::size_bytes).sum();
    let nodes: u64 = trees.iter().map(|t| t.stats.nodes).sum();
    let topology: u64 = trees.iter().map(|t| t.stats.topology_bytes).sum();
    let point = TreePoint {
        step,
        bytes,
        bpp: 8.0 * bytes as f64 / (img.width * img.height) as f64,
        psnr: psnr(&decoded, &img.texels),
        topology_per_node: topology as f64 / nodes as f64,
        nodes,
        forests: trees.iter().map(|t| t.forest).collect(),
    };
    Ok((point, trees))
}

fn rgba(img: &TestImage) -> Rgba8 {
    if img.channels == 1 {
        Rgba8::from_gray(img.width, img.height, &img.texels)
    } else {
        let texels = img
            .texels
            .chunks_exact(3)
            .flat_map(|c| [c[0], c[1], c[2], 255])
            .collect();
        Rgba8::new(img.width, img.height, texels)
    }
}

/// The codecs' points on `img`. A grey image is coded as grey RGB and read back as the mean of
/// the channels (after BC1's 5:6:5 the three disagree, and their mean is the better estimate).
pub fn codecs(img: &TestImage) -> Vec<CodecPoint> {
    let source = rgba(img);
    let texels = (img.width * img.height) as f64;
    let score = |decoded: &Rgba8| {
        if img.channels == 1 {
            psnr(&decoded.to_gray(), &img.texels)
        } else {
            psnr_rgb(&source, decoded)
        }
    };
    let mut out = vec![
        CodecPoint {
            codec: "BC1".into(),
            bpp: 4.0,
            psnr: score(&bc1_roundtrip(&source)),
        },
        CodecPoint {
            codec: "BC7".into(),
            bpp: 8.0,
            psnr: score(&bc7_roundtrip(&source)),
        },
    ];
    let (vq, codebook) = vq2x2_roundtrip(&source);
    out.push(CodecPoint {
        codec: "VQ 2×2, 256 codewords".into(),
        bpp: 2.0 + 8.0 * codebook as f64 / texels,
        psnr: score(&vq),
    });
    if img.channels == 1 {
        out.push(CodecPoint {
            codec: "BC4".into(),
            bpp: 4.0,
            psnr: score(&bc4_roundtrip(&source)),
        });
    }
    out
}

/// The tree's PSNR at `bpp` by linear interpolation on its curve (None outside it).
pub fn psnr_at(curve: &[TreePoint], bpp: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = curve.iter().map(|p| (p.bpp, p.psnr)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        (x0 <= bpp && bpp <= x1 && x1 > x0).then(|| y0 + (y1 - y0) * (bpp - x0) / (x1 - x0))
    })
}

/// Steps of the ladder: 2^(k/4) grey levels from 1/4 to 64.
pub fn ladder() -> Vec<f32> {
    (-8..=24).map(|k| 2f32.powf(k as f32 / 4.0)).collect()
}

/// Measures `img`: the curve at `steps`, the codecs, the first match of BC1 along the ladder.
pub fn measure(img: &TestImage, steps: &[f32]) -> anyhow::Result<ImageRd> {
    let codecs = codecs(img);
    let bc1 = codecs[0].psnr;
    let mut tree = Vec::new();
    for &s in steps {
        tree.push(tree_point(img, s)?.0);
    }
    // From the coarse end (the lowest rate) towards finer steps: the first point at or above
    // BC1's PSNR.
    let mut matches_bc1 = None;
    let mut table = Vec::new();
    let mut costs = None;
    for &s in ladder().iter().rev() {
        let (p, trees) = tree_point(img, s)?;
        if p.psnr >= bc1 {
            table = trees[0]
                .stats
                .rows
                .iter()
                .map(|r| TableRow {
                    level: r.level,
                    nodes: r.nodes,
                    internal: r.internal,
                    scale: r.scale,
                    padding: r.padding,
                })
                .collect();
            let c = TopologyCosts::of(&trees[0].stats, 2);
            costs = Some(Costs {
                pointer: c.pointer,
                sibling: c.sibling,
                autumnal: c.autumnal,
                compact_rooted: c.compact_rooted,
                compact: c.compact,
            });
            matches_bc1 = Some(p);
            break;
        }
    }
    Ok(ImageRd {
        image: img.name.clone(),
        what: img.what.clone(),
        width: img.width,
        height: img.height,
        channels: img.channels,
        tree_at_4bpp: psnr_at(&tree, 4.0),
        tree_at_8bpp: psnr_at(&tree, 8.0),
        tree,
        codecs,
        matches_bc1,
        table,
        costs,
    })
}
