//! Multiscale synthesis from exemplar graphs: the thesis' worked example of admissible sets
//! and superexemplar depth sets, graph file errors, the fitted colour transfer, the
//! one-exemplar graph against the 2D synthesizer (bit for bit), windows agreeing on their
//! overlaps, synthesis deeper than any exemplar through a loop, and GPU = CPU.

use lazysolid_synth::multiscale::{
    analyze_topology, fit_transfer, synthesize_multiscale_cpu, CorrectionVariant, ExemplarGraph,
    GraphError, MultiscaleAnalysis, MultiscaleGpu, MultiscaleParams, Topology, MAGNIFIED,
    TRANSFER_ONE,
};
use lazysolid_synth::{
    analyze, default_jitter, default_passes, synthesize_cpu, AnalysisParams, Exemplar, Region,
    SynthParams, DEFAULT_PERIOD_PENALTY,
};
use lazysolid_tests::{asset_exemplar, exemplar_crop, with_gpu};
use std::collections::HashSet;
use std::path::Path;
use std::sync::OnceLock;

fn window(x: i32, y: i32, w: u32, h: u32) -> Region {
    Region {
        origin: [x, y],
        size: [w, h],
    }
}

/// The paper's example graph (Fig. 4 / thesis Fig. 4.2): E0, E1, E2 with edges (0, 1, 2),
/// (0, 2, 3) and the loop (2, 2, 1), exemplars of 128² (L = 7).
fn example() -> Topology {
    Topology::new(vec![7, 7, 7], &[(0, 1, 2), (0, 2, 3), (2, 2, 1)], 0)
}

#[test]
fn admissible_sets_match_the_worked_example() {
    let g = example();
    // T:965–985: A(E^0_5) = {E^0_5, E^1_3, E^2_2}; E^2_1 is not admissible.
    assert_eq!(g.admissible(0, 5), vec![(0, 5), (1, 3), (2, 2)]);
    assert!(!g.admissible(0, 5).contains(&(2, 1)));
    // Through the reflexive edge, E^2_5 ∈ A(E^2_6).
    assert!(g.admissible(2, 6).contains(&(2, 5)));
    assert_eq!(g.admissible(2, 6), vec![(2, 5), (2, 6)]);
    // Finest levels are never admissible.
    for i in 0..3 {
        for k in 0..=7 {
            assert!(g.admissible(i, k).iter().all(|&(j, l)| l < g.finest[j]));
        }
    }
    assert_eq!(g.admissible(0, 7), vec![(1, 5), (2, 4)]);
    assert_eq!(g.admissible(2, 7), vec![(2, 6)]);
    // E1 is a leaf: under the leaf policy its finest level corrects within itself.
    assert!(g.admissible(1, 7).is_empty());
    assert!(g.is_leaf(1) && !g.is_leaf(0) && !g.is_leaf(2));
    assert_eq!(g.correction_levels(1, 7), vec![(1, 7)]);
}

#[test]
fn superexemplar_depth_sets_of_the_example() {
    let g = example();
    let s = g.superexemplar();
    assert_eq!(s.depth(0), &[(0, 0)]);
    assert_eq!(s.depth(1), &[(0, 1)]);
    assert_eq!(s.depth(2), &[(0, 2), (1, 0)]);
    assert_eq!(s.depth(3), &[(0, 3), (1, 1), (2, 0)]);
    // (2, 1) reaches (2, 0) through the loop: both have the scale of depth 4.
    assert_eq!(s.depth(4), &[(0, 4), (1, 2), (2, 0), (2, 1)]);
    assert_eq!(
        s.depth(7),
        &[(0, 7), (1, 5), (2, 0), (2, 1), (2, 2), (2, 3), (2, 4)]
    );
    // Past the root's finest level (a non-leaf: always corrected away) only E1 and E2 are
    // left; E1 ends at its finest level (a leaf, then magnified), E2 loops forever.
    assert_eq!(
        s.depth(8),
        &[(1, 6), (2, 0), (2, 1), (2, 2), (2, 3), (2, 4), (2, 5)]
    );
    assert_eq!(
        s.depth(9),
        &[
            (1, 7),
            (2, 0),
            (2, 1),
            (2, 2),
            (2, 3),
            (2, 4),
            (2, 5),
            (2, 6)
        ]
    );
    // E2's finest level appears (upsampled, then corrected away), and the sets repeat.
    assert_eq!(
        s.depth(10),
        &[
            (1, 7),
            (2, 0),
            (2, 1),
            (2, 2),
            (2, 3),
            (2, 4),
            (2, 5),
            (2, 6),
            (2, 7)
        ]
    );
    assert_eq!(s.depth(11), s.depth(10));
    assert_eq!(s.depth(25), s.depth(10));
    assert_eq!((s.sets.len(), s.loop_start), (11, 10));
    // The sequence is finite and periodic; every depth has its set.
    let period = s.sequence.len() - s.loop_start;
    assert!(period >= 1);
    for t in 0..40 {
        let d = s.depth(t);
        assert!(!d.is_empty());
        if t as usize >= s.loop_start {
            assert_eq!(d, s.depth(t + period as u32));
        }
        // Every depth set is closed under the correction levels.
        for &(i, k) in d {
            assert!(g.correction_levels(i, k).iter().all(|x| d.contains(x)));
        }
    }
    // One exemplar, no edges: depth t holds level t, then the magnified finest level.
    let single = Topology::new(vec![6], &[], 0).superexemplar();
    for t in 0..=6 {
        assert_eq!(single.depth(t), &[(0, t)]);
    }
    assert_eq!(single.depth(9), &[(0, 6)]);
}

