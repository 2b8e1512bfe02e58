//! Range min/max queries over the glint example by the three methods of `bench glints`: the
//! sparse table (one lookup), the min–max mip (maximal aligned blocks) and brute force. On the
//! CPU all three equal a brute-force min/max computed here independently, exactly (every
//! square of a 16² example, random squares of 64² examples); the device-built mip equals its
//! CPU build; the query kernel's three methods answer one batch identically to the CPU.
//!
//! The examples are random normals per texel (every texel differs from its neighbours, which
//! exercises every block boundary); exactness does not depend on the content.

use glam::Vec2;
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_renderer::glint::gpu_range_query::range_query_kernel;
use lazysolid_renderer::glint::minmax_mip::{
    brute_force, dyadic_pieces, minmax_mip_bytes, table_query,
};
use lazysolid_renderer::glint::range_table::{quantize_texels, unpack};
use lazysolid_renderer::glint::{
    build_range_table, random_squares, record_range_queries, GpuMinMaxMip, MinMaxMip,
    NormalExample, RangeMethod, RangeSquare, RangeTable,
};
use lazysolid_tests::{rng, with_gpu};
use rand::Rng;

fn random_example(size: usize, seed: u64) -> NormalExample {
    let mut r = rng(seed);
    let texels = (0..size * size)
        .map(|_| {
            let (a, rad) = (r.random::<f32>() * std::f32::consts::TAU, r.random::<f32>());
            Vec2::new(a.cos(), a.sin()) * rad * 0.95
        })
        .collect();
    NormalExample::from_normals("random normals", size, texels).unwrap()
}

/// Min/max of the float texels of the square, quantized like the table (floor, ceil): an
/// oracle independent of the packed unions.
fn oracle(e: &NormalExample, q: RangeSquare) -> (Vec2, Vec2) {
    let span = 1usize << q.level;
    let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
    for y in q.y as usize..=q.y as usize + span {
        for x in q.x as usize..=q.x as usize + span {
            lo = lo.min(e.texel(x, y));
            hi = hi.max(e.texel(x, y));
        }
    }
    (lo, hi)
}

fn check_square(e: &NormalExample, table: &RangeTable, mip: &MinMaxMip, q: RangeSquare) {
    let quantized = quantize_texels(e);
    let t = table_query(table, q);
    assert_eq!(mip.query(q), t, "mip at {q:?}");
    assert_eq!(
        brute_force(&quantized, e.size(), q),
        t,
        "brute force at {q:?}"
    );
    let (lo, hi) = oracle(e, q);
    let i = unpack(t).unwrap();
    // Floor/ceil to 16 bits: contains the true range and is less than a step (2/65535) wider.
    let step = 2.0 / 65535.0 + 1e-6;
    assert!(
        i.contains(lo, 0.0) && i.contains(hi, 0.0),
        "{q:?}: {i:?} vs {lo} {hi}"
    );
    assert!(
        (lo - i.lo).max_element() < step && (i.hi - hi).max_element() < step,
        "{q:?}: {i:?} vs {lo} {hi}"
    );
}

#[test]
fn dyadic_pieces_are_the_maximal_aligned_intervals() {
    for start in 0..70u32 {
        for len in 1..70u32 {
            let pieces = dyadic_pieces(start, start + len);
            let mut p = start;
            for &(s, lg) in &pieces {
                assert_eq!(s, p);
                assert_eq!(s % (1 << lg), 0, "{start}+{len}: {pieces:?}");
                p += 1 << lg;
            }
            assert_eq!(p, start + len);
            // Maximal: no two neighbours of one size merge into an aligned interval.
            for w in pieces.windows(2) {
                assert!(
                    !(w[0].1 == w[1].1 && w[0].0 % (2 << w[0].1) == 0),
                    "{start}+{len}: {pieces:?}"
                );
            }
            assert!(
                pieces.len() <= 2 * (32 - len.leading_zeros() as usize),
                "{pieces:?}"
            );
        }
    }
}

