//! What `bench ctree` writes besides the harness's table: per image the rate–distortion plot,
//! the image and the trees' decoding where they first match BC1, and for all images `ctree-rd.csv`, `ctree-rd.json` and `ctree-tables.md` (Table 4.2's
//! columns and the topology costs where each tree first matches BC1, and the verdicts at BC1's
//! and BC7's rates).

use super::images::TestImage;
use super::rate::{trees, ImageRd};
use crate::bench::plot::{rgb_image, xy_chart, Series};
use crate::cli::output::write_atomically;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// The image and its trees' decoding where they first match BC1 (`image-<name>.png`,
/// `tree-<name>.png`), to look at what the figures measure.
pub fn save_pictures(dir: &Path, img: &TestImage, rd: &ImageRd) -> anyhow::Result<()> {
    let rgb = |texels: &[u8]| -> Vec<u8> {
        if img.channels == 3 {
            texels.to_vec()
        } else {
            texels.iter().flat_map(|&g| [g, g, g]).collect()
        }
    };
    let name = &img.name;
    rgb_image(
        &dir.join(format!("image-{name}.png")),
        img.width,
        img.height,
        rgb(&img.texels),
    )?;
    if let Some(p) = &rd.matches_bc1 {
        let (_, decoded) = trees(img, p.step)?;
        rgb_image(
            &dir.join(format!("tree-{name}.png")),
            img.width,
            img.height,
            rgb(&decoded),
        )?;
    }
    Ok(())
}

/// The rate–distortion plot of one image.
pub fn plot_rd(dir: &Path, rd: &ImageRd) -> anyhow::Result<()> {
    let mut series = vec![Series {
        name: "compressed tree".into(),
        points: rd.tree.iter().map(|p| (p.bpp, p.psnr)).collect(),
    }];
    for c in &rd.codecs {
        let name = if c.psnr.is_finite() {
            c.codec.clone()
        } else {
            format!("{}: lossless, off the chart", c.codec)
        };
        series.push(Series {
            name,
            points: vec![(c.bpp, c.psnr)],
        });
    }
    xy_chart(
        &dir.join(format!("rd-{}.png", rd.image)),
        &format!(
            "{} ({}×{}): PSNR against bits per texel",
            rd.image, rd.width, rd.height
        ),
        "bits per texel",
        "PSNR (dB)",
        &series,
        false,
    )
}

/// A PSNR for the tables: lossless where the error is zero.
fn db(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.2} dB")
    } else {
        "lossless".into()
    }
}

/// Who wins at `bpp`: the tree's PSNR there (interpolated on its curve) against the codec's.
/// Outside the curve, the nearest end decides when it can: a tree that falls short of the codec
/// at a higher rate falls short at this one too (and one that beats it at a lower rate beats it).
fn verdict(curve: &[super::rate::TreePoint], tree: Option<f64>, bpp: f64, codec: f64) -> String {
    let c = db(codec);
    if let Some(v) = tree {
        return if v > codec {
            format!("tree {} > {c}: the tree wins", db(v))
        } else {
            format!("tree {} ≤ {c}: the codec wins", db(v))
        };
    }
    let lowest = curve.iter().min_by(|a, b| a.bpp.total_cmp(&b.bpp));
    let highest = curve.iter().max_by(|a, b| a.bpp.total_cmp(&b.bpp));
    match (lowest, highest) {
        (Some(l), _) if l.bpp > bpp && l.psnr <= codec => format!(
            "the codec wins ({c}): the tree's lowest rate, {:.2} bpp, gives only {}",
            l.bpp,
            db(l.psnr)
        ),
        (_, Some(h)) if h.bpp < bpp && h.psnr > codec => format!(
            "the tree wins: {} at {:.2} bpp already beats the codec's {c}",
            db(h.psnr),
            h.bpp
        ),
        _ => format!("undecided outside the tree's curve (codec {c})"),
    }
}

/// The CSV, JSON and Markdown of every image; notes for the harness's JSON.
pub fn write_rd(dir: &Path, all: &[ImageRd], notes: &mut Vec<(String, f64)>) -> anyhow::Result<()> {
    let mut csv = String::from("image,method,step,bpp,psnr_db,topology_bytes_per_node\n");
    for rd in all {
        for p in &rd.tree {
            writeln!(
                csv,
                "{},tree,{},{:.4},{:.3},{:.4}",
                rd.image, p.step, p.bpp, p.psnr, p.topology_per_node
            )?;
        }
        for c in &rd.codecs {
            writeln!(csv, "{},{},,{:.4},{:.3},", rd.image, c.codec, c.bpp, c.psnr)?;
        }
    }
    write_atomically(&dir.join("ctree-rd.csv"), |w| {
        Ok(w.write_all(csv.as_bytes())?)
    })?;
    let json = serde_json::to_string_pretty(all)?;
    write_atomically(&dir.join("ctree-rd.json"), |w| {
        Ok(w.write_all(json.as_bytes())?)
    })?;
    let mut md = String::new();
    for rd in all {
        writeln!(md, "## {} — {}\n", rd.image, rd.what)?;
        let codec = |name: &str| rd.codecs.iter().find(|c| c.codec == name).map(|c| c.psnr);
        let bc1 = codec("BC1").unwrap_or(f64::NAN);
        let bc7 = codec("BC7").unwrap_or(f64::NAN);
        writeln!(
            md,
            "- at 4 bpp against BC1: {}",
            verdict(&rd.tree, rd.tree_at_4bpp, 4.0, bc1)
        )?;
        writeln!(
            md,
            "- at 8 bpp against BC7: {}",
            verdict(&rd.tree, rd.tree_at_8bpp, 8.0, bc7)
        )?;
        for c in &rd.codecs {
            writeln!(md, "- {}: {:.3} bpp, {}", c.codec, c.bpp, db(c.psnr))?;
        }
        match &rd.matches_bc1 {
            None => writeln!(md, "- the tree never reaches BC1's PSNR on the ladder\n")?,
            Some(p) => {
                writeln!(
                    md,
                    "- first match of BC1 from the coarse end: step {:.3}, {:.3} bpp, {:.2} dB, \
                     topology {:.3} B/node over {} nodes, forest level(s) {:?}\n",
                    p.step, p.bpp, p.psnr, p.topology_per_node, p.nodes, p.forests
                )?;
                notes.push((format!("{}: bpp matching BC1", rd.image), p.bpp));
                notes.push((
                    format!("{}: topology B/node there", rd.image),
                    p.topology_per_node,
                ));
                writeln!(
                    md,
                    "| level | nodes | internal | scale | padding (bytes) |\n|---|---|---|---|---|"
                )?;
                for r in &rd.table {
                    writeln!(
                        md,
                        "| {} | {} | {} | {} | {} |",
                        r.level, r.nodes, r.internal, r.scale, r.padding
                    )?;
                }
                if let Some(c) = &rd.costs {
                    writeln!(
                        md,
                        "\nTopology bytes per node of this tree: pointer {:.2}, sibling {:.2}, \
                         autumnal {:.3}, compact from the root {:.3}, compact with the forest \
                         {:.3}.\n",
                        c.pointer, c.sibling, c.autumnal, c.compact_rooted, c.compact
                    )?;
                }
            }
        }
    }
    write_atomically(&dir.join("ctree-tables.md"), |w| {
        Ok(w.write_all(md.as_bytes())?)
    })?;
    print!("{md}");
    Ok(())
}
