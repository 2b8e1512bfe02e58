//! The TileTree on the device: the plan's tree, leaf records and tile map in buffers, the GPU
//! fill of the tile map, the lookup harness and the tile-map image.

use super::plan::Plan;
use super::{TileTreeConfig, TileTreeHost, TileTreeStats, NAME};
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult};
use crate::kernels::store;
use crate::store::colours::{fill_colours, ByKey, KeyedColours};
use crate::store::kernels::{timed_lookup, LookupMode, StoreKernels, TimedLookup};
use crate::store::{
    ColourSource, Filter, InsertUnit, SparseStore, StoreError, StoreReport, StoreSample,
};
use crate::voxel::VoxelKeys;
use glam::{Vec3, Vec4};
use std::path::Path;
use std::sync::Arc;

crate::push_block! {
    /// What `store/tiletree.glsl` receives: the `TileTreeParams` struct, field for field.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct TileTreeParams<'a> {
        /// Device address of the node cells.
        pub nodes: DeviceAddress<'a>,
        /// Device address of the leaf records.
        pub leaves: DeviceAddress<'a>,
        /// Device address of the tile map.
        pub map: DeviceAddress<'a>,
        /// The root's entry.
        pub root: u32,
        /// R.
        pub resolution: u32,
        /// Tile map width in texels.
        pub map_width: u32,
        /// 0.
        pub pad: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy, Default)]
    pub(crate) struct FillPush<'a> {
        tiles: DeviceAddress<'a>,
        triangles: DeviceAddress<'a>,
        positions: DeviceAddress<'a>,
        indices: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        colours: DeviceAddress<'a>,
        filled_in: DeviceAddress<'a>,
        filled_out: DeviceAddress<'a>,
        map: DeviceAddress<'a>,
        n_tiles: u32,
        n_texels: u32,
        resolution: u32,
        map_width: u32,
        mode: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LookupPush<'a> {
        store: TileTreeParams<'a>,
        points: DeviceAddress<'a>,
        normals: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        mode: u32,
    }
}

/// The TileTree store. It is built from a mesh; new surface (the caps of a cut) is added by
/// [`TileTree::insert_surface`], which re-plans the tree over the whole surface and keeps the
/// colours of the voxels it held; [`TileTree::refill`] recolours every texel.
pub struct TileTree {
    kernels: Arc<StoreKernels>,
    config: TileTreeConfig,
    plan: Plan,
    nodes: GpuBuffer<u32>,
    leaves: GpuBuffer<u32>,
    map: GpuBuffer<u32>,
}

/// The per-texel buffers of one fill of a plan (step 1 done: voxels and surface hits), and
/// the tile map they fill.
struct Texels<'a> {
    tiles: GpuBuffer<u32>,
    triangles: GpuBuffer<u32>,
    positions: GpuBuffer<f32>,
    indices: GpuBuffer<u32>,
    keys: VoxelKeys,
    colours: GpuBuffer<u32>,
    hits: GpuBuffer<u32>,
    spare: GpuBuffer<u32>,
    map: &'a GpuBuffer<u32>,
    n_tiles: u32,
    resolution: u32,
    map_width: u32,
}

impl Texels<'_> {
    /// The fill kernels' push block in `mode`, reading `filled_in` and writing `filled_out`.
    fn push<'b>(
        &'b self,
        mode: u32,
        filled_in: &'b GpuBuffer<u32>,
        filled_out: &'b GpuBuffer<u32>,
    ) -> FillPush<'b> {
        FillPush {
            tiles: self.tiles.address(),
            triangles: self.triangles.address(),
            positions: self.positions.address(),
            indices: self.indices.address(),
            keys: self.keys.keys.address(),
            colours: self.colours.address(),
            filled_in: filled_in.address(),
            filled_out: filled_out.address(),
            map: self.map.address(),
            n_tiles: self.n_tiles,
            n_texels: self.keys.len as u32,
            resolution: self.resolution,
            map_width: self.map_width,
            mode,
        }
    }
}

