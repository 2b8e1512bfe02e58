//! Where texel colours come from: the procedural marble evaluated on the GPU, a function of the
//! voxel evaluated on the CPU (in parallel), or colours a kernel already computed on the device
//! (lazy synthesis), which stay there.

use super::error::StoreError;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Recorder};
use crate::hash::morton_decode;
use crate::kernels::store;
use crate::voxel::VoxelKeys;
use rayon::prelude::*;
use std::collections::HashMap;

/// The colour (RGBA8, red in the low byte) of each voxel a store is built from or extended by.
#[derive(Clone, Copy)]
pub enum ColourSource<'a> {
    /// [`marble_rgba8`](super::marble_rgba8) with this seed, filled on the GPU.
    Marble {
        /// Noise seed.
        seed: u32,
    },
    /// The colour of voxel `[x, y, z]`, evaluated on the CPU over all cores (the keys are read
    /// back, the colours uploaded).
    Fn(&'a (dyn Fn([u32; 3]) -> u32 + Sync)),
    /// Colours already on the device, as a kernel computed them: `colours[i]` is the colour of
    /// voxel `keys[i]` (keys sorted and unique). A store whose keys are these very keys copies
    /// the colours; any other set of voxels (a subset, or the TileTree's texel voxels) looks
    /// each one up by a binary search on the device. Nothing goes through the CPU; a voxel
    /// the source lacks is [`StoreError::MissingColour`].
    Buffer {
        /// The voxels, sorted and unique.
        keys: &'a VoxelKeys,
        /// Their RGBA8 colours, at least `keys.len` of them.
        colours: &'a GpuBuffer<u32>,
    },
}

impl ColourSource<'_> {
    /// A CPU evaluator of this source, for references and CPU-side builds: the marble and a
    /// function as they are, a device buffer read back into a map (`None` for a voxel it
    /// lacks).
    ///
    /// # Errors
    /// Device errors (reading a buffer source back), a buffer shorter than its keys.
    pub fn to_host(&self) -> Result<HostColours<'_>, StoreError> {
        Ok(match *self {
            ColourSource::Marble { seed } => HostColours::Marble { seed },
            ColourSource::Fn(f) => HostColours::Fn(f),
            ColourSource::Buffer { keys, colours } => {
                check_buffer("store", keys, colours)?;
                let k = keys.read()?;
                let c = colours.read_range(0, keys.len)?;
                HostColours::Map(k.into_iter().zip(c).collect())
            }
        })
    }
}

/// [`ColourSource`] evaluated on the CPU.
pub enum HostColours<'a> {
    /// The marble.
    Marble {
        /// Noise seed.
        seed: u32,
    },
    /// A function of the voxel.
    Fn(&'a (dyn Fn([u32; 3]) -> u32 + Sync)),
    /// Colours by Morton key.
    Map(HashMap<u64, u32>),
}

impl HostColours<'_> {
    /// The colour of `voxel`, `None` when a map source lacks it.
    pub fn colour(&self, voxel: [u32; 3], resolution: u32) -> Option<u32> {
        match self {
            HostColours::Marble { seed } => Some(super::marble_rgba8(voxel, resolution, *seed)),
            HostColours::Fn(f) => Some(f(voxel)),
            HostColours::Map(m) => m.get(&crate::hash::morton_encode(voxel, 3)).copied(),
        }
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct FillPush<'a> {
        keys: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        n: u32,
        resolution: u32,
        seed: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ByKeyPush<'a> {
        queries: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        colours: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        required: DeviceAddress<'a>,
        need_out: DeviceAddress<'a>,
        counters: DeviceAddress<'a>,
        n: u32,
        n_keys: u32,
        zero_missing: u32,
    }
}

fn check_buffer(
    store: &'static str,
    keys: &VoxelKeys,
    colours: &GpuBuffer<u32>,
) -> Result<(), StoreError> {
    if colours.len() < keys.len {
        return Err(StoreError::Config {
            store,
            problem: format!(
                "the colour buffer holds {} colours for {} keys; give one colour per key",
                colours.len(),
                keys.len
            ),
        });
    }
    Ok(())
}

/// A table of colours by sorted key for [`ByKey`] lookups.
pub(crate) struct KeyedColours<'a> {
    pub keys: &'a GpuBuffer<u64>,
    pub colours: &'a GpuBuffer<u32>,
    pub len: usize,
}

/// One lookup of `queries[..n]` in a [`KeyedColours`] table (`colours_by_key.comp`).
pub(crate) struct ByKey<'a> {
    pub queries: &'a GpuBuffer<u64>,
    pub n: usize,
    pub table: KeyedColours<'a>,
    /// Written where found (and zeroed elsewhere with `zero_missing`).
    pub dst: Option<&'a GpuBuffer<u32>>,
    /// Per query: only those with a non-zero flag are looked up (`None`: all).
    pub required: Option<&'a GpuBuffer<u32>>,
    /// Per query: 1 where required and not found.
    pub need_out: Option<&'a GpuBuffer<u32>>,
    /// Counts (and names the smallest of) the required queries not found.
    pub counters: Option<&'a GpuBuffer<u64>>,
    pub zero_missing: bool,
}

/// The address of an optional buffer, [`DeviceAddress::NULL`] when absent.
fn address<T: bytemuck::Pod>(buffer: Option<&GpuBuffer<T>>) -> DeviceAddress<'_> {
    buffer.map_or(DeviceAddress::NULL, GpuBuffer::address)
}

