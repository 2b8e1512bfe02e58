//! CPU checks of the tree against the pyramid it codes and an independent walk of its bytes.

use super::field::{from_fixed, ScalarField};
use super::lookup::POS_FRAC_BITS;
use super::residuals::Residuals;
use super::tree::{byte_code, Border, CompressedTree, CtreeOptions, NO_SUBTREE};

fn smooth(dims: u32, side: u32, seed: u32) -> ScalarField {
    let size = if dims == 2 {
        [side, side, 1]
    } else {
        [side; 3]
    };
    let mut values = Vec::new();
    for z in 0..size[2] {
        for y in 0..size[1] {
            for x in 0..size[0] {
                let (fx, fy, fz) = (
                    x as f32 / side as f32,
                    y as f32 / side as f32,
                    z as f32 / side as f32,
                );
                let s = seed as f32;
                let v = 128.0
                    + 60.0 * (6.0 * fx + s).sin() * (4.0 * fy + 0.5 * s).cos()
                    + 40.0
                        * (-((fx - 0.3).powi(2) + (fy - 0.6).powi(2) + (fz - 0.5).powi(2)) * 20.0)
                            .exp();
                values.push(v);
            }
        }
    }
    ScalarField::new("smooth", dims, size, values).unwrap()
}

fn noisy(side: u32) -> ScalarField {
    let mut state = 12345u32;
    let values = (0..side * side)
        .map(|_| {
            state = state.wrapping_mul(1664525).wrapping_add(1013904223);
            (state >> 24) as f32
        })
        .collect();
    ScalarField::new("noise", 2, [side, side, 1], values).unwrap()
}

/// Walks every record from the indirection table and checks each pointer lands in the bytes
/// on a record whose own code is the child's code, and every data byte is the child's code.
fn walk(tree: &CompressedTree, res: &Residuals) -> u64 {
    let lat = &tree.lattice;
    let f = tree.forest;
    let mut stack: Vec<(u32, usize, u32)> = Vec::new();
    for (i, &a) in tree.indirection.iter().enumerate() {
        if a != NO_SUBTREE {
            assert!(res.internal[f as usize][i]);
            stack.push((f, i, a));
        } else {
            assert!(!res.internal[f as usize][i]);
        }
    }
    let mut records = 0;
    while let Some((l, i, a)) = stack.pop() {
        records += 1;
        let q = lat.coords(l, i);
        let open = lat.open_axes(l, q);
        let size = 1 + lat.child_count(open);
        assert_eq!(
            byte_code(tree.bytes[a as usize]),
            res.codes[l as usize][i] as i32
        );
        for c in 0..lat.brood() {
            if !super::residuals::child_exists(lat, open, c) {
                continue;
            }
            let j = lat.index(l + 1, lat.child(l, q, c));
            let b = tree.bytes[(a + 1 + lat.slot(open, c)) as usize];
            if b & 0x80 != 0 {
                let scale = tree.scales[l as usize];
                let child = a + size + (b & 0x7F) as u32 * scale;
                assert!(res.internal[l as usize + 1][j], "pointer to a leaf");
                stack.push((l + 1, j, child));
            } else {
                assert!(!res.internal[l as usize + 1][j]);
                assert_eq!(byte_code(b), res.codes[l as usize + 1][j] as i32);
            }
        }
    }
    records
}

#[test]
fn trees_decode_within_half_a_step_and_their_bytes_walk() {
    for (field, step) in [
        (smooth(2, 200, 1), 1.0),
        (smooth(2, 129, 2), 4.0),
        (smooth(3, 33, 3), 2.0),
        (noisy(64), 2.0),
    ] {
        let tree = CompressedTree::build(
            &field,
            &CtreeOptions {
                step,
                ..Default::default()
            },
        )
        .unwrap();
        let res = Residuals::build(&field, (step * 64.0) as i32, Border::Anchored);
        let records = walk(&tree, &res);
        let below: u64 = tree.stats.rows[tree.forest as usize..]
            .iter()
            .map(|r| r.internal)
            .sum();
        assert_eq!(records, below);
        let decoded = tree.decode();
        let finest = *tree.steps.last().unwrap();
        let bound = from_fixed(finest) / 2.0 + 4.0 / 64.0;
        let worst = decoded
            .iter()
            .zip(&field.values)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f32::max);
        assert!(worst <= bound, "{:?}: error {worst} > {bound}", field.size);
    }
}

#[test]
fn every_forest_level_decodes_the_same() {
    let field = smooth(2, 65, 4);
    let first = CompressedTree::build(
        &field,
        &CtreeOptions {
            step: 1.0,
            forest: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    let reference = first.decode();
    for f in 2..=first.lattice.finest() {
        let tree = CompressedTree::build(
            &field,
            &CtreeOptions {
                step: 1.0,
                forest: Some(f),
                ..Default::default()
            },
        )
        .unwrap();
        // The pyramid holds the encoder's values of level F; a lower forest reaches the same
        // samples through early exits, which interpolate in one step what the encoder
        // predicted level by level, rounding down at each: a few 1/64 of a grey level apart.
        let worst = tree
            .decode()
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f32::max);
        assert!(worst <= 4.0 / 64.0, "forest {f}: {worst}");
        let centre = [17u32 << POS_FRAC_BITS, 30 << POS_FRAC_BITS, 0];
        assert_eq!(tree.lookup_fixed(centre, 0), tree.texel_fixed([17, 30, 0]));
    }
}

#[test]
fn the_scale_search_finds_the_least_padding() {
    let mut state = 7u64;
    let mut next = |m: u64| {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 33) % m
    };
    for case in 0..200 {
        let records = 1 + next(4) as usize;
        let lists: Vec<Vec<u64>> = (0..records)
            .map(|_| {
                (0..1 + next(4))
                    .map(|_| 1 + next(if case % 2 == 0 { 40 } else { 900 }))
                    .collect()
            })
            .collect();
        let refs: Vec<&[u64]> = lists.iter().map(|l| l.as_slice()).collect();
        let found = super::pack::search_scale(&refs);
        let best = (1..=2000u64)
            .filter_map(|s| {
                let pads: Option<u64> = refs
                    .iter()
                    .map(|l| super::pack::place(l, s).map(|p| p.1))
                    .sum();
                pads.map(|p| (p, s))
            })
            .min()
            .unwrap();
        assert_eq!((found.padding, found.scale as u64), best, "{lists:?}");
    }
}
