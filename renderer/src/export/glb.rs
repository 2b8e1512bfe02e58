//! glTF 2.0 binary (`.glb`) of a broken object: one node per piece with its mesh, its baked
//! atlas as the base colour (sRGB, as glTF reads `baseColorTexture`) and its rest pose, and
//! for an explosion one animation whose channels are the pieces' poses at the scene's frames.
//! The document is built with `gltf-json`'s types; the GLB container around it (a 12-byte
//! header, the JSON chunk padded with spaces, the binary chunk padded with zeros) is written
//! here, following the specification's section 4.4.

use super::atlas::PieceAtlas;
use super::ExportError;
use glam::Affine3A;
use gltf_json as json;
use json::validation::{Checked::Valid, USize64};
use std::collections::BTreeMap;
use std::path::Path;

/// Per piece: its name, its atlas, its PNG and its pose at each animation time.
pub(crate) struct GlbPiece<'a> {
    pub name: String,
    pub atlas: &'a PieceAtlas,
    pub png: &'a [u8],
    pub poses: Vec<Affine3A>,
}

/// Accumulates the binary chunk and the document's views and accessors.
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
}

impl Builder {
    /// Appends `bytes` as a buffer view, aligned to 4 bytes as every accessor needs.
    fn view(
        &mut self,
        bytes: &[u8],
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::buffer::View> {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: target.map(Valid),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// An accessor over a whole view of `count` elements.
    fn accessor(
        &mut self,
        view: json::Index<json::buffer::View>,
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
        bounds: Option<(Vec<f32>, Vec<f32>)>,
    ) -> json::Index<json::Accessor> {
        let (min, max) = bounds.map_or((None, None), |(lo, hi)| {
            (Some(json::Value::from(lo)), Some(json::Value::from(hi)))
        });
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(type_),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// Floats as a vertex or animation accessor of `n` components per element, with their
    /// bounds (which glTF requires for positions and animation inputs).
    fn floats(&mut self, values: &[f32], n: usize, vertex: bool) -> json::Index<json::Accessor> {
        let mut lo = vec![f32::INFINITY; n];
        let mut hi = vec![f32::NEG_INFINITY; n];
        for chunk in values.chunks_exact(n) {
            for k in 0..n {
                lo[k] = lo[k].min(chunk[k]);
                hi[k] = hi[k].max(chunk[k]);
            }
        }
        let target = vertex.then_some(json::buffer::Target::ArrayBuffer);
        let view = self.view(bytemuck::cast_slice(values), target);
        let type_ = match n {
            1 => json::accessor::Type::Scalar,
            2 => json::accessor::Type::Vec2,
            3 => json::accessor::Type::Vec3,
            _ => json::accessor::Type::Vec4,
        };
        self.accessor(
            view,
            values.len() / n,
            json::accessor::ComponentType::F32,
            type_,
            Some((lo, hi)),
        )
    }
}

/// The pieces as one glTF binary at `path` (written through a temporary name). `times` are
/// the animation's sample times in seconds (each piece has one pose per time); with fewer
/// than two there is no animation. Node transforms are the poses at the first time.
pub(crate) fn write_glb(
    path: &Path,
    object: &str,
    pieces: &[GlbPiece<'_>],
    times: &[f32],
) -> Result<(), ExportError> {
    let mut b = Builder {
        root: json::Root {
            asset: json::Asset {
                generator: Some(format!("lazysolid {}", env!("CARGO_PKG_VERSION"))),
                version: "2.0".into(),
                ..Default::default()
            },
            ..Default::default()
        },
        bin: Vec::new(),
    };
    let sampler = b.root.push(json::texture::Sampler {
        mag_filter: Some(Valid(json::texture::MagFilter::Linear)),
        min_filter: Some(Valid(json::texture::MinFilter::LinearMipmapLinear)),
        wrap_s: Valid(json::texture::WrappingMode::ClampToEdge),
        wrap_t: Valid(json::texture::WrappingMode::ClampToEdge),
        ..Default::default()
    });
    let mut nodes = Vec::with_capacity(pieces.len());
    for piece in pieces {
        let a = piece.atlas;
        let positions: Vec<f32> = a.positions.iter().flat_map(|p| p.to_array()).collect();
        let uvs: Vec<f32> = a.uvs.iter().flat_map(|u| u.to_array()).collect();
        let indices: Vec<u32> = a.triangles.iter().flatten().copied().collect();
        let position = b.floats(&positions, 3, true);
        let uv = b.floats(&uvs, 2, true);
        let index_view = b.view(
            bytemuck::cast_slice(&indices),
            Some(json::buffer::Target::ElementArrayBuffer),
        );
        let index = b.accessor(
            index_view,
            indices.len(),
            json::accessor::ComponentType::U32,
            json::accessor::Type::Scalar,
            None,
        );
        let image_view = b.view(piece.png, None);
        let image = b.root.push(json::Image {
            buffer_view: Some(image_view),
            mime_type: Some(json::image::MimeType("image/png".into())),
            name: Some(format!("{} matter", piece.name)),
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        let texture = b.root.push(json::Texture {
            name: None,
            sampler: Some(sampler),
            source: image,
            extensions: None,
            extras: Default::default(),
        });
        let material = b.root.push(json::Material {
            name: Some(piece.name.clone()),
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_texture: Some(json::texture::Info {
                    index: texture,
                    tex_coord: 0,
                    extensions: None,
                    extras: Default::default(),
                }),
                metallic_factor: json::material::StrengthFactor(0.0),
                roughness_factor: json::material::StrengthFactor(1.0),
                ..Default::default()
            },
            ..Default::default()
        });
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), position);
        attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), uv);
        let mesh = b.root.push(json::Mesh {
            name: Some(piece.name.clone()),
            primitives: vec![json::mesh::Primitive {
                attributes,
                indices: Some(index),
                material: Some(material),
                mode: Valid(json::mesh::Mode::Triangles),
                targets: None,
                extensions: None,
                extras: Default::default(),
            }],
            weights: None,
            extensions: None,
            extras: Default::default(),
        });
        let (scale, rotation, translation) = piece
            .poses
            .first()
            .copied()
            .unwrap_or(Affine3A::IDENTITY)
            .to_scale_rotation_translation();
        nodes.push(b.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(piece.name.clone()),
            rotation: Some(json::scene::UnitQuaternion(rotation.to_array())),
            scale: Some(scale.to_array()),
            translation: Some(translation.to_array()),
            ..Default::default()
        }));
    }
    if times.len() > 1 {
        let input = b.floats(times, 1, false);
        let mut channels = Vec::new();
        let mut samplers = Vec::new();
        for (piece, &node) in pieces.iter().zip(&nodes) {
            let (mut t, mut r, mut s) = (Vec::new(), Vec::new(), Vec::new());
            for pose in &piece.poses {
                let (scale, rotation, translation) = pose.to_scale_rotation_translation();
                t.extend(translation.to_array());
                r.extend(rotation.to_array());
                s.extend(scale.to_array());
            }
            for (values, n, path) in [
                (t, 3, json::animation::Property::Translation),
                (r, 4, json::animation::Property::Rotation),
                (s, 3, json::animation::Property::Scale),
            ] {
                let output = b.floats(&values, n, false);
                let sampler = json::Index::push(
                    &mut samplers,
                    json::animation::Sampler {
                        input,
                        interpolation: Valid(json::animation::Interpolation::Linear),
                        output,
                        extensions: None,
                        extras: Default::default(),
                    },
                );
                channels.push(json::animation::Channel {
                    sampler,
                    target: json::animation::Target {
                        node,
                        path: Valid(path),
                        extensions: None,
                        extras: Default::default(),
                    },
                    extensions: None,
                    extras: Default::default(),
                });
            }
        }
        b.root.push(json::Animation {
            name: Some(format!("{object} explosion")),
            channels,
            samplers,
            extensions: None,
            extras: Default::default(),
        });
    }
    while b.bin.len() % 4 != 0 {
        b.bin.push(0);
    }
    b.root.push(json::Buffer {
        byte_length: USize64::from(b.bin.len()),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let scene = b.root.push(json::Scene {
        name: Some(object.to_string()),
        nodes,
        extensions: None,
        extras: Default::default(),
    });
    b.root.scene = Some(scene);
    let mut text = json::serialize::to_vec(&b.root)
        .map_err(|e| ExportError::Glb(format!("serializing the document: {e}")))?;
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + b.bin.len();
    let total = u32::try_from(total)
        .map_err(|_| ExportError::Glb(format!("{total} bytes: a GLB holds at most 4 GiB")))?;
    let mut glb = Vec::with_capacity(total as usize);
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&total.to_le_bytes());
    glb.extend_from_slice(&(text.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&text);
    glb.extend_from_slice(&(b.bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&b.bin);
    lazysolid_compute::atomic_file::write_bytes_atomically(path, &glb)
        .map_err(|e| ExportError::Write(e.into()))
}
