//! Broken objects leave lazysolid with their matter: every piece of a cut or fractured
//! instance is unwrapped into a texture atlas, the atlas is baked from the same store the path
//! tracer reads (outer surface and cut faces alike), and the pieces are written as one glTF
//! binary per object (a node per piece, the explosion as animation) and as OBJ with the atlas
//! as `map_Kd`. Design, crates and measurements: `docs/fracture.md`, "Export".

mod atlas;
mod glb;
mod obj;

pub use atlas::{barycentric, PieceAtlas};

use crate::output::OutputError;
use crate::render::{RenderError, SceneStores};
use crate::scene::Scene;
use image::ImageEncoder as _;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Largest texel density an export accepts, texels per unit of object space: the unit cube's
/// surface at that density already fills a 16k atlas.
pub const MAX_TEXELS_PER_UNIT: f32 = 8192.0;
/// Most mip levels the padding is sized for (padding 2^k texels).
pub const MAX_MIP_LEVELS: u32 = 8;

/// How to export.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExportOptions {
    /// Texels per unit of object space (the unit cube); `None`: the store's resolution, one
    /// texel per voxel.
    pub texels_per_unit: Option<f32>,
    /// Mip levels that must not bleed between charts: charts get 2^k texels of padding,
    /// filled with their border colours.
    pub mip_levels: u32,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            texels_per_unit: None,
            mip_levels: 3,
        }
    }
}

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// An option out of range.
    #[error("{0}")]
    Options(String),
    /// A broken instance whose material reads no store: there is no matter to bake.
    #[error("[[instance]] {instance} ({mesh}): its material has no store (a synthesized, volume or procedural `texture` with `store`), so there is no matter to export")]
    NoStore {
        /// 1-based index in the scene file's `[[instance]]` list.
        instance: usize,
        /// The mesh it was cut from.
        mesh: String,
    },
    /// The unwrapper refused a piece.
    #[error("unwrapping a piece into an atlas: {0}")]
    Unwrap(String),
    /// The glTF document could not be made.
    #[error("glTF: {0}")]
    Glb(String),
    /// A store lookup failed.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// A file could not be written.
    #[error(transparent)]
    Write(#[from] OutputError),
}

/// One piece as exported, kept for tests and messages.
#[derive(Clone, Debug)]
pub struct ExportedPiece {
    /// Index of the piece's instance in [`Scene::instances`].
    pub instance: usize,
    /// The atlas and its geometry (object space).
    pub atlas: PieceAtlas,
    /// Its OBJ file.
    pub obj: PathBuf,
    /// Its atlas image.
    pub png: PathBuf,
}

/// One broken object as exported.
#[derive(Clone, Debug)]
pub struct ExportedObject {
    /// The name of the mesh it was cut from.
    pub name: String,
    /// The glTF binary.
    pub glb: PathBuf,
    /// Texel density used.
    pub texels_per_unit: f32,
    /// Padding around each chart, texels.
    pub padding: u32,
    /// Animation samples (1: no animation).
    pub times: usize,
    /// Its pieces, in scene order.
    pub pieces: Vec<ExportedPiece>,
}

impl ExportedObject {
    /// Texels of matter over all pieces (centres on a triangle), for messages.
    #[must_use]
    pub fn covered(&self) -> usize {
        self.pieces.iter().map(|p| p.atlas.covered).sum()
    }

    /// Covered texels with no stored matter over all pieces (painted magenta).
    #[must_use]
    pub fn holes(&self) -> usize {
        self.pieces.iter().map(|p| p.atlas.holes).sum()
    }

    /// Charts over all pieces' atlases.
    #[must_use]
    pub fn charts(&self) -> u32 {
        self.pieces.iter().map(|p| p.atlas.charts).sum()
    }
}