fn parse(text: &str) -> Result<ExemplarGraph, GraphError> {
    let load = |value: &str| -> Result<Exemplar, String> {
        let side = match value {
            "big" => 128,
            "small" => 64,
            "huge" => 300,
            _ => return Err(format!("no image {value:?}")),
        };
        Exemplar::from_rgb(
            value,
            side,
            side,
            vec![[9, 9, 9]; side as usize * side as usize],
        )
        .map_err(|e| e.to_string())
    };
    ExemplarGraph::parse(Path::new("g.toml"), text, &load)
}

#[test]
fn graph_files_parse_and_bad_ones_get_their_errors() {
    let good = "root = \"a\"\n\
                [[exemplar]]\nname = \"a\"\nimage = \"big\"\n\
                [[exemplar]]\nname = \"b\"\nimage = \"small\"\n\
                [[edge]]\nsource = \"a\"\ndestination = \"b\"\nr = 2\n\
                [[edge]]\nsource = \"b\"\ndestination = \"b\"\nr = 1\n";
    let g = parse(good).unwrap();
    assert_eq!(g.names, ["a", "b"]);
    assert_eq!(g.topology.finest, [7, 6]);
    assert_eq!(g.topology.edges.len(), 2);
    let err = |text: &str| parse(text).unwrap_err().to_string();
    // Unknown exemplar in an edge, with its line and field.
    let e = err(&good.replace("destination = \"b\"", "destination = \"c\""));
    assert!(
        e.starts_with("g.toml:10: edge #1.destination: no exemplar is named \"c\""),
        "{e}"
    );
    // Unknown root.
    let e = err(&good.replace("root = \"a\"", "root = \"z\""));
    assert!(
        e.starts_with("g.toml:1: root: no exemplar is named \"z\""),
        "{e}"
    );
    // r at r_max (L = 6 for b: r_max = 3) and negative r.
    let e = err(&good.replace("r = 1", "r = 3"));
    assert!(
        e.starts_with("g.toml:15: edge #2.r: r = 3; it must lie in 0..3"),
        "{e}"
    );
    let e = err(&good.replace("r = 2", "r = -1"));
    assert!(e.starts_with("g.toml:11: edge #1.r: r = -1"), "{e}");
    // An exemplar no edge reaches.
    let e = err(&good.replace("source = \"a\"", "source = \"b\""));
    assert!(
        e.starts_with("g.toml:6: exemplar \"b\": not reachable from the root \"a\""),
        "{e}"
    );
    // An image that does not load.
    let e = err(&good.replace("\"small\"", "\"nothing\""));
    assert!(
        e.starts_with("g.toml:7: exemplar \"b\".image: no image"),
        "{e}"
    );
    // An image the 2D synthesizer takes but the multiscale atlas cannot (8-bit positions).
    let e = err(&good.replace("\"small\"", "\"huge\""));
    assert!(
        e.starts_with(
            "g.toml:7: exemplar \"b\".image: huge is 300x300; multiscale exemplars are at most 256"
        ),
        "{e}"
    );
    // A duplicate name, a missing field, an unknown field, a syntax error.
    let e = err(&good.replace("name = \"b\"", "name = \"a\""));
    assert!(e.starts_with("g.toml:6: exemplar #2.name:"), "{e}");
    let e = err(&good.replace("r = 2\n", ""));
    assert!(
        e.starts_with("g.toml:") && e.contains("missing field `r`"),
        "{e}"
    );
    let e = err(&good.replace("r = 2", "r = 2\nscale = 3"));
    assert!(e.contains("unknown field `scale`"), "{e}");
    let e = err("root = \n");
    assert!(e.starts_with("g.toml:1:"), "{e}");
}

