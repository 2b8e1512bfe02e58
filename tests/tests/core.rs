//! The Vulkan core on the real device: device requirements, buffers, the kernel cache,
//! descriptor binding, limits, timing.

use lazysolid_compute::gpu::{
    check_features, elapsed_ns, DeviceAddress, Feature, Gpu, GpuBuffer, GpuError, GpuOptions,
    Kernel, MemoryMode, REQUIRED_FEATURES,
};
use lazysolid_compute::kernels;
use lazysolid_compute::prims::push::{CopyCountPush, CopyPush};
use lazysolid_compute::shader_constants::DEFAULT_WORKGROUP_SIZE;
use lazysolid_tests::{random_u32, with_fresh_gpu, with_gpu, with_gpu_options};
use std::sync::Arc;

/// The device choice refuses a device that lacks a required feature before creating it, naming
/// the device and each missing feature; the check is fed the device's own feature list minus
/// one feature at a time.
#[test]
fn a_missing_device_feature_is_reported_by_name() {
    let devices = Gpu::list_devices().unwrap();
    let usable = devices
        .iter()
        .find(|d| d.missing_requirements().is_empty())
        .expect("the test machine has a usable device");
    usable.check_requirements().unwrap();
    for &missing in REQUIRED_FEATURES {
        let without: Vec<Feature> = usable
            .features
            .iter()
            .copied()
            .filter(|&f| f != missing)
            .collect();
        let err = check_features(&usable.name, &without, REQUIRED_FEATURES).unwrap_err();
        assert!(matches!(err, GpuError::MissingFeature { .. }), "{err}");
        let text = err.to_string();
        assert!(
            text.contains(missing.name()) && text.contains(&usable.name),
            "{text}"
        );
    }
    let err = check_features(
        "a device",
        &[],
        &[Feature::ShaderInt64, Feature::BufferDeviceAddress],
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("\"a device\"") && err.contains("shaderInt64, bufferDeviceAddress"),
        "{err}"
    );
}

/// One pipeline per (kernel, workgroup size, specialization constants) per device, shared by
/// every request and every clone of the device.
#[test]
fn the_kernel_cache_builds_each_pipeline_once() {
    with_fresh_gpu(|gpu| {
        let before = gpu.pipelines_created();
        let a = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        let b = gpu.clone().kernel(&kernels::prims::COPY_WORDS).unwrap();
        assert!(Arc::ptr_eq(&a, &b));
        assert_eq!(gpu.pipelines_created(), before + 1);
        let c = gpu
            .kernel_with(&kernels::prims::COPY_WORDS, 64, &[])
            .unwrap();
        assert!(!Arc::ptr_eq(&a, &c));
        assert_eq!(c.workgroup_size(), 64);
        let d = gpu
            .kernel_with(&kernels::prims::COPY_WORDS, DEFAULT_WORKGROUP_SIZE, &[])
            .unwrap();
        assert!(Arc::ptr_eq(&a, &d));
        assert_eq!(gpu.pipelines_created(), before + 2);
        assert_eq!(gpu.cached_kernels(), vec!["prims/copy_words.comp"]);
        // A workgroup over the device limit is refused by name, and nothing is cached.
        let err = gpu
            .kernel_with(&kernels::prims::COPY_WORDS, u32::MAX, &[])
            .err()
            .unwrap();
        assert!(err.to_string().contains("prims/copy_words.comp"), "{err}");
        assert_eq!(gpu.pipelines_created(), before + 2);
    });
}