/// Exports every broken instance of `scene` into `dir` (created if missing): `<mesh>.glb` and
/// a folder `<mesh>/` (`<mesh>_instanceN` for a further broken instance of the same mesh) with `piece_NNN.obj`, `.mtl` and `.png` per piece, baked from
/// `stores` (the stores the scene's path tracer reads). Returns what was written; an
/// instance that is not broken is not exported.
///
/// # Errors
/// Options out of range, a broken instance without a store, an unwrap, lookup or write
/// failure.
pub fn export_broken(
    scene: &Scene,
    stores: &SceneStores,
    dir: &Path,
    options: &ExportOptions,
) -> Result<Vec<ExportedObject>, ExportError> {
    if options.mip_levels > MAX_MIP_LEVELS {
        return Err(ExportError::Options(format!(
            "--export-mips {}: at most {MAX_MIP_LEVELS} mip levels",
            options.mip_levels
        )));
    }
    if let Some(d) = options.texels_per_unit {
        if !(d.is_finite() && d > 0.0 && d <= MAX_TEXELS_PER_UNIT) {
            return Err(ExportError::Options(format!(
                "--export-density {d}: texels per unit must be above 0 and at most {MAX_TEXELS_PER_UNIT}"
            )));
        }
    }
    let padding = 1u32 << options.mip_levels;
    let mut objects: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (i, inst) in scene.instances.iter().enumerate() {
        if let Some(p) = &inst.piece {
            objects.entry(p.broken).or_default().push(i);
        }
    }
    let times: Vec<f32> = match (scene.animation, scene.explosion) {
        (Some(a), Some(_)) if a.frames > 1 => (0..a.frames).map(|f| scene.frame_time(f)).collect(),
        _ => vec![0.0],
    };
    let mut out = Vec::new();
    for (broken, instances) in objects {
        let first = instances[0];
        let full_name = &scene.meshes[scene.instances[first].mesh].name;
        let mut name = full_name.split('#').next().unwrap_or(full_name).to_string();
        // Two broken instances of one mesh get files of their own.
        if out.iter().any(|o: &ExportedObject| o.name == name) {
            name = format!("{name}_instance{}", broken + 1);
        }
        let slot = stores.slot_of(first).ok_or_else(|| ExportError::NoStore {
            instance: broken + 1,
            mesh: name.clone(),
        })?;
        let texels_per_unit = options
            .texels_per_unit
            .unwrap_or_else(|| stores.info()[slot].resolution as f32);
        let folder = dir.join(&name);
        std::fs::create_dir_all(&folder).map_err(|cause| OutputError::Io {
            file: folder.clone(),
            action: "create the folder".into(),
            cause,
        })?;
        let mut pieces = Vec::with_capacity(instances.len());
        let mut pngs = Vec::with_capacity(instances.len());
        for (k, &i) in instances.iter().enumerate() {
            let mesh = &scene.meshes[scene.instances[i].mesh];
            let interior = mesh.cut_from.as_ref().map_or_else(
                || vec![false; mesh.mesh.triangles.len()],
                |(_, f)| f.clone(),
            );
            let mut atlas = atlas::unwrap(
                &mesh.mesh.positions,
                &mesh.mesh.triangles,
                &interior,
                texels_per_unit,
                padding,
            )?;
            let texels = atlas.texel_points();
            let colours = stores.albedo_srgb(slot, &texels.points, &texels.normals)?;
            atlas.paint(&texels.texels, &colours);
            let stem = format!("piece_{k:03}");
            let png = folder.join(format!("{stem}.png"));
            let bytes = encode_png(&atlas, &png)?;
            lazysolid_compute::atomic_file::write_bytes_atomically(&png, &bytes)
                .map_err(OutputError::from)?;
            let rest = scene.instance_transform(i, times[0]);
            obj::write_obj(&folder, &stem, &atlas, rest)?;
            pngs.push(bytes);
            pieces.push(ExportedPiece {
                instance: i,
                atlas,
                obj: folder.join(format!("{stem}.obj")),
                png,
            });
        }
        let glb_pieces: Vec<glb::GlbPiece<'_>> = pieces
            .iter()
            .zip(&pngs)
            .enumerate()
            .map(|(k, (p, png))| glb::GlbPiece {
                name: format!("{name} piece {k}"),
                atlas: &p.atlas,
                png,
                poses: times
                    .iter()
                    .map(|&t| scene.instance_transform(p.instance, t))
                    .collect(),
            })
            .collect();
        let glb_path = dir.join(format!("{name}.glb"));
        glb::write_glb(&glb_path, &name, &glb_pieces, &times)?;
        out.push(ExportedObject {
            name,
            glb: glb_path,
            texels_per_unit,
            padding,
            times: times.len(),
            pieces,
        });
    }
    Ok(out)
}

/// The atlas as PNG bytes (RGBA8; the colours are sRGB, as the PNG's default says).
fn encode_png(atlas: &PieceAtlas, path: &Path) -> Result<Vec<u8>, ExportError> {
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(
            &atlas.pixels,
            atlas.width,
            atlas.height,
            image::ExtendedColorType::Rgba8,
        )
        .map_err(|e| ExportError::Glb(format!("{}: encoding the atlas: {e}", path.display())))?;
    Ok(bytes)
}
