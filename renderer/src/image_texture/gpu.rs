//! A scene's image textures on the device: one record per image (`ImageRecord` in
//! `glsl/include/render/image.glsl`) and every level of every image in one texel buffer.

use super::{ImageError, ImageTexture, MAX_IMAGE_TEXELS};
use crate::shader_constants::IMAGE_MAX_LEVELS;
use bytemuck::{Pod, Zeroable};
use lazysolid_compute::gpu::{BufferArg, Gpu, GpuBuffer, GpuResult};

/// Most MIP levels of one image (from [`IMAGE_MAX_LEVELS`]).
pub const MAX_IMAGE_LEVELS: usize = IMAGE_MAX_LEVELS as usize;

/// One image as the kernels read it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuImageRecord {
    /// Level 0 width.
    pub width: u32,
    /// Level 0 height.
    pub height: u32,
    /// Number of levels.
    pub levels: u32,
    /// `IMAGE_ENCODING_*`.
    pub encoding: u32,
    /// First texel of each level in the texel buffer.
    pub level_offset: [u32; MAX_IMAGE_LEVELS],
    /// Keeps the record a multiple of 16 bytes.
    pub pad: [u32; 2],
}

const _: () = assert!(size_of::<GpuImageRecord>() == 80);

/// The images of a scene, gathered on the CPU and uploaded once.
#[derive(Default)]
pub struct ImageSet {
    records: Vec<GpuImageRecord>,
    texels: Vec<u32>,
}

impl ImageSet {
    /// Adds `image`; returns its record index (what a material stores).
    ///
    /// # Errors
    /// [`ImageError::Total`] when the scene's texels would exceed one device buffer.
    pub fn add(&mut self, image: &ImageTexture) -> Result<u32, ImageError> {
        let total = self.texels.len() as u64 + image.texel_count();
        if total > MAX_IMAGE_TEXELS {
            return Err(ImageError::Total {
                texels: total,
                max: MAX_IMAGE_TEXELS,
            });
        }
        assert!(
            image.levels.len() <= MAX_IMAGE_LEVELS,
            "{}: {} levels",
            image.name,
            image.levels.len()
        );
        let mut record = GpuImageRecord {
            width: image.width,
            height: image.height,
            levels: image.levels.len() as u32,
            encoding: image.encoding.code(),
            ..Default::default()
        };
        for (l, level) in image.levels.iter().enumerate() {
            record.level_offset[l] = self.texels.len() as u32;
            self.texels.extend_from_slice(level);
        }
        self.records.push(record);
        Ok(self.records.len() as u32 - 1)
    }

    /// Number of images.
    pub fn len(&self) -> usize {
        self.records.len()
    }

    /// True without images.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }

    /// Uploads the records and texels (one placeholder each when empty: a binding needs a
    /// buffer).
    ///
    /// # Errors
    /// Allocation and upload errors.
    pub fn upload(&self, gpu: &Gpu) -> GpuResult<DeviceImages> {
        let records = if self.records.is_empty() {
            vec![GpuImageRecord::default()]
        } else {
            self.records.clone()
        };
        let texels = if self.texels.is_empty() {
            vec![0]
        } else {
            self.texels.clone()
        };
        Ok(DeviceImages {
            records: GpuBuffer::from_slice(gpu, "image records", &records)?,
            texels: GpuBuffer::from_slice(gpu, "image texels", &texels)?,
        })
    }
}

/// The uploaded images: one owner of both buffers.
pub struct DeviceImages {
    records: GpuBuffer<GpuImageRecord>,
    texels: GpuBuffer<u32>,
}

impl DeviceImages {
    /// The bindings of `render/image.glsl`, by block name.
    pub fn bindings(&self) -> [(&'static str, BufferArg<'_>); 2] {
        [
            ("ImageRecords", self.records.arg()),
            ("ImageTexels", self.texels.arg()),
        ]
    }

    /// Exact GPU bytes.
    pub fn bytes(&self) -> u64 {
        self.records.bytes() + self.texels.bytes()
    }
}
