//! NRRD volumes: what `lazysolid solid` writes and what a scene's `kind = "volume"` texture
//! reads (and what ParaView, 3D Slicer and ImageJ open and export): raw 8-bit RGB, x fastest.
//! Writer and reader live together so the two cannot drift apart.

use super::volume::MAX_VOLUME_SIDE;
use std::io::Write;
use std::path::Path;

/// An RGB box of voxels, sRGB-encoded bytes, x fastest, then y, then z.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbVolume {
    /// Voxels along x, y and z.
    pub size: [u32; 3],
    /// sRGB colour per voxel.
    pub rgb: Vec<[u8; 3]>,
}

/// Encodes an RGB cube of side `n` as NRRD (raw bytes, x fastest), the format ParaView, 3D
/// Slicer and ImageJ open, with `notes` as comment lines of its header (kept ASCII, as
/// readers expect of a header: `→` is written `->`).
pub fn encode_nrrd(colours: &[[u8; 3]], n: u32, notes: &[String]) -> Vec<u8> {
    let mut out = Vec::with_capacity(colours.len() * 3 + 200);
    let _ = write!(out, "NRRD0004\n# lazysolid solid texture\n");
    for note in notes {
        let ascii: String = note
            .replace('→', "->")
            .chars()
            .map(|c| if c.is_ascii() && c != '\n' { c } else { '?' })
            .collect();
        let _ = writeln!(out, "# {ascii}");
    }
    let _ = write!(
        out,
        "type: uint8\ndimension: 4\nsizes: 3 {n} {n} {n}\nkinds: RGB-color domain domain domain\nspacings: NaN 1 1 1\nencoding: raw\n\n"
    );
    out.extend(colours.iter().flatten());
    out
}

