//! `[explosion]` and `[animation]`: pieces at rest until the start and rigid after it, the main
//! job's scene, and `ground`, which stops falling pieces in every frame.

use crate::support::{broken, example, expect, parse};
use glam::Vec3;
use lazysolid_renderer::scene::{Scene, SolidTextureKind};

/// Pieces stay at rest until the explosion starts, then move rigidly: their centre of mass
/// flies away from the centre at the given speed and falls; lookups keep rest-pose object
/// coordinates, so only the transform changes.
#[test]
fn pieces_fly_apart_rigidly_after_the_start() {
    let s = parse(&broken(
        "[[fracture]]\ninstance = \"b\"\npieces = 3\nseed = 1\n\
         [explosion]\ncentre = [0.5, 0.5, 0.5]\nspeed = 2\nspin = 45\ngravity = [0, -1, 0]\nstart = 0.5\n\
         [animation]\nframes = 10\nfps = 4\n",
    ))
    .unwrap();
    let a = s.animation.unwrap();
    assert_eq!((a.frames, a.fps), (10, 4.0));
    assert_eq!(s.frame_time(3), 0.75);
    for (i, inst) in s.instances.iter().enumerate() {
        let p = inst.piece.unwrap();
        assert_eq!(s.instance_transform(i, 0.5), inst.transform);
        let t = 1.5;
        let m = s.instance_transform(i, t);
        let at = inst.transform.transform_point3(p.centroid);
        let away = (at - Vec3::splat(0.5)).normalize();
        let want = at + away * 2.0 * 1.0 + Vec3::new(0.0, -0.5, 0.0);
        assert!((m.transform_point3(p.centroid) - want).length() < 1e-4);
        // Rigid: distances between the piece's vertices are kept.
        let v = &s.meshes[inst.mesh].mesh.positions;
        let d0 = v[0].distance(v[v.len() / 2]);
        let d1 = m
            .transform_point3(v[0])
            .distance(m.transform_point3(v[v.len() / 2]));
        assert!((d0 - d1).abs() < 1e-5);
    }
}

/// The main job's scene: the armadillo broken into 14 closed pieces sharing its synthesized
/// texture, an explosion, and an animation rendered smaller than the still.
#[test]
fn explosion_scene_loads() {
    let s = example("explosion.toml");
    assert_eq!(s.instances.len(), 15);
    assert_eq!(s.instances.iter().filter(|i| i.piece.is_some()).count(), 14);
    let e = s.explosion.expect("an explosion");
    assert_eq!((e.speed, e.start), (1.6, 0.25));
    assert_eq!(s.render.spp, 32);
    let a = s.animation.expect("an animation");
    assert_eq!((a.frames, a.width, a.height, a.spp), (16, 320, 240, 8));
    assert_eq!((s.render.width, s.render.height), (640, 480));
    let synthesized = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(synthesized.kind, SolidTextureKind::Synthesized);
    assert!(
        synthesized.synthesized.as_ref().unwrap().relief > 0.0,
        "the main job shows the matter's relief"
    );
}

/// The lowest point of every piece, along the explosion's "up", in each frame of the scene's
/// animation (sampled four times per frame): per frame, the minimum over pieces, and the
/// minimum over pieces of their own lowest point at rest.
fn lowest_per_frame(s: &Scene) -> (Vec<f32>, f32) {
    let e = s.explosion.unwrap();
    let up = e.up();
    let a = s.animation.unwrap();
    let lowest_at = |i: usize, t: f32| {
        let m = s.instance_transform(i, t);
        s.meshes[s.instances[i].mesh]
            .mesh
            .positions
            .iter()
            .map(|&p| up.dot(m.transform_point3(p)))
            .fold(f32::INFINITY, f32::min)
    };
    let pieces: Vec<usize> = (0..s.instances.len())
        .filter(|&i| s.instances[i].piece.is_some())
        .collect();
    let rest = pieces
        .iter()
        .map(|&i| lowest_at(i, 0.0))
        .fold(f32::INFINITY, f32::min);
    let frames = (0..a.frames * 4)
        .map(|k| {
            let t = k as f32 / (4.0 * a.fps);
            pieces
                .iter()
                .map(|&i| lowest_at(i, t))
                .fold(f32::INFINITY, f32::min)
        })
        .collect();
    (frames, rest)
}

/// With `[explosion] ground`, no piece of the main job's scene or the fracture test scene goes
/// below the ground (or below its own rest height, for pieces standing on it) in any frame;
/// without it the same pieces do, so the check can fail. Pieces that touch it keep their pose.
#[test]
fn pieces_stop_on_the_ground() {
    for name in ["explosion.toml", "test/fracture.toml"] {
        let s = example(name);
        let e = s.explosion.unwrap();
        let ground = e.ground.expect("the scene has a ground");
        let (frames, rest) = lowest_per_frame(&s);
        let floor = ground.min(rest);
        for (k, &h) in frames.iter().enumerate() {
            assert!(
                h >= floor - 1e-4,
                "{name} sample {k}: lowest point {h} below {floor}"
            );
        }
        let stopped = s
            .instances
            .iter()
            .filter(|i| i.piece.is_some_and(|p| p.contact.is_some()))
            .count();
        println!("{name}: ground {ground}, rest {rest}, {stopped} piece(s) stop on it, lowest per frame {frames:?}");
        assert!(stopped > 0, "{name}: no piece reaches the ground");
        // A stopped piece keeps its pose.
        for (i, inst) in s.instances.iter().enumerate() {
            if let Some(c) = inst.piece.and_then(|p| p.contact) {
                let t = e.start + c;
                assert_eq!(
                    s.instance_transform(i, t + 2.0),
                    s.instance_transform(i, t + 0.5)
                );
            }
        }
        // Without the ground, pieces fall through it.
        let mut free = s.clone();
        for inst in &mut free.instances {
            if let Some(p) = &mut inst.piece {
                p.contact = None;
            }
        }
        let (frames, _) = lowest_per_frame(&free);
        let deepest = frames.iter().copied().fold(f32::INFINITY, f32::min);
        assert!(
            deepest < floor - 0.05,
            "{name}: without a ground the lowest point is {deepest}"
        );
    }
    expect(
        &broken(
            "[[fracture]]\ninstance = \"b\"\npieces = 2\n[explosion]\nspeed = 1\nground = 1e9\n",
        ),
        25,
        "explosion.ground",
    );
}