#[test]
fn fitted_transfer_of_a_shifted_copy_is_the_shift() {
    let a = exemplar_crop("terra.pat", 0, 0, 32, 32);
    // Shift by (+20, −13, +7) levels: terra's colours stay inside 0..=255 after it.
    let shift = [20i32, -13, 7];
    let b_rgb: Vec<[u8; 3]> = a
        .rgb
        .iter()
        .map(|c| std::array::from_fn(|i| (c[i] as i32 + shift[i]).clamp(0, 255) as u8))
        .collect();
    assert!(a
        .rgb
        .iter()
        .all(|c| (0..3).all(|i| (0..=255).contains(&(c[i] as i32 + shift[i])))));
    let b = Exemplar::from_rgb("shifted", 32, 32, b_rgb).unwrap();
    let topology = Topology::new(vec![5, 5], &[(0, 1, 0)], 0);
    // A spread of 32 leaves no second candidate in E0 (32² torus: no texel is 32 away), so
    // every second candidate lies in E1.
    let params = AnalysisParams {
        spread: 32,
        ..AnalysisParams::default()
    };
    let analysis = analyze_topology(&[a, b], &topology, &params).unwrap();
    // Level 2 of E0 admits level 2 of E1 (r = 0): candidates in E0 carry no transfer, the
    // candidate at the same texel of E1 carries −shift exactly.
    let set = analysis.depth(2);
    let m = set.member(0, 2).unwrap();
    let mut same_texel = 0;
    for (i, pair) in set.members[m].candidates.chunks(2).enumerate() {
        assert_eq!(pair[0].member as usize, m);
        assert_eq!(pair[0].transfer, [0; 3]);
        assert_eq!(set.members[pair[1].member as usize].exemplar, 1);
        let u = (i as u32 % 32) | ((i as u32 / 32) << 16);
        if pair[1].coord == u {
            same_texel += 1;
            assert_eq!(pair[1].transfer, shift.map(|s| -s * TRANSFER_ONE));
        }
    }
    assert!(same_texel > 10, "{same_texel}");
    // The fit itself, both ways, at any texels and spacings.
    let px = |e: &Exemplar| -> Vec<[f32; 3]> { e.rgb.iter().map(|c| c.map(f32::from)).collect() };
    let (pa, pb) = (
        px(&analysis_exemplar(&analysis, 0)),
        px(&analysis_exemplar(&analysis, 1)),
    );
    let t = fit_transfer((&pa, 32, 32, 1), (3, 4), (&pb, 32, 32, 1), (3, 4), true);
    assert_eq!(t, shift.map(|s| -s * TRANSFER_ONE));
    let t = fit_transfer((&pb, 32, 32, 4), (30, 1), (&pa, 32, 32, 4), (30, 1), true);
    assert_eq!(t, shift.map(|s| s * TRANSFER_ONE));
}

fn analysis_exemplar(a: &MultiscaleAnalysis, i: usize) -> Exemplar {
    let e = &a.exemplars[i];
    Exemplar::from_rgb("x", e.width, e.height, e.stack[e.finest as usize].clone()).unwrap()
}

/// GIMP's 64² leather as a one-exemplar graph, its multiscale and 2D analyses.
fn leather() -> &'static (Exemplar, MultiscaleAnalysis) {
    static CELL: OnceLock<(Exemplar, MultiscaleAnalysis)> = OnceLock::new();
    CELL.get_or_init(|| {
        let e = Exemplar::load(&asset_exemplar("leather.pat")).unwrap();
        let a = analyze_topology(
            std::slice::from_ref(&e),
            &Topology::new(vec![6], &[], 0),
            &AnalysisParams::default(),
        )
        .unwrap();
        (e, a)
    })
}

