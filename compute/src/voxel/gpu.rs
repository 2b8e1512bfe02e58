//! The GPU surface voxelizer. Work is bounded per column, not per bounding box: each triangle
//! is walked in columns along its dominant normal axis (one invocation per column, found by a
//! binary search over the scanned column counts), and a column holds at most 7 candidate cells
//! whatever the triangle's size. A triangle thus costs its projected area in cells, never its
//! bounding volume. Steps: count columns per triangle, scan, count overlapping cells per
//! column, scan, write their Morton keys, radix sort, unique.

use super::error::VoxelError;
use super::grid::VoxelGrid;
use super::keys::{SortUnique, VoxelKeys};
use super::surface_cpu::check_triangles;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use crate::kernels::voxel;
use crate::prims::{Scan, MAX_ELEMENTS};
use glam::Vec3;
use std::sync::Arc;

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ColumnsPush<'a> {
        positions: DeviceAddress<'a>,
        triangles: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        total: DeviceAddress<'a>,
        n_triangles: u32,
        extent: u32,
        r: f32,
        shift: f32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct HitsPush<'a> {
        positions: DeviceAddress<'a>,
        triangles: DeviceAddress<'a>,
        column_offsets: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        total: DeviceAddress<'a>,
        n_triangles: u32,
        n_columns: u32,
        extent: u32,
        r: f32,
        shift: f32,
        center_offset: f32,
        half_size: f32,
        write: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct DilatePush<'a> {
        cells: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        n: u32,
        resolution: u32,
    }
}

/// The GPU voxelizer; keeps its kernels and scratch between meshes.
pub struct Voxelizer {
    gpu: Gpu,
    columns: Arc<Kernel>,
    hits: Arc<Kernel>,
    dilate: Arc<Kernel>,
    scan: Scan,
    unique: SortUnique,
}

impl Voxelizer {
    /// Builds the kernels.
    pub fn new(gpu: &Gpu) -> Result<Voxelizer, VoxelError> {
        Ok(Voxelizer {
            gpu: gpu.clone(),
            columns: gpu.kernel(&voxel::COLUMNS)?,
            hits: gpu.kernel(&voxel::HITS)?,
            dilate: gpu.kernel(&voxel::DILATE)?,
            scan: Scan::new(gpu)?,
            unique: SortUnique::new(gpu)?,
        })
    }

    /// The sort + unique step, for builders that derive key sets from voxel keys.
    pub fn sort_unique(&mut self) -> &mut SortUnique {
        &mut self.unique
    }

    /// The voxels of the `resolution`³ grid that the triangles touch: exactly
    /// [`surface_voxels_cpu`](super::surface_voxels_cpu).
    ///
    /// # Errors
    /// A resolution outside 1..=[`MAX_RESOLUTION`](super::MAX_RESOLUTION), a bad vertex index,
    /// more columns or hits than the primitives count, or a device failure.
    pub fn surface(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        resolution: u32,
    ) -> Result<VoxelKeys, VoxelError> {
        self.cells(positions, triangles, VoxelGrid::voxels(resolution)?)
    }

    /// The voxels trilinear filtering reads on the surface: exactly
    /// [`interpolation_voxels_cpu`](super::interpolation_voxels_cpu).
    ///
    /// # Errors
    /// As [`Voxelizer::surface`].
    pub fn interpolation(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        resolution: u32,
    ) -> Result<VoxelKeys, VoxelError> {
        let cells = self.cells(positions, triangles, VoxelGrid::cells(resolution)?)?;
        self.dilate(&cells, resolution)
    }

    /// The corner voxels of interpolation cells (Morton keys of the shifted grid), clamped onto
    /// the `resolution`³ grid: exactly [`dilate_cells_cpu`](super::dilate_cells_cpu).
    ///
    /// # Errors
    /// A bad resolution, or a device failure.
    pub fn dilate(&mut self, cells: &VoxelKeys, resolution: u32) -> Result<VoxelKeys, VoxelError> {
        let grid = VoxelGrid::voxels(resolution)?;
        let n = cells.len * 8;
        self.check_count("corner voxels", n as u64, 0, resolution)?;
        let gpu = self.gpu.clone();
        let corners = GpuBuffer::<u64>::new(&gpu, "interpolation corners", n)?;
        gpu.submit(|rec| {
            let push = DilatePush {
                cells: cells.keys.address(),
                dst: corners.address(),
                n: cells.len as u32,
                resolution,
            };
            rec.dispatch(
                &self.dilate,
                self.dilate.groups_for(cells.len as u64),
                &[],
                &push,
            )
        })?;
        Ok(self
            .unique
            .run(&corners, n, grid.key_bits(), "interpolation voxels")?)
    }

