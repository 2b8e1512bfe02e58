//! Every class of refused scene, each named by file, line and field: TOML syntax, unknown keys
//! and wrong types, missing fields, fields of another kind, out-of-range values, degenerate
//! cameras, unknown or duplicate names and a scene with nothing to render. All of them edit
//! `BASE`, which is checked valid first so that each error is the one edit's.

use crate::support::{append, counts, edit, expect, parse, BASE};
use glam::Vec3;
use lazysolid_renderer::scene::Environment;

#[test]
fn base_scene_is_valid() {
    let s = parse(BASE).unwrap();
    assert_eq!(counts(&s), [1, 1, 1, 0]);
    assert_eq!(s.environment, Environment::Constant(Vec3::ZERO));
}

#[test]
fn toml_syntax_errors_name_the_line() {
    expect(&edit(4, "fov_y = = 40"), 4, "TOML syntax error");
    expect(&edit(10, "name = \"box"), 10, "TOML syntax error");
    expect(
        &append("[camera]\nfov_y = 3\n"),
        19,
        "TOML syntax error: duplicate key (at `camera`)",
    );
}

#[test]
fn unknown_keys_and_wrong_types_name_the_field() {
    expect(
        &edit(4, "fov_y = 40\nfov = 3"),
        5,
        "camera.fov: unknown field `fov`",
    );
    expect(
        &append("[[material]]\nname = \"glass\"\nkind = \"dielectric\"\niorr = 1.5\n"),
        22,
        "material \"glass\".iorr: unknown field `iorr`",
    );
    expect(
        &append("[sky]\nradiance = 1\n"),
        19,
        "sky: unknown field `sky`",
    );
    expect(
        &edit(6, "width = \"64\""),
        6,
        "render.width: invalid type: string \"64\", expected u32",
    );
    expect(
        &edit(6, "width = -64"),
        6,
        "render.width: invalid value: integer `-64`",
    );
    expect(
        &edit(2, "position = [0, 1]"),
        2,
        "camera.position: invalid length 2",
    );
    expect(
        &edit(2, "position = [0, \"1\", 5]"),
        2,
        "camera.position[1]: invalid type: string \"1\", expected f32",
    );
    expect(
        &edit(14, "kind = \"glas\""),
        14,
        "material \"white\".kind: unknown variant `glas`",
    );
    expect(
        &append("[[light]]\nkind = \"point\"\n"),
        20,
        "light #1.kind: unknown variant `point`",
    );
    expect(
        &append("[[instance]]\nmesh = \"box\"\nmaterial = \"white\"\nscale = [1, 2, 1]\n"),
        22,
        "instance #2.scale: invalid type: sequence, expected f32",
    );
}

#[test]
fn missing_required_fields_name_the_table() {
    expect(&edit(8, ""), 5, "render: missing field `spp`");
    let no_camera = BASE.replacen("[camera]", "[kamera]", 1);
    expect(&no_camera, 1, "kamera: unknown field `kamera`");
    let no_camera: String = BASE.lines().skip(4).map(|l| format!("{l}\n")).collect();
    expect(&no_camera, 1, "scene: missing field `camera`");
    expect(&edit(10, ""), 9, "mesh #1: missing field `name`");
    expect(
        &edit(11, ""),
        9,
        "mesh \"box\": needs path = \"file.obj|off\" or shape",
    );
    expect(
        &edit(15, ""),
        12,
        "material \"white\".color: missing (a lambertian material needs color, texture or albedo_map)",
    );
    expect(
        &append("[[material]]\nname = \"glass\"\nkind = \"dielectric\"\n"),
        19,
        "material \"glass\".ior: missing (a dielectric needs it, in (1, 4])",
    );
    expect(
        &append("[[material]]\nname = \"metal\"\nkind = \"conductor\"\nroughness = 0.2\n"),
        19,
        "material \"metal\".color: missing (a conductor needs preset, or color (η) and k (κ))",
    );
    expect(
        &append("[[material]]\nname = \"shiny\"\nkind = \"plastic\"\ncolor = [0.5, 0.5, 0.5]\n"),
        19,
        "material \"shiny\".roughness: missing (a plastic material needs it, in [0, 1])",
    );
    expect(
        &append("[[material]]\nname = \"lamp\"\nkind = \"emissive\"\n"),
        19,
        "material \"lamp\".emission: missing (an emissive material needs it)",
    );
    expect(
        &append("[[light]]\nkind = \"sphere\"\nradiance = [1, 1, 1]\nradius = 1\n"),
        19,
        "light #1.center: missing (a sphere light needs center, radius and radiance)",
    );
    expect(
        &append("[[light]]\nkind = \"quad\"\nradiance = [1, 1, 1]\ncorner = [0, 2, 0]\nedge_u = [1, 0, 0]\n"),
        19,
        "light #1.edge_v: missing (a quad light needs corner, edge_u, edge_v and radiance)",
    );
    expect(
        &edit(4, "fov_y = 40\naperture_radius = 0.1"),
        5,
        "camera.focus_distance: missing: a thin lens needs both",
    );
    expect(
        &append("[[material]]\nname = \"m\"\nkind = \"lambertian\"\ntexture = { kind = \"wood\", color_a = [1, 1, 1] }\n"),
        22,
        "material \"m\".texture.color_b: missing (a marble, wood or checker texture blends two colours)",
    );
    expect(
        &append("[environment]\n"),
        19,
        "environment: needs radiance = [r, g, b] or path",
    );
}

