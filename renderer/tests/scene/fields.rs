//! What accepted fields turn into: the order of an instance's translate, rotate and scale, the
//! thin-lens camera and the conductor presets. The refused values are in `errors`.

use crate::support::{parse, BASE};
use glam::Vec3;
use lazysolid_renderer::scene::{Lens, MaterialKind};

#[test]
fn instance_transform_is_translate_rotate_x_then_y_then_z_scale() {
    let text = BASE.replace(
        "material = \"white\"\n",
        "material = \"white\"\nrotate = [90, 90, 0]\nscale = 2\ntranslate = [10, 20, 30]\n",
    );
    let s = parse(&text).unwrap();
    let t = s.instances[0].transform;
    // x first: (0, 1, 0) → (0, 0, 1) about x, then → (1, 0, 0) about y.
    let p = t.transform_point3(Vec3::Y);
    assert!((p - Vec3::new(12.0, 20.0, 30.0)).length() < 1e-5, "{p}");
    let v = t.transform_vector3(Vec3::Z);
    // (0, 0, 1) → (0, -1, 0) about x, unchanged about y, doubled.
    assert!((v - Vec3::new(0.0, -2.0, 0.0)).length() < 1e-5, "{v}");
}

#[test]
fn thin_lens_and_presets() {
    let text = BASE
        .replace(
            "fov_y = 40\n",
            "fov_y = 40\naperture_radius = 0.05\nfocus_distance = 4.5\n",
        )
        .replace(
            "kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]",
            "kind = \"conductor\"\npreset = \"copper\"\nroughness = 0.1",
        );
    let s = parse(&text).unwrap();
    assert_eq!(
        s.camera.lens,
        Lens::ThinLens {
            aperture_radius: 0.05,
            focus_distance: 4.5
        }
    );
    let m = &s.materials[0];
    assert_eq!((m.kind, m.roughness), (MaterialKind::Conductor, 0.1));
    // Copper: reddish (κ and reflectance highest in red).
    assert!(m.k.x > m.k.y && m.k.y > m.k.z, "{m:?}");
}
