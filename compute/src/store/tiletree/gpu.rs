//! The TileTree on the device: the plan's tree, leaf records and tile map in buffers, the GPU
//! fill of the tile map, the lookup harness and the tile-map image.

use super::plan::Plan;
use super::{TileTreeConfig, TileTreeHost, TileTreeStats, NAME};
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult};
use crate::kernels::store;
use crate::store::colours::fill_colours;
use crate::store::kernels::{prepare_lookup, StoreKernels, TimedLookup};
use crate::store::{ColourSource, Filter, SparseStore, StoreError, StoreReport};
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

/// The TileTree store. The tree is static: it is built from a mesh, and its colours can be
/// refilled from another source ([`TileTree::refill`]); voxel inserts are refused.
pub struct TileTree {
    kernels: Arc<StoreKernels>,
    plan: Plan,
    nodes: GpuBuffer<u32>,
    leaves: GpuBuffer<u32>,
    map: GpuBuffer<u32>,
}

impl TileTree {
    /// Builds the TileTree of a mesh (unit-cube coordinates, outward-facing triangles) at
    /// equivalent resolution `resolution` and fills it from `colours`.
    ///
    /// # Errors
    /// A resolution that is not a power of two in 2..=2048, a bad configuration, an empty or
    /// malformed mesh (no triangle, bad index, vertex outside the unit cube, only degenerate
    /// triangles), a tile map above [`MAX_MAP_TEXELS`](super::MAX_MAP_TEXELS), device errors.
    pub fn build(
        kernels: &Arc<StoreKernels>,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        resolution: u32,
        colours: &ColourSource<'_>,
        config: TileTreeConfig,
    ) -> Result<(TileTree, StoreReport), StoreError> {
        let plan = Plan::new(positions, triangles, resolution, config)?;
        let gpu = &kernels.gpu;
        let nodes = GpuBuffer::from_slice(gpu, "tiletree nodes", &plan.nodes)?;
        let leaves = GpuBuffer::from_slice(gpu, "tiletree leaves", &plan.leaf_records)?;
        let map = GpuBuffer::<u32>::zeroed(
            gpu,
            "tiletree tile map",
            plan.stats.map_width as usize * plan.stats.map_height as usize,
        )?;
        let tree = TileTree {
            kernels: kernels.clone(),
            plan,
            nodes,
            leaves,
            map,
        };
        tree.refill(colours)?;
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

    /// Refills every texel (borders included) from `colours`: the tree and tiles stay, the
    /// GPU recomputes hits, colours, dilation and the map.
    ///
    /// # Errors
    /// Device errors.
    pub fn refill(&self, colours: &ColourSource<'_>) -> Result<(), StoreError> {
        let gpu = &self.kernels.gpu;
        let plan = &self.plan;
        let n = plan.texel_count();
        let tiles = GpuBuffer::from_slice(gpu, "tiletree tiles", &plan.tile_records())?;
        let tris = GpuBuffer::from_slice(gpu, "tiletree tile triangles", &plan.tile_triangles)?;
        let flat: Vec<f32> = plan
            .surface
            .positions
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let positions = GpuBuffer::from_slice(gpu, "tiletree positions", &flat)?;
        let indices = GpuBuffer::from_slice(
            gpu,
            "tiletree indices",
            plan.surface.triangles.as_flattened(),
        )?;
        let keys = VoxelKeys {
            keys: GpuBuffer::new(gpu, "tiletree texel voxels", n)?,
            len: n,
        };
        let mut texel_colours = GpuBuffer::<u32>::new(gpu, "tiletree texel colours", n)?;
        let filled_a = GpuBuffer::<u32>::new(gpu, "tiletree filled texels", n)?;
        let filled_b = GpuBuffer::<u32>::new(gpu, "tiletree filled texels", n)?;
        // The texel kernel writes keys only; the colours are filled in between.
        let texel_push = FillPush {
            tiles: tiles.address(),
            triangles: tris.address(),
            positions: positions.address(),
            indices: indices.address(),
            keys: keys.keys.address(),
            colours: DeviceAddress::NULL,
            filled_in: filled_b.address(),
            filled_out: filled_a.address(),
            map: self.map.address(),
            n_tiles: plan.tiles.len() as u32,
            n_texels: n as u32,
            resolution: plan.resolution,
            map_width: plan.stats.map_width,
            mode: 0,
        };
        let texels = gpu.kernel(&store::TILETREE_TEXELS)?;
        let dilate = gpu.kernel(&store::TILETREE_DILATE)?;
        let scatter = gpu.kernel(&store::TILETREE_SCATTER)?;
        let groups = texels.groups_for(n as u64);
        gpu.submit(|rec| rec.dispatch(&texels, groups, &[], &texel_push))?;
        // The colour source sees the texel voxels like any store's keys (not sorted: it maps
        // each key to its colour independently).
        fill_colours(gpu, &keys, colours, plan.resolution, &mut texel_colours, 0)?;
        let push = FillPush {
            colours: texel_colours.address(),
            ..texel_push
        };
        let rows = FillPush {
            filled_in: filled_a.address(),
            filled_out: filled_b.address(),
            mode: 0,
            ..push
        };
        let columns = FillPush {
            filled_in: filled_b.address(),
            filled_out: filled_a.address(),
            mode: 1,
            ..push
        };
        gpu.submit(|rec| {
            rec.dispatch(&dilate, groups, &[], &rows)?;
            rec.dispatch(&dilate, groups, &[], &columns)?;
            rec.dispatch(&scatter, groups, &[], &push)
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
            .map(|(&p, &n)| super::lookup_cpu(&host, p, n, filter))
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
        let tmp = path.with_extension("png.partial");
        image
            .save_with_format(&tmp, image::ImageFormat::Png)
            .map_err(|e| io(e.to_string()))?;
        std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io(e.to_string())
        })
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

    /// Refused: a TileTree's texels follow the mesh's surface, not a voxel set. Rebuild it
    /// from the mesh, or recolour it with [`TileTree::refill`].
    fn insert(
        &mut self,
        _keys: &VoxelKeys,
        _colours: &ColourSource<'_>,
    ) -> Result<StoreReport, StoreError> {
        Err(StoreError::Unsupported {
            store: NAME,
            what: "insert of voxel keys (the tiles follow the mesh's surface: rebuild from the mesh, or recolour with TileTree::refill)",
        })
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
    fn timed_lookup(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
        filter: Filter,
    ) -> Result<TimedLookup<'_>, StoreError> {
        check_normals(points, normals)?;
        let k = &self.kernels;
        let kernel = k.gpu.kernel(&store::TILETREE_LOOKUP)?;
        let groups = kernel.groups_for(points.len() as u64);
        let (n, mode) = (points.len() as u32, (filter == Filter::Trilinear) as u32);
        Ok(prepare_lookup(k, points, normals, move |rec, a| {
            let push = LookupPush {
                store: self.params(),
                points: a.points,
                normals: a.normals,
                results: a.results,
                n,
                mode,
            };
            rec.dispatch(&kernel, groups, &[], &push)
        })?)
    }
}
