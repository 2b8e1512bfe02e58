//! The coherent-hash store: a Robin Hood table with the coherent probe sequence (García et al.
//! 2011) keyed by the voxels' Morton keys, whose payload is the index of the texel's colour in
//! an RGBA8 array. (A 64-bit cell of a 2048³ Morton universe leaves 26 payload bits and
//! reserves the all-ones payload, so the colour itself does not fit; the index does.)
//! Nearest = one query; trilinear = 8 queries over the interpolation voxels.

use super::colours::{fill_colours, new_colours, ColourSource};
use super::error::StoreError;
use super::kernels::{timed_lookup, LookupMode, StoreKernels, TimedLookup};
use super::keys::check_keys;
use super::{InsertUnit, SparseStore, StoreReport};
use crate::gpu::{DeviceAddress, GpuBuffer};
use crate::hash::{
    fastmod_multiplier, morton_decode, HashError, KeyLayout, RobinHoodConfig, RobinHoodTable,
    Universe,
};
use crate::kernels::store;
use crate::voxel::VoxelKeys;
use glam::Vec3;
use std::sync::Arc;

crate::push_block! {
    /// What `store/hash.glsl` receives: the `HashStoreParams` struct, field for field.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct HashStoreParams<'a> {
        /// Device address of the table's 64-bit cells.
        pub cells: DeviceAddress<'a>,
        /// Device address of the RGBA8 colours.
        pub colours: DeviceAddress<'a>,
        /// The table size's reciprocal for the branch-free modulo.
        pub fastmod_m: u64,
        /// Cells.
        pub table_size: u32,
        /// Bits of key + 1 in a cell.
        pub key_bits: u32,
        /// Probe sequence id.
        pub probe: u32,
        /// R.
        pub resolution: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LookupPush<'a> {
        store: HashStoreParams<'a>,
        points: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        mode: u32,
    }
}

/// The coherent-hash store.
pub struct HashStore {
    kernels: Arc<StoreKernels>,
    table: RobinHoodTable,
    colours: GpuBuffer<u32>,
    len: u64,
    resolution: u32,
}

const NAME: &str = "hash";

impl HashStore {
    /// Builds the store over `keys` of the `resolution`³ grid with the table `config` (its
    /// width must be 64-bit; growth applies as for the table).
    ///
    /// # Errors
    /// Keys outside the grid, a 32-bit cell width, and the table's and device's errors.
    pub fn build(
        kernels: &Arc<StoreKernels>,
        resolution: u32,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
        config: RobinHoodConfig,
    ) -> Result<HashStore, StoreError> {
        if config.width != crate::hash::CellWidth::Bits64 {
            return Err(StoreError::Config {
                store: NAME,
                problem: "the store's GLSL lookup reads 64-bit cells; use CellWidth::Bits64".into(),
            });
        }
        let universe = universe(resolution)?;
        check_keys(kernels, NAME, keys, resolution)?;
        let gpu = kernels.gpu.clone();
        let n = keys.len;
        let buffer = new_colours(&gpu, NAME, "hash store colours", keys, colours, resolution)?;
        let indices: Vec<u32> = (0..n as u32).collect();
        let payloads = GpuBuffer::from_slice(&gpu, "hash store colour indices", &indices)?;
        let table =
            RobinHoodTable::build(&kernels.hash, universe, &keys.keys, &payloads, n, config)?;
        Ok(HashStore {
            kernels: kernels.clone(),
            table,
            colours: buffer,
            len: n as u64,
            resolution,
        })
    }

    /// The table (for its report: load factor, max age).
    pub fn table(&self) -> &RobinHoodTable {
        &self.table
    }
}

fn universe(resolution: u32) -> Result<Universe, StoreError> {
    if resolution == 0 || resolution > crate::voxel::MAX_RESOLUTION {
        return Err(StoreError::Config {
            store: NAME,
            problem: format!(
                "resolution {resolution} is outside 1..={}",
                crate::voxel::MAX_RESOLUTION
            ),
        });
    }
    Ok(Universe::new_3d([resolution; 3], KeyLayout::Morton)?)
}

impl SparseStore for HashStore {
    type Params<'a> = HashStoreParams<'a>;

    fn name(&self) -> &'static str {
        NAME
    }

    fn resolution(&self) -> u32 {
        self.resolution
    }

    fn len(&self) -> u64 {
        self.len
    }

    fn insert_unit(&self) -> InsertUnit {
        InsertUnit::Voxels
    }

    fn insert(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        check_keys(&self.kernels, NAME, keys, self.resolution)?;
        let gpu = self.kernels.gpu.clone();
        let n = keys.len;
        let old = self.len as usize;
        let mut reallocations = Vec::new();
        // Colours first, into spare capacity or a doubled array; the table is what makes them
        // visible, so a failed insert leaves the store as it was.
        let mut grown = None;
        if old + n > self.colours.len() {
            let capacity = (old + n).max(2 * self.colours.len());
            let bigger = GpuBuffer::<u32>::new(&gpu, "hash store colours", capacity)?;
            gpu.submit(|rec| rec.copy(&self.colours, 0, &bigger, 0, old))?;
            reallocations.push(format!(
                "colour array grown from {} to {capacity} texels ({} bytes) for {} texels",
                self.colours.len(),
                bigger.bytes(),
                old + n
            ));
            grown = Some(bigger);
        }
        let target = match grown.as_mut() {
            Some(bigger) => bigger,
            None => &mut self.colours,
        };
        fill_colours(
            &gpu,
            NAME,
            keys,
            colours,
            self.resolution,
            (target, old),
            None,
        )?;
        let indices: Vec<u32> = (old as u32..(old + n) as u32).collect();
        let payloads = GpuBuffer::from_slice(&gpu, "hash store colour indices", &indices)?;
        match self.table.insert(&keys.keys, &payloads, n) {
            Ok(report) => reallocations.extend(report.rebuilds.iter().cloned()),
            Err(HashError::DuplicateKey { key, count }) => {
                return Err(StoreError::AlreadyStored {
                    store: NAME,
                    voxel: morton_decode(key, 3),
                    count,
                })
            }
            Err(e) => return Err(e.into()),
        }
        if let Some(b) = grown {
            self.colours = b;
        }
        self.len += n as u64;
        Ok(StoreReport {
            texels: self.len,
            added: n as u64,
            reallocations,
        })
    }

    fn bytes(&self) -> u64 {
        self.table.bytes() + self.colours.bytes()
    }

    fn params(&self) -> HashStoreParams<'_> {
        HashStoreParams {
            cells: self.table.cells_address(),
            colours: self.colours.address(),
            fastmod_m: fastmod_multiplier(self.table.table_size()),
            table_size: self.table.table_size(),
            key_bits: self.table.format().key_bits,
            probe: self.table.config().probe.id(),
            resolution: self.resolution,
        }
    }

    fn timed_lookup_mode(
        &self,
        points: &[Vec3],
        _normals: &[Vec3],
        mode: LookupMode,
    ) -> Result<TimedLookup<'_>, StoreError> {
        Ok(timed_lookup(
            &self.kernels,
            &store::HASH_LOOKUP,
            points,
            &[],
            mode,
            move |rec, c| {
                let push = LookupPush {
                    store: self.params(),
                    points: c.points,
                    results: c.results,
                    n: c.n,
                    mode: c.mode,
                };
                rec.dispatch(c.kernel, c.groups, &[], &push)
            },
        )?)
    }
}