#[test]
fn fields_of_another_kind_name_the_kinds_that_accept_them() {
    expect(
        &edit(15, "color = [0.5, 0.5, 0.5]\nior = 1.5"),
        16,
        "material \"white\".ior: does not apply to a lambertian material (accepted by: plastic, dielectric)",
    );
    expect(
        &append("[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 1.5\ntexture = { kind = \"wood\", color_a = [1, 1, 1], color_b = [0, 0, 0] }\n"),
        23,
        "material \"glass\".texture: does not apply to a dielectric material (accepted by: lambertian, plastic)",
    );
    expect(
        &append("[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nemission = [1, 1, 1]\nroughness = 0.5\n"),
        23,
        "material \"lamp\".roughness: does not apply to an emissive material",
    );
    expect(
        &append("[[material]]\nname = \"gold\"\nkind = \"conductor\"\npreset = \"gold\"\nroughness = 0.2\nk = [1, 1, 1]\n"),
        24,
        "material \"gold\".k: a preset gives both η and κ",
    );
    expect(
        &append("[[material]]\nname = \"m\"\nkind = \"plastic\"\nroughness = 0.2\ncolor = [1, 1, 1]\ntexture = { kind = \"wood\", color_a = [1, 1, 1], color_b = [0, 0, 0] }\n"),
        24,
        "material \"m\".texture: color and texture are exclusive",
    );
    expect(
        &append("[[light]]\nkind = \"sphere\"\nradiance = [1, 1, 1]\ncenter = [0, 2, 0]\nradius = 1\ntwo_sided = true\n"),
        24,
        "light #1.two_sided: only quad lights have it",
    );
    expect(
        &edit(11, "shape = \"cube\"\nsubdivisions = 2"),
        12,
        "mesh \"box\".subdivisions: only shape = \"sphere\" has it",
    );
    expect(
        &edit(11, "shape = \"cube\"\nnormalize = false"),
        12,
        "mesh \"box\".normalize: only mesh files have it",
    );
    expect(
        &edit(11, "shape = \"cube\"\npath = \"cube.off\""),
        11,
        "mesh \"box\".shape: path and shape are exclusive",
    );
    expect(
        &append("[environment]\nradiance = [1, 1, 1]\nintensity = 2\n"),
        21,
        "environment.intensity: only a map (path) has it",
    );
    expect(
        &append("[environment]\nradiance = [1, 1, 1]\npath = \"sky.exr\"\n"),
        21,
        "environment.path: radiance and path are exclusive",
    );
}