/// A device kept between tests is checked by its ownership instead of its destruction: it is
/// its handle's alone again only when every clone, buffer and kernel handed out is gone, and
/// `with_gpu` fails a test that leaves one alive.
#[test]
fn a_kept_device_is_owned_again_only_when_its_objects_are_gone() {
    with_fresh_gpu(|gpu| {
        assert!(gpu.is_sole_owner());
        let clone = gpu.clone();
        assert!(!gpu.is_sole_owner(), "a clone");
        drop(clone);
        let buffer = GpuBuffer::<u32>::zeroed(gpu, "held", 4).unwrap();
        assert!(!gpu.is_sole_owner(), "a buffer");
        drop(buffer);
        let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        assert!(!gpu.is_sole_owner(), "a kernel handed out");
        drop(kernel);
        assert!(gpu.is_sole_owner(), "the cache's own kernel does not count");
    });
    let mut kept = None;
    let failed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        with_gpu(|gpu| kept = Some(GpuBuffer::<u32>::zeroed(gpu, "kept", 4).unwrap()))
    }));
    assert!(failed.is_err(), "a buffer outlived its test unnoticed");
    drop(kept);
}

/// A kernel of one device cannot be dispatched on another.
#[test]
fn a_kernel_of_another_device_is_refused() {
    with_fresh_gpu(|gpu| {
        let other = Gpu::new(&lazysolid_compute::gpu::GpuOptions::for_tests()).unwrap();
        let foreign: Arc<Kernel> = other.kernel(&kernels::prims::COPY_WORDS).unwrap();
        let a = GpuBuffer::<u32>::zeroed(gpu, "a", 4).unwrap();
        let err = gpu
            .submit(|rec| {
                rec.dispatch(
                    &foreign,
                    [1, 1, 1],
                    &[("Src", a.arg()), ("Dst", a.arg())],
                    &CopyCountPush { n: 4 },
                )
            })
            .unwrap_err();
        assert!(err.to_string().contains("another device"), "{err}");
    });
}

lazysolid_compute::push_block! {
    /// A count of the wrong width for `copy_words.comp`.
    struct WideCount {
        n: u64,
    }
}

lazysolid_compute::push_block! {
    /// `copy_vec4.comp`'s block with its addresses swapped.
    struct SwappedCopy<'a> {
        dst: DeviceAddress<'a>,
        src: DeviceAddress<'a>,
        n: u32,
    }
}

#[test]
fn a_push_block_that_differs_from_glsl_is_refused_at_dispatch() {
    with_fresh_gpu(|gpu| {
        let kernel = gpu.kernel(&kernels::prims::COPY_VEC4).unwrap();
        let a = GpuBuffer::<u32>::zeroed(gpu, "a", 16).unwrap();
        let b = GpuBuffer::<u32>::zeroed(gpu, "b", 16).unwrap();
        let push = SwappedCopy {
            dst: b.address(),
            src: a.address(),
            n: 4,
        };
        let result = gpu.submit(|rec| rec.dispatch(&kernel, [1, 1, 1], &[], &push));
        if cfg!(debug_assertions) {
            let err = result.unwrap_err();
            assert!(
                matches!(err, GpuError::KernelInterface { .. })
                    && err
                        .to_string()
                        .contains("`uint64_t dst` at byte 0 on the host"),
                "{err}"
            );
        }
    });
}

#[test]
fn recorded_work_keeps_the_buffers_it_addresses_alive() {
    with_fresh_gpu(|gpu| {
        let kernel = gpu.kernel(&kernels::prims::COPY_VEC4).unwrap();
        let data = random_u32(1024, 7);
        let dst = GpuBuffer::<u32>::zeroed(gpu, "dst", data.len()).unwrap();
        gpu.submit(|rec| {
            // The source is dropped before the submission runs: the recorder holds its memory.
            let src = GpuBuffer::from_slice(gpu, "short-lived src", &data)?;
            let push = CopyPush {
                src: src.address(),
                dst: dst.address(),
                n: data.len() as u32,
            };
            rec.dispatch(
                &kernel,
                kernel.groups_for(data.len() as u64 / 4),
                &[],
                &push,
            )
        })
        .unwrap();
        assert_eq!(dst.read().unwrap(), data);
    });
}

