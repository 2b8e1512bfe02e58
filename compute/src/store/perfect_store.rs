//! The perfect-hash store (Lefebvre and Hoppe 2006, thesis §4.2.2): a perfect spatial hash of
//! the voxels' grid points, built where it is faster on the device (`PerfectConstruction`),
//! whose payload is the texel's RGBA8 colour itself — two reads per texel and about 4 bits of
//! offset table per texel beside the colours. Two layouts, as in thesis Table 4.1:
//!
//! - texel layout ([`PerfectStore::build`]): one texel per key; nearest = one lookup, trilinear = 8 lookups
//!   over the interpolation voxels;
//! - blocked layout ([`PerfectStore::build_blocked`]): keys are blocks of b×b×b interpolation cells holding (b+1)³
//!   texels with duplicated borders, so one offset read and one block serve a trilinear lookup
//!   (built from the interpolation *cells*).
//!
//! The hash is static: inserting further voxels (or cells) rebuilds it over all of them,
//! reported in the [`StoreReport`]. The stored keys (and, for the blocked layout, the blocks)
//! are kept on the host for that rebuild; device memory stays the hash's.

use super::colours::{new_colours, ColourSource, HostColours};
use super::error::StoreError;
use super::kernels::{timed_lookup, LookupMode, StoreKernels, TimedLookup};
use super::keys::check_keys;
use super::{InsertUnit, SparseStore, StoreReport};
use crate::gpu::{DeviceAddress, GpuBuffer};
use crate::hash::perfect::{
    BlockedPerfectHash, PerfectAccess, PerfectConfig, PerfectConstruction, PerfectHashGpu,
    PerfectParams,
};
use crate::hash::{morton_decode, HashError, KeyLayout, Universe};
use crate::kernels::store;
use crate::voxel::VoxelKeys;
use glam::Vec3;
use std::collections::HashMap;
use std::sync::Arc;

crate::push_block! {
    /// What `store/perfect.glsl` receives: the `PerfectStoreParams` struct, field for field.
    #[derive(Clone, Copy, Debug, Default)]
    pub struct PerfectStoreParams<'a> {
        /// The hash table.
        pub table: PerfectParams<'a>,
        /// R.
        pub resolution: u32,
        /// b of the blocked layout, 0 for the texel layout.
        pub block: u32,
        /// 1 when absent voxels are detected (tags stored).
        pub unconstrained: u32,
        /// Padding.
        pub pad: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LookupPush<'a> {
        store: PerfectStoreParams<'a>,
        points: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        mode: u32,
    }
}

/// The perfect-hash store.
pub struct PerfectStore {
    kernels: Arc<StoreKernels>,
    table: PerfectHashGpu,
    access: PerfectAccess,
    /// Where the texel layout is built, and rebuilt on insert.
    construction: PerfectConstruction,
    block: u32,
    resolution: u32,
    /// Host copies of the keys and colours (texel layout) or of the cells (blocked layout), for
    /// rebuilds on insert.
    keys: Vec<u64>,
    colours: Vec<u32>,
    /// The blocked layout's host table (its blocks hold the texels a rebuild keeps).
    blocked: Option<BlockedPerfectHash>,
    len: u64,
}

const NAME: &str = "perfect";

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

fn duplicate(e: HashError) -> StoreError {
    match e {
        HashError::DuplicateKey { key, count } => StoreError::AlreadyStored {
            store: NAME,
            voxel: morton_decode(key, 3),
            count,
        },
        e => e.into(),
    }
}

impl PerfectStore {
    /// Builds the texel layout over the voxels `keys` of the `resolution`³ grid, with the
    /// construction that is faster on the device ([`PerfectConstruction::Auto`]).
    /// Unconstrained access stores a tag per slot so that unstored voxels read (0, 0, 0, 0);
    /// constrained access (the texturing case of the thesis) stores none, and reading an
    /// unstored voxel returns some stored texel.
    ///
    /// # Errors
    /// Keys outside the grid, repeated keys, with unconstrained access a colour equal to
    /// `HASH_NOT_FOUND` (opaque white, which marks absent keys), the hash's size limits and
    /// device failures.
    pub fn build(
        kernels: &Arc<StoreKernels>,
        resolution: u32,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
        access: PerfectAccess,
    ) -> Result<PerfectStore, StoreError> {
        let auto = PerfectConstruction::Auto;
        Self::build_with(kernels, resolution, keys, colours, access, auto)
    }

