//! Union and difference of sorted voxel key sets on the device: what a store that grows by new
//! surfaces needs (the voxels it lacks, the voxels it then holds) without reading its keys back.
//! Both lists are merged as tagged keys (`k << 1 | 0` for `a`, `| 1` for `b`), sorted, flagged
//! and compacted (`glsl/voxel/key_sets.comp`); [`union_cpu`] and [`difference_cpu`] are the
//! references.

use super::keys::VoxelKeys;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult};
use crate::kernels::voxel;
use crate::prims::{RadixSort, Scan};
use crate::shader_constants::{KEY_SET_DIFFERENCE, KEY_SET_UNION};

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct KeySetPush<'a> {
        a: DeviceAddress<'a>,
        b: DeviceAddress<'a>,
        tagged: DeviceAddress<'a>,
        flags: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        na: u32,
        nb: u32,
        phase: u32,
        op: u32,
    }
}

/// Set operations on sorted, distinct `u64` keys, with their scan and sort scratch.
pub struct KeySets {
    gpu: Gpu,
    scan: Scan,
    sort: RadixSort,
}

impl KeySets {
    /// The operations for `gpu`; the kernel comes from the device's kernel cache at first use.
    pub fn new(gpu: &Gpu) -> GpuResult<KeySets> {
        Ok(KeySets {
            gpu: gpu.clone(),
            scan: Scan::new(gpu)?,
            sort: RadixSort::new(gpu)?,
        })
    }

    /// `a ∪ b`, sorted; keys have at most `key_bits` significant bits (at most 63).
    ///
    /// # Errors
    /// `key_bits` above 63, or a device failure.
    pub fn union(&mut self, a: &VoxelKeys, b: &VoxelKeys, key_bits: u32) -> GpuResult<VoxelKeys> {
        self.run(a, b, key_bits, KEY_SET_UNION, "key union")
    }

    /// The keys of `a` that `b` lacks, sorted; keys as for [`KeySets::union`].
    ///
    /// # Errors
    /// As [`KeySets::union`].
    pub fn difference(
        &mut self,
        a: &VoxelKeys,
        b: &VoxelKeys,
        key_bits: u32,
    ) -> GpuResult<VoxelKeys> {
        self.run(a, b, key_bits, KEY_SET_DIFFERENCE, "key difference")
    }

    fn run(
        &mut self,
        a: &VoxelKeys,
        b: &VoxelKeys,
        key_bits: u32,
        op: u32,
        name: &str,
    ) -> GpuResult<VoxelKeys> {
        if key_bits > 63 {
            return Err(GpuError::InvalidArgument(format!(
                "{name}: keys of {key_bits} bits leave no bit for the set tag (at most 63)"
            )));
        }
        let gpu = self.gpu.clone();
        let n = a.len + b.len;
        if n == 0 {
            let keys = GpuBuffer::<u64>::new(&gpu, name, 1)?;
            return Ok(VoxelKeys { keys, len: 0 });
        }
        let kernel = gpu.kernel(&voxel::KEY_SETS)?;
        let groups = kernel.groups_for(n as u64);
        let tagged = GpuBuffer::<u64>::new(&gpu, format!("{name}: tagged keys"), n)?;
        let flags = GpuBuffer::<u32>::new(&gpu, format!("{name}: kept"), n)?;
        let total = GpuBuffer::<u32>::zeroed(&gpu, format!("{name}: count"), 1)?;
        fn push<'p>(
            (a, b, tagged, flags): (
                &'p VoxelKeys,
                &'p VoxelKeys,
                &'p GpuBuffer<u64>,
                &'p GpuBuffer<u32>,
            ),
            dst: DeviceAddress<'p>,
            phase: u32,
            op: u32,
        ) -> KeySetPush<'p> {
            KeySetPush {
                a: a.keys.address(),
                b: b.keys.address(),
                tagged: tagged.address(),
                flags: flags.address(),
                dst,
                na: a.len as u32,
                nb: b.len as u32,
                phase,
                op,
            }
        }
        let bufs = (a, b, &tagged, &flags);
        gpu.submit(|rec| {
            rec.dispatch(
                &kernel,
                groups,
                &[],
                &push(bufs, DeviceAddress::NULL, 0, op),
            )?;
            self.sort.record_u64(rec, &tagged, None, n, key_bits + 1)?;
            rec.dispatch(
                &kernel,
                groups,
                &[],
                &push(bufs, DeviceAddress::NULL, 1, op),
            )?;
            self.scan.record(rec, &flags, &flags, n, Some(&total))
        })?;
        let len = total.read()?[0] as usize;
        let dst = GpuBuffer::<u64>::new(&gpu, name, len.max(1))?;
        gpu.submit(|rec| rec.dispatch(&kernel, groups, &[], &push(bufs, dst.address(), 2, op)))?;
        Ok(VoxelKeys { keys: dst, len })
    }
}

/// The sorted union of two sorted, distinct key lists: the reference of [`KeySets::union`].
pub fn union_cpu(a: &[u64], b: &[u64]) -> Vec<u64> {
    let mut all: Vec<u64> = a.iter().chain(b).copied().collect();
    all.sort_unstable();
    all.dedup();
    all
}

/// The keys of sorted `a` that sorted `b` lacks: the reference of [`KeySets::difference`].
pub fn difference_cpu(a: &[u64], b: &[u64]) -> Vec<u64> {
    a.iter()
        .copied()
        .filter(|k| b.binary_search(k).is_err())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_of_union_and_difference() {
        assert_eq!(union_cpu(&[1, 4, 9], &[2, 4, 10]), [1, 2, 4, 9, 10]);
        assert_eq!(difference_cpu(&[1, 2, 4, 10], &[2, 4, 9]), [1, 10]);
        assert!(difference_cpu(&[], &[1]).is_empty());
        assert_eq!(union_cpu(&[], &[3]), [3]);
    }
}
