//! How often a candidate triple can continue coherently in two roles at once: what the
//! candidate sets allow a step that keeps two roles' copies running.
//!
//! Two roles `e` and `f` share one world axis `s` (`roles.rs`). One voxel further along `s`, a
//! triple that continues both roles coherently has `e`'s and `f`'s coordinates each moved by
//! one exemplar step along their image of `s`. The correction only places candidate triples,
//! so such a continuation exists only where the set of `e`'s next pixel holds a triple with
//! `f`'s coordinate moved by that step. Where it does not, a coherent run in `e`'s plane ends
//! or turns incoherent in `f`'s. Measured in `docs/log/solid.md` ("What caps the slices'
//! coherence").

use super::candidates::CandidateSets;
use super::roles::{image_axis, shared_axis, ROLES};
use super::strips::along;
use crate::coords::unpack;

/// Per role `e`: over every candidate `t` of every pixel and each of `e`'s two other roles
/// `f`, the share for which the set of `e`'s pixel one step `h` further along the world axis
/// `e` and `f` share holds a triple whose `f` coordinate is `t`'s moved by the same step
/// (`sets` one level's sets of `E_x`, `E_y`, `E_z` over an `m`×`m` exemplar).
pub fn advance_closure(sets: &[CandidateSets; ROLES], h: u32, m: u32) -> [f64; ROLES] {
    let index = |c: u32| {
        let (x, y) = unpack(c);
        y * m + x
    };
    std::array::from_fn(|e| {
        let (mut continued, mut pairs) = (0u64, 0u64);
        for p in 0..m * m {
            for t in sets[e].of(p as usize) {
                for f in (0..ROLES).filter(|&f| f != e) {
                    let s = shared_axis(e, f);
                    let (ie, jf) = (image_axis(e, s).unwrap(), image_axis(f, s).unwrap());
                    let next = along(p, ie, h as i32, m);
                    let want = along(index(t[f]), jf, h as i32, m);
                    pairs += 1;
                    continued += u64::from(
                        sets[e]
                            .of(next as usize)
                            .iter()
                            .any(|u| index(u[f]) == want),
                    );
                }
            }
        }
        continued as f64 / pairs.max(1) as f64
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coords::pack;
    use crate::solid::ROLE_AXES;

    /// One candidate per pixel, `triple(e, u, v)` for pixel `(u, v)` of role `e`.
    fn sets(m: u32, triple: impl Fn(usize, u32, u32) -> [u32; 3]) -> [CandidateSets; ROLES] {
        std::array::from_fn(|e| CandidateSets {
            slots: 1,
            triples: (0..m * m).map(|p| triple(e, p % m, p / m)).collect(),
            errors: vec![0; (m * m) as usize],
            counts: vec![1; (m * m) as usize],
        })
    }

    #[test]
    fn a_three_d_exemplar_is_closed_and_a_constant_role_is_not() {
        let m = 16;
        // The triples of a volume that is every role's exemplar laid out in place: pixel (u, v)
        // of role e is the world position with e's axes at (u, v) and 0 along e's normal, and
        // each role's coordinate is that position seen in the role's plane.
        let volume = sets(m, |e, u, v| {
            let mut w = [0u32; 3];
            let [a, b] = ROLE_AXES[e];
            (w[a], w[b]) = (u, v);
            std::array::from_fn(|r| {
                let [a, b] = ROLE_AXES[r];
                pack(w[a], w[b])
            })
        });
        assert_eq!(advance_closure(&volume, 1, m), [1.0; 3]);
        assert_eq!(advance_closure(&volume, 4, m), [1.0; 3]);
        // Every other coordinate at the origin: no step continues it.
        let constant = sets(m, |e, u, v| {
            std::array::from_fn(|r| if r == e { pack(u, v) } else { pack(0, 0) })
        });
        assert_eq!(advance_closure(&constant, 1, m), [0.0; 3]);
    }
}
