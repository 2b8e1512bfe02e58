//! The memory part: the constant storage of the method (the example as 2 × f32 per texel, the
//! sparse table, the Gaussianization tables) against the materialized normal map the explicit
//! method needs for a coverage of C² texels (2 × f32 per texel and its 16-bit min–max mip),
//! beside the paper's Table 1 (35 MB against 7,896 MB for the Chair's 5K² map: 0.44 %; against
//! 1,119.9 MB for the Kettle's 2K² map: 3.1 %). It exists because the saving in memory is the
//! method's claim: no map of the covered surface is ever made.

use lazysolid_renderer::glint::minmax_mip::minmax_mip_bytes;

/// The paper's Table 1 (MB): its constant storage for a 512² example, and the explicit maps.
const PAPER_OURS_MB: f64 = 35.0;
const PAPER_EXPLICIT: [(u64, f64, &str); 2] = [(5120, 7896.0, "Chair"), (2048, 1119.9, "Kettle")];

/// Bytes per texel of Yan et al. 2016's explicit map in the paper: 7,896 MB for 5120².
const YAN16_BYTES_PER_TEXEL: f64 = 7896.0e6 / (5120.0 * 5120.0);

/// Bytes of the explicit method's materialized map of `edge`² texels: (n_x, n_y) as 2 × f32
/// and the 16-bit min–max mip over it.
fn explicit_bytes(edge: u64) -> u64 {
    edge * edge * 8 + minmax_mip_bytes(edge)
}

pub(super) fn memory_part(
    storage: &[(String, u32, u64, u64, u64)],
    coverage: &[u64],
    notes: &mut Vec<(String, f64)>,
) {
    println!(
        "memory: constant storage (example 2 x f32 per texel + sparse table + Gaussianization \
         tables) against the explicit method's materialized map (2 x f32 per texel + 16-bit \
         min–max mip), MB = 10^6 bytes:"
    );
    println!(
        "{:<22} {:>5} {:>9} {:>9} {:>8} {:>9} {:>10} {:>11} {:>8} {:>13} {:>14}",
        "example",
        "l",
        "example",
        "table",
        "tables",
        "total",
        "coverage",
        "explicit",
        "ratio",
        "ratio @Yan16",
        "paper"
    );
    let mb = |b: u64| b as f64 / 1e6;
    for (label, patch, texels, table, gauss) in storage {
        let total = texels + table + gauss;
        notes.push((format!("{label}: constant storage bytes"), total as f64));
        notes.push((
            format!("{label}: gaussianization table bytes"),
            *gauss as f64,
        ));
        for &c in coverage {
            let explicit = explicit_bytes(c);
            let ratio = total as f64 / explicit as f64 * 100.0;
            // The explicit map at Yan et al.'s bytes per texel (the Chair's 7,896 MB / 5120²).
            let yan = total as f64 / (YAN16_BYTES_PER_TEXEL * (c * c) as f64) * 100.0;
            let paper = PAPER_EXPLICIT
                .iter()
                .find(|p| p.0 == c)
                .map(|p| format!("{:.2} % {}", PAPER_OURS_MB / p.1 * 100.0, p.2))
                .unwrap_or_default();
            println!(
                "{:<22} {:>5} {:>9.2} {:>9.2} {:>8.4} {:>9.2} {:>10} {:>11.1} {:>7.3}% {:>12.3}% {:>14}",
                label,
                patch,
                mb(*texels),
                mb(*table),
                mb(*gauss),
                mb(total),
                format!("{c}²"),
                mb(explicit),
                ratio,
                yan,
                paper
            );
            notes.push((
                format!("{label} against coverage {c}²: constant / explicit %"),
                ratio,
            ));
            notes.push((
                format!("{label} against coverage {c}² at Yan16 bytes per texel: %"),
                yan,
            ));
        }
    }
    for &c in coverage {
        notes.push((
            format!("coverage {c}²: explicit map bytes"),
            explicit_bytes(c) as f64,
        ));
    }
    for (c, explicit_mb, scene) in PAPER_EXPLICIT {
        notes.push((
            format!(
                "paper {scene}: 512² example {PAPER_OURS_MB} MB / {c}² explicit {explicit_mb} MB %"
            ),
            PAPER_OURS_MB / explicit_mb * 100.0,
        ));
        notes.push((
            format!("paper {scene}: explicit bytes per texel"),
            explicit_mb * 1e6 / (c * c) as f64,
        ));
    }
    println!(
        "paper (Table 1): 35.0 MB for a 512² example against 7,896.0 MB for the Chair's 5K² \
         map (0.44 %, about {:.0} bytes per texel: Yan et al. 2016 store Gaussian elements and \
         their hierarchy) and 1,119.9 MB for the Kettle's 2K² map (3.1 %)",
        YAN16_BYTES_PER_TEXEL
    );
}
