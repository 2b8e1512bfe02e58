//! Relief from the synthesized feature channel in the path tracer (`scenes/test/relief.toml`:
//! a cube of cracked stone on a grey floor, direct light only, one sample per pixel): the
//! render with relief differs from the one without only where the camera sees the textured
//! cube, and there on most pixels (all but the flat ground beyond the features' walls); the albedo is the same (the relief code in alpha does not
//! leak into the colour), only the shading normals bend.

use lazysolid_renderer::output::Film;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::Scene;
use lazysolid_tests::with_gpu;
use std::path::Path;

fn render(scene: &Scene) -> Film {
    with_gpu(|gpu| PathTracer::new(gpu, scene).unwrap().render(|_| {}).unwrap())
}

#[test]
fn relief_changes_only_the_textured_surfaces() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/test/relief.toml");
    let with = Scene::load(&file).unwrap();
    assert_eq!(
        with.render.spp, 1,
        "one sample: the AOVs describe the whole pixel"
    );
    assert_eq!(
        with.render.max_depth, 1,
        "direct light only: the floor cannot see the bumps"
    );
    let mut without = with.clone();
    for m in &mut without.materials {
        if let Some(s) = m.texture.as_mut().and_then(|t| t.synthesized.as_mut()) {
            assert!(s.relief > 0.0);
            s.relief = 0.0;
        }
    }
    let (a, b) = (render(&with), render(&without));
    let (albedo, albedo_b) = (a.albedo().unwrap(), b.albedo().unwrap());
    let (normal, normal_b) = (a.normal().unwrap(), b.normal().unwrap());
    // The floor's albedo is its colour, the sky's 0, the light's its normalized radiance:
    // anything else is the textured cube.
    let grey = [0.5f32; 3];
    let mut textured = 0;
    let mut changed = 0;
    let mut bent = 0;
    for i in 0..a.len() {
        let close = |x: [f32; 3], y: [f32; 3], tol: f32| (0..3).all(|c| (x[c] - y[c]).abs() <= tol);
        assert!(
            close(albedo[i], albedo_b[i], 2e-3),
            "pixel {i}: albedo {:?} with relief, {:?} without",
            albedo[i],
            albedo_b[i]
        );
        let cube = albedo[i] != grey && albedo[i] != [0.0; 3] && albedo[i].iter().all(|&v| v < 0.9);
        if cube {
            textured += 1;
            changed += (a.color()[i] != b.color()[i]) as usize;
            bent += !close(normal[i], normal_b[i], 1e-3) as usize;
        } else {
            assert_eq!(a.color()[i], b.color()[i], "pixel {i} off the cube changed");
            assert_eq!(normal[i], normal_b[i], "pixel {i} off the cube");
        }
    }
    assert!(
        textured > a.len() / 10,
        "the cube fills {textured} of {} pixels",
        a.len()
    );
    // Flat ground far from every feature (beyond the distance's clamp) has no slope, so not
    // every cube pixel changes.
    println!("{changed} of {textured} cube pixels changed, {bent} normals bent");
    assert!(
        bent * 2 > textured,
        "{bent} of {textured} cube normals bent"
    );
    assert!(
        changed * 2 > textured,
        "{changed} of {textured} cube pixels changed"
    );
}
