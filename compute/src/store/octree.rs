//! The N³-tree texture store (Lefebvre, Hornus and Neyret, "Octree textures on the GPU", 2005):
//! a node pool of RGBA8 words where each node holds its average colour and N³ cells tagged by
//! their alpha byte (empty, child pointer, or leaf colour stored in place — the autumnal tree),
//! N chosen per level so that products such as 8·8·4·4 reach R exactly (Dachsbacher and
//! Lefebvre 2008). Built level by level on the GPU with sort + unique, scan and binary
//! searches; a full pool is reallocated at double size (reported) and, pointers being
//! absolute addresses, copied as is. Layout: `glsl/include/store/octree.glsl`.

use super::colours::{new_colours, ColourSource};
use super::error::StoreError;
use super::kernels::{timed_lookup, LookupMode, StoreKernels, TimedLookup};
use super::keys::check_keys;
use super::{Filter, InsertUnit, SparseStore, StoreReport};
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult, Recorder};
use crate::hash::morton_decode;
use crate::kernels::store;
use crate::prims::{RadixSort, ReduceOp, Scan};
use crate::voxel::{VoxelGrid, VoxelKeys};
use glam::{Vec3, Vec4};
use std::sync::Arc;

/// Most levels of a tree (2048 = 2^11 with N = 2 everywhere).
pub const MAX_OCTREE_LEVELS: usize = 11;
/// Largest N of a level (a node of 64³ cells is 1 MiB).
pub const MAX_OCTREE_N: u32 = 64;
/// Addresses are 24 bits in units of 8 words (the thesis' 2^24 limit).
const MAX_ADDRESS: u64 = 1 << 24;

const NAME: &str = "octree";

/// The shape of a tree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OctreeConfig {
    /// N of each level, root first; their product is R.
    pub levels: Vec<u32>,
    /// Words the pool starts with (it doubles when full).
    pub initial_pool_words: usize,
}

impl OctreeConfig {
    /// Levels of N = 8 first, then 4 and 2, then any remaining prime factors of `resolution`
    /// (e.g. 1024 = 8·8·4·4, 256 = 8·8·4, 100 = 5·5·4).
    pub fn for_resolution(resolution: u32) -> Result<OctreeConfig, StoreError> {
        let mut rest = resolution.max(1);
        let mut levels = Vec::new();
        // Powers of two: as many 8s as possible, then a 4 or a 2 (or two 4s for a 16 rest).
        let mut twos = rest.trailing_zeros();
        rest >>= twos;
        while twos >= 3 && twos != 4 {
            levels.push(8);
            twos -= 3;
        }
        match twos {
            4 => levels.extend([4, 4]),
            2 => levels.push(4),
            1 => levels.push(2),
            _ => {}
        }
        let mut p = 3;
        while rest > 1 {
            while rest % p == 0 {
                levels.push(p);
                rest /= p;
            }
            p += 2;
        }
        levels.sort_by(|a, b| b.cmp(a));
        let config = OctreeConfig {
            levels,
            initial_pool_words: 1 << 16,
        };
        config.check(resolution)?;
        Ok(config)
    }

    /// Checks the levels against `resolution` and the limits.
    pub fn check(&self, resolution: u32) -> Result<(), StoreError> {
        let problem = if self.levels.is_empty() || self.levels.len() > MAX_OCTREE_LEVELS {
            Some(format!(
                "{} levels given; a tree has 1..={MAX_OCTREE_LEVELS}",
                self.levels.len()
            ))
        } else if let Some(n) = self
            .levels
            .iter()
            .find(|&&n| !(2..=MAX_OCTREE_N).contains(&n))
        {
            Some(format!("level size N = {n} is outside 2..={MAX_OCTREE_N}"))
        } else if self.levels.iter().map(|&n| n as u64).product::<u64>() != resolution as u64 {
            Some(format!(
                "the level sizes {:?} multiply to {}, not the resolution {resolution}",
                self.levels,
                self.levels.iter().map(|&n| n as u64).product::<u64>()
            ))
        } else {
            None
        };
        match problem {
            Some(problem) => Err(StoreError::Config {
                store: NAME,
                problem,
            }),
            None => Ok(()),
        }
    }

    /// Addresses (8 words) a node of level size `n` takes: its average and n³ cells.
    pub fn stride_of(n: u32) -> u32 {
        (n * n * n + 1).div_ceil(8)
    }

