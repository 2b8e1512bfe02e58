//! From text to [`Scene`]: deserialize, validate every table, resolve names into indices and
//! load the meshes (last, so that cheap mistakes are reported before slow loads).

use super::location::{element_label, join, Doc};
use super::raw::{RawInstance, RawScene};
use super::{broken, camera, lights, material, meshes, motion};
use super::{Instance, Material, Scene, SceneError, SceneMesh};
use glam::{Affine3A, Quat, Vec3};
use std::collections::HashMap;
use std::path::Path;
use toml::Spanned;

impl Scene {
    /// Reads and parses a scene file; relative paths inside it are resolved against its folder.
    ///
    /// # Errors
    /// An unreadable file, or any error of [`Scene::parse`].
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            file: path.to_path_buf(),
            source,
        })?;
        Scene::parse(&text, path)
    }

    /// Parses scene text as if read from `source`: `source` names the file in messages and
    /// its folder is where relative mesh and map paths start (the text itself is not read
    /// from it, which lets tests and tools build scenes in memory).
    ///
    /// # Errors
    /// TOML syntax, unknown keys, wrong types, missing or out-of-range values, unknown or
    /// duplicate names, no instance, missing files and mesh loading errors, each with the
    /// scene file, the line and the field path.
    pub fn parse(text: &str, source: &Path) -> Result<Scene, SceneError> {
        let doc = Doc { file: source, text };
        let raw: RawScene = doc.deserialize()?;
        let base = source.parent().unwrap_or(Path::new(""));

        let camera = camera::camera(&doc, &raw.camera)?;
        let render = camera::render(&doc, raw.render.get_ref())?;
        let mesh_names = names(
            &doc,
            "mesh",
            raw.mesh.iter().map(|m| &m.get_ref().name).enumerate(),
        )?;
        let material_names = names(
            &doc,
            "material",
            raw.material.iter().map(|m| &m.get_ref().name).enumerate(),
        )?;
        let materials = raw
            .material
            .iter()
            .map(|m| {
                let label = element_label("material", 0, Some(m.get_ref().name.get_ref()));
                material::resolve(&doc, m, &label, base)
            })
            .collect::<Result<Vec<_>, _>>()?;
        if raw.instance.is_empty() {
            return Err(doc.invalid(
                doc.text.trim_end().len()..doc.text.len(),
                "instance",
                "the scene has no [[instance]]: there would be nothing to render",
            ));
        }
        let instance_names = names(
            &doc,
            "instance",
            raw.instance
                .iter()
                .enumerate()
                .filter_map(|(k, i)| Some((k, i.get_ref().name.as_ref()?))),
        )?;
        let instances = raw
            .instance
            .iter()
            .enumerate()
            .map(|(i, inst)| {
                let label = element_label("instance", i, None);
                instance(&doc, inst.get_ref(), &label, &mesh_names, &material_names)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let broken = !raw.cut.is_empty() || !raw.fracture.is_empty();
        let explosion = broken::explosion(&doc, raw.explosion.as_ref(), broken)?;
        let animation = broken::animation(&doc, raw.animation.as_ref(), &render)?;
        let lights = raw
            .light
            .iter()
            .enumerate()
            .map(|(i, l)| lights::light(&doc, l, &element_label("light", i, None)))
            .collect::<Result<Vec<_>, _>>()?;
        let environment = lights::environment(&doc, raw.environment.as_ref(), base)?;
        let mut meshes = raw
            .mesh
            .iter()
            .map(|m| {
                let label = element_label("mesh", 0, Some(m.get_ref().name.get_ref()));
                meshes::mesh(&doc, m, &label, base)
            })
            .collect::<Result<Vec<_>, _>>()?;
        uvs_where_read(&doc, &raw, &instances, &instance_names, &materials, &meshes)?;
        let mut instances = broken::break_instances(
            &doc,
            &raw.cut,
            &raw.fracture,
            &instance_names,
            &mut meshes,
            instances,
            render.seed,
        )?;
        if let Some(e) = &explosion {
            for inst in &mut instances {
                if let Some(piece) = &mut inst.piece {
                    piece.contact =
                        motion::contact_time(e, inst.transform, piece, &meshes[inst.mesh].mesh);
                }
            }
        }

        Ok(Scene {
            source: source.to_path_buf(),
            camera,
            render,
            meshes,
            materials,
            instances,
            lights,
            environment,
            explosion,
            animation,
        })
    }
}

/// Index of every name of a section, given with the index of its table (tables without a name
/// are left out); names must be non-empty and unique.
fn names<'a>(
    doc: &Doc,
    section: &str,
    names: impl Iterator<Item = (usize, &'a Spanned<String>)>,
) -> Result<HashMap<&'a str, usize>, SceneError> {
    let mut index: HashMap<&str, (usize, usize)> = HashMap::new();
    for (i, name) in names {
        let label = join(&element_label(section, i, None), "name");
        let line = doc.line(name.span().start);
        if name.get_ref().is_empty() {
            return Err(doc.invalid(name.span(), label, "must not be empty"));
        }
        if let Some(&(_, first_line)) = index.get(name.get_ref().as_str()) {
            return Err(doc.invalid(
                name.span(),
                label,
                format!(
                    "duplicate name: {section} {:?} is already defined on line {first_line}",
                    name.get_ref()
                ),
            ));
        }
        index.insert(name.get_ref(), (i, line));
    }
    Ok(index.into_iter().map(|(k, (i, _))| (k, i)).collect())
}

