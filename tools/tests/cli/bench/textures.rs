//! `lazysolid bench textures`: the volume stores' table and pictures (the same texels through every
//! structure), and resolutions, meshes, stores and filters that measure nothing refused.

use crate::support::{lazysolid, repo, run, BenchRun};

#[test]
fn bench_textures_writes_the_table_pictures_and_files() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "textures", "--voxel-res", "64", "--res", "64x64"])
            .args(["--runs", "1", "--warmup", "0", "--mesh"])
            .arg(repo("assets/meshes/bunny00.off")),
        out.path(),
        &[
            "Table 4.1 on",
            "octree 8·8 (nearest)",
            "octree 4·4·4 (8 descents)",
            "coherent hash (8 lookups)",
            "perfect hash (nearest)",
            "perfect hash blocked, b = ",
            "tiletree (bilinear, 1 fetch)",
            "stands for the thesis' octree texture, 8 lookups (Table 4.1)",
        ],
    );
    let json = bench.json();
    // --builder auto: the perfect hash (texel layout) is built on the host on a CPU device,
    // on the GPU otherwise; the blocked layout always on the host; other rows name none.
    let auto = if json["run"]["device_type"] == "cpu" {
        "cpu"
    } else {
        "gpu"
    };
    for row in json["rows"].as_array().unwrap() {
        let implementation = row["implementation"].as_str().unwrap();
        let expected = if implementation.starts_with("perfect hash blocked") {
            Some("cpu")
        } else if implementation.starts_with("perfect hash") {
            Some(auto)
        } else {
            None
        };
        assert_eq!(row["builder"].as_str(), expected, "{implementation}");
    }
    let derived = json["derived"].as_object().unwrap();
    let seen = derived["viewpoint surface points"].as_f64().unwrap();
    assert!(seen > 500.0, "{seen}");
    // The voxelization is conservative: every point the camera sees lies in stored texels.
    let missing: Vec<_> = derived
        .iter()
        .filter(|(k, _)| k.ends_with("points not stored"))
        .collect();
    assert_eq!(missing.len(), 2 * 6 + 1, "{missing:?}");
    assert!(
        missing.iter().all(|(_, v)| v.as_f64() == Some(0.0)),
        "{missing:?}"
    );
    let figures = bench.figures();
    let picture = |name: &str| image::open(figures.join(name)).unwrap().to_rgb8();
    for f in [
        "textures-memory.png",
        "textures-speed.png",
        "tiletree-tile-map.png",
    ] {
        assert!(figures.join(f).exists(), "missing {f}");
    }
    // The same texels through different structures: nearest pictures are identical, trilinear
    // ones agree to float rounding.
    for other in ["coherent-hash-nearest.png", "perfect-hash-nearest.png"] {
        assert_eq!(picture("octree-8-8-nearest.png"), picture(other), "{other}");
    }
    let a = picture("octree-8-8-8-descents.png");
    assert_eq!(a.dimensions(), (64, 64));
    for other in ["coherent-hash-8-lookups.png", "perfect-hash-8-lookups.png"] {
        let worst = a
            .as_raw()
            .iter()
            .zip(picture(other).as_raw())
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap();
        assert!(worst <= 1, "{other}: {worst}");
    }
    // The TileTree samples the surface where the volume stores sample voxel centres: close to
    // the trilinear picture (FLIP), closer than the nearest one is.
    let flip = |a: &str, b: &str| {
        let (ok, out, err) = run(lazysolid()
            .arg("diff")
            .arg(figures.join(a))
            .arg(figures.join(b)));
        assert!(ok, "{err}");
        let mean = out
            .lines()
            .find_map(|l| l.strip_prefix("FLIP mean"))
            .unwrap_or_else(|| panic!("no FLIP mean in {out}"));
        mean.trim().parse::<f64>().unwrap()
    };
    let tile = flip("octree-8-8-8-descents.png", "tiletree-bilinear-1-fetch.png");
    let nearest = flip("octree-8-8-8-descents.png", "octree-8-8-nearest.png");
    assert!(
        tile < 0.05 && tile < nearest,
        "tiletree {tile}, nearest {nearest}"
    );
}

#[test]
fn bench_textures_refuses_bad_resolutions_views_and_meshes() {
    let (ok, _, err) = run(lazysolid().args(["bench", "textures", "--res", "8x8"]));
    assert!(
        !ok && err.contains("--res 8x8 is out of range (16..=4096 per side)"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "textures", "--mesh", "/no/such/mesh.off"]));
    assert!(!ok && err.contains("/no/such/mesh.off"), "{err}");
    let (ok, _, err) = run(lazysolid()
        .args(["bench", "textures", "--voxel-res", "100000", "--mesh"])
        .arg(repo("assets/meshes/cube.off")));
    assert!(!ok && err.contains("100000"), "{err}");
    let (ok, _, err) = run(lazysolid()
        .args([
            "bench",
            "textures",
            "--voxel-res",
            "64",
            "--octree",
            "8.4",
            "--mesh",
        ])
        .arg(repo("assets/meshes/cube.off")));
    assert!(!ok && err.contains("--octree \"8.4\""), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bench_textures_refuses_store_and_filter_choices_that_measure_nothing() {
    let (ok, _, err) = run(lazysolid().args([
        "bench",
        "textures",
        "--stores",
        "perfect-blocked",
        "--filters",
        "nearest",
    ]));
    assert!(!ok && err.contains("trilinear"), "{err}");
    let (ok, _, err) = run(lazysolid().args(["bench", "textures", "--stores", "kd-tree"]));
    assert!(
        !ok && err.contains("'kd-tree'")
            && err.contains("octree, hash, perfect, perfect-blocked, tiletree"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "psh", "--builder", "fpga"]));
    assert!(
        !ok && err.contains("'fpga'") && err.contains("auto, cpu, gpu"),
        "{err}"
    );
}