/// Decodes the bytes of an NRRD file read from `path` (named in the errors): `type` 8-bit
/// unsigned, `dimension: 4` with `sizes: 3 X Y Z` (an RGB triple per voxel, each side
/// 1..=[`MAX_VOLUME_SIDE`]), `encoding: raw`.
///
/// # Errors
/// The file's path, the header field and what it must be, in one line.
pub fn decode_nrrd(bytes: &[u8], path: &Path) -> Result<RgbVolume, String> {
    let bad = |what: String| format!("{}: {what}", path.display());
    if !bytes.starts_with(b"NRRD000") {
        return Err(bad(
            "not an NRRD file (it must start with NRRD0001..NRRD0005)".into(),
        ));
    }
    let end = bytes
        .windows(2)
        .position(|w| w == b"\n\n")
        .ok_or_else(|| bad("the header has no end (an empty line before the data)".into()))?;
    let header =
        std::str::from_utf8(&bytes[..end]).map_err(|_| bad("the header is not text".into()))?;
    let (mut kind, mut dimension, mut sizes, mut encoding) = (None, None, None, None);
    for line in header.lines().skip(1) {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        // `key: value`; `key:=value` lines are key-value pairs of the data, not fields.
        let Some((key, value)) = line.split_once(": ") else {
            continue;
        };
        let value = value.trim();
        match key.trim() {
            "type" => kind = Some(value.to_string()),
            "dimension" => dimension = Some(value.to_string()),
            "sizes" => sizes = Some(value.to_string()),
            "encoding" => encoding = Some(value.to_string()),
            _ => {}
        }
    }
    let field = |name: &str, v: Option<String>| {
        v.ok_or_else(|| bad(format!("the header has no `{name}` field")))
    };
    let kind = field("type", kind)?;
    if !["uint8", "uchar", "unsigned char", "uint8_t"].contains(&kind.as_str()) {
        return Err(bad(format!(
            "type: {kind} is not supported (must be uint8: 8-bit sRGB)"
        )));
    }
    let dimension = field("dimension", dimension)?;
    if dimension != "4" {
        return Err(bad(format!(
            "dimension: {dimension} is not supported (must be 4: RGB, x, y, z)"
        )));
    }
    let encoding = field("encoding", encoding)?;
    if encoding != "raw" {
        return Err(bad(format!(
            "encoding: {encoding} is not supported (must be raw)"
        )));
    }
    let sizes_text = field("sizes", sizes)?;
    let sizes: Vec<u32> = sizes_text
        .split_whitespace()
        .map(|s| s.parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad(format!("sizes: {sizes_text} are not four whole numbers")))?;
    if sizes.len() != 4 || sizes[0] != 3 {
        return Err(bad(format!(
            "sizes: {sizes_text} must be `3 X Y Z` (three channels per voxel)"
        )));
    }
    let size = [sizes[1], sizes[2], sizes[3]];
    if let Some(s) = size.iter().find(|&&s| !(1..=MAX_VOLUME_SIDE).contains(&s)) {
        return Err(bad(format!(
            "sizes: a side of {s} voxels is outside 1..={MAX_VOLUME_SIDE}"
        )));
    }
    let voxels = size.iter().map(|&s| s as usize).product::<usize>();
    let data = &bytes[end + 2..];
    if data.len() != voxels * 3 {
        return Err(bad(format!(
            "holds {} bytes of data, sizes {sizes_text} need {}",
            data.len(),
            voxels * 3
        )));
    }
    Ok(RgbVolume {
        size,
        rgb: data.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nrrd(header: &str, data: &[u8]) -> Vec<u8> {
        let mut b = header.as_bytes().to_vec();
        b.extend_from_slice(data);
        b
    }

    const GOOD: &str = "NRRD0004\n# c\ntype: uint8\ndimension: 4\nsizes: 3 2 1 1\nkinds: RGB-color domain domain domain\nencoding: raw\n\n";

    #[test]
    fn reads_what_lazysolid_solid_writes() {
        let v = decode_nrrd(&nrrd(GOOD, &[1, 2, 3, 4, 5, 6]), Path::new("v.nrrd")).unwrap();
        assert_eq!(v.size, [2, 1, 1]);
        assert_eq!(v.rgb, vec![[1, 2, 3], [4, 5, 6]]);
    }

    #[test]
    fn reads_back_what_it_writes() {
        let colours: Vec<[u8; 3]> = (0..27u8).map(|i| [i, 2 * i, 255 - i]).collect();
        let notes = ["seed 3 → x".to_string(), "two\nlines".to_string()];
        let bytes = encode_nrrd(&colours, 3, &notes);
        let header = String::from_utf8_lossy(&bytes[..bytes.len() - 81]).to_string();
        assert!(header.contains("# seed 3 -> x\n"), "{header}");
        assert!(header.contains("# two?lines\n"), "{header}");
        let v = decode_nrrd(&bytes, Path::new("v.nrrd")).unwrap();
        assert_eq!(v.size, [3, 3, 3]);
        assert_eq!(v.rgb, colours);
    }

    #[test]
    fn names_the_field_that_is_wrong() {
        let p = Path::new("dir/v.nrrd");
        for (bytes, needles) in [
            (b"P6\n".to_vec(), &["dir/v.nrrd", "not an NRRD"][..]),
            (
                nrrd(&GOOD.replace("uint8", "float"), &[0; 6]),
                &["type: float", "uint8"][..],
            ),
            (
                nrrd(&GOOD.replace("dimension: 4", "dimension: 3"), &[0; 6]),
                &["dimension: 3"][..],
            ),
            (
                nrrd(&GOOD.replace("raw", "gzip"), &[0; 6]),
                &["encoding: gzip"][..],
            ),
            (
                nrrd(&GOOD.replace("3 2 1 1", "1 2 1 1"), &[0; 2]),
                &["sizes: 1 2 1 1", "3 X Y Z"][..],
            ),
            (
                nrrd(&GOOD.replace("3 2 1 1", "3 2000 1 1"), &[0; 6]),
                &["2000", "1..=1024"][..],
            ),
            (nrrd(GOOD, &[0; 5]), &["5 bytes", "need 6"][..]),
            (GOOD.replace("\n\n", "\n").into_bytes(), &["no end"][..]),
        ] {
            let e = decode_nrrd(&bytes, p).unwrap_err();
            for n in needles {
                assert!(e.contains(n), "{n:?} not in {e:?}");
            }
        }
    }
}
