//! Solid textures baked into a store (`store`, `resolution`, `filter`): every structure by
//! name, the resolutions each can hold, and volume textures, which read their NRRD file and can
//! only be read through a store.

use crate::support::{edit, error, expect, parse};
use lazysolid_renderer::scene::{Scene, SolidTextureKind};

#[test]
fn textures_baked_into_stores() {
    use lazysolid_renderer::scene::{StoreFilter, StoreKind, StoreSpec};
    let tex = |extra: &str| {
        edit(
            15,
            &format!(
                "texture = {{ kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0]{extra} }}"
            ),
        )
    };
    let s = parse(&tex(
        ", store = \"octree\", resolution = 256, filter = \"trilinear\"",
    ))
    .unwrap();
    assert_eq!(
        s.materials[0].texture.clone().unwrap().store,
        Some(StoreSpec {
            kind: StoreKind::Octree,
            resolution: 256,
            filter: StoreFilter::Trilinear
        })
    );
    let s = parse(&tex(", store = \"coherent_hash\", resolution = 64")).unwrap();
    assert_eq!(
        s.materials[0]
            .texture
            .clone()
            .unwrap()
            .store
            .unwrap()
            .filter,
        StoreFilter::Nearest
    );
    assert!(parse(&tex("")).unwrap().materials[0]
        .texture
        .clone()
        .unwrap()
        .store
        .is_none());
    expect(
        &tex(", store = \"octree\""),
        15,
        "material \"white\".texture.resolution: is required with `store`",
    );
    expect(
        &tex(", resolution = 64"),
        15,
        "material \"white\".texture.store: is required with `resolution`",
    );
    expect(
        &tex(", store = \"octree\", resolution = 4096"),
        15,
        "material \"white\".texture.resolution: 4096 is out of range (must be in 2..=2048)",
    );
    expect(
        &tex(", filter = \"trilinear\""),
        15,
        "material \"white\".texture.filter: applies only to a texture baked into a store",
    );
    expect(
        &tex(", store = \"octree\", resolution = 2039"),
        15,
        "material \"white\".texture.resolution: 2039 cannot be an octree resolution",
    );
    assert!(parse(&tex(", store = \"coherent_hash\", resolution = 2039")).is_ok());
    let e = error(&tex(", store = \"kd_tree\", resolution = 64"));
    assert!(
        e.contains("scenes/t.toml:15") && e.contains("kd_tree"),
        "{e}"
    );
    // Every structure has a name; the error for an unknown one lists them.
    for name in StoreKind::ALL.iter().map(|k| k.name()) {
        assert!(e.contains(&format!("`{name}`")), "{e}");
        for (filter, want) in [
            ("nearest", StoreFilter::Nearest),
            ("trilinear", StoreFilter::Trilinear),
        ] {
            let s = parse(&tex(&format!(
                ", store = \"{name}\", resolution = 128, filter = \"{filter}\""
            )))
            .unwrap();
            let spec = s.materials[0].texture.clone().unwrap().store.unwrap();
            assert_eq!((spec.kind.name(), spec.filter), (name, want));
        }
    }
    assert_eq!(
        parse(&tex(", store = \"tiletree\", resolution = 64"))
            .unwrap()
            .materials[0]
            .texture
            .clone()
            .unwrap()
            .store
            .unwrap()
            .kind,
        StoreKind::TileTree
    );
    expect(
        &tex(", store = \"tiletree\", resolution = 100"),
        15,
        "material \"white\".texture.resolution: 100 cannot be a tiletree resolution",
    );
    assert!(parse(&tex(", store = \"perfect_hash\", resolution = 100")).is_ok());
    expect(
        &tex(", store = \"perfect_hash\", resolution = 64, filter = \"cubic\""),
        15,
        "material \"white\".texture.filter: unknown variant `cubic`",
    );
}

#[test]
fn volume_textures_read_their_file_through_a_store() {
    // Red then blue along x.
    let nrrd = b"NRRD0004\ntype: uint8\ndimension: 4\nsizes: 3 2 1 1\nencoding: raw\n\n\xff\x00\x00\x00\x00\xff";
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("v.nrrd"), nrrd).unwrap();
    std::fs::write(dir.path().join("bad.nrrd"), b"P6\n").unwrap();
    let scene = dir.path().join("scene.toml");
    let tex = |body: &str| edit(15, &format!("texture = {{ kind = \"volume\"{body} }}"));
    let store = ", store = \"octree\", resolution = 64";
    let s = Scene::parse(&tex(&format!(", path = \"v.nrrd\"{store}")), &scene).unwrap();
    let t = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(t.kind, SolidTextureKind::Volume);
    let v = t.volume.as_ref().unwrap();
    assert_eq!(v.size, [2, 1, 1]);
    assert_eq!(v.at_voxel([31, 0, 0], 64), [255, 0, 0]);
    assert_eq!(v.at_voxel([32, 63, 63], 64), [0, 0, 255]);
    // The flat preview colour is the mean in linear RGB.
    assert!((s.materials[0].color - glam::Vec3::new(0.5, 0.0, 0.5)).length() < 1e-6);

    let err = |text: String| Scene::parse(&text, &scene).unwrap_err().to_string();
    for (body, needle) in [
        (
            ", path = \"v.nrrd\"".to_string(),
            "material \"white\".texture.store: missing: a volume texture is read through a store",
        ),
        (
            store.to_string(),
            "material \"white\".texture.path: missing (a volume texture names its NRRD file)",
        ),
        (
            format!(", path = \"v.nrrd\", color_a = [1, 1, 1]{store}"),
            "material \"white\".texture.color_a: a volume texture has its colours in its file",
        ),
        (
            format!(", path = \"v.nrrd\", scale = 2{store}"),
            "material \"white\".texture.scale: a volume texture",
        ),
        (
            format!(", path = \"absent.nrrd\"{store}"),
            "absent.nrrd does not exist",
        ),
        (
            format!(", path = \"bad.nrrd\"{store}"),
            "bad.nrrd: not an NRRD file",
        ),
    ] {
        let e = err(tex(&body));
        assert!(
            e.contains(":15: ") && e.contains(needle),
            "{needle:?} in {e}"
        );
    }
    let e = err(edit(
        15,
        "texture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], path = \"v.nrrd\" }",
    ));
    assert!(
        e.contains("material \"white\".texture.path: only kind = \"volume\" reads a file"),
        "{e}"
    );
    let e = err(edit(
        15,
        "texture = { kind = \"marble\", color_a = [1, 1, 1] }",
    ));
    assert!(
        e.contains("material \"white\".texture.color_b: missing"),
        "{e}"
    );
}
