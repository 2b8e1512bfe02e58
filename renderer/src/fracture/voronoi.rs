//! Voronoi fracture: each piece is the part of the solid nearer to its site than to any other,
//! made by clipping the mesh with the bisector planes of the site pairs.

use super::plane_split::{check_flags, cut, Cut, Keep, Plane};
use super::topology::{check_closed, used_bounds};
use super::{FractureError, Fragment};
use crate::mesh::Mesh;
use glam::{DVec2, DVec3, Vec3};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Most pieces one fracture may make. Cost grows with pieces × their bisector neighbours
/// and every cell starts from the whole mesh, so far more pieces would rather be made by
/// fracturing fragments again.
pub const MAX_PIECES: usize = 1024;

/// Fractures `mesh` into the Voronoi cells of `sites`, returning the non-empty cells in site
/// order (a site outside the solid may own no part of it; such cells are left out, see
/// [`fracture_cells`] to know which).
///
/// # Errors
/// As [`fracture_cells`].
pub fn fracture(mesh: &Mesh, sites: &[Vec3]) -> Result<Vec<Fragment>, FractureError> {
    Ok(fracture_cells(mesh, sites)?.into_iter().flatten().collect())
}

/// Fractures like [`fracture`] but returns one entry per site, `None` where the cell holds
/// none of the solid. Cap faces are flagged in [`Fragment::interior`].
///
/// # Errors
/// No sites or more than [`MAX_PIECES`], a non-finite or repeated site, a mesh that is invalid
/// or not closed, or a cross-section that cannot be capped (self-intersecting surface).
pub fn fracture_cells(mesh: &Mesh, sites: &[Vec3]) -> Result<Vec<Option<Fragment>>, FractureError> {
    fracture_cells_flagged(mesh, None, sites)
}

/// [`fracture_cells`] with per-triangle interior flags for the input (e.g. to fracture a
/// [`Fragment`] again via [`Fragment::to_mesh`] and its `interior`); flagged triangles keep
/// the flag in the pieces.
///
/// # Errors
/// As [`fracture_cells`], or [`FractureError::FlagCount`] when `interior` does not match.
pub fn fracture_cells_flagged(
    mesh: &Mesh,
    interior: Option<&[bool]>,
    sites: &[Vec3],
) -> Result<Vec<Option<Fragment>>, FractureError> {
    if sites.is_empty() || sites.len() > MAX_PIECES {
        return Err(FractureError::PieceCount {
            requested: sites.len(),
            max: MAX_PIECES,
        });
    }
    if let Some(index) = sites.iter().position(|s| !s.is_finite()) {
        return Err(FractureError::InvalidSite { index });
    }
    let mut order: Vec<usize> = (0..sites.len()).collect();
    order.sort_by(|&a, &b| {
        let (p, q) = (sites[a], sites[b]);
        p.x.total_cmp(&q.x)
            .then(p.y.total_cmp(&q.y))
            .then(p.z.total_cmp(&q.z))
    });
    for w in order.windows(2) {
        if sites[w[0]] == sites[w[1]] {
            return Err(FractureError::DuplicateSites {
                first: w[0].min(w[1]),
                second: w[0].max(w[1]),
            });
        }
    }
    check_closed(mesh)?;
    check_flags(&mesh.triangles, interior, &mesh.source)?;
    (0..sites.len())
        .map(|i| cell(mesh, interior, sites, i))
        .collect()
}