#[test]
fn out_of_range_values_state_the_limit() {
    let cases: &[(usize, &str, &str)] = &[
        (6, "width = 0", "render.width: 0 is out of range (must be in 1..=8192)"),
        (7, "height = 8193", "render.height: 8193 is out of range (must be in 1..=8192)"),
        (8, "spp = 0", "render.spp: 0 is out of range (must be in 1..=1048576)"),
        (8, "spp = 1048577", "render.spp: 1048577 is out of range"),
        (8, "spp = 4\nmax_depth = 65", "render.max_depth: 65 is out of range (must be in 0..=64)"),
        (8, "spp = 4\nrr_depth = 65", "render.rr_depth: 65 is out of range (must be in 0..=64)"),
        (4, "fov_y = 180", "camera.fov_y: 180 is out of range (must be in (0, 180) degrees)"),
        (4, "fov_y = 0", "camera.fov_y: 0 is out of range"),
        (4, "fov_y = nan", "camera.fov_y: NaN is not finite"),
        (4, "fov_y = inf", "camera.fov_y: inf is not finite"),
        (2, "position = [0, inf, 5]", "camera.position: [0.0, inf, 5.0] has a non-finite component"),
        (
            15,
            "color = [0.5, 1.2, 0.5]",
            "material \"white\".color: channel 1 of [0.5, 1.2, 0.5] is 1.2, out of range (must be in [0, 1]",
        ),
        (15, "color = [-0.1, 0.5, 0.5]", "material \"white\".color: channel 0 of [-0.1, 0.5, 0.5] is -0.1"),
        (15, "color = [0.5, 0.5, nan]", "material \"white\".color: [0.5, 0.5, NaN] has a non-finite component"),
        (18, "material = \"white\"\nscale = 0", "instance #1.scale: 0 is out of range (must be > 0)"),
        (18, "material = \"white\"\nscale = -2", "instance #1.scale: -2 is out of range"),
        (18, "material = \"white\"\nrotate = [0, nan, 0]", "instance #1.rotate: [0.0, NaN, 0.0] has a non-finite component"),
        (11, "shape = \"sphere\"\nsubdivisions = 8", "mesh \"box\".subdivisions: 8 is out of range (must be in 0..=7)"),
        (4, "fov_y = 40\nfocus_distance = 3\naperture_radius = 0", "camera.aperture_radius: 0 is out of range (must be > 0)"),
    ];
    for &(line, with, expected) in cases {
        let report_line = line + with.lines().count() - 1;
        expect(&edit(line, with), report_line, expected);
    }
    let more: &[(&str, usize, &str)] = &[
        (
            "[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 0.8\n",
            22,
            "material \"glass\".ior: 0.8 is out of range (must be in (1, 4])",
        ),
        (
            "[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 4.5\n",
            22,
            "material \"glass\".ior: 4.5 is out of range (must be in (1, 4])",
        ),
        (
            "[[material]]\nname = \"m\"\nkind = \"plastic\"\ncolor = [1, 1, 1]\nroughness = 1.5\n",
            23,
            "material \"m\".roughness: 1.5 is out of range (must be in [0, 1])",
        ),
        (
            "[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nemission = [5, -1, 5]\n",
            22,
            "material \"lamp\".emission: channel 1 of [5.0, -1.0, 5.0] is -1, out of range (must be ≥ 0)",
        ),
        (
            "[[material]]\nname = \"m\"\nkind = \"lambertian\"\ntexture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 2, 0] }\n",
            22,
            "material \"m\".texture.color_b: channel 1 of [0.0, 2.0, 0.0] is 2",
        ),
        (
            "[[material]]\nname = \"m\"\nkind = \"lambertian\"\ntexture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], scale = -1 }\n",
            22,
            "material \"m\".texture.scale: -1 is out of range (must be > 0)",
        ),
        (
            "[[light]]\nkind = \"sphere\"\ncenter = [0, 2, 0]\nradius = 0\nradiance = [1, 1, 1]\n",
            22,
            "light #1.radius: 0 is out of range (must be > 0)",
        ),
        (
            "[[light]]\nkind = \"sphere\"\ncenter = [0, 2, 0]\nradius = 1\nradiance = [1, inf, 1]\n",
            23,
            "light #1.radiance: [1.0, inf, 1.0] has a non-finite component",
        ),
        (
            "[[light]]\nkind = \"quad\"\ncorner = [0, 2, 0]\nedge_u = [1, 0, 0]\nedge_v = [2, 0, 0]\nradiance = [1, 1, 1]\n",
            23,
            "light #1.edge_v: the quad has zero area (edge_u [1, 0, 0] and edge_v [2, 0, 0] are parallel or zero)",
        ),
        (
            "[[light]]\nkind = \"quad\"\ncorner = [0, 2, 0]\nedge_u = [0, 0, 0]\nedge_v = [0, 0, 1]\nradiance = [1, 1, 1]\n",
            23,
            "light #1.edge_v: the quad has zero area",
        ),
        (
            "[environment]\nradiance = [-1, 0, 0]\n",
            20,
            "environment.radiance: channel 0 of [-1.0, 0.0, 0.0] is -1",
        ),
    ];
    for &(text, line, expected) in more {
        expect(&append(text), line, expected);
    }
}

#[test]
fn degenerate_cameras_are_rejected() {
    expect(
        &edit(3, "look_at = [0, 1, 5]"),
        3,
        "camera.look_at: [0, 1, 5] equals camera.position: the view direction is undefined",
    );
    expect(
        &edit(3, "look_at = [0, -3, 5]"),
        1,
        "camera.up: the default up [0, 1, 0] is parallel to the view direction",
    );
    expect(
        &edit(3, "look_at = [0, 1, 0]\nup = [0, 0, -2]"),
        4,
        "camera.up: camera.up is parallel to the view direction",
    );
    expect(
        &edit(3, "look_at = [0, 1, 0]\nup = [0, 0, 0]"),
        4,
        "camera.up: camera.up is parallel",
    );
}

#[test]
fn names_must_be_unique_and_known() {
    expect(
        &edit(17, "mesh = \"boxx\""),
        17,
        "instance #1.mesh: unknown mesh \"boxx\" (defined: \"box\")",
    );
    expect(
        &edit(18, "material = \"red\""),
        18,
        "instance #1.material: unknown material \"red\" (defined: \"white\")",
    );
    expect(
        &append("[[mesh]]\nname = \"box\"\nshape = \"quad\"\n"),
        20,
        "mesh #2.name: duplicate name: mesh \"box\" is already defined on line 10",
    );
    expect(
        &append("[[material]]\nname = \"white\"\nkind = \"lambertian\"\ncolor = [1, 1, 1]\n"),
        20,
        "material #2.name: duplicate name: material \"white\" is already defined on line 13",
    );
    expect(
        &edit(10, "name = \"\""),
        10,
        "mesh #1.name: must not be empty",
    );
}

#[test]
fn a_scene_without_instances_is_rejected() {
    let text: String = BASE.lines().take(15).map(|l| format!("{l}\n")).collect();
    expect(
        &text,
        15,
        "instance: the scene has no [[instance]]: there would be nothing to render",
    );
}
