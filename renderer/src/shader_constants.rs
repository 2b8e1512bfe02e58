//! Constants shared by the renderer's Rust code and its GLSL (`glsl/render/`,
//! `glsl/include/render/`), defined once here.
//!
//! `build.rs` reads this file (after `lazysolid_compute::shader_constants`, whose constants the
//! store includes use) and passes every `pub const NAME: u32 = LITERAL;` line to the GLSL
//! compiler as `#define NAME VALUE`. Only plain `u32` literals are allowed on such lines.

/// Workgroup width of kernels that trace rays through `render/cwbvh.glsl`: their traversal
/// stacks (`CWBVH_STACK_SIZE` entries of 8 bytes per invocation) fill 32 KiB of shared memory,
/// lavapipe's `maxComputeSharedMemorySize` and the smallest of common desktop GPUs (NVIDIA
/// 48 KiB, AMD and Intel 64 KiB). `ray_queries::cwbvh_kernel` checks it against the device.
pub const CWBVH_WORKGROUP_SIZE: u32 = 128;
/// Entries of each invocation's CWBVH traversal stack in shared memory (obvhs's CPU traversal
/// uses 32).
pub const CWBVH_STACK_SIZE: u32 = 32;
/// Material kinds of the path tracer (`renderer::scene::MaterialKind`), as stored in the
/// GPU material's `kind` field.
pub const MATERIAL_LAMBERTIAN: u32 = 0;
/// See [`MATERIAL_LAMBERTIAN`].
pub const MATERIAL_CONDUCTOR: u32 = 1;
/// See [`MATERIAL_LAMBERTIAN`].
pub const MATERIAL_PLASTIC: u32 = 2;
/// See [`MATERIAL_LAMBERTIAN`].
pub const MATERIAL_DIELECTRIC: u32 = 3;
/// See [`MATERIAL_LAMBERTIAN`].
pub const MATERIAL_EMISSIVE: u32 = 4;
/// See [`MATERIAL_LAMBERTIAN`].
pub const MATERIAL_GLINT: u32 = 5;

/// Knots of a plastic coat's directional-albedo table in the GPU material: knot i holds the
/// coat's reflectance at cos θ = (i / (knots − 1))², denser towards grazing where it changes
/// fastest.
pub const PLASTIC_COAT_KNOTS: u32 = 16;

/// Solid texture kinds of a GPU material: none means the albedo is the material's colour.
pub const TEXTURE_NONE: u32 = 0;
/// See [`TEXTURE_NONE`].
pub const TEXTURE_MARBLE: u32 = 1;
/// See [`TEXTURE_NONE`].
pub const TEXTURE_WOOD: u32 = 2;
/// See [`TEXTURE_NONE`].
pub const TEXTURE_CHECKER: u32 = 3;
/// See [`TEXTURE_NONE`]: an albedo image read at the mesh's texture coordinates.
pub const TEXTURE_IMAGE: u32 = 4;

/// Texel encodings of an image texture (`renderer::image_texture::ImageEncoding`): sRGB colour
/// and linear alpha.
pub const IMAGE_ENCODING_SRGB: u32 = 0;
/// A tangent-space normal map, xyz = 2·rgb − 1.
pub const IMAGE_ENCODING_NORMAL: u32 = 1;
/// An sRGB colour image read through three compressed random-access trees (Y, Co, Cg;
/// `lazysolid_compute::ctree`) instead of its MIP pyramid.
pub const IMAGE_ENCODING_CTREE: u32 = 2;
/// Most taps of an anisotropic image lookup along its footprint's long axis: beyond it the
/// level rises instead (the footprint is blurred along its short axis).
pub const IMAGE_MAX_ANISOTROPY: u32 = 8;
/// Most MIP levels of an image texture (an edge of 8192 has 14).
pub const IMAGE_MAX_LEVELS: u32 = 14;
/// How a normal map is read over a footprint (`renderer::scene::NormalFilter`): the finest
/// level's nearest texel.
pub const NORMAL_FILTER_NONE: u32 = 0;
/// The footprint's mean normal from the plain MIP pyramid, renormalized.
pub const NORMAL_FILTER_MIP: u32 = 1;
/// A vMF mixture per texel of every level.
pub const NORMAL_FILTER_VMF: u32 = 2;
/// Largest vMF concentration the path tracer derives from a lobe's mean length (the CPU fit's
/// `MAX_KAPPA`, 1e5): a lobe 0.26° wide.
pub const VMF_MAX_KAPPA: u32 = 100000;
/// Most vMF lobes per texel (`renderer::normal_map::pyramid::LOBES_PER_TEXEL`'s end): the
/// size of the path tracer's per-hit lobe arrays.
pub const VMF_MAX_LOBES: u32 = 8;
/// Covered normals one invocation of the vMF EM accumulation reads: with up to
/// [`VMF_MAX_LOBES`] lobes its loops stay under lavapipe's 65 535 iterations per invocation.
pub const VMF_EM_CHUNK: u32 = 2048;
/// EM iterations per texel at most (`renderer::normal_map::mixture::MAX_EM_ITERATIONS`).
pub const VMF_EM_MAX_ITERATIONS: u32 = 30;
/// Specialization constant id of the path tracer's vMF lobes per texel (the largest `J` of the
/// scene's vMF-filtered normal maps; 0 compiles the mixture BSDF out).
pub const PATH_TRACE_VMF_LOBES_ID: u32 = 6;
/// `GpuMaterial::albedo_image` / `normal_image` of a material without that image.
pub const IMAGE_NONE: u32 = 4294967295;