#[test]
fn one_exemplar_graph_reproduces_the_2d_synthesizer() {
    let (e, ms) = leather();
    let flat = analyze(e, &AnalysisParams::default()).unwrap();
    // Same appearance, records and similarity sets at every level.
    for (l, level) in flat.levels.iter().enumerate() {
        let m = &ms.depth(l as u32).members[0];
        assert_eq!(m.appearance, level.appearance, "level {l}");
        assert_eq!(m.neighbourhoods, level.neighbourhoods, "level {l}");
        let coords: Vec<u32> = m.candidates.iter().map(|c| c.coord).collect();
        assert_eq!(coords, level.coherence, "level {l}");
    }
    for (seed, w) in [(1, window(0, 0, 48, 40)), (7, window(-77, 33, 40, 24))] {
        let p2 = SynthParams::new(7, seed, &default_passes(7), &default_jitter(7)).unwrap();
        let flat_out = synthesize_cpu(&flat, &p2, w).unwrap();
        let pm = MultiscaleParams::new(seed, 6, &[], &[], DEFAULT_PERIOD_PENALTY).unwrap();
        assert_eq!(pm.jitter, p2.jitter);
        assert_eq!(pm.passes, p2.passes);
        let out = synthesize_multiscale_cpu(ms, &pm, w).unwrap();
        let states = out.window_states();
        assert_eq!(
            states.iter().map(|s| s.coord).collect::<Vec<_>>(),
            flat_out.window_coords()
        );
        assert!(states
            .iter()
            .all(|s| s.level() == 6 && s.transfer == [0; 3]));
        assert_eq!(out.colours(ms), flat_out.colours(e));
    }
}

/// Leather with a reflexive r = 1 edge: a self-similar loop that keeps every pixel native at
/// any depth.
fn looped() -> &'static MultiscaleAnalysis {
    static CELL: OnceLock<MultiscaleAnalysis> = OnceLock::new();
    CELL.get_or_init(|| {
        let (e, _) = leather();
        analyze_topology(
            std::slice::from_ref(e),
            &Topology::new(vec![6], &[(0, 0, 1)], 0),
            &AnalysisParams::default(),
        )
        .unwrap()
    })
}

/// Leather (L = 6) and a 32² terra crop (L = 5) analysed with `edges`.
fn leather_terra(edges: &[(usize, usize, u32)]) -> MultiscaleAnalysis {
    let (e, _) = leather();
    let terra = exemplar_crop("terra.pat", 0, 0, 32, 32);
    analyze_topology(
        &[e.clone(), terra],
        &Topology::new(vec![6, 5], edges, 0),
        &AnalysisParams::default(),
    )
    .unwrap()
}

/// Leather with terra (a leaf) reached with r = 1: at depth 6 leather's finest level is
/// inadmissible, so every pixel moves to terra's level 4 with a colour transfer, and from
/// depth 8 on terra's pixels are magnified.
fn mixed() -> &'static MultiscaleAnalysis {
    static CELL: OnceLock<MultiscaleAnalysis> = OnceLock::new();
    CELL.get_or_init(|| leather_terra(&[(0, 1, 1)]))
}

/// [`mixed`] with a loop on terra (r = 1): past depth 6 the pixels carry transfers into depth
/// sets holding terra's coarsest levels, whose candidates can be period-penalized.
fn mixed_loop() -> &'static MultiscaleAnalysis {
    static CELL: OnceLock<MultiscaleAnalysis> = OnceLock::new();
    CELL.get_or_init(|| leather_terra(&[(0, 1, 1), (1, 1, 1)]))
}

#[test]
fn windows_agree_on_their_overlaps_at_several_levels() {
    let a = mixed();
    for depth in [3u32, 6, 8] {
        let p = MultiscaleParams::new(5, depth, &[], &[], DEFAULT_PERIOD_PENALTY).unwrap();
        let w1 = window(-20, 7, 36, 28);
        let w2 = window(-3, 21, 30, 30);
        let s1 = synthesize_multiscale_cpu(a, &p, w1).unwrap();
        let s2 = synthesize_multiscale_cpu(a, &p, w2).unwrap();
        let l1 = s1.levels.last().unwrap();
        let l2 = s2.levels.last().unwrap();
        let overlap = window(-3, 21, 19, 14);
        assert_eq!(l1.crop(overlap), l2.crop(overlap), "depth {depth}");
        // And at a coarser level of the same syntheses, on the exact regions' overlap.
        if depth > 1 {
            let c1 = &s1.levels[depth as usize - 1];
            let c2 = &s2.levels[depth as usize - 1];
            let ov = window(-2, 12, 8, 6);
            assert_eq!(c1.crop(ov), c2.crop(ov), "depth {}", depth - 1);
        }
    }
}

