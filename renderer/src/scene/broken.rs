//! `[[cut]]`, `[[fracture]]`, `[explosion]` and `[animation]`: named instances broken into
//! closed pieces (plane cuts first, in file order, then Voronoi cells of every piece), each
//! piece a mesh of its own in the broken mesh's coordinates with its cap faces marked, and one
//! instance per piece in place of the broken one.

use super::location::{element_label, join, Doc};
use super::raw::{RawAnimation, RawCut, RawExplosion, RawFracture};
use super::{
    Animation, Explosion, Instance, Piece, RenderSettings, SceneError, SceneMesh, MAX_IMAGE_SIDE,
    MAX_SPP,
};
use crate::fracture::{
    cut_pieces, fracture_cells_flagged, random_sites, Fragment, Plane, MAX_PIECES,
};
use crate::mesh::Mesh;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use std::collections::HashMap;
use toml::Spanned;

/// What `[[cut]]` and `[[fracture]]` ask of one instance.
#[derive(Default)]
struct Breaks<'a> {
    cuts: Vec<(&'a RawCut, String)>,
    fracture: Option<(&'a RawFracture, String)>,
}

/// Replaces every instance named by a `[[cut]]` or `[[fracture]]` with its pieces (new meshes
/// appended to `meshes`).
pub(super) fn break_instances(
    doc: &Doc,
    cuts: &[Spanned<RawCut>],
    fractures: &[Spanned<RawFracture>],
    instance_names: &HashMap<&str, usize>,
    meshes: &mut Vec<SceneMesh>,
    instances: Vec<Instance>,
    seed: u32,
) -> Result<Vec<Instance>, SceneError> {
    let mut breaks: HashMap<usize, Breaks> = HashMap::new();
    for (i, c) in cuts.iter().enumerate() {
        let label = element_label("cut", i, None);
        let inst = named_instance(doc, instance_names, &c.get_ref().instance, &label)?;
        breaks
            .entry(inst)
            .or_default()
            .cuts
            .push((c.get_ref(), label));
    }
    for (i, f) in fractures.iter().enumerate() {
        let label = element_label("fracture", i, None);
        let inst = named_instance(doc, instance_names, &f.get_ref().instance, &label)?;
        let entry = breaks.entry(inst).or_default();
        if entry.fracture.is_some() {
            return Err(doc.invalid(
                f.get_ref().instance.span(),
                join(&label, "instance"),
                format!(
                    "instance {:?} is already fractured by an earlier [[fracture]]",
                    f.get_ref().instance.get_ref()
                ),
            ));
        }
        entry.fracture = Some((f.get_ref(), label));
    }
    let mut out = Vec::with_capacity(instances.len());
    for (index, inst) in instances.into_iter().enumerate() {
        let Some(b) = breaks.get(&index) else {
            out.push(inst);
            continue;
        };
        let source = inst.mesh;
        let pieces = pieces(doc, &meshes[source].mesh, b)?;
        let bounds = meshes[source].mesh.bounds();
        let centre = (bounds.min + bounds.max) * 0.5;
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed as u64 ^ (index as u64) << 32);
        for (k, piece) in pieces.into_iter().enumerate() {
            let axis = loop {
                let v = Vec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                let l = v.length();
                if l > 0.1 && l <= 1.0 {
                    break v / l;
                }
            };
            let spin_share = rng.random_range(0.5..=1.0);
            let centroid = piece.centroid();
            let resolved_crossings = piece.resolved_crossings;
            let separated_vertices = piece.separated_vertices + piece.split_edges;
            let name = format!("{}#{index}.{k}", meshes[source].name);
            meshes.push(SceneMesh {
                mesh: Mesh {
                    positions: piece.positions,
                    triangles: piece.triangles,
                    // A cut makes new faces the source's coordinates do not cover: pieces
                    // carry no UVs (scene checks refuse UV materials on broken instances).
                    uvs: None,
                    source: meshes[source].mesh.source.clone(),
                },
                name,
                cut_from: Some((source, piece.interior)),
            });
            out.push(Instance {
                mesh: meshes.len() - 1,
                piece: Some(Piece {
                    broken: index,
                    centroid,
                    centre,
                    spin_axis: axis,
                    spin_share,
                    contact: None,
                    resolved_crossings,
                    separated_vertices,
                }),
                ..inst
            });
        }
    }
    Ok(out)
}

fn named_instance(
    doc: &Doc,
    names: &HashMap<&str, usize>,
    name: &Spanned<String>,
    label: &str,
) -> Result<usize, SceneError> {
    names.get(name.get_ref().as_str()).copied().ok_or_else(|| {
        let mut known: Vec<String> = names.keys().map(|k| format!("{k:?}")).collect();
        known.sort();
        let known = if known.is_empty() {
            "no [[instance]] has a name".to_string()
        } else {
            format!("named instances: {}", known.join(", "))
        };
        doc.invalid(
            name.span(),
            join(label, "instance"),
            format!("unknown instance {:?} ({known})", name.get_ref()),
        )
    })
}

