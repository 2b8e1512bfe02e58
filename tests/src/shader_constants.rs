//! Constants of the test-only kernels (`glsl/render_test/`), shared by their Rust callers and
//! GLSL like every crate's `shader_constants.rs` (`build.rs` passes each
//! `pub const NAME: u32 = LITERAL;` line to the kernels as `#define NAME VALUE`).

/// What `glsl/render_test/shading_test.comp` evaluates for each case: the BSDF entry points, the
/// solid textures, the lights, the environment, or the random numbers and warps.
pub const SHADING_TEST_BSDF: u32 = 0;
/// See [`SHADING_TEST_BSDF`].
pub const SHADING_TEST_TEXTURE: u32 = 1;
/// See [`SHADING_TEST_BSDF`].
pub const SHADING_TEST_LIGHT: u32 = 2;
/// See [`SHADING_TEST_BSDF`].
pub const SHADING_TEST_ENVIRONMENT: u32 = 3;
/// See [`SHADING_TEST_BSDF`].
pub const SHADING_TEST_RNG: u32 = 4;
