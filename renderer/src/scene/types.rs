//! The resolved scene: what a scene file describes once it is parsed, validated and its meshes
//! loaded. Everything the GPU upload and the integrator need, nothing about TOML.

use super::volume::VolumeTexture;
use crate::mesh::Mesh;
use glam::{Affine3A, Vec3};
use std::path::PathBuf;

/// A scene ready to be uploaded and rendered.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The scene file it came from (for messages and relative paths).
    pub source: PathBuf,
    /// The camera.
    pub camera: Camera,
    /// Resolution, sampling and seed.
    pub render: RenderSettings,
    /// Meshes, each loaded once and instanced any number of times.
    pub meshes: Vec<SceneMesh>,
    /// Materials; instances refer to them by index.
    pub materials: Vec<Material>,
    /// Placed meshes: the top level of the two-level BVH.
    pub instances: Vec<Instance>,
    /// Analytic area lights (sampled by next-event estimation and hit by rays).
    pub lights: Vec<Light>,
    /// What a ray that leaves the scene sees.
    pub environment: Environment,
    /// How the pieces of cut and fractured instances fly apart (none: they stay at rest).
    pub explosion: Option<Explosion>,
    /// The frames an animated render makes.
    pub animation: Option<Animation>,
}

/// Pieces pushed away from a centre, spinning, under gravity, from a start time on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Explosion {
    /// Where the pieces fly away from (world); `None`: the centre of each broken instance's
    /// bounds.
    pub centre: Option<Vec3>,
    /// Initial speed of every piece, world units per second.
    pub speed: f32,
    /// Largest spin in degrees per second (each piece spins at 50–100 % of it about its own
    /// random axis).
    pub spin_deg: f32,
    /// Acceleration (world units per second²).
    pub gravity: Vec3,
    /// Time (seconds) at which the pieces start moving.
    pub start: f32,
    /// Height of the ground plane along "up" (against gravity; +y without gravity): a piece
    /// stops where it first touches it ([`Piece::contact`]). `None`: pieces fall freely.
    pub ground: Option<f32>,
}

impl Explosion {
    /// The unit "up" the ground height is measured along: against gravity, or +y without it.
    #[must_use]
    pub fn up(&self) -> Vec3 {
        (-self.gravity).try_normalize().unwrap_or(Vec3::Y)
    }
}

/// The frames of an animation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Animation {
    /// Number of frames (frame k shows time k / fps).
    pub frames: u32,
    /// Frames per second.
    pub fps: f32,
    /// Pixels across of each frame (default: `[render]`'s): an animation is often rendered
    /// smaller than a still.
    pub width: u32,
    /// Pixels down of each frame (default: `[render]`'s).
    pub height: u32,
    /// Samples per pixel of each frame (default: `[render]`'s).
    pub spp: u32,
}

/// A named mesh in the rest pose that solid textures are evaluated in.
#[derive(Clone, Debug)]
pub struct SceneMesh {
    /// Name instances refer to.
    pub name: String,
    /// The triangles, already normalized into the unit cube when the scene asked for it.
    pub mesh: Mesh,
    /// For a piece of a cut or fractured mesh: the mesh it was cut from (an index into
    /// [`Scene::meshes`]; same coordinates, so a solid texture reads the same matter) and, per
    /// triangle, whether it is a cap (new surface inside the solid).
    pub cut_from: Option<(usize, Vec<bool>)>,
}

/// The camera model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3,
    /// Point the camera looks at.
    pub look_at: Vec3,
    /// Up direction (need not be orthogonal to the view direction, must not be parallel).
    pub up: Vec3,
    /// Vertical field of view in degrees, in (0, 180).
    pub fov_y_deg: f32,
    /// Pinhole or thin lens.
    pub lens: Lens,
}

/// Lens model of the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lens {
    /// Everything in focus.
    Pinhole,
    /// Depth of field: a disc aperture focused at a distance.
    ThinLens {
        /// Radius of the aperture in scene units (> 0).
        aperture_radius: f32,
        /// Distance along the view direction that is in focus (> 0).
        focus_distance: f32,
    },
}