/// The colours a tree held, by voxel: every texel that met the surface, sorted by key (texels
/// without a hit sort last under a key above the grid's).
struct Kept {
    keys: GpuBuffer<u64>,
    colours: GpuBuffer<u32>,
    len: usize,
}

impl Kept {
    fn table(&self) -> KeyedColours<'_> {
        KeyedColours {
            keys: &self.keys,
            colours: &self.colours,
            len: self.len,
        }
    }
}

impl TileTree {
    /// Builds the TileTree of a mesh (unit-cube coordinates, outward-facing triangles) at
    /// equivalent resolution `resolution` and fills it from `colours` (a
    /// [`ColourSource::Buffer`] must hold the voxel of every texel that meets the surface: the
    /// mesh's surface voxels do).
    ///
    /// # Errors
    /// A resolution that is not a power of two in 2..=2048, a bad configuration, an empty or
    /// malformed mesh (no triangle, bad index, vertex outside the unit cube, only degenerate
    /// triangles), a tile map above [`MAX_MAP_TEXELS`](super::MAX_MAP_TEXELS), a buffer source
    /// without a needed voxel, device errors.
    pub fn build(
        kernels: &Arc<StoreKernels>,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        resolution: u32,
        colours: &ColourSource<'_>,
        config: TileTreeConfig,
    ) -> Result<(TileTree, StoreReport), StoreError> {
        let plan = Plan::new(positions, triangles, resolution, config)?;
        let tree = TileTree::upload(kernels, plan, config)?;
        tree.fill(colours, None)?;
        let texels = tree.plan.stats.tile_texels;
        Ok((
            tree,
            StoreReport {
                texels,
                added: texels,
                reallocations: Vec::new(),
            },
        ))
    }

    /// The plan's tree, leaves and an empty map on the device.
    fn upload(
        kernels: &Arc<StoreKernels>,
        plan: Plan,
        config: TileTreeConfig,
    ) -> Result<TileTree, StoreError> {
        let gpu = &kernels.gpu;
        let nodes = GpuBuffer::from_slice(gpu, "tiletree nodes", &plan.nodes)?;
        let leaves = GpuBuffer::from_slice(gpu, "tiletree leaves", &plan.leaf_records)?;
        let map = GpuBuffer::<u32>::zeroed(
            gpu,
            "tiletree tile map",
            plan.stats.map_width as usize * plan.stats.map_height as usize,
        )?;
        Ok(TileTree {
            kernels: kernels.clone(),
            config,
            plan,
            nodes,
            leaves,
            map,
        })
    }

    /// Refills every texel (borders included) from `colours`: the tree and tiles stay, the
    /// GPU recomputes hits, colours, dilation and the map.
    ///
    /// # Errors
    /// A buffer source without a needed voxel, device errors.
    pub fn refill(&self, colours: &ColourSource<'_>) -> Result<(), StoreError> {
        self.fill(colours, None)
    }