/// Looks a name up, listing the defined ones when it is unknown.
fn lookup(
    doc: &Doc,
    names: &HashMap<&str, usize>,
    name: &Spanned<String>,
    section: &str,
    field: String,
) -> Result<usize, SceneError> {
    names.get(name.get_ref().as_str()).copied().ok_or_else(|| {
        let mut known: Vec<String> = names.keys().map(|k| format!("{k:?}")).collect();
        known.sort();
        let known = if known.is_empty() {
            format!("the scene defines no [[{section}]]")
        } else {
            format!("defined: {}", known.join(", "))
        };
        doc.invalid(
            name.span(),
            field,
            format!("unknown {section} {:?} ({known})", name.get_ref()),
        )
    })
}

/// Fails where a material that reads texture coordinates (an albedo or normal map, glint
/// `uv = "mesh"`) is placed on a mesh without them, or on an instance that is cut or
/// fractured (a cut's new faces have no coordinates).
fn uvs_where_read(
    doc: &Doc,
    raw: &RawScene,
    instances: &[Instance],
    instance_names: &HashMap<&str, usize>,
    materials: &[Material],
    meshes: &[SceneMesh],
) -> Result<(), SceneError> {
    const READS: &str =
        "reads texture coordinates (albedo_map, normal_map, height_map or glint uv = \"mesh\")";
    for (i, inst) in instances.iter().enumerate() {
        let material = &materials[inst.material];
        let mesh = &meshes[inst.mesh];
        if material.needs_uvs() && mesh.mesh.uvs.is_none() {
            let span = raw.instance[i].get_ref().material.span();
            return Err(doc.invalid(
                span,
                join(&element_label("instance", i, None), "material"),
                format!(
                    "material {:?} {READS}, but mesh {:?} ({}) has none: give the OBJ vt coordinates, or use the built-in quad",
                    material.name,
                    mesh.name,
                    mesh.mesh.source.display()
                ),
            ));
        }
    }
    let cuts = raw
        .cut
        .iter()
        .enumerate()
        .map(|(k, c)| (k, &c.get_ref().instance, "cut"));
    let fractures = raw
        .fracture
        .iter()
        .enumerate()
        .map(|(k, f)| (k, &f.get_ref().instance, "fracture"));
    for (k, name, section) in cuts.chain(fractures) {
        if let Some(&i) = instance_names.get(name.get_ref().as_str()) {
            let material = &materials[instances[i].material];
            if material.needs_uvs() {
                return Err(doc.invalid(
                    name.span(),
                    join(&element_label(section, k, None), "instance"),
                    format!(
                        "instance {:?} has material {:?}, which {READS}: the faces a {section} makes have none",
                        name.get_ref(),
                        material.name
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Validates one instance: names resolved, transform built as translate · rotate · scale with
/// the rotation about x first, then y, then z (all fixed world axes).
fn instance(
    doc: &Doc,
    raw: &RawInstance,
    label: &str,
    mesh_names: &HashMap<&str, usize>,
    material_names: &HashMap<&str, usize>,
) -> Result<Instance, SceneError> {
    let field = |key: &str| join(label, key);
    let mesh = lookup(doc, mesh_names, &raw.mesh, "mesh", field("mesh"))?;
    let material = lookup(
        doc,
        material_names,
        &raw.material,
        "material",
        field("material"),
    )?;
    let translate = match &raw.translate {
        Some(t) => doc.vec3(t, &field("translate"))?,
        None => Vec3::ZERO,
    };
    let rotate = match &raw.rotate {
        Some(r) => doc.vec3(r, &field("rotate"))?,
        None => Vec3::ZERO,
    };
    let scale = match &raw.scale {
        Some(s) => doc.number(s, &field("scale"), |v| v > 0.0, "> 0")?,
        None => 1.0,
    };
    let r = rotate * (std::f32::consts::PI / 180.0);
    let rotation =
        Quat::from_rotation_z(r.z) * Quat::from_rotation_y(r.y) * Quat::from_rotation_x(r.x);
    Ok(Instance {
        mesh,
        material,
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::splat(scale),
            rotation,
            translate,
        ),
        piece: None,
    })
}