    /// Addresses a node of `level` takes.
    pub fn stride(&self, level: usize) -> u32 {
        Self::stride_of(self.levels[level])
    }

    /// Voxels per cell of each level.
    pub fn spans(&self) -> Vec<u32> {
        (0..self.levels.len())
            .map(|l| self.levels[l + 1..].iter().product())
            .collect()
    }
}

crate::push_block! {
    /// What `store/octree.glsl` receives: the `OctreeParams` struct, field for field.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct OctreeParams<'a> {
        /// Device address of the node pool.
        pub pool: DeviceAddress<'a>,
        /// R.
        pub resolution: u32,
        /// Levels in use.
        pub levels: u32,
        /// N of each level (unused entries 0).
        pub n: [u32; MAX_OCTREE_LEVELS],
        /// Voxels per cell of each level.
        pub span: [u32; MAX_OCTREE_LEVELS],
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LookupPush<'a> {
        store: OctreeParams<'a>,
        points: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        mode: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy, Default)]
    pub(crate) struct BuildPush<'a> {
        src: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        aux: DeviceAddress<'a>,
        dst_addrs: DeviceAddress<'a>,
        search_keys: DeviceAddress<'a>,
        search_addrs: DeviceAddress<'a>,
        pool: DeviceAddress<'a>,
        counter: DeviceAddress<'a>,
        n: u32,
        search_count: u32,
        span: u32,
        mode: u32,
        base: u32,
        stride: u32,
        root_parent: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct AveragePush<'a> {
        pool: DeviceAddress<'a>,
        addrs: DeviceAddress<'a>,
        n: u32,
        cells_per_axis: u32,
        root: u32,
    }
}

/// The sorted node keys of one level below the root, with their addresses.
struct Level {
    keys: GpuBuffer<u64>,
    addrs: GpuBuffer<u32>,
    count: usize,
}

/// The N³-tree texture store.
pub struct OctreeStore {
    kernels: Arc<StoreKernels>,
    config: OctreeConfig,
    spans: Vec<u32>,
    pool: GpuBuffer<u32>,
    top: u32,
    levels: Vec<Level>,
    len: u64,
    resolution: u32,
    /// Scratch of the new-node scan and of the level sort, kept between levels and inserts.
    scan: Scan,
    /// Boxed: its scratch buffers would make every store value large.
    sort: Box<RadixSort>,
}

impl OctreeStore {
    /// Builds the tree over `keys` of the `resolution`³ grid.
    ///
    /// # Errors
    /// A configuration that does not fit `resolution`, keys outside the grid, colours whose
    /// alpha is 0 or 1 (the tags), a tree over the 2^24-address limit, device errors.
    pub fn build(
        kernels: &Arc<StoreKernels>,
        resolution: u32,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
        config: OctreeConfig,
    ) -> Result<(OctreeStore, StoreReport), StoreError> {
        config.check(resolution)?;
        let gpu = kernels.gpu.clone();
        let root_words = 8 * config.stride(0) as usize;
        let pool = GpuBuffer::<u32>::zeroed(
            &gpu,
            "octree node pool",
            config.initial_pool_words.max(root_words),
        )?;
        let levels = (1..config.levels.len())
            .map(|_| {
                Ok(Level {
                    keys: GpuBuffer::new(&gpu, "octree level keys", 0)?,
                    addrs: GpuBuffer::new(&gpu, "octree level addresses", 0)?,
                    count: 0,
                })
            })
            .collect::<GpuResult<Vec<_>>>()?;
        let mut store = OctreeStore {
            kernels: kernels.clone(),
            spans: config.spans(),
            top: config.stride(0),
            config,
            pool,
            levels,
            len: 0,
            resolution,
            scan: Scan::new(&gpu)?,
            sort: Box::new(RadixSort::new(&gpu)?),
        };
        let report = store.insert(keys, colours)?;
        Ok((store, report))
    }

    /// The pool, up to its top (for comparisons with [`OctreeCpu`](super::OctreeCpu)).
    pub fn pool_words(&self) -> GpuResult<Vec<u32>> {
        self.pool.read_range(0, 8 * self.top as usize)
    }

    /// Words allocated for the pool (its capacity).
    pub fn pool_capacity(&self) -> usize {
        self.pool.len()
    }