#[test]
fn a_loop_synthesizes_deeper_than_any_exemplar() {
    let a = looped();
    // Depth 10: 16 times finer than leather's own texels (L = 6).
    let p = MultiscaleParams::new(2, 10, &[], &[], DEFAULT_PERIOD_PENALTY).unwrap();
    let s = synthesize_multiscale_cpu(a, &p, window(1000, -300, 24, 24)).unwrap();
    let states = s.window_states();
    assert!(states
        .iter()
        .all(|s| s.level() != MAGNIFIED && s.level() < 6));
    let colours = s.colours(a);
    let mut distinct = colours.clone();
    distinct.sort();
    distinct.dedup();
    assert!(distinct.len() > 50, "{} colours", distinct.len());
    // Without the loop, the same graph magnifies past leather's finest level.
    let (e, _) = leather();
    let leaf = analyze_topology(
        std::slice::from_ref(e),
        &Topology::new(vec![6], &[], 0),
        &AnalysisParams::default(),
    )
    .unwrap();
    let s = synthesize_multiscale_cpu(&leaf, &p, window(0, 0, 8, 8)).unwrap();
    assert!(s.window_states().iter().all(|s| s.level() == MAGNIFIED));
}

#[test]
fn gpu_equals_cpu_on_every_level() {
    with_gpu(|gpu| {
        // The chain leather → terra (a leaf reached across exemplars, magnified pixels,
        // transfers) at a negative offset, the loop with uneven passes, one depth with none,
        // and the chain with a loop on terra (transfers and the period test together).
        let cases: [(&MultiscaleAnalysis, MultiscaleParams, Region); 3] = [
            (
                mixed(),
                MultiscaleParams::new(3, 9, &[], &[], DEFAULT_PERIOD_PENALTY).unwrap(),
                window(-45, 17, 23, 19),
            ),
            (
                looped(),
                MultiscaleParams::new(11, 8, &[2, 1, 0, 3, 1, 2, 1, 1, 2], &[0.5], 0).unwrap(),
                window(300, -9, 20, 26),
            ),
            (
                mixed_loop(),
                MultiscaleParams::new(7, 8, &[], &[], DEFAULT_PERIOD_PENALTY).unwrap(),
                window(-6, 40, 18, 15),
            ),
        ];
        let mut variants = HashSet::new();
        for (case, (analysis, params, w)) in cases.into_iter().enumerate() {
            let cpu = synthesize_multiscale_cpu(analysis, &params, w).unwrap();
            let g = MultiscaleGpu::new(gpu, analysis).unwrap();
            let (out, times, tested) = g.synthesize_counted(analysis, &params, w, true).unwrap();
            // The kernels that ran: where the test is available the device runs it from the
            // subpass after a pixel reaches a level offering candidates it can penalize.
            for (t, v) in g
                .correction_variants(analysis, &params)
                .into_iter()
                .enumerate()
            {
                let subpasses = 4 * params.passes[t];
                assert!(tested[t] <= subpasses);
                assert!(v.period || tested[t] == 0);
                if tested[t] > 0 {
                    variants.insert(v);
                }
                if tested[t] < subpasses {
                    variants.insert(CorrectionVariant { period: false, ..v });
                }
            }
            assert_eq!(times.len(), cpu.levels.len());
            for (t, (a, b)) in cpu.levels.iter().zip(&out.levels).enumerate() {
                assert_eq!(a.region, b.region);
                let differ = a
                    .states
                    .iter()
                    .zip(&b.states)
                    .filter(|(x, y)| x != y)
                    .count();
                assert_eq!(differ, 0, "case {case}, depth {t}: {differ} states differ");
            }
            // The case exercises what it is meant to: transfers and several exemplars.
            if case == 0 {
                let last = &cpu.levels.last().unwrap().states;
                assert!(last
                    .iter()
                    .all(|s| s.exemplar() == 1 && s.level() == MAGNIFIED));
                assert!(last.iter().filter(|s| s.transfer != [0; 3]).count() > last.len() / 2);
            }
        }
        // Every correction kernel (with and without transfers, with and without the period
        // test) was compared.
        assert_eq!(variants.len(), 4, "variants run: {variants:?}");
    });
}
