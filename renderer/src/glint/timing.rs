//! The glint material's render-time cases, for benchmarks and the tests: the same scene with
//! its glint materials evaluated by the pruned traversal, by the explicit reference (every
//! texel of each footprint, no pruning), and replaced by the plain conductor they are made of
//! (same η and κ, a GGX roughness instead of the P-NDF).

use crate::output::Film;
use crate::render::{PathTracer, RenderError};
use crate::scene::{MaterialKind, Scene};
use lazysolid_compute::gpu::Gpu;
use std::time::Duration;

/// How a scene's glint materials are rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GlintCase {
    /// The P-NDF by the pruned traversal (the material as the scene gives it).
    Pruned,
    /// The P-NDF summed over every texel of each footprint (the explicit reference).
    Explicit,
    /// Each glint material replaced by a GGX conductor of this roughness with its η and κ.
    Conductor {
        /// GGX roughness (α = roughness²).
        roughness: f32,
    },
}

impl GlintCase {
    /// The three cases of the note: pruned, explicit, and the conductor at roughness 0.3.
    pub const ALL: [GlintCase; 3] = [
        GlintCase::Pruned,
        GlintCase::Explicit,
        GlintCase::Conductor { roughness: 0.3 },
    ];

    /// A short name for tables.
    pub fn name(self) -> &'static str {
        match self {
            GlintCase::Pruned => "glint (pruned)",
            GlintCase::Explicit => "glint (explicit)",
            GlintCase::Conductor { .. } => "conductor",
        }
    }

    /// `scene` with its glint materials rendered this way.
    pub fn apply(self, scene: &Scene) -> Scene {
        let mut s = scene.clone();
        for m in &mut s.materials {
            if m.kind != MaterialKind::Glint {
                continue;
            }
            match self {
                GlintCase::Pruned | GlintCase::Explicit => {
                    if let Some(g) = &mut m.glint {
                        g.explicit = self == GlintCase::Explicit;
                    }
                }
                GlintCase::Conductor { roughness } => {
                    m.kind = MaterialKind::Conductor;
                    m.roughness = roughness;
                    m.glint = None;
                }
            }
        }
        s
    }
}

/// One case rendered.
pub struct GlintTiming {
    /// The case.
    pub case: GlintCase,
    /// The picture.
    pub film: Film,
    /// Time of the passes after a one-sample warm-up (kernel compilation and first-use costs
    /// excluded), scaled to the scene's samples per pixel.
    pub time: Duration,
}

/// Renders `scene` in each of `cases` on `gpu`: one warm-up sample, then the scene's samples
/// per pixel, timed.
///
/// # Errors
/// Device failures and scenes the path tracer refuses.
pub fn render_glint_cases(
    gpu: &Gpu,
    scene: &Scene,
    cases: &[GlintCase],
) -> Result<Vec<GlintTiming>, RenderError> {
    cases
        .iter()
        .map(|&case| {
            let s = case.apply(scene);
            let mut warm = s.clone();
            warm.render.spp = 1;
            PathTracer::new(gpu, &warm)?.render(|_| {})?;
            let mut t = PathTracer::new(gpu, &s)?;
            let mut time = Duration::ZERO;
            let film = t.render(|p| time += p.time)?;
            Ok(GlintTiming { case, film, time })
        })
        .collect()
}