    /// Adds surface: the triangles `triangles` over the vertices `positions` (unit-cube
    /// coordinates, outward-facing, their own vertex list), e.g. the caps of a cut. The tree is
    /// re-planned over the old and the new triangles (refinement, tiles and packing, reported
    /// in [`StoreReport::reallocations`]) and every texel refilled: a texel whose voxel the tree
    /// held keeps that voxel's colour, the others take `colours` (a buffer source must hold
    /// those voxels: the surface voxels of the new triangles and of old surface near them that
    /// the new tiles sample). The result equals a tree built from the whole surface with the
    /// union of the colours. On an error the tree is unchanged.
    ///
    /// # Errors
    /// As [`TileTree::build`] for the new triangles (indices into `positions`).
    pub fn insert_surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        let r = self.plan.resolution;
        let old = &self.plan.surface;
        let base = old.positions.len() as u32;
        // Grid units back to the unit cube: exact, R being a power of two.
        let mut all_positions: Vec<Vec3> = old.positions.iter().map(|&p| p / r as f32).collect();
        all_positions.extend_from_slice(positions);
        let mut all_triangles = old.triangles.clone();
        all_triangles.extend(triangles.iter().map(|t| t.map(|i| i.saturating_add(base))));
        if let Some(t) = triangles
            .iter()
            .find(|t| t.iter().any(|&i| i as usize >= positions.len()))
        {
            return Err(StoreError::Config {
                store: NAME,
                problem: format!(
                    "inserted triangle {t:?} indexes past the {} inserted vertices",
                    positions.len()
                ),
            });
        }
        let plan = Plan::new(&all_positions, &all_triangles, r, self.config)?;
        let kept = self.kept_colours()?;
        let tree = TileTree::upload(&self.kernels, plan, self.config)?;
        tree.fill(colours, Some(&kept))?;
        let (a, b) = (&self.plan.stats, &tree.plan.stats);
        let message = format!(
            "tree re-planned for {} + {} triangles: {} -> {} leaves, {} -> {} tiles, tile map {}×{} -> {}×{} ({} -> {} bytes)",
            self.plan.surface.triangles.len(),
            triangles.len(),
            a.leaves,
            b.leaves,
            a.tiles,
            b.tiles,
            a.map_width,
            a.map_height,
            b.map_width,
            b.map_height,
            self.bytes(),
            tree.bytes()
        );
        let added = b.tile_texels as i64 - a.tile_texels as i64;
        *self = tree;
        Ok(StoreReport {
            texels: self.plan.stats.tile_texels,
            added: added.max(0) as u64,
            reallocations: vec![message],
        })
    }

    /// Step 1 of a fill: the buffers, and per texel its voxel and whether it met the surface.
    fn texels<'a>(&self, map: &'a GpuBuffer<u32>) -> Result<Texels<'a>, StoreError> {
        let gpu = &self.kernels.gpu;
        let plan = &self.plan;
        let n = plan.texel_count();
        let flat: Vec<f32> = plan
            .surface
            .positions
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let t = Texels {
            tiles: GpuBuffer::from_slice(gpu, "tiletree tiles", &plan.tile_records())?,
            triangles: GpuBuffer::from_slice(gpu, "tiletree tile triangles", &plan.tile_triangles)?,
            positions: GpuBuffer::from_slice(gpu, "tiletree positions", &flat)?,
            indices: GpuBuffer::from_slice(
                gpu,
                "tiletree indices",
                plan.surface.triangles.as_flattened(),
            )?,
            keys: VoxelKeys {
                keys: GpuBuffer::new(gpu, "tiletree texel voxels", n)?,
                len: n,
            },
            colours: GpuBuffer::<u32>::new(gpu, "tiletree texel colours", n)?,
            hits: GpuBuffer::<u32>::new(gpu, "tiletree filled texels", n)?,
            spare: GpuBuffer::<u32>::new(gpu, "tiletree filled texels", n)?,
            map,
            n_tiles: plan.tiles.len() as u32,
            resolution: plan.resolution,
            map_width: plan.stats.map_width,
        };
        let push = t.push(0, &t.spare, &t.hits);
        let k = gpu.kernel(&store::TILETREE_TEXELS)?;
        gpu.submit(|rec| rec.dispatch(&k, k.groups_for(n as u64), &[], &push))?;
        Ok(t)
    }

    /// The voxel and colour of every texel that meets the surface, sorted by voxel.
    fn kept_colours(&self) -> Result<Kept, StoreError> {
        let t = self.texels(&self.map)?;
        let k = &self.kernels;
        let n = t.keys.len;
        let gather = t.push(2, &t.hits, &t.hits);
        let key_bits = 3 * self.plan.resolution.trailing_zeros() + 1;
        let mut sort = k.hash.sort.lock().unwrap();
        let s = k.gpu.kernel(&store::TILETREE_SCATTER)?;
        k.gpu.submit(|rec| {
            rec.dispatch(&s, s.groups_for(n as u64), &[], &gather)?;
            sort.record_u64(rec, &t.keys.keys, Some(&t.colours), n, key_bits)
        })?;
        drop(sort);
        Ok(Kept {
            keys: t.keys.keys,
            colours: t.colours,
            len: n,
        })
    }

    /// Fills every texel: surface hits, colours (`kept` ones first, then `colours`), dilation,
    /// the map.
    fn fill(&self, colours: &ColourSource<'_>, kept: Option<&Kept>) -> Result<(), StoreError> {
        let mut t = self.texels(&self.map)?;
        let k = &self.kernels;
        let gpu = &k.gpu;
        let n = t.keys.len;
        // Which texels the source must colour: those that meet the surface and, after an
        // insert, whose voxel the tree did not hold.
        let mut required = &t.hits;
        if let (Some(kept), ColourSource::Buffer { .. }) = (kept, colours) {
            gpu.submit(|rec| {
                ByKey {
                    queries: &t.keys.keys,
                    n,
                    table: kept.table(),
                    dst: None,
                    required: Some(&t.hits),
                    need_out: Some(&t.spare),
                    counters: None,
                    zero_missing: false,
                }
                .record(rec, gpu)
            })?;
            required = &t.spare;
        }
        // The colour source sees the texel voxels like any store's keys (not sorted: it maps
        // each key to its colour independently).
        fill_colours(
            gpu,
            NAME,
            &t.keys,
            colours,
            self.plan.resolution,
            (&mut t.colours, 0),
            Some(required),
        )?;
        if let Some(kept) = kept {
            gpu.submit(|rec| {
                ByKey {
                    queries: &t.keys.keys,
                    n,
                    table: kept.table(),
                    dst: Some(&t.colours),
                    required: Some(&t.hits),
                    need_out: None,
                    counters: None,
                    zero_missing: false,
                }
                .record(rec, gpu)
            })?;
        }
        let rows = t.push(0, &t.hits, &t.spare);
        let columns = t.push(1, &t.spare, &t.hits);
        let scatter = t.push(0, &t.spare, &t.hits);
        let dilate = gpu.kernel(&store::TILETREE_DILATE)?;
        let scatter_k = gpu.kernel(&store::TILETREE_SCATTER)?;
        let groups = dilate.groups_for(n as u64);
        gpu.submit(|rec| {
            rec.dispatch(&dilate, groups, &[], &rows)?;
            rec.dispatch(&dilate, groups, &[], &columns)?;
            rec.dispatch(&scatter_k, groups, &[], &scatter)
        })?;
        Ok(())
    }

    /// The CPU-side plan: tree, leaves, tiles and packing.
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// Counts of the tree, tiles and map.
    pub fn stats(&self) -> &TileTreeStats {
        &self.plan.stats
    }

    /// The tile map, read back (row-major RGBA8 words).
    pub fn map_words(&self) -> GpuResult<Vec<u32>> {
        self.map.read()
    }

    /// Bytes of the node cells, the leaf records and the tile map.
    pub fn bytes_by_part(&self) -> [u64; 3] {
        [self.nodes.bytes(), self.leaves.bytes(), self.map.bytes()]
    }

    /// Runs [`lookup_cpu`](super::lookup_cpu) against the read-back map.
    ///
    /// # Errors
    /// Device errors (reading the map).
    pub fn lookup_cpu(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        filter: Filter,
    ) -> Result<Vec<Vec4>, StoreError> {
        self.with_host(points, normals, |host, p, n| {
            super::lookup_cpu(host, p, n, filter)
        })
    }

    /// Runs [`sample_cpu`](super::sample_cpu) against the read-back map.
    ///
    /// # Errors
    /// Device errors (reading the map).
    pub fn sample_cpu(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
    ) -> Result<Vec<StoreSample>, StoreError> {
        self.with_host(points, normals, super::sample_cpu)
    }

    /// `read` at every point and normal against the read-back map.
    fn with_host<T>(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        read: impl Fn(&TileTreeHost<'_>, Vec3, Vec3) -> T,
    ) -> Result<Vec<T>, StoreError> {
        check_normals(points, normals)?;
        let map = self.map_words()?;
        let host = TileTreeHost {
            resolution: self.plan.resolution,
            nodes: &self.plan.nodes,
            root: self.plan.root,
            leaves: &self.plan.leaf_records,
            map: &map,
            map_width: self.plan.stats.map_width,
        };
        Ok(points
            .iter()
            .zip(normals)
            .map(|(&p, &n)| read(&host, p, n))
            .collect())
    }

    /// Writes the tile map as an RGBA PNG (texels outside tiles are transparent black). The
    /// image goes to a temporary file next to `path` first, so a failure leaves no partial
    /// file.
    ///
    /// # Errors
    /// Device errors, or the file cannot be written (the path is named).
    pub fn write_tile_map_png(&self, path: &Path) -> Result<(), StoreError> {
        let words = self.map_words()?;
        let bytes: Vec<u8> = bytemuck::cast_slice(&words).to_vec();
        let image = image::RgbaImage::from_raw(
            self.plan.stats.map_width,
            self.plan.stats.map_height,
            bytes,
        )
        .expect("the map holds width × height words");
        let io = |e: String| StoreError::Config {
            store: NAME,
            problem: format!("cannot write the tile map image {}: {e}", path.display()),
        };
        let mut png = Vec::new();
        image
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .map_err(|e| io(e.to_string()))?;
        crate::atomic_file::write_bytes_atomically(path, &png).map_err(|e| io(e.to_string()))
    }
}