/// Resolution, sampling and determinism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Most scattering events (bounces) on a path: 0 sees emitters only, 1 adds direct
    /// lighting, k counts every path of up to k bounces once.
    pub max_depth: u32,
    /// Depth from which Russian roulette may end paths.
    pub rr_depth: u32,
    /// Seed of every random number of the render: same seed, same image.
    pub seed: u32,
}

/// Scattering model of a material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaterialKind {
    /// Ideal diffuse reflector.
    Lambertian,
    /// GGX microfacet metal with complex index of refraction (`color` = η, `k` = κ per channel).
    Conductor,
    /// Diffuse base under a GGX dielectric coat of index `ior`.
    Plastic,
    /// Glass: smooth when `roughness` is 0, GGX rough otherwise; `color` tints transmission.
    Dielectric,
    /// Emits `emission`, reflects nothing.
    Emissive,
    /// A conductor (`color` = η, `k` = κ) whose NDF is the P-NDF of a glint microstructure
    /// by example ([`GlintSpec`]).
    Glint,
}

/// Surface coordinates of a glint material: a projection of the object-space hit point, or the
/// mesh's own texture coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlintProjection {
    /// (x, z) of object space: the plane of the built-in quad, and of any surface that is a
    /// height field over it (a bent quad).
    Planar,
    /// Longitude and colatitude about the object-space point (0.5, 0.5, 0.5) (the built-in
    /// sphere's centre), times the distance to it: arc lengths on a sphere, stretched towards
    /// its poles (y axis).
    Spherical,
    /// The mesh's texture coordinates (its UV unit square spans `scale` scene units).
    Mesh,
}

/// The microstructure of a glint material.
#[derive(Clone, Debug)]
pub struct GlintSpec {
    /// The infinite normal map by example (example, tables, patch edge, seed, blending).
    pub map: std::sync::Arc<crate::glint::ByExampleMap>,
    /// The example's file.
    pub source: std::path::PathBuf,
    /// How the file became the example (cut or resampled to a power-of-two square).
    pub fit: crate::glint::example::MapFit,
    /// σ_r of the P-NDF's Gaussian elements (normal units).
    pub intrinsic_roughness: f32,
    /// Width of the example in scene units (world units: the instance scale does not change it).
    pub scale: f32,
    /// Where the surface coordinates come from.
    pub projection: GlintProjection,
    /// Evaluate every texel of the footprint without pruning (the explicit reference).
    pub explicit: bool,
    /// GGX α of the Smith shadowing term: the example's RMS slope.
    pub shadow_alpha: f32,
}

impl PartialEq for GlintSpec {
    fn eq(&self, o: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.map, &o.map)
            && self.source == o.source
            && self.fit == o.fit
            && self.intrinsic_roughness == o.intrinsic_roughness
            && self.scale == o.scale
            && self.projection == o.projection
            && self.explicit == o.explicit
            && self.shadow_alpha == o.shadow_alpha
    }
}

/// A material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name instances refer to.
    pub name: String,
    /// Scattering model.
    pub kind: MaterialKind,
    /// Albedo (Lambertian, plastic), η (conductor) or transmission tint (dielectric).
    pub color: Vec3,
    /// Extinction κ of a conductor (unused otherwise).
    pub k: Vec3,
    /// Emitted radiance (emissive; zero otherwise).
    pub emission: Vec3,
    /// GGX α = roughness² convention: `roughness` in [0, 1].
    pub roughness: f32,
    /// Index of refraction of a dielectric or of the plastic coat (> 1).
    pub ior: f32,
    /// Solid texture replacing `color` as albedo, evaluated in rest-pose object coordinates.
    pub texture: Option<SolidTexture>,
    /// The microstructure of a [`MaterialKind::Glint`] material.
    pub glint: Option<GlintSpec>,
    /// An albedo image replacing `color`, read at the mesh's texture coordinates (Lambertian,
    /// plastic).
    pub albedo_map: Option<ImageMap>,
    /// A tangent-space normal map read at the mesh's texture coordinates, bending the shading
    /// normal (Lambertian, conductor, plastic).
    pub normal_map: Option<NormalMap>,
}

