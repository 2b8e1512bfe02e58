//! Every GPU primitive against its CPU reference: edge sizes, and inputs larger than one
//! 128 MiB storage-buffer binding.

use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_compute::prims::{
    compact_cpu, exclusive_scan_cpu, reduce_cpu, sort_pairs_cpu, CompactOutput, Compactor, KeepCpu,
    RadixSort, Reduce, ReduceOp, Scan,
};
use lazysolid_tests::{random_u32, rng, with_gpu, EDGE_SIZES};
use rand::Rng;

/// More than 128 MiB of u32 words: 40M words = 160 MiB.
const BIG: usize = 40 << 20;

#[test]
fn scan_edge_sizes() {
    with_gpu(|gpu| {
        let mut scan = Scan::new(gpu).unwrap();
        for &n in EDGE_SIZES {
            // Small values, and full-range values that wrap.
            for input in [
                random_u32(n, n as u64)
                    .iter()
                    .map(|v| v % 100)
                    .collect::<Vec<_>>(),
                random_u32(n, 7 + n as u64),
            ] {
                assert_eq!(
                    scan.run(&input).unwrap(),
                    exclusive_scan_cpu(&input),
                    "n = {n}"
                );
            }
        }
    });
}

#[test]
fn scan_reduce_compaction_with_short_segments_as_on_gpus() {
    with_gpu(|gpu| {
        // GPUs get 16-word segments: deeper recursion and many more chunks per binding.
        let mut scan = Scan::new(gpu).unwrap();
        scan.segment_length = Some(16);
        let mut reduce = Reduce::new(gpu).unwrap();
        reduce.segment_length = Some(16);
        for &n in EDGE_SIZES {
            let input = random_u32(n, 41 + n as u64);
            assert_eq!(
                scan.run(&input).unwrap(),
                exclusive_scan_cpu(&input),
                "n = {n}"
            );
            assert_eq!(
                reduce.run(&input, ReduceOp::Max).unwrap(),
                reduce_cpu(&input, ReduceOp::Max),
                "n = {n}"
            );
        }
    });
}

#[test]
fn reduce_edge_sizes_all_ops() {
    with_gpu(|gpu| {
        let mut reduce = Reduce::new(gpu).unwrap();
        for &n in EDGE_SIZES {
            let input = random_u32(n, 11 + n as u64);
            for op in [ReduceOp::Sum, ReduceOp::Min, ReduceOp::Max] {
                assert_eq!(
                    reduce.run(&input, op).unwrap(),
                    reduce_cpu(&input, op),
                    "n = {n}, {op:?}"
                );
            }
        }
    });
}

#[test]
fn compaction_edge_sizes() {
    with_gpu(|gpu| {
        let mut compactor = Compactor::new(gpu).unwrap();
        for &n in EDGE_SIZES {
            let values: Vec<u32> = random_u32(n, 3 + n as u64).iter().map(|v| v % 4).collect();
            let flags: Vec<u32> = random_u32(n, 5 + n as u64).iter().map(|v| v % 3).collect();
            for output in [CompactOutput::Values, CompactOutput::Indices] {
                for keep in [KeepCpu::Flags(&flags), KeepCpu::NotEqual(0)] {
                    assert_eq!(
                        compactor.run(&values, keep, output).unwrap(),
                        compact_cpu(&values, keep, output),
                        "n = {n}, {output:?}"
                    );
                }
            }
            // All kept and none kept.
            let all = vec![1u32; n];
            assert_eq!(
                compactor
                    .run(&values, KeepCpu::Flags(&all), CompactOutput::Values)
                    .unwrap(),
                values
            );
            assert!(compactor
                .run(&vec![9u32; n], KeepCpu::NotEqual(9), CompactOutput::Values)
                .unwrap()
                .is_empty());
        }
    });
}