#[test]
fn buffer_round_trip_and_empty_buffers() {
    with_fresh_gpu(|gpu| {
        let data = random_u32(10_007, 1);
        let mut buf = GpuBuffer::from_slice(gpu, "round trip", &data).unwrap();
        assert_eq!(buf.read().unwrap(), data);
        assert_eq!(buf.read_range(17, 100).unwrap(), &data[17..117]);
        let empty = GpuBuffer::<u32>::new(gpu, "empty", 0).unwrap();
        assert!(empty.read().unwrap().is_empty());
        let zeros = GpuBuffer::<u64>::zeroed(gpu, "zeros", 1000).unwrap();
        assert!(zeros.read().unwrap().iter().all(|&z| z == 0));
        let err = buf.write(10_000, &[1, 2, 3, 4, 5, 6, 7, 8]).unwrap_err();
        assert!(err.to_string().contains("round trip"), "{err}");
    });
}

#[test]
fn descriptor_bound_copy_kernel() {
    with_fresh_gpu(|gpu| {
        let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        for n in [1usize, 255, 256, 257, 100_000] {
            let data = random_u32(n, n as u64);
            let src = GpuBuffer::from_slice(gpu, "src", &data).unwrap();
            let dst = GpuBuffer::<u32>::zeroed(gpu, "dst", n).unwrap();
            copy_words(gpu, &kernel, &src, &dst, n);
            assert_eq!(dst.read().unwrap(), data, "n = {n}");
        }
    });
}

#[test]
fn dispatch_interface_errors_name_the_kernel() {
    with_fresh_gpu(|gpu| {
        let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        let a = GpuBuffer::<u32>::zeroed(gpu, "a", 16).unwrap();
        let missing = gpu
            .submit(|rec| {
                rec.dispatch(
                    &kernel,
                    [1, 1, 1],
                    &[("Src", a.arg())],
                    &CopyCountPush { n: 16 },
                )
            })
            .unwrap_err();
        assert!(
            matches!(missing, GpuError::KernelInterface { .. })
                && missing.to_string().contains("Dst"),
            "{missing}"
        );
        let unknown = gpu
            .submit(|rec| {
                rec.dispatch(
                    &kernel,
                    [1, 1, 1],
                    &[("Src", a.arg()), ("Dst", a.arg()), ("Nope", a.arg())],
                    &CopyCountPush { n: 16 },
                )
            })
            .unwrap_err();
        assert!(unknown.to_string().contains("Nope"), "{unknown}");
        let push = gpu
            .submit(|rec| {
                rec.dispatch(
                    &kernel,
                    [1, 1, 1],
                    &[("Src", a.arg()), ("Dst", a.arg())],
                    &WideCount { n: 16 },
                )
            })
            .unwrap_err();
        assert!(
            push.to_string()
                .contains("push constants are 8 bytes on the host but 4 bytes"),
            "{push}"
        );
    });
}

#[test]
fn over_limit_requests_are_refused_with_the_limit_named() {
    with_fresh_gpu(|gpu| {
        let info = gpu.info().clone();
        // Larger than the heap (2 GiB on lavapipe): refused before any allocation.
        let too_big = (info.heap_size.min(info.max_memory_allocation_size) / 4 + 1) as usize;
        let err = GpuBuffer::<u32>::new(gpu, "huge", too_big)
            .err()
            .expect("over-limit buffer must be refused");
        match &err {
            GpuError::OverLimit {
                limit_name,
                requested,
                limit,
                ..
            } => {
                assert!(requested > limit);
                assert!(
                    [
                        "maxMemoryAllocationSize",
                        "device heap size",
                        "maxBufferSize"
                    ]
                    .contains(limit_name),
                    "{err}"
                );
            }
            other => panic!("expected OverLimit, got {other}"),
        }
        assert!(err.to_string().contains("huge"), "{err}");
        // A buffer over maxStorageBufferRange (128 MiB on lavapipe) cannot be a binding.
        let range = info.max_storage_buffer_range;
        if range < info.heap_size / 4 {
            let words = (range / 4 + 1024) as usize;
            let big = GpuBuffer::<u32>::new(gpu, "big source", words).unwrap();
            let small = GpuBuffer::<u32>::new(gpu, "small", 16).unwrap();
            let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
            let err = gpu
                .submit(|rec| {
                    rec.dispatch(
                        &kernel,
                        [1, 1, 1],
                        &[("Src", big.arg()), ("Dst", small.arg())],
                        &CopyCountPush { n: 16 },
                    )
                })
                .unwrap_err();
            match &err {
                GpuError::OverLimit {
                    limit_name, limit, ..
                } => {
                    assert_eq!(*limit_name, "maxStorageBufferRange");
                    assert_eq!(*limit, range);
                }
                other => panic!("expected OverLimit, got {other}"),
            }
            assert!(
                err.to_string().contains("big source")
                    && err.to_string().contains("maxStorageBufferRange"),
                "{err}"
            );
        }
    });
}