fn check_normals(points: &[Vec3], normals: &[Vec3]) -> Result<(), StoreError> {
    if points.len() != normals.len() {
        return Err(StoreError::Config {
            store: NAME,
            problem: format!(
                "lookup with {} points but {} normals; give one normal per point",
                points.len(),
                normals.len()
            ),
        });
    }
    Ok(())
}

impl SparseStore for TileTree {
    type Params<'a> = TileTreeParams<'a>;

    fn name(&self) -> &'static str {
        NAME
    }

    fn resolution(&self) -> u32 {
        self.plan.resolution
    }

    /// Texels of all tiles, borders included.
    fn len(&self) -> u64 {
        self.plan.stats.tile_texels
    }

    fn insert_unit(&self) -> InsertUnit {
        InsertUnit::Surface
    }

    /// Refused: a TileTree's texels follow the mesh's surface, not a voxel set; insert the
    /// new surface's triangles with [`SparseStore::insert_surface`].
    fn insert(
        &mut self,
        _keys: &VoxelKeys,
        _colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        Err(StoreError::Unsupported {
            store: NAME,
            what: "insert of voxel keys (the tiles follow the mesh's surface: insert the new triangles with insert_surface)",
        })
    }

    fn insert_surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        TileTree::insert_surface(self, positions, triangles, colours)
    }

    fn bytes(&self) -> u64 {
        self.bytes_by_part().iter().sum()
    }

    fn params(&self) -> TileTreeParams<'_> {
        TileTreeParams {
            nodes: self.nodes.address(),
            leaves: self.leaves.address(),
            map: self.map.address(),
            root: self.plan.root,
            resolution: self.plan.resolution,
            map_width: self.plan.stats.map_width,
            pad: 0,
        }
    }

    /// Refused: the face to read depends on the surface normal; use
    /// [`SparseStore::lookup_with_normals`].
    fn lookup(&self, _points: &[Vec3], _filter: Filter) -> Result<Vec<Vec4>, StoreError> {
        Err(StoreError::Unsupported {
            store: NAME,
            what: "lookup without normals (the face is chosen from the surface normal: use lookup_with_normals)",
        })
    }

    /// `Filter::Trilinear` runs the tile's bilinear filter, `Filter::Nearest` the nearest texel.
    fn timed_lookup_mode(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        mode: LookupMode,
    ) -> Result<TimedLookup<'_>, StoreError> {
        check_normals(points, normals)?;
        Ok(timed_lookup(
            &self.kernels,
            &store::TILETREE_LOOKUP,
            points,
            normals,
            mode,
            move |rec, c| {
                let push = LookupPush {
                    store: self.params(),
                    points: c.points,
                    normals: c.normals,
                    results: c.results,
                    n: c.n,
                    mode: c.mode,
                };
                rec.dispatch(c.kernel, c.groups, &[], &push)
            },
        )?)
    }
}