    /// Nodes per level (the root's level first).
    pub fn node_counts(&self) -> Vec<usize> {
        std::iter::once(1)
            .chain(self.levels.iter().map(|l| l.count))
            .collect()
    }

    /// The configuration.
    pub fn config(&self) -> &OctreeConfig {
        &self.config
    }

    fn key_bits(&self) -> u32 {
        VoxelGrid::voxels(self.resolution)
            .map(|g| g.key_bits())
            .unwrap_or(33)
    }

    /// Colours of `keys` in a new buffer, checked against the reserved alpha values.
    fn colours_for(
        &self,
        keys: &VoxelKeys,
        source: &ColourSource<'_>,
    ) -> Result<GpuBuffer<u32>, StoreError> {
        let gpu = &self.kernels.gpu;
        let buffer = new_colours(
            gpu,
            NAME,
            "octree new colours",
            keys,
            source,
            self.resolution,
        )?;
        if !matches!(source, ColourSource::Marble { .. }) && keys.len > 0 {
            // Alpha is the high byte, so the smallest word has the smallest alpha: one
            // reduction on the device, and only a refused colour is read back to be named.
            let least = GpuBuffer::<u32>::new(gpu, "octree least colour", 1)?;
            let mut reduce = self.kernels.hash.reduce.lock().unwrap();
            gpu.submit(|rec| reduce.record(rec, &buffer, keys.len, ReduceOp::Min, &least))?;
            drop(reduce);
            if least.read()?[0] >> 24 < 2 {
                let colours = buffer.read_range(0, keys.len)?;
                let i = colours.iter().position(|c| c >> 24 < 2).unwrap_or(0);
                let key = keys.keys.read_range(i, 1)?[0];
                return Err(StoreError::ReservedAlpha {
                    store: NAME,
                    voxel: morton_decode(key, 3),
                    rgba: colours[i],
                    alpha: colours[i] >> 24,
                    min_alpha: 2,
                });
            }
        }
        Ok(buffer)
    }

