//! Holding buffers' memory for as long as something on the device may read it.

use super::buffer::BufferMemory;
use std::sync::Arc;

/// The memory of every buffer that recorded work or device records refer to. A recorder holds
/// one until its submission has completed; [`DeviceRecords`](super::DeviceRecords) hold one for
/// as long as they live. Dropping the last `GpuBuffer` of such memory only lets go of it.
#[derive(Default)]
pub struct KeepAlive {
    held: Vec<Arc<BufferMemory>>,
}

impl KeepAlive {
    pub(crate) fn hold(&mut self, memory: &Arc<BufferMemory>) {
        if !self.held.iter().any(|m| Arc::ptr_eq(m, memory)) {
            self.held.push(memory.clone());
        }
    }
}
