//! A scene's image textures on the device: one record per image (`ImageRecord` in
//! `glsl/include/render/image.glsl`) and every level of every image in one texel buffer.

use super::{ImageError, ImageTexture, MAX_IMAGE_TEXELS};
use crate::normal_map::pyramid::VmfPyramid;
use crate::shader_constants::{IMAGE_ENCODING_CTREE, IMAGE_MAX_LEVELS, NORMAL_FILTER_VMF};
use bytemuck::{Pod, Zeroable};
use lazysolid_compute::ctree::colour::ColourTrees;
use lazysolid_compute::ctree::{CtreeParams, DeviceTree};
use lazysolid_compute::gpu::{BufferArg, DeviceRecords, Gpu, GpuBuffer, GpuResult};
use std::sync::Arc;

/// Most vMF lobes of a scene (all levels of all maps, at the scene's stride): one 128 MiB
/// storage buffer of (α, α·r) in f32.
pub const MAX_VMF_LOBES: u64 = (128 << 20) / 16;

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
    /// A normal map's `NORMAL_FILTER_*` (0 for colour images).
    pub normal_filter: u32,
    /// A vMF-filtered normal map's first lobe of each level in the lobe buffer is
    /// `vmf_level_offset[l]` of its [`GpuVmfRecord`], at this index (0 otherwise).
    pub vmf_record: u32,
    /// A tree-coded image's record in `ImageCtrees` (`IMAGE_ENCODING_CTREE`; 0 otherwise).
    pub ctree_record: u32,
}

/// Where a vMF-filtered normal map's lobes lie: every texel holds the scene's `VMF_LOBES`
/// lobes as (α, α·r) (zero weight for lobes beyond the map's own `J`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuVmfRecord {
    /// First lobe of each level in the lobe buffer.
    pub level_offset: [u32; MAX_IMAGE_LEVELS],
    /// Keeps the record a multiple of 16 bytes.
    pub pad: [u32; 2],
}

const _: () = assert!(size_of::<GpuVmfRecord>() == 64);

const _: () = assert!(size_of::<GpuImageRecord>() == 84);

/// The images of a scene, gathered on the CPU and uploaded once.
#[derive(Default)]
pub struct ImageSet {
    records: Vec<GpuImageRecord>,
    texels: Vec<u32>,
    vmf_records: Vec<GpuVmfRecord>,
    vmf_lobes: Vec<[f32; 4]>,
    vmf_stride: usize,
    ctrees: Vec<Arc<ColourTrees>>,
}

impl ImageSet {
    /// An empty set whose vMF texels hold `vmf_stride` lobes each (the scene's largest `J`).
    pub fn with_vmf_stride(vmf_stride: usize) -> ImageSet {
        ImageSet {
            vmf_stride,
            ..Default::default()
        }
    }

    /// Adds a normal map's plain MIP levels (`image`), read with `filter`
    /// (`NORMAL_FILTER_*`), and with [`NORMAL_FILTER_VMF`] its mixtures; returns its record
    /// index.
    ///
    /// # Errors
    /// As [`ImageSet::add`], and [`ImageError::Total`] when the lobes exceed one device
    /// buffer.
    ///
    /// # Panics
    /// When a vMF map comes without its pyramid, or its `J` exceeds the set's stride
    /// (caller errors).
    pub fn add_normal_map(
        &mut self,
        image: &ImageTexture,
        filter: u32,
        pyramid: Option<&VmfPyramid>,
    ) -> Result<u32, ImageError> {
        let index = self.add(image)?;
        let record = &mut self.records[index as usize];
        record.normal_filter = filter;
        if filter == NORMAL_FILTER_VMF {
            let pyramid = pyramid.expect("a vMF-filtered map comes with its pyramid");
            let j = pyramid.lobes_per_texel;
            assert!(
                j <= self.vmf_stride,
                "{j} lobes, stride {}",
                self.vmf_stride
            );
            let texels: usize = pyramid.levels.iter().map(|l| l.size * l.size).sum();
            let total = (self.vmf_lobes.len() + texels * self.vmf_stride) as u64;
            if total > MAX_VMF_LOBES {
                return Err(ImageError::Total {
                    texels: total,
                    max: MAX_VMF_LOBES,
                });
            }
            let mut vmf = GpuVmfRecord::default();
            for (l, level) in pyramid.levels.iter().enumerate() {
                vmf.level_offset[l] = self.vmf_lobes.len() as u32;
                for texel in level.lobes.chunks_exact(j) {
                    for k in 0..self.vmf_stride {
                        self.vmf_lobes.push(match texel.get(k) {
                            Some(lobe) => {
                                let (a, ar) = lobe.moments();
                                [a as f32, ar.x as f32, ar.y as f32, ar.z as f32]
                            }
                            None => [0.0; 4],
                        });
                    }
                }
            }
            record.vmf_record = self.vmf_records.len() as u32;
            self.vmf_records.push(vmf);
        }
        Ok(index)
    }

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