    /// As [`build`](Self::build), constructed where `construction` says (inserts rebuild there
    /// too).
    ///
    /// # Errors
    /// As [`build`](Self::build).
    pub fn build_with(
        kernels: &Arc<StoreKernels>,
        resolution: u32,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
        access: PerfectAccess,
        construction: PerfectConstruction,
    ) -> Result<PerfectStore, StoreError> {
        check_keys(kernels, NAME, keys, resolution)?;
        let host_keys = keys.read()?;
        let gpu = kernels.gpu.clone();
        let buffer = new_colours(
            &gpu,
            NAME,
            "perfect store colours",
            keys,
            colours,
            resolution,
        )?;
        let host_colours = buffer.read_range(0, keys.len)?;
        let mut store = PerfectStore {
            kernels: kernels.clone(),
            table: Self::hash(kernels, resolution, keys, &buffer, access, construction)?,
            access,
            construction,
            block: 0,
            resolution,
            keys: host_keys,
            colours: host_colours,
            blocked: None,
            len: keys.len as u64,
        };
        store.len = store.keys.len() as u64;
        Ok(store)
    }

    fn hash(
        kernels: &Arc<StoreKernels>,
        resolution: u32,
        keys: &VoxelKeys,
        colours: &GpuBuffer<u32>,
        access: PerfectAccess,
        construction: PerfectConstruction,
    ) -> Result<PerfectHashGpu, StoreError> {
        let config = PerfectConfig {
            access,
            ..PerfectConfig::default()
        };
        let universe = universe(resolution)?;
        construction
            .build(
                &kernels.perfect,
                universe,
                &keys.keys,
                colours,
                keys.len,
                config,
            )
            .map_err(duplicate)
    }

    /// Builds the blocked layout from the interpolation cells `cells` (Morton keys of the
    /// shifted grid, as `Voxelizer::cells(.., VoxelGrid::cells(resolution))` returns them):
    /// each key is a block of b×b×b cells holding the (b+1)³ texels they read. `block: None`
    /// tries b = 1..=4 and keeps the b of least memory. Constrained access only (only points
    /// whose footprint cell was given may be read).
    ///
    /// # Errors
    /// A block size outside 1..=4, cells outside the shifted grid, the hash's errors.
    pub fn build_blocked(
        kernels: &Arc<StoreKernels>,
        resolution: u32,
        cells: &VoxelKeys,
        colours: &ColourSource<'_>,
        block: Option<u32>,
    ) -> Result<PerfectStore, StoreError> {
        universe(resolution)?;
        check_keys(kernels, NAME, cells, resolution + 1)?;
        let host_cells = cells.read()?;
        let host = colours.to_host()?;
        let blocked = blocked_table(&host_cells, resolution, &HashMap::new(), &host, block)?;
        let table = blocked.upload(&kernels.perfect)?;
        Ok(PerfectStore {
            kernels: kernels.clone(),
            table,
            access: PerfectAccess::Constrained,
            construction: PerfectConstruction::Cpu,
            block: blocked.layout.block,
            resolution,
            keys: host_cells,
            colours: Vec::new(),
            len: blocked.table.sizes.slots() as u64 * blocked.layout.block_words() as u64,
            blocked: Some(blocked),
        })
    }

    /// The hash table (sizes, construction report).
    pub fn table(&self) -> &PerfectHashGpu {
        &self.table
    }

    /// Where the table was built: `Cpu` or `Gpu` (`Auto` resolved on the device; the blocked
    /// layout is always built on the host).
    pub fn construction(&self) -> PerfectConstruction {
        self.construction.resolve(&self.kernels.gpu)
    }

