//! Plain open addressing on the GPU (first come, first served): the age every key ends at,
//! for the histograms that show what Robin Hood buys (thesis Fig. 4.16). The ages depend on the
//! order in which invocations win their slots, so only their distribution is meaningful.

use super::kernels::HashKernels;
use super::probe::Probe;
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult};
use crate::kernels::hash;

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct AgesPush<'a> {
        cells: DeviceAddress<'a>,
        fastmod_m: u64,
        keys: DeviceAddress<'a>,
        ages: DeviceAddress<'a>,
        n: u32,
        table_size: u32,
        probe: u32,
        max_age: u32,
    }
}

/// Inserts `keys` into `table_size` empty cells without Robin Hood and returns each key's age
/// (0 when it found no slot within `max_age` probes).
pub fn plain_open_addressing_ages(
    kernels: &HashKernels,
    keys: &[u64],
    table_size: u32,
    probe: Probe,
    max_age: u32,
) -> GpuResult<Vec<u32>> {
    let gpu = &kernels.gpu;
    let kernel = kernels.kernel(&hash::OPEN_ADDRESSING_AGES)?;
    let k = GpuBuffer::from_slice(gpu, "open addressing keys", keys)?;
    let cells = GpuBuffer::<u64>::zeroed(gpu, "open addressing cells", table_size as usize)?;
    let ages = GpuBuffer::<u32>::new(gpu, "open addressing ages", keys.len())?;
    let push = AgesPush {
        cells: cells.address(),
        fastmod_m: super::probe::fastmod_multiplier(table_size),
        keys: k.address(),
        ages: ages.address(),
        n: keys.len() as u32,
        table_size,
        probe: probe.id(),
        max_age,
    };
    gpu.submit(|rec| rec.dispatch(&kernel, kernel.groups_for(keys.len() as u64), &[], &push))?;
    ages.read()
}