    /// A push block whose parent level is `level` (searching its keys, or the root).
    fn parent_push(&self, level: usize) -> BuildPush<'_> {
        Self::parent_push_of(&self.pool, self.config.levels[level], &self.levels, level)
    }

    /// [`Self::parent_push`] from the fields it reads, so that a caller may borrow the others
    /// mutably meanwhile.
    fn parent_push_of<'a>(
        pool: &'a GpuBuffer<u32>,
        span: u32,
        levels: &'a [Level],
        level: usize,
    ) -> BuildPush<'a> {
        let mut p = BuildPush {
            pool: pool.address(),
            span,
            root_parent: (level == 0) as u32,
            ..Default::default()
        };
        if level > 0 {
            let l = &levels[level - 1];
            p.search_keys = l.keys.address();
            p.search_addrs = l.addrs.address();
            p.search_count = l.count as u32;
        }
        p
    }

    /// Runs the leaf kernel in `mode` over `keys` with colours `aux`; returns the counters.
    fn leaves(&self, keys: &VoxelKeys, aux: &GpuBuffer<u32>, mode: u32) -> GpuResult<[u32; 2]> {
        let gpu = &self.kernels.gpu;
        let counter = GpuBuffer::<u32>::zeroed(gpu, "octree counters", 2)?;
        let last = self.config.levels.len() - 1;
        let push = BuildPush {
            src: keys.keys.address(),
            aux: aux.address(),
            counter: counter.address(),
            n: keys.len as u32,
            mode,
            ..self.parent_push(last)
        };
        let k = gpu.kernel(&store::OCTREE_LINK)?;
        gpu.submit(|rec| rec.dispatch(&k, k.groups_for(keys.len as u64), &[], &push))?;
        let c = counter.read()?;
        Ok([c[0], c[1]])
    }

    /// Adds the nodes of level `l` that `keys` need; returns a reallocation message if the
    /// pool grew.
    fn add_level(&mut self, l: usize, keys: &VoxelKeys) -> Result<Option<String>, StoreError> {
        let gpu = self.kernels.gpu.clone();
        let n = keys.len;
        let nodes_k = gpu.kernel(&store::OCTREE_NODES)?;
        // Candidate node keys: the nodes containing the voxels, sorted and unique.
        let tmp = GpuBuffer::<u64>::new(&gpu, "octree candidate nodes", n)?;
        let push = BuildPush {
            src: keys.keys.address(),
            dst: tmp.address(),
            n: n as u32,
            span: self.spans[l - 1],
            mode: 0,
            ..Default::default()
        };
        gpu.submit(|rec| rec.dispatch(&nodes_k, nodes_k.groups_for(n as u64), &[], &push))?;
        let key_bits = self.key_bits();
        let cand =
            self.kernels
                .unique
                .lock()
                .unwrap()
                .run(&tmp, n, key_bits, "octree candidate nodes")?;
        drop(tmp);
        let m = cand.len;
        // Which are new.
        let level = &self.levels[l - 1];
        let flags = GpuBuffer::<u32>::new(&gpu, "octree new-node flags", m)?;
        let total = GpuBuffer::<u32>::zeroed(&gpu, "octree new-node count", 1)?;
        let search = BuildPush {
            src: cand.keys.address(),
            aux: flags.address(),
            search_keys: level.keys.address(),
            search_count: level.count as u32,
            n: m as u32,
            mode: 1,
            ..Default::default()
        };
        gpu.submit(|rec| {
            rec.dispatch(&nodes_k, nodes_k.groups_for(m as u64), &[], &search)?;
            self.scan.record(rec, &flags, &flags, m, Some(&total))
        })?;
        let added = total.read()?[0] as usize;
        if added == 0 {
            return Ok(None);
        }
        let stride = self.config.stride(l);
        let new_top = self.top as u64 + added as u64 * stride as u64;
        if new_top > MAX_ADDRESS {
            return Err(StoreError::Capacity {
                store: NAME,
                what: "node pool addresses (units of 8 words)",
                requested: new_top,
                limit: MAX_ADDRESS,
            });
        }
        let mut message = None;
        let words = 8 * new_top as usize;
        if words > self.pool.len() {
            let capacity = words.max(2 * self.pool.len()).min(8 * MAX_ADDRESS as usize);
            let bigger = GpuBuffer::<u32>::zeroed(&gpu, "octree node pool", capacity)?;
            gpu.submit(|rec| rec.copy(&self.pool, 0, &bigger, 0, self.pool.len()))?;
            message = Some(format!(
                "node pool full: reallocated from {} to {capacity} words ({} bytes) for {words} words",
                self.pool.len(),
                bigger.bytes()
            ));
            self.pool = bigger;
        }
        // New level arrays: the old ones, then the new nodes, linked, then sorted by key.
        let old = level.count;
        let count = old + added;
        let keys_out = GpuBuffer::<u64>::new(&gpu, "octree level keys", count)?;
        let addrs_out = GpuBuffer::<u32>::new(&gpu, "octree level addresses", count)?;
        let scatter = BuildPush {
            dst: keys_out.address_at(old)?,
            dst_addrs: addrs_out.address_at(old)?,
            base: self.top,
            stride,
            mode: 2,
            ..search
        };
        let link = BuildPush {
            src: keys_out.address_at(old)?,
            aux: addrs_out.address_at(old)?,
            n: added as u32,
            mode: 0,
            ..Self::parent_push_of(&self.pool, self.config.levels[l - 1], &self.levels, l - 1)
        };
        let link_k = gpu.kernel(&store::OCTREE_LINK)?;
        let sort = &mut self.sort;
        gpu.submit(|rec: &mut Recorder<'_>| {
            rec.dispatch(&nodes_k, nodes_k.groups_for(m as u64), &[], &scatter)?;
            rec.copy(&level.keys, 0, &keys_out, 0, old)?;
            rec.copy(&level.addrs, 0, &addrs_out, 0, old)?;
            rec.dispatch(&link_k, link_k.groups_for(added as u64), &[], &link)?;
            sort.record_u64(rec, &keys_out, Some(&addrs_out), count, key_bits)
        })?;
        self.levels[l - 1] = Level {
            keys: keys_out,
            addrs: addrs_out,
            count,
        };
        self.top = new_top as u32;
        Ok(message)
    }

    /// Recomputes every node's average colour, deepest level first.
    fn average(&self) -> GpuResult<()> {
        let k = self.kernels.gpu.kernel(&store::OCTREE_AVERAGE)?;
        self.kernels.gpu.submit(|rec| {
            for l in (0..self.config.levels.len()).rev() {
                let (addrs, n) = if l == 0 {
                    (DeviceAddress::NULL, 1)
                } else {
                    let level = &self.levels[l - 1];
                    (level.addrs.address(), level.count)
                };
                let push = AveragePush {
                    pool: self.pool.address(),
                    addrs,
                    n: n as u32,
                    cells_per_axis: self.config.levels[l],
                    root: (l == 0) as u32,
                };
                rec.dispatch(&k, k.groups_for(n as u64), &[], &push)?;
            }
            Ok(())
        })
    }

    /// Replaces the colours of stored voxels in place on the GPU (a paint or re-synthesis),
    /// then recomputes the averages.
    ///
    /// # Errors
    /// A voxel that is not stored (nothing is changed then), reserved alpha values, device
    /// errors.
    pub fn update(
        &mut self,
        keys: &VoxelKeys,
        colours: &ColourSource<'_>,
    ) -> Result<(), StoreError> {
        check_keys(&self.kernels, NAME, keys, self.resolution)?;
        let buffer = self.colours_for(keys, colours)?;
        let [_, absent] = self.leaves(keys, &buffer, 3)?;
        if absent > 0 {
            return Err(StoreError::Config {
                store: NAME,
                problem: format!(
                    "update of {absent} voxel(s) that are not stored; insert them first"
                ),
            });
        }
        self.leaves(keys, &buffer, 4)?;
        Ok(self.average()?)
    }
}