    /// Adds a colour image read through its compressed trees (`IMAGE_ENCODING_CTREE`) instead
    /// of texels; returns its index.
    pub fn add_ctree(&mut self, image: &ImageTexture, trees: &Arc<ColourTrees>) -> u32 {
        self.records.push(GpuImageRecord {
            width: image.width,
            height: image.height,
            levels: 1,
            encoding: IMAGE_ENCODING_CTREE,
            ctree_record: self.ctrees.len() as u32,
            ..Default::default()
        });
        self.ctrees.push(trees.clone());
        self.records.len() as u32 - 1
    }

    /// Whether an image is read through compressed trees (the kernels that read the set compile
    /// that lookup in only then: `IMAGE_CTREES_ID`).
    pub fn has_ctrees(&self) -> bool {
        !self.ctrees.is_empty()
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
        let vmf_records = if self.vmf_records.is_empty() {
            vec![GpuVmfRecord::default()]
        } else {
            self.vmf_records.clone()
        };
        let vmf_lobes = if self.vmf_lobes.is_empty() {
            vec![[0.0; 4]]
        } else {
            self.vmf_lobes.clone()
        };
        let trees = self
            .ctrees
            .iter()
            .map(|t| {
                let [y, co, cg] = &t.channels;
                Ok([
                    DeviceTree::upload(gpu, y)?,
                    DeviceTree::upload(gpu, co)?,
                    DeviceTree::upload(gpu, cg)?,
                ])
            })
            .collect::<GpuResult<Vec<_>>>()?;
        let mut ctree_records: Vec<ImageCtree> = trees
            .iter()
            .map(|[y, co, cg]| ImageCtree {
                y: y.params(),
                co: co.params(),
                cg: cg.params(),
            })
            .collect();
        if ctree_records.is_empty() {
            ctree_records.push(ImageCtree::default());
        }
        let ctree_bytes = trees.iter().flatten().map(DeviceTree::size_bytes).sum();
        Ok(DeviceImages {
            ctree_records: DeviceRecords::new(gpu, "image ctree records", &ctree_records)?,
            ctree_bytes,
            records: GpuBuffer::from_slice(gpu, "image records", &records)?,
            texels: GpuBuffer::from_slice(gpu, "image texels", &texels)?,
            vmf_records: GpuBuffer::from_slice(gpu, "vmf records", &vmf_records)?,
            vmf_lobes: GpuBuffer::from_slice(gpu, "vmf lobes", &vmf_lobes)?,
        })
    }
}

lazysolid_compute::push_block! {
    /// What `ImageCtrees` holds per tree-coded image: its three trees.
    #[derive(Clone, Copy, Default)]
    pub struct ImageCtree<'a> {
        /// Luma.
        pub y: CtreeParams<'a>,
        /// Orange chroma.
        pub co: CtreeParams<'a>,
        /// Green chroma.
        pub cg: CtreeParams<'a>,
    }
}

/// The uploaded images: one owner of both buffers.
pub struct DeviceImages {
    /// The records of the tree-coded images, holding their trees' buffers.
    ctree_records: DeviceRecords,
    ctree_bytes: u64,
    records: GpuBuffer<GpuImageRecord>,
    texels: GpuBuffer<u32>,
    vmf_records: GpuBuffer<GpuVmfRecord>,
    vmf_lobes: GpuBuffer<[f32; 4]>,
}

impl DeviceImages {
    /// The bindings of `render/image.glsl`, by block name.
    pub fn bindings(&self) -> [(&'static str, BufferArg<'_>); 3] {
        [
            ("ImageRecords", self.records.arg()),
            ("ImageTexels", self.texels.arg()),
            ("ImageCtrees", self.ctree_records.arg()),
        ]
    }

    /// The bindings of `render/vmf.glsl`, by block name.
    pub fn vmf_bindings(&self) -> [(&'static str, BufferArg<'_>); 2] {
        [
            ("VmfRecords", self.vmf_records.arg()),
            ("VmfLobes", self.vmf_lobes.arg()),
        ]
    }

    /// Exact GPU bytes.
    pub fn bytes(&self) -> u64 {
        self.records.bytes()
            + self.texels.bytes()
            + self.vmf_records.bytes()
            + self.vmf_lobes.bytes()
            + self.ctree_bytes
    }
}
