//! Where the instances are at a time: pieces of broken instances fly out from the explosion's
//! centre, spin about their own axis through their centre of mass and fall; everything else
//! stays at rest. Only the object-to-world transforms change: a solid texture is read at
//! rest-pose object coordinates, so the matter stays continuous across every crack.

use super::{Instance, Scene};
use glam::{Affine3A, Quat};

impl Scene {
    /// The time of frame `frame` of the scene's animation (0 without one).
    pub fn frame_time(&self, frame: u32) -> f32 {
        self.animation.map_or(0.0, |a| frame as f32 / a.fps)
    }

    /// The object-to-world transform of instance `i` at `time` (seconds).
    pub fn instance_transform(&self, i: usize, time: f32) -> Affine3A {
        let inst: &Instance = &self.instances[i];
        let (Some(piece), Some(e)) = (inst.piece, self.explosion) else {
            return inst.transform;
        };
        let t = (time - e.start).max(0.0);
        if t == 0.0 {
            return inst.transform;
        }
        let at = inst.transform.transform_point3(piece.centroid);
        let from = e
            .centre
            .unwrap_or_else(|| inst.transform.transform_point3(piece.centre));
        let away = (at - from).try_normalize().unwrap_or(glam::Vec3::Y);
        let moved = at + away * (e.speed * t) + e.gravity * (0.5 * t * t);
        let angle = (e.spin_deg * piece.spin_share * t).to_radians();
        let spin = Quat::from_axis_angle(piece.spin_axis, angle);
        Affine3A::from_translation(moved)
            * Affine3A::from_quat(spin)
            * Affine3A::from_translation(-at)
            * inst.transform
    }
}