/// The pieces of `mesh` after the cuts (each cutting every piece so far) and the fracture.
fn pieces(doc: &Doc, mesh: &Mesh, b: &Breaks) -> Result<Vec<Fragment>, SceneError> {
    let fail = |span: std::ops::Range<usize>, field: String, e: &dyn std::fmt::Display| {
        doc.invalid(span, field, e.to_string())
    };
    let mut pieces = vec![Fragment::whole(mesh)];
    for (cut, label) in &b.cuts {
        let point = doc.vec3(&cut.point, &join(label, "point"))?;
        let normal = doc.vec3(&cut.normal, &join(label, "normal"))?;
        if normal == Vec3::ZERO {
            return Err(doc.invalid(cut.normal.span(), join(label, "normal"), "must not be zero"));
        }
        let plane = Plane::through(point.as_dvec3(), normal.as_dvec3());
        let (next, missed) = cut_pieces(pieces, plane, &mesh.source)
            .map_err(|e| fail(cut.point.span(), label.clone(), &e))?;
        if missed {
            return Err(doc.invalid(
                cut.point.span(),
                join(label, "point"),
                format!(
                    "the plane through {point} with normal {normal} misses the mesh (object space: the mesh's unit cube)"
                ),
            ));
        }
        pieces = next;
    }
    let Some((f, label)) = &b.fracture else {
        return Ok(pieces);
    };
    let sites: Vec<Vec3> = match (&f.pieces, &f.sites) {
        (Some(_), Some(s)) => {
            return Err(doc.invalid(
                s.span(),
                join(label, "sites"),
                "pieces and sites are exclusive: random sites or given ones",
            ))
        }
        (None, None) => {
            return Err(doc.invalid(
                f.instance.span(),
                label.clone(),
                "needs pieces = N (random sites) or sites = [[x, y, z], ...]",
            ))
        }
        (Some(n), None) => {
            let n = doc.integer(n, &join(label, "pieces"), 1..=MAX_PIECES as u32)?;
            let seed = f.seed.as_ref().map_or(1, |s| *s.get_ref());
            random_sites(mesh, n as usize, seed as u64)
                .map_err(|e| fail(f.instance.span(), label.clone(), &e))?
        }
        (None, Some(s)) => {
            doc.reject(
                &f.seed,
                label,
                "seed",
                "only random sites (pieces = N) have it",
            )?;
            let sites = s.get_ref();
            if sites.is_empty() || sites.len() > MAX_PIECES {
                return Err(doc.invalid(
                    s.span(),
                    join(label, "sites"),
                    format!("{} sites: a fracture takes 1 to {MAX_PIECES}", sites.len()),
                ));
            }
            sites.iter().map(|&p| Vec3::from_array(p)).collect()
        }
    };
    let mut out = Vec::new();
    for piece in &pieces {
        let as_mesh = piece.to_mesh(mesh.source.clone());
        let cells = fracture_cells_flagged(&as_mesh, Some(&piece.interior), &sites)
            .map_err(|e| fail(f.instance.span(), label.clone(), &e))?;
        out.extend(cells.into_iter().flatten().map(|mut cell| {
            cell.resolved_crossings += piece.resolved_crossings;
            cell
        }));
    }
    Ok(out)
}

/// `[explosion]`.
pub(super) fn explosion(
    doc: &Doc,
    raw: Option<&Spanned<RawExplosion>>,
    broken: bool,
) -> Result<Option<Explosion>, SceneError> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let label = "explosion";
    if !broken {
        return Err(doc.invalid(
            raw.span(),
            label,
            "nothing to blow apart: no [[cut]] or [[fracture]] breaks an instance",
        ));
    }
    let e = raw.get_ref();
    let f = |k: &str| join(label, k);
    Ok(Some(Explosion {
        centre: e
            .centre
            .as_ref()
            .map(|c| doc.vec3(c, &f("centre")))
            .transpose()?,
        speed: doc.number(
            &e.speed,
            &f("speed"),
            |v| (0.0..=1e4).contains(&v),
            "in [0, 10000]",
        )?,
        spin_deg: match &e.spin {
            Some(s) => doc.number(
                s,
                &f("spin"),
                |v| (0.0..=1e5).contains(&v),
                "in [0, 100000]",
            )?,
            None => 0.0,
        },
        gravity: match &e.gravity {
            Some(g) => doc.vec3(g, &f("gravity"))?,
            None => Vec3::new(0.0, -9.81, 0.0),
        },
        start: match &e.start {
            Some(s) => doc.number(s, &f("start"), |v| v >= 0.0 && v.is_finite(), ">= 0")?,
            None => 0.0,
        },
        ground: e
            .ground
            .as_ref()
            .map(|g| {
                doc.number(
                    g,
                    &f("ground"),
                    |v| v.abs() <= 1e6,
                    "a finite height in [-1e6, 1e6]",
                )
            })
            .transpose()?,
    }))
}

/// `[animation]`; frame size and samples default to `render`'s.
pub(super) fn animation(
    doc: &Doc,
    raw: Option<&Spanned<RawAnimation>>,
    render: &RenderSettings,
) -> Result<Option<Animation>, SceneError> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let a = raw.get_ref();
    let or = |v: &Option<Spanned<u32>>,
              key: &str,
              range: std::ops::RangeInclusive<u32>,
              default: u32| match v {
        Some(v) => doc.integer(v, &join("animation", key), range),
        None => Ok(default),
    };
    Ok(Some(Animation {
        frames: doc.integer(&a.frames, "animation.frames", 1..=100_000)?,
        fps: doc.number(
            &a.fps,
            "animation.fps",
            |v| v > 0.0 && v <= 1000.0,
            "in (0, 1000]",
        )?,
        width: or(&a.width, "width", 1..=MAX_IMAGE_SIDE, render.width)?,
        height: or(&a.height, "height", 1..=MAX_IMAGE_SIDE, render.height)?,
        spp: or(&a.spp, "spp", 1..=MAX_SPP, render.spp)?,
    }))
}