    fn check_count(
        &self,
        what: &'static str,
        count: u64,
        triangles: usize,
        resolution: u32,
    ) -> Result<(), VoxelError> {
        if count > MAX_ELEMENTS as u64 {
            return Err(VoxelError::TooMany {
                what,
                count,
                limit: MAX_ELEMENTS as u64,
                triangles,
                resolution,
            });
        }
        Ok(())
    }

    /// The cells of `grid` that the triangles touch, as sorted unique Morton keys: exactly
    /// [`grid_cells_cpu`](super::grid_cells_cpu).
    ///
    /// # Errors
    /// As [`Voxelizer::surface`].
    pub fn cells(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        grid: VoxelGrid,
    ) -> Result<VoxelKeys, VoxelError> {
        check_triangles(positions, triangles)?;
        let r = grid.resolution;
        self.check_count("triangles", triangles.len() as u64, triangles.len(), r)?;
        let gpu = self.gpu.clone();
        if triangles.is_empty() {
            return Ok(VoxelKeys {
                keys: GpuBuffer::new(&gpu, "voxel keys", 0)?,
                len: 0,
            });
        }
        let flat: Vec<f32> = positions.iter().flat_map(|p| p.to_array()).collect();
        let pos = GpuBuffer::from_slice(&gpu, "voxelizer positions", &flat)?;
        let tris = GpuBuffer::from_slice(&gpu, "voxelizer triangles", triangles.as_flattened())?;
        let nt = triangles.len();
        let column_offsets = GpuBuffer::<u32>::new(&gpu, "voxelizer column offsets", nt)?;
        let total = GpuBuffer::<u64>::zeroed(&gpu, "voxelizer total", 1)?;
        let rf = r as f32;
        gpu.submit(|rec| {
            let push = ColumnsPush {
                positions: pos.address(),
                triangles: tris.address(),
                counts: column_offsets.address(),
                total: total.address(),
                n_triangles: nt as u32,
                extent: grid.extent(),
                r: rf,
                shift: grid.grid_shift(),
            };
            rec.dispatch(
                &self.columns,
                self.columns.groups_for(nt as u64),
                &[],
                &push,
            )?;
            self.scan
                .record(rec, &column_offsets, &column_offsets, nt, None)
        })?;
        let n_columns = total.read()?[0];
        self.check_count("columns", n_columns, nt, r)?;
        let counts = GpuBuffer::<u32>::new(&gpu, "voxelizer column hits", n_columns as usize)?;
        let mut push = HitsPush {
            positions: pos.address(),
            triangles: tris.address(),
            column_offsets: column_offsets.address(),
            counts: counts.address(),
            keys: DeviceAddress::NULL,
            total: total.address(),
            n_triangles: nt as u32,
            n_columns: n_columns as u32,
            extent: grid.extent(),
            r: rf,
            shift: grid.grid_shift(),
            center_offset: grid.center_offset(),
            half_size: 0.5 / rf,
            write: 0,
        };
        let groups = self.hits.groups_for(n_columns);
        gpu.submit(|rec| {
            rec.fill(&total, 0);
            rec.dispatch(&self.hits, groups, &[], &push)?;
            self.scan
                .record(rec, &counts, &counts, n_columns as usize, None)
        })?;
        let n_hits = total.read()?[0];
        self.check_count("voxel hits", n_hits, nt, r)?;
        let keys = GpuBuffer::<u64>::new(&gpu, "voxelizer hits", n_hits as usize)?;
        push.keys = keys.address();
        push.write = 1;
        gpu.submit(|rec| rec.dispatch(&self.hits, groups, &[], &push))?;
        Ok(self
            .unique
            .run(&keys, n_hits as usize, grid.key_bits(), "voxel keys")?)
    }
}
