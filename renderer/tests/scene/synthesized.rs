//! `kind = "synthesized"` textures: the exemplar by path or asset name and how it is fitted, the
//! store it is read through, the synthesis state's memory policy, and `relief` with its range.

use crate::support::{edit, expect, scene_dir};
use lazysolid_renderer::scene::{Scene, SceneError};

/// `kind = "synthesized"`: an exemplar by path (relative to the scene) or asset name, read
/// through a store; a missing file, an unknown name, an unreadable image and a missing store
/// each name the file, the line and the field.
#[test]
fn synthesized_textures_name_their_exemplar_and_store() {
    let (dir, scene) = scene_dir(&[("bad.png", "not a png")]);
    image::RgbImage::new(8, 8)
        .save(dir.path().join("tiny.png"))
        .unwrap();
    let texture = |fields: &str| {
        edit(
            15,
            &format!("texture = {{ kind = \"synthesized\", {fields} }}"),
        )
    };
    let e = Scene::parse(
        &texture("exemplar = \"ex/missing.png\", resolution = 64, store = \"coherent_hash\""),
        &scene,
    )
    .unwrap_err();
    assert!(
        matches!(e, SceneError::MissingFile { line: 15, .. }),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "{}:15: material \"white\".texture.exemplar: {} does not exist",
            scene.display(),
            dir.path().join("ex/missing.png").display()
        )
    );
    let e = Scene::parse(
        &texture("exemplar = \"bad.png\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.exemplar: ") && e.contains("bad.png"),
        "{e}"
    );
    let e = Scene::parse(
        &texture("exemplar = \"no_such_exemplar\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.exemplar: ")
            && (e.contains("no exemplar named \"no_such_exemplar\"") || e.contains("assets/")),
        "{e}"
    );
    expect(
        &texture("exemplar = \"leather\""),
        15,
        "material \"white\".texture.store: missing: a synthesized texture is read through a store",
    );
    // An image of any size is fitted by `lazysolid solid`'s rule, which the render reports.
    let s = Scene::parse(
        &texture("exemplar = \"ground1\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(
        spec.synthesized.as_ref().unwrap().fit.to_string(),
        "ground1.pat 100x100 RGB → Lanczos3 resample 128x128"
    );
    let e = Scene::parse(
        &texture("exemplar = \"tiny.png\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.exemplar: ")
            && e.contains("tiny.png: the image is 8x8; solid synthesis needs at least 16"),
        "{e}"
    );
    expect(
        &texture("exemplar = \"leather\", resolution = 64, store = \"kd_tree\""),
        15,
        "material \"white\".texture.store",
    );
    expect(
        &edit(
            15,
            "texture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], seed = 3 }",
        ),
        15,
        "material \"white\".texture.seed",
    );
    // The synthesis state's memory policy: "keep" or a budget in MB; anything else, or the
    // field on another kind, is refused with the field.
    let s = Scene::parse(
        &texture("exemplar = \"leather\", resolution = 64, store = \"octree\", memory = \"keep\""),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(
        spec.synthesized.as_ref().unwrap().policy,
        lazysolid_synth::solid::lazy::MemoryPolicy::Keep
    );
    for bad in ["lots", "0MB", "12"] {
        let e = Scene::parse(
            &texture(&format!(
                "exemplar = \"leather\", resolution = 64, store = \"octree\", memory = \"{bad}\""
            )),
            &scene,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains(":15: material \"white\".texture.memory: ")
                && e.contains("\"keep\" or a budget in whole MB"),
            "{bad}: {e}"
        );
    }
    expect(
        &edit(
            15,
            "texture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], memory = \"keep\" }",
        ),
        15,
        "material \"white\".texture.memory",
    );
}

/// `relief` on a synthesized texture read through a filtered store: its slope is kept; out of
/// range, not finite, on a nearest store, or on a texture without a feature channel it is
/// refused with the field, the line and the limit.
#[test]
fn relief_is_a_synthesized_texture_field_with_a_stated_range() {
    let (_dir, scene) = scene_dir(&[]);
    let texture = |fields: &str| {
        edit(
            15,
            &format!("texture = {{ kind = \"synthesized\", exemplar = \"cracked\", resolution = 64, {fields} }}"),
        )
    };
    let s = Scene::parse(
        &texture("store = \"coherent_hash\", filter = \"trilinear\", relief = 0.75"),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(spec.synthesized.as_ref().unwrap().relief, 0.75);
    let s = Scene::parse(
        &texture("store = \"tiletree\", filter = \"trilinear\""),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(
        spec.synthesized.as_ref().unwrap().relief,
        0.0,
        "no relief by default"
    );
    for (bad, why) in [
        ("-0.5", "is out of range (must be in [0, 4]"),
        ("4.5", "is out of range (must be in [0, 4]"),
        ("nan", "is not finite"),
        ("inf", "is not finite"),
    ] {
        let e = Scene::parse(
            &texture(&format!(
                "store = \"octree\", filter = \"trilinear\", relief = {bad}"
            )),
            &scene,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains(":15: material \"white\".texture.relief: ") && e.contains(why),
            "{bad}: {e}"
        );
    }
    let e = Scene::parse(&texture("store = \"octree\", relief = 1"), &scene)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.relief: needs a filtered store (filter = \"trilinear\")"),
        "{e}"
    );
    expect(
        &edit(
            15,
            "texture = { kind = \"checker\", color_a = [1, 1, 1], color_b = [0, 0, 0], relief = 1 }",
        ),
        15,
        "material \"white\".texture.relief: relief is read from a synthesized texture's feature channel",
    );
}