#[test]
fn every_square_of_a_small_example_is_exact_by_every_method() {
    let e = random_example(16, 1);
    // Levels up to 8 (the table can store levels past the target patch of a map).
    let table = RangeTable::build(&e, 8);
    let mip = MinMaxMip::build(&e);
    assert_eq!(mip.bytes(), (256 + 64 + 16 + 4 + 1) * 8);
    assert_eq!(mip.bytes(), minmax_mip_bytes(16));
    for level in 0..4u32 {
        for y in 0..16 - (1 << level) {
            for x in 0..16 - (1 << level) {
                check_square(&e, &table, &mip, RangeSquare { x, y, level });
            }
        }
    }
}

#[test]
fn random_squares_are_exact_and_mip_blocks_stay_few() {
    for seed in [2, 3] {
        let e = random_example(64, seed);
        let table = RangeTable::build(&e, 16);
        let mip = MinMaxMip::build(&e);
        let squares = random_squares(64, table.levels(), 3000, seed);
        assert!(squares.iter().any(|q| q.level == 4) && squares.iter().any(|q| q.level == 0));
        for &q in &squares {
            check_square(&e, &table, &mip, q);
            // At most (2 log2(span) + 1)² rectangles of at most 2^level squares each, and
            // never more than the texels.
            let blocks = mip.query_counted(q).1;
            assert!(
                blocks <= ((1usize << q.level) + 1).pow(2),
                "{q:?}: {blocks}"
            );
        }
    }
    // A square at an odd start needs its first column as single texels: 2^k + 1 of them.
    let e = random_example(64, 4);
    let mip = MinMaxMip::build(&e);
    let q = RangeSquare {
        x: 1,
        y: 1,
        level: 4,
    };
    assert!(mip.query_counted(q).1 >= 17);
    assert_eq!(
        mip.query_counted(RangeSquare {
            x: 16,
            y: 32,
            level: 4
        })
        .1,
        // [16, 32] per axis: one 16-block and one texel: 1 + 16 + 16 + 1.
        34
    );
}

#[test]
fn device_mip_and_queries_equal_the_cpu() {
    let examples = [random_example(64, 5), random_example(128, 6)];
    with_gpu(|gpu| {
        let kernel = range_query_kernel(gpu).unwrap();
        for e in &examples {
            let n = e.size();
            let patch = (n / 4) as u32;
            let cpu_table = RangeTable::build(e, patch);
            let cpu_mip = MinMaxMip::build(e);
            let table = build_range_table(gpu, e, patch).unwrap();
            let mip = GpuMinMaxMip::build(gpu, e).unwrap();
            assert_eq!(mip.to_host().unwrap(), cpu_mip, "{n}²: device mip");
            let squares = random_squares(n, cpu_table.levels(), 4096, n as u64);
            let expected: Vec<[u32; 2]> = squares
                .iter()
                .map(|q| table_query(&cpu_table, *q))
                .collect();
            let square_buf = GpuBuffer::from_slice(gpu, "squares", &squares).unwrap();
            let results = GpuBuffer::<[u32; 2]>::new(gpu, "answers", squares.len()).unwrap();
            for m in RangeMethod::ALL {
                let structure = match m {
                    RangeMethod::SparseTable => &table,
                    _ => &mip.entries,
                };
                gpu.submit(|rec| {
                    // A stale answer of the previous method must not pass.
                    rec.fill(&results, 0x5555_5555);
                    rec.barrier();
                    record_range_queries(
                        rec,
                        &kernel,
                        m,
                        structure,
                        n,
                        &square_buf,
                        &results,
                        squares.len(),
                    )
                })
                .unwrap();
                let got = results.read().unwrap();
                let wrong = (0..squares.len())
                    .filter(|&i| got[i] != expected[i])
                    .count();
                assert_eq!(
                    wrong,
                    0,
                    "{n}² {}: {wrong} of {} differ",
                    m.name(),
                    squares.len()
                );
            }
        }
    });
}