impl ByKey<'_> {
    pub(crate) fn record(&self, rec: &mut Recorder<'_>, gpu: &Gpu) -> GpuResult<()> {
        if self.n == 0 {
            return Ok(());
        }
        let push = ByKeyPush {
            queries: self.queries.address(),
            keys: self.table.keys.address(),
            colours: self.table.colours.address(),
            dst: address(self.dst),
            required: address(self.required),
            need_out: address(self.need_out),
            counters: address(self.counters),
            n: self.n as u32,
            n_keys: self.table.len as u32,
            zero_missing: self.zero_missing as u32,
        };
        let k = gpu.kernel(&store::COLOURS_BY_KEY)?;
        rec.dispatch(&k, k.groups_for(self.n as u64), &[], &push)
    }
}

/// Counters of required queries that a [`ByKey`] lookup did not find.
pub(crate) fn missing_counters(gpu: &Gpu) -> GpuResult<GpuBuffer<u64>> {
    GpuBuffer::from_slice(gpu, "missing colour counters", &[0, u64::MAX])
}

/// [`StoreError::MissingColour`] when `counters` counted a missing voxel.
pub(crate) fn missing_error(
    store: &'static str,
    counters: &GpuBuffer<u64>,
) -> Result<(), StoreError> {
    let c = counters.read()?;
    if c[0] > 0 {
        return Err(StoreError::MissingColour {
            store,
            voxel: morton_decode(c[1], 3),
            count: c[0],
        });
    }
    Ok(())
}

/// Plain-Rust reference of `colours_by_key.comp`: per required query, its colour in the sorted
/// table, else `None`.
pub fn colours_by_key_cpu(
    queries: &[u64],
    keys: &[u64],
    colours: &[u32],
    required: Option<&[u32]>,
) -> Vec<Option<u32>> {
    queries
        .iter()
        .enumerate()
        .map(|(i, q)| {
            if required.is_some_and(|r| r[i] == 0) {
                return None;
            }
            let j = keys.partition_point(|k| k < q);
            (j < keys.len() && keys[j] == *q).then(|| colours[j])
        })
        .collect()
}

/// The colours of `keys` in a new buffer named `label`, one per key (at least one element, so
/// an empty key set still has a buffer to point at).
pub(crate) fn new_colours(
    gpu: &Gpu,
    store: &'static str,
    label: &str,
    keys: &VoxelKeys,
    source: &ColourSource<'_>,
    resolution: u32,
) -> Result<GpuBuffer<u32>, StoreError> {
    let mut buffer = GpuBuffer::<u32>::new(gpu, label, keys.len.max(1))?;
    fill_colours(gpu, store, keys, source, resolution, (&mut buffer, 0), None)?;
    Ok(buffer)
}

/// Writes the colours of `keys` into `dst[offset..offset + keys.len]`. With `required`, a
/// buffer source only needs (and only writes) the keys whose flag is set; the others get 0.
pub(crate) fn fill_colours(
    gpu: &Gpu,
    store: &'static str,
    keys: &VoxelKeys,
    source: &ColourSource<'_>,
    resolution: u32,
    (dst, offset): (&mut GpuBuffer<u32>, usize),
    required: Option<&GpuBuffer<u32>>,
) -> Result<(), StoreError> {
    match *source {
        ColourSource::Marble { seed } => {
            let fill = gpu.kernel(&store::FILL_MARBLE)?;
            gpu.submit(|rec| {
                let push = FillPush {
                    keys: keys.keys.address(),
                    dst: dst.address_at(offset)?,
                    n: keys.len as u32,
                    resolution,
                    seed,
                };
                rec.dispatch(&fill, fill.groups_for(keys.len as u64), &[], &push)
            })?;
        }
        ColourSource::Fn(f) => {
            let colours: Vec<u32> = keys
                .read()?
                .into_par_iter()
                .map(|k| f(morton_decode(k, 3)))
                .collect();
            dst.write(offset, &colours)?;
        }
        ColourSource::Buffer {
            keys: source_keys,
            colours,
        } => {
            check_buffer(store, source_keys, colours)?;
            let same = source_keys.len == keys.len
                && source_keys.keys.address() == keys.keys.address()
                && required.is_none();
            if same {
                gpu.submit(|rec| rec.copy(colours, 0, dst, offset, keys.len))?;
                return Ok(());
            }
            // The lookup writes from dst's start: go through a scratch buffer at an offset.
            let dst: &GpuBuffer<u32> = dst;
            let scratch;
            let target = if offset == 0 {
                dst
            } else {
                scratch = GpuBuffer::<u32>::new(gpu, "store colours by key", keys.len)?;
                &scratch
            };
            let counters = missing_counters(gpu)?;
            gpu.submit(|rec| {
                ByKey {
                    queries: &keys.keys,
                    n: keys.len,
                    table: KeyedColours {
                        keys: &source_keys.keys,
                        colours,
                        len: source_keys.len,
                    },
                    dst: Some(target),
                    required,
                    need_out: None,
                    counters: Some(&counters),
                    zero_missing: true,
                }
                .record(rec, gpu)?;
                if offset != 0 {
                    rec.copy(target, 0, dst, offset, keys.len)?;
                }
                Ok(())
            })?;
            missing_error(store, &counters)?;
        }
    }
    Ok(())
}