impl SparseStore for OctreeStore {
    type Params<'a> = OctreeParams<'a>;

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
        let buffer = self.colours_for(keys, colours)?;
        let [present, _] = self.leaves(keys, &buffer, 1)?;
        if present > 0 {
            return Err(StoreError::AlreadyStored {
                store: NAME,
                voxel: [0, 0, 0],
                count: present as u64,
            });
        }
        let mut reallocations = Vec::new();
        for l in 1..self.config.levels.len() {
            reallocations.extend(self.add_level(l, keys)?);
        }
        self.leaves(keys, &buffer, 2)?;
        self.average()?;
        self.len += keys.len as u64;
        Ok(StoreReport {
            texels: self.len,
            added: keys.len as u64,
            reallocations,
        })
    }

    fn bytes(&self) -> u64 {
        // The pool is what lookups read; the per-level key and address arrays are what
        // inserts search and stay allocated too.
        self.pool.bytes()
            + self
                .levels
                .iter()
                .map(|l| l.keys.bytes() + l.addrs.bytes())
                .sum::<u64>()
    }

    fn params(&self) -> OctreeParams<'_> {
        let mut p = OctreeParams {
            pool: self.pool.address(),
            resolution: self.resolution,
            levels: self.config.levels.len() as u32,
            n: [0; MAX_OCTREE_LEVELS],
            span: [0; MAX_OCTREE_LEVELS],
        };
        for (l, &n) in self.config.levels.iter().enumerate() {
            p.n[l] = n;
            p.span[l] = self.spans[l];
        }
        p
    }

    fn timed_lookup_mode(
        &self,
        points: &[Vec3],
        _normals: &[Vec3],
        mode: LookupMode,
    ) -> Result<TimedLookup<'_>, StoreError> {
        Ok(self.lookup_in_mode(points, mode, None)?)
    }
}

impl OctreeStore {
    /// MIP lookup: the average colour of the node of level `depth` containing each point.
    pub fn lookup_mip(&self, points: &[Vec3], depth: u32) -> Result<Vec<Vec4>, StoreError> {
        let lookup = self.lookup_in_mode(points, Filter::Nearest.into(), Some(depth))?;
        lookup.run()?;
        Ok(lookup.results()?)
    }

    /// The lookup kernel at `points`: by `mode`, or the MIP of level `mip` (mode 2 + depth).
    fn lookup_in_mode(
        &self,
        points: &[Vec3],
        mode: LookupMode,
        mip: Option<u32>,
    ) -> GpuResult<TimedLookup<'_>> {
        timed_lookup(
            &self.kernels,
            &store::OCTREE_LOOKUP,
            points,
            &[],
            mode,
            move |rec, c| {
                let push = LookupPush {
                    store: self.params(),
                    points: c.points,
                    results: c.results,
                    n: c.n,
                    mode: mip.map_or(c.mode, |depth| 2 + depth),
                };
                rec.dispatch(c.kernel, c.groups, &[], &push)
            },
        )
    }
}