#[test]
fn timestamps_measure_elapsed_work() {
    with_fresh_gpu(|gpu| {
        let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        let n = 1 << 20;
        let src = GpuBuffer::<u32>::zeroed(gpu, "src", n).unwrap();
        let dst = GpuBuffer::<u32>::zeroed(gpu, "dst", n).unwrap();
        let ((), times) = gpu
            .submit_timed(|rec| {
                rec.timestamp()?;
                rec.dispatch(
                    &kernel,
                    kernel.groups_for(n as u64),
                    &[("Src", src.arg()), ("Dst", dst.arg())],
                    &CopyCountPush { n: n as u32 },
                )?;
                rec.timestamp()
            })
            .unwrap();
        assert_eq!(times.len(), 2);
        assert!(times[1] > times[0], "{times:?}");
    });
}

/// Every submission is one host wait, counted; while timing is on, timestamps around each
/// submission add its device time, and while profiling, timestamps around each dispatch add
/// its kernel's. A readback of device-local memory is a submission of its own.
#[test]
fn submissions_count_their_waits_and_time_their_work() {
    with_fresh_gpu(|gpu| {
        let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        let n = 1 << 18;
        let src = GpuBuffer::<u32>::zeroed(gpu, "src", n).unwrap();
        let dst = GpuBuffer::<u32>::zeroed(gpu, "dst", n).unwrap();
        let before = gpu.submissions();
        copy_words(gpu, &kernel, &src, &dst, n);
        let one = gpu.submissions().since(before);
        assert_eq!((one.waits, one.timed, one.device_ns), (1, 0, 0), "{one:?}");

        gpu.time_submissions(true);
        gpu.profile_dispatches(true);
        let before = gpu.submissions();
        for _ in 0..3 {
            copy_words(gpu, &kernel, &src, &dst, n);
        }
        let three = gpu.submissions().since(before);
        assert_eq!((three.waits, three.timed), (3, 3), "{three:?}");
        assert!(three.device_ns > 0, "{three:?}");
        let profile = gpu.take_dispatch_profile();
        assert_eq!(profile.len(), 1, "{profile:?}");
        let copy = &profile[0];
        assert_eq!(copy.kernel, kernels::prims::COPY_WORDS.name);
        assert_eq!((copy.dispatches, copy.untimed), (3, 0), "{copy:?}");
        assert!(
            copy.device_ns > 0.0 && copy.device_ns <= three.device_ns as f64 + 1e3,
            "{copy:?} within {three:?}"
        );
        assert!(gpu.take_dispatch_profile().is_empty(), "taking clears it");

        gpu.time_submissions(false);
        gpu.profile_dispatches(false);
        let before = gpu.submissions();
        copy_words(gpu, &kernel, &src, &dst, n);
        let after = gpu.submissions().since(before);
        assert_eq!((after.waits, after.timed), (1, 0), "{after:?}");
        assert!(gpu.take_dispatch_profile().is_empty());
    });
}

