//! OpenEXR output: the faithful HDR record of a render, with its auxiliary layers.
//!
//! Samples are stored as 32-bit floats, not halves: a path tracer's radiance can exceed the
//! f16 maximum (65504) on bright emitters and fireflies, reference images must round-trip
//! exactly for comparisons, and f16 would add a 2^-11 relative error to every pixel. The files
//! are twice as large, which is irrelevant at the sizes we render. Compression is ZIP over 16
//! scanlines: lossless and read by every EXR tool.
//!
//! The layers use the single-part naming convention that Blender, OpenImageIO and Nuke
//! understand: `R`, `G`, `B` for the image, `albedo.R`, `albedo.G`, `albedo.B`, `normal.X`,
//! `normal.Y`, `normal.Z` and `depth.Z` for the auxiliary layers.

use super::{write_atomically, Film, OutputError};
use exr::prelude::{
    AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, ReadChannels,
    ReadLayers, WritableImage,
};
use std::io::BufReader;
use std::path::Path;

fn channel(name: &str, samples: Vec<f32>) -> AnyChannel<FlatSamples> {
    AnyChannel::new(name, FlatSamples::F32(samples))
}

/// Adds one channel per component of a three-component layer.
fn push_rgb(channels: &mut Vec<AnyChannel<FlatSamples>>, names: [&str; 3], layer: &[[f32; 3]]) {
    for (i, name) in names.iter().enumerate() {
        channels.push(channel(name, layer.iter().map(|p| p[i]).collect()));
    }
}

/// Writes the film as an f32 OpenEXR: `R`, `G`, `B` plus `albedo.*`, `normal.*` and `depth.Z`
/// for the layers the film has. Values are written as they are (NaN and inf included).
///
/// # Errors
/// The folder is missing or not writable, or the encoder fails; the error names `path`, and
/// no file is left at `path` (a previous file there is kept).
pub fn write_exr(film: &Film, path: impl AsRef<Path>) -> Result<(), OutputError> {
    let path = path.as_ref();
    let mut channels = Vec::with_capacity(10);
    push_rgb(&mut channels, ["R", "G", "B"], film.color());
    if let Some(albedo) = film.albedo() {
        push_rgb(&mut channels, ["albedo.R", "albedo.G", "albedo.B"], albedo);
    }
    if let Some(normal) = film.normal() {
        push_rgb(&mut channels, ["normal.X", "normal.Y", "normal.Z"], normal);
    }
    if let Some(depth) = film.depth() {
        channels.push(channel("depth.Z", depth.to_vec()));
    }
    let layer = Layer::new(
        (film.width() as usize, film.height() as usize),
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    write_atomically(path, |writer| {
        Image::from_layer(layer)
            .write()
            .to_buffered(writer)
            .map_err(|cause| OutputError::Exr {
                file: path.to_path_buf(),
                cause,
            })
    })
}

/// Reads the main image of an OpenEXR file: the `R`, `G` and `B` channels of the first layer
/// that has all three, as `(width, height, row-major pixels, top row first)`. Other channels
/// (alpha, auxiliary layers) are ignored; half or integer samples are converted to f32.
///
/// # Errors
/// The file is missing or unreadable, is not a valid OpenEXR file, or has no layer with all of
/// `R`, `G` and `B` (the error lists the channels it has).
pub fn read_exr_rgb(path: impl AsRef<Path>) -> Result<(u32, u32, Vec<[f32; 3]>), OutputError> {
    read_exr_layer(path, ["R", "G", "B"])
}

/// Reads three channels of an OpenEXR file by name (`["albedo.R", "albedo.G", "albedo.B"]` for
/// the albedo layer lazysolid writes), from the first layer that has all three, as `(width,
/// height, row-major pixels, top row first)`; half or integer samples are converted to f32.
///
/// # Errors
/// The file is missing or unreadable, is not a valid OpenEXR file, or has no layer with all
/// three channels (the error lists the channels it has).
pub fn read_exr_layer(
    path: impl AsRef<Path>,
    names: [&str; 3],
) -> Result<(u32, u32, Vec<[f32; 3]>), OutputError> {
    let path = path.as_ref();
    let file = std::fs::File::open(path).map_err(|cause| OutputError::Io {
        file: path.to_path_buf(),
        action: "open".into(),
        cause,
    })?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_buffered(BufReader::new(file))
        .map_err(|cause| OutputError::Exr {
            file: path.to_path_buf(),
            cause,
        })?;
    let mut found = Vec::new();
    for layer in &image.layer_data {
        let list = &layer.channel_data.list;
        let find = |name: &str| list.iter().find(|c| c.name.eq(name));
        if let (Some(r), Some(g), Some(b)) = (find(names[0]), find(names[1]), find(names[2])) {
            let pixels = r
                .sample_data
                .values_as_f32()
                .zip(g.sample_data.values_as_f32())
                .zip(b.sample_data.values_as_f32())
                .map(|((r, g), b)| [r, g, b])
                .collect();
            return Ok((layer.size.0 as u32, layer.size.1 as u32, pixels));
        }
        found.extend(list.iter().map(|c| c.name.to_string()));
    }
    Err(OutputError::MissingRgb {
        file: path.to_path_buf(),
        wanted: names.join(", "),
        found: if found.is_empty() {
            "none".into()
        } else {
            found.join(", ")
        },
    })
}