#[test]
fn radix_sort_u32_edge_sizes() {
    with_gpu(|gpu| {
        let mut sort = RadixSort::new(gpu).unwrap();
        for &n in EDGE_SIZES {
            let keys = random_u32(n, 13 + n as u64);
            let mut expected = keys.clone();
            expected.sort_unstable();
            assert_eq!(sort.run_u32(&keys).unwrap(), expected, "n = {n}");
        }
        // Many duplicates, already sorted and reversed input.
        let dups: Vec<u32> = random_u32(70_001, 17).iter().map(|v| v % 5).collect();
        let mut expected = dups.clone();
        expected.sort_unstable();
        assert_eq!(sort.run_u32(&dups).unwrap(), expected);
        let reversed: Vec<u32> = (0..50_000u32).rev().collect();
        assert_eq!(
            sort.run_u32(&reversed).unwrap(),
            (0..50_000u32).collect::<Vec<_>>()
        );
    });
}

#[test]
fn radix_sort_pairs_are_stable_for_every_key_width() {
    with_gpu(|gpu| {
        let mut sort = RadixSort::new(gpu).unwrap();
        let mut r = rng(19);
        for &n in EDGE_SIZES {
            // Few distinct keys, so stability is visible in the values.
            let keys: Vec<u64> = (0..n)
                .map(|_| (r.random::<u64>() % 1000) | (r.random::<u64>() << 40))
                .collect();
            let values: Vec<u32> = (0..n as u32).collect();
            for bits in [64, 40, 13, 8, 1] {
                assert_eq!(
                    sort.run_u64_pairs(&keys, &values, bits).unwrap(),
                    sort_pairs_cpu(&keys, &values, bits),
                    "n = {n}, bits = {bits}"
                );
            }
        }
    });
}

#[test]
fn radix_sort_u32_pairs_with_few_bits() {
    use lazysolid_compute::gpu::GpuBuffer;
    with_gpu(|gpu| {
        let mut sort = RadixSort::new(gpu).unwrap();
        let n = 300_007;
        let keys: Vec<u32> = random_u32(n, 23).iter().map(|k| k & 0xfff).collect();
        let values: Vec<u32> = (0..n as u32).collect();
        let k = GpuBuffer::from_slice(gpu, "keys", &keys).unwrap();
        let v = GpuBuffer::from_slice(gpu, "values", &values).unwrap();
        gpu.submit(|rec| sort.record_u32_pairs(rec, &k, &v, n, 12))
            .unwrap();
        assert_eq!(
            (k.read().unwrap(), v.read().unwrap()),
            sort_pairs_cpu(&keys, &values, 12)
        );
    });
}

#[test]
fn primitives_beyond_one_binding() {
    with_gpu(|gpu| {
        assert!((BIG * 4) as u64 > gpu.info().max_storage_buffer_range.min(128 << 20));
        let input: Vec<u32> = random_u32(BIG, 29).iter().map(|v| v % 1000).collect();
        assert_eq!(
            Scan::new(gpu).unwrap().run(&input).unwrap(),
            exclusive_scan_cpu(&input),
            "scan"
        );
        let mut reduce = Reduce::new(gpu).unwrap();
        for op in [ReduceOp::Sum, ReduceOp::Min, ReduceOp::Max] {
            assert_eq!(
                reduce.run(&input, op).unwrap(),
                reduce_cpu(&input, op),
                "{op:?}"
            );
        }
        let keep = KeepCpu::NotEqual(7);
        assert_eq!(
            Compactor::new(gpu)
                .unwrap()
                .run(&input, keep, CompactOutput::Indices)
                .unwrap(),
            compact_cpu(&input, keep, CompactOutput::Indices)
        );
        let keys = random_u32(BIG, 31);
        let mut expected = keys.clone();
        expected.sort_unstable();
        assert_eq!(
            RadixSort::new(gpu).unwrap().run_u32(&keys).unwrap(),
            expected,
            "u32 sort"
        );
    });
}

#[test]
fn radix_sort_u64_pairs_beyond_one_binding() {
    with_gpu(|gpu| {
        // 17M u64 keys = 136 MiB.
        let n = 17 << 20;
        let mut r = rng(37);
        let keys: Vec<u64> = (0..n).map(|_| r.random()).collect();
        let values: Vec<u32> = (0..n as u32).collect();
        assert_eq!(
            RadixSort::new(gpu)
                .unwrap()
                .run_u64_pairs(&keys, &values, 64)
                .unwrap(),
            sort_pairs_cpu(&keys, &values, 64)
        );
    });
}