/// Timestamps count only their valid bits and wrap there; a tick is `timestampPeriod` ns.
#[test]
fn timestamp_differences_wrap_at_the_valid_bits_and_scale_by_the_period() {
    assert_eq!(elapsed_ns(100, 350, 64, 1.0), 250.0);
    // A 36-bit counter that wrapped between the two stamps (as on some GPUs).
    let top = (1u64 << 36) - 10;
    assert_eq!(elapsed_ns(top, 5, 36, 1.0), 15.0);
    // Bits above the valid ones are garbage and ignored.
    assert_eq!(
        elapsed_ns(0xdead_0000_0000_0007, 0x0000_0000_0000_0009, 32, 1.0),
        2.0
    );
    // 41.67 ns ticks (e.g. a 24 MHz counter); no precision lost to huge raw counts.
    let start = u64::MAX - 1000;
    let ns = elapsed_ns(start, start + 1000, 64, 41.67);
    assert!((ns - 41_670.0).abs() < 0.01, "{ns}");
}

/// The discrete-GPU path on any device: under `MemoryMode::DeviceLocal` every upload and
/// readback goes through a staging buffer and a transfer (none is a mapped copy), and data
/// survives the trip through kernels, fills and partial writes and reads.
#[test]
fn device_local_memory_moves_every_upload_and_readback_through_staging() {
    let options = GpuOptions {
        memory: Some(MemoryMode::DeviceLocal),
        ..GpuOptions::for_tests()
    };
    with_gpu_options(&options, |gpu| {
        assert_eq!(gpu.memory_mode(), MemoryMode::DeviceLocal);
        let kernel = gpu.kernel(&kernels::prims::COPY_WORDS).unwrap();
        let n = 100_003;
        let data = random_u32(n, 7);
        let before = gpu.staging_copies();
        let mut src = GpuBuffer::from_slice(gpu, "staged src", &data).unwrap();
        assert_eq!(
            gpu.staging_copies(),
            before + 1,
            "the upload was not staged"
        );
        let dst = GpuBuffer::<u32>::zeroed(gpu, "staged dst", n).unwrap();
        assert_eq!(gpu.staging_copies(), before + 1, "a fill needs no staging");
        copy_words(gpu, &kernel, &src, &dst, n);
        assert_eq!(dst.read().unwrap(), data);
        assert_eq!(dst.read_range(101, 7).unwrap(), &data[101..108]);
        src.write(3, &[9, 8, 7]).unwrap();
        let mut expected = data.clone();
        expected[3..6].copy_from_slice(&[9, 8, 7]);
        assert_eq!(src.read().unwrap(), expected);
        assert_eq!(gpu.staging_copies(), before + 5);
        // Sizes that are not a multiple of 4 bytes copy exactly.
        let bytes = GpuBuffer::from_slice(gpu, "odd bytes", &[1u8, 2, 3, 4, 5]).unwrap();
        assert_eq!(bytes.read_range(1, 3).unwrap(), vec![2, 3, 4]);
    });
}

/// In the default mode, lavapipe's host-visible coherent heap takes no staging at all.
#[test]
fn auto_memory_maps_a_host_visible_heap_directly() {
    let options = GpuOptions {
        memory: Some(MemoryMode::Auto),
        ..GpuOptions::for_tests()
    };
    with_gpu_options(&options, |gpu| {
        let buf = GpuBuffer::from_slice(gpu, "mapped", &[1u32, 2, 3]).unwrap();
        assert_eq!(buf.read().unwrap(), vec![1, 2, 3]);
        if gpu.info().device_type == "cpu" {
            assert_eq!(gpu.staging_copies(), 0);
        } else {
            // A GPU may give a buffer host-visible memory (resizable BAR) or not.
            assert!([0, 2].contains(&gpu.staging_copies()));
        }
    });
}

#[test]
fn a_named_device_that_does_not_exist_is_an_error_listing_devices() {
    let options = lazysolid_compute::gpu::GpuOptions {
        device: Some("no such device 42".into()),
        ..Default::default()
    };
    let err = lazysolid_compute::gpu::Gpu::new(&options)
        .err()
        .expect("unknown device must be refused");
    assert!(matches!(err, GpuError::DeviceNotFound { .. }), "{err}");
    assert!(
        err.to_string().contains("no such device 42") && err.to_string().contains("0: "),
        "{err}"
    );
}