/// An instance's store slot (written by `SceneStores::build`, read from `instance_stores` by
/// `path_trace.comp`) when its albedo is not read from a store. Like the sentinels below it is
/// `u32::MAX`, spelled as a literal because only literals become `#define`s.
pub const NO_STORE: u32 = 4294967295;
/// `GpuInstance::uv_offset` of an instance whose mesh has no texture coordinates
/// (`surface_uv` in `path_trace.comp` then reports none).
pub const NO_UVS: u32 = 4294967295;
/// Marks "no hit": `TraceHit::instance` in `render/cwbvh.glsl`, `GpuRayHit::instance` and
/// `triangle` as `trace_rays.comp` writes them, and the CPU reference's.
pub const NO_HIT: u32 = 4294967295;

/// Analytic light kinds of a GPU light.
pub const LIGHT_SPHERE: u32 = 0;
/// See [`LIGHT_SPHERE`].
pub const LIGHT_QUAD: u32 = 1;

/// Environment kinds: the same radiance everywhere, or a lat-long HDR map.
pub const ENVIRONMENT_CONSTANT: u32 = 0;
/// See [`ENVIRONMENT_CONSTANT`].
pub const ENVIRONMENT_LATLONG: u32 = 1;

/// Sparse stores a renderer record may describe.
pub const STORE_KIND_HASH: u32 = 0;
/// See [`STORE_KIND_HASH`].
pub const STORE_KIND_OCTREE: u32 = 1;
/// See [`STORE_KIND_HASH`].
pub const STORE_KIND_PERFECT: u32 = 2;
/// See [`STORE_KIND_HASH`].
pub const STORE_KIND_TILETREE: u32 = 3;
/// Specialization constant id of the path tracer's store-kind mask (bit `STORE_KIND_*` set for
/// each kind the scene uses; the others' lookups are compiled out).
pub const PATH_TRACE_STORE_KINDS_ID: u32 = 2;
/// Specialization constant id of the path tracer's material-kind mask (bit `MATERIAL_*` set for
/// each kind the scene's materials use; the others' BSDFs are compiled out).
pub const PATH_TRACE_MATERIAL_KINDS_ID: u32 = 3;
/// Specialization constant id of the path tracer's texture-kind mask (bit `TEXTURE_*` set for
/// each procedural kind the scene's materials use).
pub const PATH_TRACE_TEXTURE_KINDS_ID: u32 = 4;
/// Specialization constant id of the path tracer's normal-map switch (1 when a scene material
/// has a normal map; 0 compiles the tangent frame and the map lookup out).
pub const PATH_TRACE_NORMAL_MAPS_ID: u32 = 5;
/// Specialization constant id of the image lookup's compressed-tree switch
/// (`render/image.glsl`: 1 when an image is read through compressed trees; 0 compiles that
/// lookup out of every kernel that reads images, lavapipe running branches masked).
pub const IMAGE_CTREES_ID: u32 = 7;
/// Nearest-texel store reads.
pub const STORE_FILTER_NEAREST: u32 = 0;
/// Trilinear store reads (the store holds the interpolation voxels).
pub const STORE_FILTER_TRILINEAR: u32 = 1;

/// Blending modes of the glint microstructure by example (`renderer::glint::BlendMode`):
/// none takes each point from the nearest vertex's patch (flakes: constant normals, no seams
/// visible); linear is Eq. 4 of the paper; variance-preserving Eq. 5; histogram-preserving
/// Eq. 6.
pub const GLINT_BLEND_NONE: u32 = 0;
/// See [`GLINT_BLEND_NONE`].
pub const GLINT_BLEND_LINEAR: u32 = 1;
/// See [`GLINT_BLEND_NONE`].
pub const GLINT_BLEND_VARIANCE: u32 = 2;
/// See [`GLINT_BLEND_NONE`].
pub const GLINT_BLEND_HISTOGRAM: u32 = 3;
/// Knots of each Gaussianization table (G and G⁻¹ per normal component).
pub const GLINT_TABLE_KNOTS: u32 = 256;
/// Surface coordinates of a glint material: object-space (x, z).
pub const GLINT_UV_PLANAR: u32 = 0;
/// Surface coordinates of a glint material: arc lengths about the built-in sphere's centre.
pub const GLINT_UV_SPHERICAL: u32 = 1;
/// Surface coordinates of a glint material: the mesh's texture coordinates.
pub const GLINT_UV_MESH: u32 = 2;
/// `GpuMaterial::glint` of a material without a microstructure.
pub const GLINT_NONE: u32 = 4294967295;