    /// b of the blocked layout, `None` for the texel layout.
    pub fn block(&self) -> Option<u32> {
        (self.block != 0).then_some(self.block)
    }

    /// The blocked layout's insert: a rebuild over the union of the cells with the same b.
    fn insert_cells(
        &mut self,
        cells: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        check_keys(&self.kernels, NAME, cells, self.resolution + 1)?;
        let new_cells = cells.read()?;
        let old = self
            .blocked
            .as_ref()
            .expect("a blocked store keeps its table");
        let mut union: Vec<u64> = self.keys.iter().chain(&new_cells).copied().collect();
        union.sort_unstable();
        if let Some(w) = union.windows(2).find(|w| w[0] == w[1]) {
            let count = union.windows(2).filter(|w| w[0] == w[1]).count() as u64;
            return Err(StoreError::AlreadyStored {
                store: NAME,
                voxel: morton_decode(w[0], 3),
                count,
            });
        }
        let kept = corner_colours(old, &self.keys);
        let host = colours.to_host()?;
        let blocked = blocked_table(&union, self.resolution, &kept, &host, Some(self.block))?;
        let table = blocked.upload(&self.kernels.perfect)?;
        let (before, after) = (*self.table.sizes(), *table.sizes());
        let message = format!(
            "blocked perfect hash (b = {}) rebuilt for {} cells: |H| {} -> {}, |Φ| {} -> {} ({} bytes)",
            self.block,
            union.len(),
            before.h,
            after.h,
            before.phi,
            after.phi,
            table.bytes()
        );
        self.len = blocked.table.sizes.slots() as u64 * blocked.layout.block_words() as u64;
        self.table = table;
        self.keys = union;
        self.blocked = Some(blocked);
        Ok(StoreReport {
            texels: self.len,
            added: new_cells.len() as u64,
            reallocations: vec![message],
        })
    }
}

/// The voxels a trilinear lookup in interpolation cell `cell` reads: its 8 corners, clamped
/// onto the grid.
fn cell_corners(cell: u64, resolution: u32) -> impl Iterator<Item = [u32; 3]> {
    let j = morton_decode(cell, 3);
    (0..8u32).map(move |o| {
        std::array::from_fn(|a| {
            (j[a] as i64 - 1 + ((o >> a) & 1) as i64).clamp(0, resolution as i64 - 1) as u32
        })
    })
}

/// The colours a blocked table holds at the corners of its `cells`.
fn corner_colours(blocked: &BlockedPerfectHash, cells: &[u64]) -> HashMap<[u32; 3], u32> {
    let layout = blocked.layout;
    let (b, side, bw) = (layout.block, layout.side(), layout.block_words() as usize);
    let mut out = HashMap::new();
    for &cell in cells {
        let j = morton_decode(cell, 3);
        let block = j.map(|c| c / b);
        let slot = blocked.table.slot(block) as usize;
        for (o, voxel) in cell_corners(cell, layout.resolution).enumerate() {
            let t: [u32; 3] = std::array::from_fn(|a| j[a] - block[a] * b + ((o >> a) & 1) as u32);
            let word = slot * bw + (t[0] + side * (t[1] + side * t[2])) as usize;
            out.insert(voxel, blocked.table.data[word]);
        }
    }
    out
}

/// A blocked table of `cells` whose texels take `kept` colours first, then `source`'s (0 for
/// block texels no cell reads and the source lacks).
///
/// # Errors
/// A corner of a cell that neither has ([`StoreError::MissingColour`]), the hash's errors.
fn blocked_table(
    cells: &[u64],
    resolution: u32,
    kept: &HashMap<[u32; 3], u32>,
    source: &HostColours<'_>,
    block: Option<u32>,
) -> Result<BlockedPerfectHash, StoreError> {
    let colour = |v: [u32; 3]| {
        kept.get(&v)
            .copied()
            .or_else(|| source.colour(v, resolution))
    };
    if let HostColours::Map(_) = source {
        let mut missing: Vec<[u32; 3]> = cells
            .iter()
            .flat_map(|&c| cell_corners(c, resolution))
            .filter(|&v| colour(v).is_none())
            .collect();
        missing.sort_unstable_by_key(|&v| crate::hash::morton_encode(v, 3));
        missing.dedup();
        if let Some(&voxel) = missing.first() {
            return Err(StoreError::MissingColour {
                store: NAME,
                voxel,
                count: missing.len() as u64,
            });
        }
    }
    Ok(BlockedPerfectHash::build(
        cells,
        resolution,
        |v| colour(v).unwrap_or(0),
        block,
    )?)
}

