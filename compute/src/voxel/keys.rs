//! Sorted unique `u64` keys on the GPU: what the voxelizers return and the stores build from,
//! and the sort + unique step that produces them.

use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult};
use crate::kernels::voxel;
use crate::prims::{RadixSort, Scan};

/// Keys `keys[..len]`, sorted ascending and unique (the buffer may be longer).
pub struct VoxelKeys {
    /// The keys' buffer.
    pub keys: GpuBuffer<u64>,
    /// How many of its elements are keys.
    pub len: usize,
}

impl VoxelKeys {
    /// Uploads host keys, which must already be sorted and unique.
    ///
    /// # Errors
    /// Keys out of order or repeated (the position is named), or an allocation failure.
    pub fn from_sorted(gpu: &Gpu, name: &str, keys: &[u64]) -> GpuResult<VoxelKeys> {
        if let Some(i) = keys.windows(2).position(|w| w[0] >= w[1]) {
            return Err(GpuError::InvalidArgument(format!(
                "{name}: keys must be sorted and unique, but key {i} ({}) is followed by {}",
                keys[i],
                keys[i + 1]
            )));
        }
        Ok(VoxelKeys {
            keys: GpuBuffer::from_slice(gpu, name, keys)?,
            len: keys.len(),
        })
    }

    /// The keys, read back.
    pub fn read(&self) -> GpuResult<Vec<u64>> {
        self.keys.read_range(0, self.len)
    }

    /// Number of keys.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there is no key.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct UniquePush<'a> {
        keys: DeviceAddress<'a>,
        flags: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        n: u32,
        write: u32,
    }
}

/// Sort + unique of `u64` keys with the radix sort and the scan.
pub struct SortUnique {
    gpu: Gpu,
    scan: Scan,
    sort: RadixSort,
}

impl SortUnique {
    /// The step for `gpu`, without scratch yet; its kernels come from the device's kernel cache
    /// when it runs.
    pub fn new(gpu: &Gpu) -> GpuResult<SortUnique> {
        Ok(SortUnique {
            gpu: gpu.clone(),
            scan: Scan::new(gpu)?,
            sort: RadixSort::new(gpu)?,
        })
    }

    /// Sorts `keys[..n]` in place by their low `key_bits` bits (higher bits must be zero) and
    /// returns the distinct keys in a new buffer.
    pub fn run(
        &mut self,
        keys: &GpuBuffer<u64>,
        n: usize,
        key_bits: u32,
        name: &str,
    ) -> GpuResult<VoxelKeys> {
        let gpu = self.gpu.clone();
        let unique = gpu.kernel(&voxel::UNIQUE)?;
        let flags = GpuBuffer::<u32>::new(&gpu, format!("{name}: run heads"), n)?;
        let total = GpuBuffer::<u32>::zeroed(&gpu, format!("{name}: distinct count"), 1)?;
        gpu.submit(|rec| {
            self.sort.record_u64(rec, keys, None, n, key_bits)?;
            let push = UniquePush {
                keys: keys.address(),
                flags: flags.address(),
                dst: DeviceAddress::NULL,
                n: n as u32,
                write: 0,
            };
            rec.dispatch(&unique, unique.groups_for(n as u64), &[], &push)?;
            self.scan.record(rec, &flags, &flags, n, Some(&total))
        })?;
        let len = total.read()?[0] as usize;
        let dst = GpuBuffer::<u64>::new(&gpu, name, len)?;
        gpu.submit(|rec| {
            let push = UniquePush {
                keys: keys.address(),
                flags: flags.address(),
                dst: dst.address(),
                n: n as u32,
                write: 1,
            };
            rec.dispatch(&unique, unique.groups_for(n as u64), &[], &push)
        })?;
        Ok(VoxelKeys { keys: dst, len })
    }
}