impl Material {
    /// True when the material reads the mesh's texture coordinates (its meshes must have them).
    pub fn needs_uvs(&self) -> bool {
        self.albedo_map.is_some()
            || self.normal_map.is_some()
            || self
                .glint
                .as_ref()
                .is_some_and(|g| g.projection == GlintProjection::Mesh)
    }
}

/// An image read at texture coordinates, with its MIP pyramid.
#[derive(Clone, Debug)]
pub struct ImageMap {
    /// The file.
    pub source: PathBuf,
    /// Its levels, as uploaded.
    pub image: std::sync::Arc<crate::image_texture::ImageTexture>,
    /// With `albedo_ctree_step`: the image as compressed random-access trees, which the
    /// renderer reads instead of the levels, and the step they were built with.
    pub ctree: Option<(
        f32,
        std::sync::Arc<lazysolid_compute::ctree::colour::ColourTrees>,
    )>,
}

impl PartialEq for ImageMap {
    fn eq(&self, o: &Self) -> bool {
        self.source == o.source
            && std::sync::Arc::ptr_eq(&self.image, &o.image)
            && match (&self.ctree, &o.ctree) {
                (None, None) => true,
                (Some((a, x)), Some((b, y))) => a == b && std::sync::Arc::ptr_eq(x, y),
                _ => false,
            }
    }
}

/// How a normal map is read over a ray's footprint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalFilter {
    /// The finest level's nearest texel, whatever the footprint: the map's own facets, the
    /// reference when rendered with many samples per pixel (and aliased with few).
    None,
    /// The footprint's mean normal from a MIP pyramid of averaged normals, renormalized: the
    /// baseline that flattens bumps at a distance (seed 000 Fig. 7.3).
    Mip,
    /// A mixture of von Mises–Fisher lobes per texel of every level (seed 000 ch. 7), chosen
    /// stochastically over the footprint and convolved with the BSDF's lobe in closed form.
    Vmf,
}

/// A tangent-space normal map (or a height map converted to one).
#[derive(Clone, Debug)]
pub struct NormalMap {
    /// The file.
    pub source: PathBuf,
    /// How the file became the example (cut or resampled to a power-of-two square).
    pub fit: crate::glint::example::MapFit,
    /// The level-0 normals (+y towards +v), what the vMF fit starts from.
    pub example: std::sync::Arc<crate::glint::NormalExample>,
    /// Its plain MIP pyramid, as uploaded.
    pub image: std::sync::Arc<crate::image_texture::ImageTexture>,
    /// How it is read over a footprint.
    pub filter: NormalFilter,
    /// vMF lobes per texel (`J`, [`crate::normal_map::pyramid::LOBES_PER_TEXEL`]).
    pub lobes: usize,
}

impl PartialEq for NormalMap {
    fn eq(&self, o: &Self) -> bool {
        self.source == o.source
            && self.fit == o.fit
            && std::sync::Arc::ptr_eq(&self.example, &o.example)
            && self.filter == o.filter
            && self.lobes == o.lobes
    }
}

/// A solid (3D) texture evaluated at the rest-pose object-space hit point.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidTexture {
    /// Which pattern.
    pub kind: SolidTextureKind,
    /// First colour of the pattern.
    pub color_a: Vec3,
    /// Second colour of the pattern.
    pub color_b: Vec3,
    /// Pattern frequency: features per unit of object space.
    pub scale: f32,
    /// The voxels of a [`SolidTextureKind::Volume`] (shared, since a texture is cloned with
    /// its material).
    pub volume: Option<std::sync::Arc<VolumeTexture>>,
    /// The exemplar and seed of a [`SolidTextureKind::Synthesized`] texture.
    pub synthesized: Option<SynthesizedSpec>,
    /// When set, the pattern is baked into a sparse store over the mesh's surface voxels and the
    /// renderer reads the store instead of evaluating the pattern: how the structures that will
    /// hold synthesized matter are rendered and compared.
    pub store: Option<StoreSpec>,
}