#[test]
fn compaction_of_flags_alone_gives_indices() {
    use lazysolid_compute::gpu::GpuBuffer;
    use lazysolid_compute::prims::Keep;
    with_gpu(|gpu| {
        let mut compactor = Compactor::new(gpu).unwrap();
        for n in [1usize, 5, 4097, 300_001] {
            let flags: Vec<u32> = random_u32(n, 43 + n as u64)
                .iter()
                .map(|v| v % 5 / 4)
                .collect();
            let f = GpuBuffer::from_slice(gpu, "flags", &flags).unwrap();
            let dst = GpuBuffer::<u32>::new(gpu, "indices", n).unwrap();
            let count = GpuBuffer::<u32>::new(gpu, "count", 1).unwrap();
            gpu.submit(|rec| {
                compactor.record(
                    rec,
                    None,
                    Keep::Flags(&f),
                    n,
                    CompactOutput::Indices,
                    &dst,
                    &count,
                )
            })
            .unwrap();
            let kept = count.read().unwrap()[0] as usize;
            let expected: Vec<u32> = (0..n as u32).filter(|&i| flags[i as usize] != 0).collect();
            assert_eq!(dst.read_range(0, kept).unwrap(), expected, "n = {n}");
        }
        // Values are required for sentinel compaction and for value output.
        let f = GpuBuffer::<u32>::zeroed(gpu, "flags", 8).unwrap();
        let count = GpuBuffer::<u32>::new(gpu, "count", 1).unwrap();
        let err = gpu
            .submit(|rec| {
                compactor.record(
                    rec,
                    None,
                    Keep::NotEqual(0),
                    8,
                    CompactOutput::Indices,
                    &f,
                    &count,
                )
            })
            .unwrap_err();
        assert!(err.to_string().contains("needs Keep::Flags"), "{err}");
    });
}

/// The counted forms, whose length is a word on the device (how the lazy dependency walk keeps
/// its lengths off the host), equal the references on the first `count` elements of a larger
/// buffer, for counts from none to all, with short (GPU) and long (CPU) scan segments; the
/// counted scan writes its total even for none, and the sort leaves the elements past the
/// count alone.
#[test]
fn counted_scan_and_sort_follow_a_length_on_the_device() {
    with_gpu(|gpu| {
        let cap = 70_001;
        let values: Vec<u32> = random_u32(cap, 23).iter().map(|v| v % 7).collect();
        let keys: Vec<u64> = random_u32(cap, 29)
            .iter()
            .zip(random_u32(cap, 31))
            .map(|(&a, b)| (a as u64) << 32 | b as u64)
            .collect();
        for segment_length in [None, Some(16)] {
            let mut scan = Scan::new(gpu).unwrap();
            scan.segment_length = segment_length;
            let mut sort = RadixSort::new(gpu).unwrap();
            for count in [0, 1, 5, 4_096, 4_097, 33_333, cap] {
                let word = GpuBuffer::from_slice(gpu, "count", &[count as u32]).unwrap();
                let src = GpuBuffer::from_slice(gpu, "values", &values).unwrap();
                let dst = GpuBuffer::<u32>::zeroed(gpu, "sums", cap).unwrap();
                let total = GpuBuffer::from_slice(gpu, "total", &[u32::MAX]).unwrap();
                let k = GpuBuffer::from_slice(gpu, "keys", &keys).unwrap();
                gpu.submit(|rec| {
                    scan.record_counted(rec, &src, &dst, cap, word.address(), Some(&total))?;
                    sort.record_u64_counted(rec, &k, cap, word.address(), 64)
                })
                .unwrap();
                let (sums, sum) = exclusive_scan_cpu(&values[..count]);
                let what = format!("count {count}, segments {segment_length:?}");
                assert_eq!(dst.read_range(0, count).unwrap(), sums, "{what}");
                assert_eq!(total.read().unwrap()[0], sum, "{what}");
                let mut sorted = keys[..count].to_vec();
                sorted.sort_unstable();
                let got = k.read().unwrap();
                assert_eq!(got[..count], sorted[..], "{what}");
                assert_eq!(got[count..], keys[count..], "{what}");
            }
        }
    });
}
