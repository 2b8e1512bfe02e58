//! How much of a rendered object's albedo falls in an exemplar's dark class: a check of a
//! synthesized texture on a rendered object that a figure can support but not replace (open
//! the picture too). The exemplar's luminance is split by Otsu's threshold into a dark and a
//! light class; the object's pixels are the EXR albedo pixels with colour (chroma above
//! `--chroma`, so a grey floor and the black background are left out), and their share below
//! the same threshold (in 8-bit sRGB, as the exemplar) is printed beside the exemplar's own.
//!
//! ```text
//! cargo run --release -p lazysolid-tools --example albedo_share -- RENDER.exr EXEMPLAR [ALBEDO.png]
//! ```
//! `EXEMPLAR` is a path or a name in assets/exemplars; `ALBEDO.png` receives the albedo layer
//! (sRGB), the object's dark pixels black and its light pixels white beside it.

use anyhow::{bail, Context};
use lazysolid_renderer::output::{read_exr_layer, srgb_oetf};
use lazysolid_synth::feature::otsu;
use lazysolid_synth::Exemplar;
use std::path::PathBuf;

/// Chroma (max − min of the 8-bit sRGB albedo, over 255) above which a pixel is the object's.
const CHROMA: f32 = 0.06;

fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 2 || args.len() > 3 {
        bail!("usage: albedo_share RENDER.exr EXEMPLAR [ALBEDO.png]");
    }
    let exemplar_path = lazysolid_renderer::assets::exemplar(&args[1], &PathBuf::from("."))
        .map_err(anyhow::Error::msg)?;
    let exemplar = Exemplar::load(&exemplar_path)?;
    let ex_lum: Vec<f32> = exemplar
        .rgb
        .iter()
        .map(|p| luminance(p.map(|v| f32::from(v) / 255.0)))
        .collect();
    let Some(t) = otsu(&ex_lum) else {
        bail!(
            "{}: every pixel has the same luminance",
            exemplar_path.display()
        );
    };
    let ex_share = ex_lum.iter().filter(|&&l| l < t).count() as f64 / ex_lum.len() as f64;

    let (w, h, albedo) = read_exr_layer(&args[0], ["albedo.R", "albedo.G", "albedo.B"])?;
    let srgb: Vec<[f32; 3]> = albedo
        .iter()
        .map(|a| a.map(|v| srgb_oetf(v.clamp(0.0, 1.0))))
        .collect();
    let object: Vec<bool> = srgb
        .iter()
        .map(|c| {
            let (lo, hi) = c
                .iter()
                .fold((1f32, 0f32), |(a, b), &v| (a.min(v), b.max(v)));
            hi - lo > CHROMA
        })
        .collect();
    let n = object.iter().filter(|&&o| o).count();
    if n == 0 {
        bail!(
            "{}: no albedo pixel has colour (chroma > {CHROMA})",
            args[0]
        );
    }
    let dark = srgb
        .iter()
        .zip(&object)
        .filter(|(c, &o)| o && luminance(**c) < t)
        .count();
    println!(
        "exemplar {}: Otsu luminance threshold {:.3}, dark share {:.1} %",
        exemplar_path.display(),
        t,
        100.0 * ex_share
    );
    println!(
        "render {}: {} object pixels of {}, dark share {:.1} %",
        args[0],
        n,
        w * h,
        100.0 * dark as f64 / n as f64
    );
    if let Some(out) = args.get(2) {
        let mut img = image::RgbImage::new(2 * w, h);
        for (i, c) in srgb.iter().enumerate() {
            let (x, y) = (i as u32 % w, i as u32 / w);
            img.put_pixel(x, y, image::Rgb(c.map(|v| (v * 255.0).round() as u8)));
            let v = match (object[i], luminance(*c) < t) {
                (false, _) => 128,
                (true, true) => 0,
                (true, false) => 255,
            };
            img.put_pixel(w + x, y, image::Rgb([v, v, v]));
        }
        img.save(out).with_context(|| format!("writing {out}"))?;
    }
    Ok(())
}