impl SolidTexture {
    /// The texture of a volume's voxels, read through `store`: its two colours are the
    /// volume's mean (what a material without a store would show), as a scene's `volume`
    /// texture and `lazysolid solid`'s carved render make it.
    pub fn of_volume(volume: VolumeTexture, store: Option<StoreSpec>) -> SolidTexture {
        let mean = glam::Vec3::from_array(volume.mean_linear());
        SolidTexture {
            kind: SolidTextureKind::Volume,
            color_a: mean,
            color_b: mean,
            scale: 1.0,
            volume: Some(std::sync::Arc::new(volume)),
            synthesized: None,
            store,
        }
    }
}

/// A solid texture synthesized from a 2D exemplar playing all three roles (lazily: only the
/// voxels the store needs are synthesized).
#[derive(Clone, Debug, PartialEq)]
pub struct SynthesizedSpec {
    /// What the matter is made from, but for the relief channel, which follows `relief`
    /// ([`SynthesizedSpec::recipe`]).
    pub(crate) colours: lazysolid_synth::solid::SolidRecipe,
    /// How the image becomes the solid exemplar (`lazysolid solid --fit auto`'s rule), decided
    /// when the scene is read and reported with the render.
    pub fit: lazysolid_synth::ExemplarFit,
    /// What the synthesis state keeps between requests (`memory = "keep"` or `"32MB"`).
    pub policy: lazysolid_synth::solid::lazy::MemoryPolicy,
    /// Slope of the relief's feature walls (`relief = …`; 0: none): the texels carry the
    /// relief channel in alpha and the path tracer bends shading normals by its gradient.
    pub relief: f32,
}

impl SynthesizedSpec {
    /// What the matter is made from: the exemplar (GIMP pattern, PNG or JPEG) fitted and
    /// oriented by the defaults `lazysolid solid` uses, the texture's seed, and the relief
    /// channel when `relief` is above 0. The same recipe gives `lazysolid solid`'s volume.
    pub fn recipe(&self) -> lazysolid_synth::solid::SolidRecipe {
        lazysolid_synth::solid::SolidRecipe {
            relief: self.relief > 0.0,
            ..self.colours.clone()
        }
    }
}

/// Which sparse store holds a baked solid texture, at what resolution, read how.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StoreSpec {
    /// The structure.
    pub kind: StoreKind,
    /// Voxels per unit of object space along each axis (the mesh's unit cube).
    pub resolution: u32,
    /// Nearest texel or trilinear interpolation.
    pub filter: StoreFilter,
}

