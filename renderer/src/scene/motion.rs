//! Where the instances are at a time: pieces of broken instances fly out from the explosion's
//! centre, spin about their own axis through their centre of mass and fall; everything else
//! stays at rest. Only the object-to-world transforms change: a solid texture is read at
//! rest-pose object coordinates, so the matter stays continuous across every crack.
//!
//! With a ground (`[explosion] ground`), a piece stops where it first touches the ground plane
//! and keeps that pose: no bounce, no sliding, no settling onto a face, and pieces do not
//! collide with each other. That is the simplest contact that keeps every piece above the
//! ground in every frame, and it needs no simulation: the pose stays a closed-form function of
//! time, so any frame renders on its own and the same frame is the same image.

use super::{Explosion, Instance, Piece, Scene};
use crate::mesh::Mesh;
use glam::{Affine3A, Quat, Vec3};

/// Step of the search for a piece's first contact, seconds: small enough that a spinning
/// piece's lowest point cannot dip below the ground and come back up between two steps at
/// the spins scenes use (0.4° per step at 100°/s).
const CONTACT_STEP: f32 = 1.0 / 480.0;
/// How long after the start the search follows a piece before giving up (it flies upwards
/// or sideways for ever, or gravity points away from the ground).
const CONTACT_HORIZON: f32 = 120.0;
/// Bisection steps that place the contact between the last step above and the first below.
const CONTACT_BISECTIONS: u32 = 40;

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
        let t = piece.contact.map_or(t, |c| t.min(c));
        pose(&e, inst.transform, &piece, t)
    }
}

/// A piece's transform `t` seconds after the explosion's start, ignoring the ground.
fn pose(e: &Explosion, rest: Affine3A, piece: &Piece, t: f32) -> Affine3A {
    if t == 0.0 {
        return rest;
    }
    let at = rest.transform_point3(piece.centroid);
    let from = e
        .centre
        .unwrap_or_else(|| rest.transform_point3(piece.centre));
    let away = (at - from).try_normalize().unwrap_or(Vec3::Y);
    let moved = at + away * (e.speed * t) + e.gravity * (0.5 * t * t);
    let angle = (e.spin_deg * piece.spin_share * t).to_radians();
    let spin = Quat::from_axis_angle(piece.spin_axis, angle);
    Affine3A::from_translation(moved)
        * Affine3A::from_quat(spin)
        * Affine3A::from_translation(-at)
        * rest
}

/// Seconds after the explosion's start at which the piece (`mesh`, placed by `rest`) first
/// goes below the ground, or below its own lowest point at rest if that is lower (a piece
/// standing on or sunk into the ground at rest may not sink further): the time it stops.
/// `None` without a ground in `e`, or when it does not get there within two minutes.
///
/// The piece's bounding sphere about its centre of mass (which does not change as it spins)
/// finds the first step at which it could touch; from there its vertices are checked step by
/// step and the contact is bisected, so the pose it keeps has its lowest vertex on the ground
/// (within f32 precision), never below it.
pub(super) fn contact_time(
    e: &Explosion,
    rest: Affine3A,
    piece: &Piece,
    mesh: &Mesh,
) -> Option<f32> {
    let ground = e.ground?;
    if mesh.positions.is_empty() {
        return None;
    }
    let up = e.up();
    let lowest = |t: f32| {
        let m = pose(e, rest, piece, t);
        mesh.positions
            .iter()
            .map(|&p| up.dot(m.transform_point3(p)))
            .fold(f32::INFINITY, f32::min)
    };
    let floor = ground.min(lowest(0.0));
    let at = rest.transform_point3(piece.centroid);
    let radius = mesh
        .positions
        .iter()
        .map(|&p| rest.transform_point3(p).distance(at))
        .fold(0.0f32, f32::max);
    let centre_height = |t: f32| up.dot(pose(e, rest, piece, t).transform_point3(piece.centroid));
    let below = |t: f32| lowest(t) < floor;
    let steps = (CONTACT_HORIZON / CONTACT_STEP) as u32;
    let mut above_t = 0.0f32;
    for k in 1..=steps {
        let t = k as f32 * CONTACT_STEP;
        if centre_height(t) - radius > floor {
            above_t = t;
            continue; // the whole piece is above the ground
        }
        if !below(t) {
            above_t = t;
            continue;
        }
        let (mut lo, mut hi) = (above_t, t);
        for _ in 0..CONTACT_BISECTIONS {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if below(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        return Some(lo);
    }
    None
}