impl SparseStore for PerfectStore {
    type Params<'a> = PerfectStoreParams<'a>;

    fn name(&self) -> &'static str {
        NAME
    }

    fn resolution(&self) -> u32 {
        self.resolution
    }

    /// Texels stored: keys (texel layout) or slots × block texels (blocked layout, borders
    /// and empty slots included).
    fn len(&self) -> u64 {
        self.len
    }

    fn insert_unit(&self) -> InsertUnit {
        match self.block {
            0 => InsertUnit::Voxels,
            _ => InsertUnit::Cells,
        }
    }

    /// Rebuilds the hash over the stored and the new voxels (a perfect hash is static); the
    /// rebuild is reported. The blocked layout takes new interpolation *cells* (keys of the
    /// shifted grid, as it was built from) and rebuilds with the same b: texels it held keep
    /// their colours, the others come from `colours`.
    fn insert(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        if self.block != 0 {
            return self.insert_cells(keys, colours);
        }
        check_keys(&self.kernels, NAME, keys, self.resolution)?;
        let new_keys = keys.read()?;
        let gpu = self.kernels.gpu.clone();
        let fresh = new_colours(
            &gpu,
            NAME,
            "perfect store colours",
            keys,
            colours,
            self.resolution,
        )?;
        let new_colours = fresh.read_range(0, keys.len)?;
        // Merge by key so the union stays sorted, as the voxelizer's sets are.
        let mut pairs: Vec<(u64, u32)> = self
            .keys
            .iter()
            .copied()
            .zip(self.colours.iter().copied())
            .chain(new_keys.iter().copied().zip(new_colours))
            .collect();
        pairs.sort_unstable_by_key(|p| p.0);
        if let Some(w) = pairs.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(StoreError::AlreadyStored {
                store: NAME,
                voxel: morton_decode(w[0].0, 3),
                count: 1,
            });
        }
        let (all_keys, all_colours): (Vec<u64>, Vec<u32>) = pairs.into_iter().unzip();
        let key_buffer = VoxelKeys::from_sorted(&gpu, "perfect store keys", &all_keys)?;
        let colour_buffer = GpuBuffer::from_slice(&gpu, "perfect store colours", &all_colours)?;
        let before = *self.table.sizes();
        let table = Self::hash(
            &self.kernels,
            self.resolution,
            &key_buffer,
            &colour_buffer,
            self.access,
            self.construction,
        )?;
        let after = *table.sizes();
        let reallocations = vec![format!(
            "perfect hash rebuilt for {} keys: |H| {} -> {}, |Φ| {} -> {} ({} bytes)",
            all_keys.len(),
            before.h,
            after.h,
            before.phi,
            after.phi,
            table.bytes()
        )];
        self.table = table;
        self.keys = all_keys;
        self.colours = all_colours;
        self.len = self.keys.len() as u64;
        Ok(StoreReport {
            texels: self.len,
            added: keys.len as u64,
            reallocations,
        })
    }

    /// The offset table, the payload (colour) table and the tags if any.
    fn bytes(&self) -> u64 {
        self.table.bytes()
    }

    fn params(&self) -> PerfectStoreParams<'_> {
        PerfectStoreParams {
            table: self.table.params(),
            resolution: self.resolution,
            block: self.block,
            unconstrained: (self.access == PerfectAccess::Unconstrained) as u32,
            pad: 0,
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
            &store::PERFECT_LOOKUP,
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
