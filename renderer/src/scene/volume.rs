//! Volume textures: an RGB box of voxels read from an NRRD file (what `lazysolid solid`
//! writes, and what ParaView, 3D Slicer and ImageJ export), stretched over the mesh's rest-pose
//! unit cube. A scene names one with `texture = { kind = "volume", path = "…", store = …,
//! resolution = … }`; the renderer reads it through the store only, since the kernel holds no
//! 3D image.

use crate::output::srgb_eotf;
use lazysolid_synth::solid::{decode_nrrd, RgbVolume, MAX_VOLUME_SIDE};
use std::path::{Path, PathBuf};

/// Largest side of a volume texture along any axis: the largest box `lazysolid solid` writes.
pub const MAX_VOLUME_TEXTURE_SIDE: u32 = MAX_VOLUME_SIDE;

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
        let RgbVolume { size, rgb } = decode_nrrd(bytes, path)?;
        Ok(VolumeTexture {
            path: path.to_path_buf(),
            size,
            rgb,
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
}