/// Clips the mesh down to the cell of site `i`, nearest bisectors first so the part shrinks
/// early and the bounding-box test can skip most of the remaining planes.
fn cell(
    mesh: &Mesh,
    flags: Option<&[bool]>,
    sites: &[Vec3],
    i: usize,
) -> Result<Option<Fragment>, FractureError> {
    let si = sites[i].as_dvec3();
    let mut others: Vec<(f64, usize)> = (0..sites.len())
        .filter(|&j| j != i)
        .map(|j| (sites[j].as_dvec3().distance_squared(si), j))
        .collect();
    others.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));

    let mut current: Option<Fragment> = None; // None: still the whole mesh
    for (_, j) in others {
        let sj = sites[j].as_dvec3();
        let normal = sj - si;
        let plane = Plane::new(normal, normal.dot((si + sj) * 0.5));
        let (positions, triangles, interior) = match &current {
            Some(f) => (&f.positions[..], &f.triangles[..], Some(&f.interior[..])),
            None => (&mesh.positions[..], &mesh.triangles[..], flags),
        };
        let Some((lo, hi)) = used_bounds(positions, triangles) else {
            return Ok(None);
        };
        // Range of `normal · x` over the box: fully below keeps all, fully above keeps nothing.
        let centre = (lo + hi) * 0.5;
        let radius = ((hi - lo) * 0.5).dot(normal.abs());
        let c = normal.dot(centre) - plane.offset;
        if c + radius < 0.0 {
            continue;
        }
        if c - radius > 0.0 {
            return Ok(None);
        }
        let unit = Plane::new(normal / normal.length(), plane.offset / normal.length());
        match cut(
            positions,
            triangles,
            interior,
            unit,
            Keep::Below,
            &mesh.source,
        )? {
            Cut::AllBelow => {}
            Cut::AllAbove => return Ok(None),
            Cut::Split { below, .. } => {
                let before = current.as_ref().map_or(0, |f| f.resolved_crossings);
                current = below.map(|mut b| {
                    b.resolved_crossings += before;
                    b
                });
            }
        }
    }
    let mut piece = current.unwrap_or_else(|| Fragment {
        positions: mesh.positions.clone(),
        triangles: mesh.triangles.clone(),
        interior: flags.map_or_else(|| vec![false; mesh.triangles.len()], <[bool]>::to_vec),
        ..Fragment::default()
    });
    piece.separate_sheets();
    Ok(Some(piece))
}

/// `n` points uniformly distributed inside the solid, deterministic for a given `seed`:
/// rejection sampling in the bounding box with a winding-number test along a +x ray (a
/// candidate whose ray grazes an edge or vertex is simply rejected, so no degenerate case
/// needs resolving).
///
/// # Errors
/// `n` is 0 or above [`MAX_PIECES`], the mesh is invalid or not closed, or too few points fall
/// inside (a solid filling a tiny part of its box, or a flat one).
pub fn random_sites(mesh: &Mesh, n: usize, seed: u64) -> Result<Vec<Vec3>, FractureError> {
    if n == 0 || n > MAX_PIECES {
        return Err(FractureError::PieceCount {
            requested: n,
            max: MAX_PIECES,
        });
    }
    check_closed(mesh)?;
    let Some((lo, hi)) = used_bounds(&mesh.positions, &mesh.triangles) else {
        return Err(FractureError::Empty {
            mesh: mesh.source.clone(),
        });
    };
    let inside = InsideTest::new(mesh, lo, hi);
    let mut rng = Pcg64::seed_from_u64(seed);
    let attempts = 10_000 + 1_000 * n;
    let mut sites = Vec::with_capacity(n);
    for _ in 0..attempts {
        let p = DVec3::new(
            rng.random_range(lo.x..=hi.x),
            rng.random_range(lo.y..=hi.y),
            rng.random_range(lo.z..=hi.z),
        );
        if inside.winding(p).is_some_and(|w| w != 0) {
            sites.push(p.as_vec3());
            if sites.len() == n {
                return Ok(sites);
            }
        }
    }
    Err(FractureError::Sampling {
        mesh: mesh.source.clone(),
        wanted: n,
        found: sites.len(),
        attempts,
    })
}

/// Winding number along a +x ray, with the triangles bucketed on a (y, z) grid so a query
/// only looks at the triangles its ray can hit.
struct InsideTest<'a> {
    mesh: &'a Mesh,
    lo: DVec2,
    cell: DVec2,
    size: usize,
    /// Triangle ids per grid cell (CSR layout).
    start: Vec<usize>,
    items: Vec<u32>,
    /// Below this |edge function| a ray counts as grazing.
    eps: f64,
}