/// Declares [`StoreKind`] from one line per kind (variant and scene name), so that the enum,
/// its names, the parser's list and every all-kinds list of the tests come from one place.
macro_rules! store_kinds {
    ($($(#[$doc:meta])* $variant:ident = $name:literal,)*) => {
        /// Sparse stores a solid texture can be baked into.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum StoreKind {
            $($(#[$doc])* $variant,)*
        }

        impl StoreKind {
            /// Every kind, in the order of the registration list.
            pub const ALL: &'static [StoreKind] = &[$(StoreKind::$variant),*];

            /// The name a scene file gives it.
            pub fn name(self) -> &'static str {
                match self {
                    $(StoreKind::$variant => $name,)*
                }
            }
        }
    };
}

store_kinds! {
    /// The coherent parallel hash keyed by voxel Morton codes.
    CoherentHash = "coherent_hash",
    /// The N³ octree texture.
    Octree = "octree",
    /// The perfect spatial hash (texel layout, constrained access: no keys stored).
    PerfectHash = "perfect_hash",
    /// The TileTree: 2D tiles on the leaves of an octree around the surface, built from the
    /// mesh itself; R must be a power of two.
    TileTree = "tiletree",
}

impl StoreKind {
    /// The kind a scene file names `name`, if any.
    pub fn from_name(name: &str) -> Option<StoreKind> {
        StoreKind::ALL.iter().copied().find(|k| k.name() == name)
    }

    /// Every scene name, quoted, for an error to list: "`coherent_hash`, `octree`, ...".
    pub fn names() -> String {
        StoreKind::ALL
            .iter()
            .map(|k| format!("`{}`", k.name()))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// How a store is sampled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StoreFilter {
    /// The texel containing the point.
    Nearest,
    /// Trilinear interpolation of the 8 surrounding texel centres.
    Trilinear,
}

/// Procedural solid patterns (until the sparse stores and the synthesizer provide matter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SolidTextureKind {
    /// Turbulent veins (sine of x plus fractal noise).
    Marble,
    /// Concentric rings around the y axis perturbed by noise.
    Wood,
    /// A 3D checkerboard (exact, handy for tests).
    Checker,
    /// An RGB volume read from a file (for example one `lazysolid solid` synthesized),
    /// stretched over the unit cube; read only through a store.
    Volume,
    /// Matter synthesized from a 2D exemplar over the unit cube, lazily (only the voxels its
    /// store needs); read only through a store.
    Synthesized,
}

/// A placed mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Index into [`Scene::meshes`].
    pub mesh: usize,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// Object-to-world rigid (or uniformly scaled) transform, at rest.
    pub transform: Affine3A,
    /// For a piece of a cut or fractured instance: how it moves in an explosion.
    pub piece: Option<Piece>,
}

/// What moves one piece of a broken instance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// Index of the broken instance in the scene file's `[[instance]]` list (its pieces share
    /// the explosion's default centre).
    pub broken: usize,
    /// The piece's centre of mass in object space.
    pub centroid: Vec3,
    /// The centre of the broken instance's bounds in object space.
    pub centre: Vec3,
    /// Unit axis it spins about.
    pub spin_axis: Vec3,
    /// Fraction (0.5–1) of the explosion's spin it turns at.
    pub spin_share: f32,
    /// Seconds after the explosion's start at which the piece first touches the ground (it
    /// keeps that pose from then on); `None` without a ground or when it never gets there.
    pub contact: Option<f32>,
    /// Crossings of cut segments resolved in the caps that made this piece (where the input
    /// surface intersects itself; 0 for a clean mesh), so that a scene's load can say so.
    pub resolved_crossings: usize,
    /// Vertex copies and edge splits that separated the sheets of the self-intersecting input
    /// where they met in this piece ([`Fragment::separated_vertices`](crate::fracture::Fragment::separated_vertices)),
    /// so that every piece is a 2-manifold.
    pub separated_vertices: usize,
}

/// Analytic area lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A sphere emitting uniformly in all directions.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius (> 0).
        radius: f32,
        /// Emitted radiance.
        radiance: Vec3,
    },
    /// A parallelogram `corner + s·edge_u + t·edge_v`, s, t in [0, 1].
    Quad {
        /// One corner.
        corner: Vec3,
        /// First edge.
        edge_u: Vec3,
        /// Second edge; emission faces `edge_u × edge_v` unless two-sided.
        edge_v: Vec3,
        /// Emitted radiance.
        radiance: Vec3,
        /// Emits on both faces.
        two_sided: bool,
    },
}

/// Radiance arriving from infinity.
#[derive(Clone, Debug, PartialEq)]
pub enum Environment {
    /// The same radiance from every direction (black for none).
    Constant(Vec3),
    /// A lat-long (equirectangular) HDR map, +y up, u = 0 at −z turning towards +x.
    LatLong {
        /// The EXR file.
        path: PathBuf,
        /// Multiplier of the map's radiance (> 0).
        intensity: f32,
        /// Rotation about +y in degrees.
        rotation_deg: f32,
    },
}
