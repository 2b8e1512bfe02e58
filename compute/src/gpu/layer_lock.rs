//! One process-wide lock between the Vulkan calls that cross the validation layer and the
//! creation or destruction of a validated instance and device.
//!
//! The Khronos validation layer that Debian 12 ships (1.3.239) keeps each instance's and each
//! device's state in one process-wide hash map. Every call through the layer looks the map up
//! without a lock; creating an instance or a device inserts an entry and destroying one erases
//! it (KhronosGroup/Vulkan-ValidationLayers issue 4391). Two devices used from two threads, as
//! tests running side by side do, can therefore crash inside the layer: a call on one device
//! walks a node that another thread's destroyed device has just freed. It was seen as a SIGSEGV
//! in `libVkLayer_khronos_validation.so` (a hash-bucket walk) during the render tests.
//!
//! So a validated [`Gpu`](super::Gpu) is created and destroyed under the exclusive lock, and
//! every other call of a validated device holds the shared lock. Shared holds nest within one
//! thread (a buffer created inside a recorded submission), and a thread that holds the exclusive
//! lock needs no shared one. Devices without the layer never take the lock: their calls do not
//! enter the layer's map.

use std::cell::Cell;
use std::sync::{PoisonError, RwLock, RwLockReadGuard, RwLockWriteGuard};

static LAYER_MAP: RwLock<()> = RwLock::new(());

/// What the current thread holds.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Held {
    Nothing,
    /// Nested shared holds.
    Shared(u32),
    Exclusive,
}

thread_local! {
    static HELD: Cell<Held> = const { Cell::new(Held::Nothing) };
}

/// A shared hold on the layer's map; released when dropped.
pub(crate) struct SharedHold {
    guard: Option<RwLockReadGuard<'static, ()>>,
    counted: bool,
}

impl Drop for SharedHold {
    fn drop(&mut self) {
        if self.counted {
            HELD.with(|h| {
                h.set(match h.get() {
                    Held::Shared(1) => Held::Nothing,
                    Held::Shared(n) => Held::Shared(n - 1),
                    other => other,
                })
            });
        }
        drop(self.guard.take());
    }
}

/// Holds the map shared for a call of a device with the layer (`validated`); nothing otherwise.
pub(crate) fn shared(validated: bool) -> SharedHold {
    if !validated {
        return SharedHold {
            guard: None,
            counted: false,
        };
    }
    HELD.with(|h| match h.get() {
        Held::Exclusive => SharedHold {
            guard: None,
            counted: false,
        },
        Held::Shared(n) => {
            h.set(Held::Shared(n + 1));
            SharedHold {
                guard: None,
                counted: true,
            }
        }
        Held::Nothing => {
            let guard = LAYER_MAP.read().unwrap_or_else(PoisonError::into_inner);
            h.set(Held::Shared(1));
            SharedHold {
                guard: Some(guard),
                counted: true,
            }
        }
    })
}

/// An exclusive hold on the layer's map, for creating or destroying a validated device.
pub(crate) struct ExclusiveHold {
    guard: Option<RwLockWriteGuard<'static, ()>>,
}

impl Drop for ExclusiveHold {
    fn drop(&mut self) {
        if self.guard.take().is_some() {
            HELD.with(|h| h.set(Held::Nothing));
        }
    }
}

/// Holds the map exclusively when `validated`. Nested in a hold of the same thread it takes
/// nothing more: inside an exclusive hold that one suffices, and inside a shared one (a device
/// dropped by the last owner while this thread is in a call of another device) waiting for
/// exclusive would wait for itself, so the device is destroyed under the shared hold.
///
/// The last case is reachable only by code that frees a validated device from within a call on
/// another; lazysolid's own code does not, and the hold is then no worse than no lock at all.
pub(crate) fn exclusive(validated: bool) -> ExclusiveHold {
    if !validated {
        return ExclusiveHold { guard: None };
    }
    HELD.with(|h| match h.get() {
        Held::Nothing => {
            let guard = LAYER_MAP.write().unwrap_or_else(PoisonError::into_inner);
            h.set(Held::Exclusive);
            ExclusiveHold { guard: Some(guard) }
        }
        Held::Shared(_) | Held::Exclusive => ExclusiveHold { guard: None },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_holds_nest_and_release_in_one_thread() {
        {
            let _a = shared(true);
            let _b = shared(true);
            assert_eq!(HELD.with(|h| h.get()), Held::Shared(2));
        }
        assert_eq!(HELD.with(|h| h.get()), Held::Nothing);
        let _w = exclusive(true);
        assert_eq!(HELD.with(|h| h.get()), Held::Exclusive);
        // A call inside the exclusive hold needs nothing more and must not wait for itself.
        let _c = shared(true);
        let _d = exclusive(true);
        assert_eq!(HELD.with(|h| h.get()), Held::Exclusive);
    }

    #[test]
    fn devices_without_the_layer_take_nothing() {
        let _a = shared(false);
        let _b = exclusive(false);
        assert_eq!(HELD.with(|h| h.get()), Held::Nothing);
    }

    #[test]
    fn an_exclusive_hold_waits_for_shared_holds_of_other_threads() {
        use std::sync::atomic::{AtomicBool, Ordering};
        use std::sync::Arc;
        let reading = shared(true);
        let done = Arc::new(AtomicBool::new(false));
        let writer = {
            let done = done.clone();
            std::thread::spawn(move || {
                let _w = exclusive(true);
                done.store(true, Ordering::SeqCst);
            })
        };
        std::thread::sleep(std::time::Duration::from_millis(50));
        assert!(
            !done.load(Ordering::SeqCst),
            "the exclusive hold did not wait"
        );
        drop(reading);
        writer.join().unwrap();
        assert!(done.load(Ordering::SeqCst));
    }
}