impl<'a> InsideTest<'a> {
    fn new(mesh: &'a Mesh, lo: DVec3, hi: DVec3) -> Self {
        let size = ((mesh.triangles.len() as f64).sqrt() as usize).clamp(1, 512);
        let lo2 = DVec2::new(lo.y, lo.z);
        let cell =
            (DVec2::new(hi.y, hi.z) - lo2).max(DVec2::splat(f64::MIN_POSITIVE)) / size as f64;
        let yz = |i: u32| {
            let p = mesh.positions[i as usize].as_dvec3();
            DVec2::new(p.y, p.z)
        };
        let range = |tri: &[u32; 3]| {
            let (a, b, c) = (yz(tri[0]), yz(tri[1]), yz(tri[2]));
            let clamp = |v: DVec2| {
                ((v - lo2) / cell)
                    .as_uvec2()
                    .min(glam::UVec2::splat(size as u32 - 1))
            };
            (clamp(a.min(b).min(c)), clamp(a.max(b).max(c)))
        };
        let mut count = vec![0usize; size * size + 1];
        for tri in &mesh.triangles {
            let (a, b) = range(tri);
            for y in a.x..=b.x {
                for z in a.y..=b.y {
                    count[y as usize * size + z as usize + 1] += 1;
                }
            }
        }
        for k in 1..count.len() {
            count[k] += count[k - 1];
        }
        let mut fill = count.clone();
        let mut items = vec![0u32; count[size * size]];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let (a, b) = range(tri);
            for y in a.x..=b.x {
                for z in a.y..=b.y {
                    let slot = &mut fill[y as usize * size + z as usize];
                    items[*slot] = t as u32;
                    *slot += 1;
                }
            }
        }
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        InsideTest {
            mesh,
            lo: lo2,
            cell,
            size,
            start: count,
            items,
            eps: 1e-12 * extent * extent,
        }
    }

    /// Signed number of surface crossings of the ray from `p` towards +x, or `None` when the
    /// ray passes (nearly) through an edge or vertex or `p` lies on the surface.
    fn winding(&self, p: DVec3) -> Option<i32> {
        let q = DVec2::new(p.y, p.z);
        let g = ((q - self.lo) / self.cell)
            .as_uvec2()
            .min(glam::UVec2::splat(self.size as u32 - 1));
        let k = g.x as usize * self.size + g.y as usize;
        let mut winding = 0;
        for &t in &self.items[self.start[k]..self.start[k + 1]] {
            let tri = self.mesh.triangles[t as usize];
            let [a, b, c] = tri.map(|i| self.mesh.positions[i as usize].as_dvec3());
            let edge = |u: DVec3, v: DVec3| {
                let (u, v) = (DVec2::new(u.y, u.z) - q, DVec2::new(v.y, v.z) - q);
                u.x * v.y - u.y * v.x
            };
            let (wa, wb, wc) = (edge(b, c), edge(c, a), edge(a, b));
            let total = wa + wb + wc;
            let all_pos = wa > 0.0 && wb > 0.0 && wc > 0.0;
            let all_neg = wa < 0.0 && wb < 0.0 && wc < 0.0;
            if !all_pos && !all_neg {
                let near = |w: f64| w.abs() <= self.eps;
                let others_agree = (wa >= -self.eps && wb >= -self.eps && wc >= -self.eps)
                    || (wa <= self.eps && wb <= self.eps && wc <= self.eps);
                if others_agree && (near(wa) || near(wb) || near(wc)) {
                    return None;
                }
                continue;
            }
            if wa.abs().min(wb.abs()).min(wc.abs()) <= self.eps {
                return None;
            }
            let x = (wa * a.x + wb * b.x + wc * c.x) / total;
            if x == p.x {
                return None;
            }
            if x > p.x {
                winding += if total > 0.0 { 1 } else { -1 };
            }
        }
        Some(winding)
    }
}
