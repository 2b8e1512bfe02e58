//! Volume textures: an RGB box of voxels read from an NRRD file (what `lazysolid solid`
//! writes, and what ParaView, 3D Slicer and ImageJ export), stretched over the mesh's rest-pose
//! unit cube. A scene names one with `texture = { kind = "volume", path = "…", store = …,
//! resolution = … }`; the renderer reads it through the store only, since the kernel holds no
//! 3D image.

use crate::output::srgb_eotf;
use std::path::{Path, PathBuf};

/// Largest side of a volume texture along any axis.
pub const MAX_VOLUME_TEXTURE_SIDE: u32 = 1024;

/// An RGB volume, sRGB-encoded bytes, x fastest, then y, then z.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeTexture {
    /// The file it was read from.
    pub path: PathBuf,
    /// Voxels along x, y and z.
    pub size: [u32; 3],
    /// sRGB colour per voxel.
    pub rgb: Vec<[u8; 3]>,
}

impl VolumeTexture {
    /// Reads an NRRD volume: `type` 8-bit unsigned, `dimension: 4` with `sizes: 3 X Y Z` (an
    /// RGB triple per voxel, each side 1..=[`MAX_VOLUME_TEXTURE_SIDE`]), `encoding: raw`.
    ///
    /// # Errors
    /// The file's path, the header field and what it must be, in one line.
    pub fn load(path: &Path) -> Result<VolumeTexture, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Self::decode(&bytes, path)
    }

    /// Decodes the bytes of an NRRD file read from `path` (named in the errors).
    ///
    /// # Errors
    /// As [`VolumeTexture::load`].
    pub fn decode(bytes: &[u8], path: &Path) -> Result<VolumeTexture, String> {
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
        if let Some(s) = size
            .iter()
            .find(|&&s| !(1..=MAX_VOLUME_TEXTURE_SIDE).contains(&s))
        {
            return Err(bad(format!(
                "sizes: a side of {s} voxels is outside 1..={MAX_VOLUME_TEXTURE_SIDE}"
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
        Ok(VolumeTexture {
            path: path.to_path_buf(),
            size,
            rgb: data.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        })
    }

    /// The colour at voxel `v` of a grid of `resolution` voxels per unit: the volume voxel
    /// holding `v`'s centre, with the volume stretched over the unit cube (clamped at its
    /// faces).
    pub fn at_voxel(&self, v: [u32; 3], resolution: u32) -> [u8; 3] {
        let i: [usize; 3] = std::array::from_fn(|a| {
            let n = self.size[a] as u64;
            (((2 * v[a] as u64 + 1) * n) / (2 * resolution as u64)).min(n - 1) as usize
        });
        let (sx, sy) = (self.size[0] as usize, self.size[1] as usize);
        self.rgb[(i[2] * sy + i[1]) * sx + i[0]]
    }

    /// The mean colour in linear RGB (a flat stand-in for previews).
    pub fn mean_linear(&self) -> [f32; 3] {
        mean_linear(self.rgb.iter().copied())
    }
}

/// The mean in linear RGB of sRGB-encoded colours (a texture's flat stand-in for previews).
pub(crate) fn mean_linear(colours: impl Iterator<Item = [u8; 3]>) -> [f32; 3] {
    let (mut sum, mut n) = ([0f64; 3], 0usize);
    for c in colours {
        for (s, v) in sum.iter_mut().zip(c) {
            *s += srgb_eotf(v as f32 / 255.0) as f64;
        }
        n += 1;
    }
    sum.map(|s| (s / n.max(1) as f64) as f32)
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
        let v =
            VolumeTexture::decode(&nrrd(GOOD, &[1, 2, 3, 4, 5, 6]), Path::new("v.nrrd")).unwrap();
        assert_eq!(v.size, [2, 1, 1]);
        assert_eq!(v.rgb, vec![[1, 2, 3], [4, 5, 6]]);
        // At resolution 4 voxels 0 and 1 lie in the first half of x, 2 and 3 in the second.
        assert_eq!(v.at_voxel([1, 0, 0], 4), [1, 2, 3]);
        assert_eq!(v.at_voxel([2, 3, 3], 4), [4, 5, 6]);
        assert_eq!(v.at_voxel([9, 9, 9], 4), [4, 5, 6]);
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
            let e = VolumeTexture::decode(&bytes, p).unwrap_err();
            for n in needles {
                assert!(e.contains(n), "{n:?} not in {e:?}");
            }
        }
    }
}