#[test]
fn the_validation_layer_reports_a_provoked_error() {
    use lazysolid_compute::ash::vk;
    use lazysolid_compute::gpu::{Gpu, GpuOptions};
    let gpu = Gpu::new(&GpuOptions::for_tests()).unwrap();
    let log = gpu.validation_log();
    assert_eq!(log.errors(), 0);
    // A zero-sized buffer violates VUID-VkBufferCreateInfo-size-00912.
    let info = vk::BufferCreateInfo::default()
        .size(0)
        .usage(vk::BufferUsageFlags::STORAGE_BUFFER);
    gpu.with_device(|device| {
        if let Ok(buffer) = unsafe { device.create_buffer(&info, None) } {
            unsafe { device.destroy_buffer(buffer, None) };
        }
    });
    drop(gpu);
    assert!(log.errors() >= 1, "the provoked error was not counted");
    assert!(
        log.messages().iter().any(|m| m.contains("00912")),
        "{:?}",
        log.messages()
    );
}

/// Copies the first `n` words of `src` to `dst` with the `COPY_WORDS` kernel.
fn copy_words(gpu: &Gpu, kernel: &Kernel, src: &GpuBuffer<u32>, dst: &GpuBuffer<u32>, n: usize) {
    gpu.submit(|rec| {
        rec.dispatch(
            kernel,
            kernel.groups_for(n as u64),
            &[("Src", src.arg()), ("Dst", dst.arg())],
            &CopyCountPush { n: n as u32 },
        )
    })
    .unwrap();
}

/// The memory meter counts every buffer: a new buffer raises the live bytes and the peak by at
/// least its size, dropping it gives them back, and a mark starts the peak from what is live,
/// so a benchmark can read what some work needed above what it started with.
#[test]
fn the_memory_meter_counts_buffers_live_and_at_their_peak() {
    with_fresh_gpu(|gpu| {
        let before = gpu.mark_memory();
        assert_eq!(gpu.memory_use().peak, before);
        let bytes = 3 << 20;
        {
            let a = GpuBuffer::<u32>::new(gpu, "meter a", bytes / 4).unwrap();
            let b = GpuBuffer::<u32>::new(gpu, "meter b", bytes / 4).unwrap();
            let used = gpu.memory_use();
            assert!(
                used.live >= before + 2 * bytes as u64,
                "{used:?} from {before}"
            );
            assert!(used.peak >= used.live);
            drop((a, b));
        }
        let after = gpu.memory_use();
        assert_eq!(after.live, before, "dropped buffers are given back");
        assert!(
            after.peak >= before + 2 * bytes as u64,
            "the peak remembers them"
        );
        assert_eq!(gpu.mark_memory(), before);
        assert_eq!(gpu.memory_use().peak, before, "a mark starts a new peak");
    });
}

/// A validated device is destroyed only when no other thread is inside a call of a validated
/// device: the validation layer keeps every device's state in one unlocked process-wide map,
/// and a device destroyed during another thread's call crashed the render tests once (a
/// SIGSEGV inside the layer; see `layer_lock` in the core). One thread stays inside a call for
/// 300 ms while another drops its own device; the drop must end after the call.
#[test]
fn a_device_is_destroyed_only_between_other_threads_calls() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::mpsc;
    let (inside_tx, inside_rx) = mpsc::channel();
    let call_ended = AtomicBool::new(false);
    let other = Gpu::new(&GpuOptions::for_tests()).unwrap();
    std::thread::scope(|s| {
        s.spawn(|| {
            with_fresh_gpu(|gpu| {
                gpu.with_device(|_| {
                    inside_tx.send(()).unwrap();
                    std::thread::sleep(std::time::Duration::from_millis(300));
                    call_ended.store(true, Ordering::SeqCst);
                })
            })
        });
        inside_rx.recv().unwrap();
        drop(other);
        assert!(
            call_ended.load(Ordering::SeqCst),
            "a validated device was destroyed while another thread was inside a call"
        );
    });
}
