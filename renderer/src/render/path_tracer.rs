//! The path tracer: owns the scene's device data and the film, and adds one sample per pixel
//! per pass, so callers can show progress and stop at any sample count.

use super::error::RenderError;
use super::frame::GpuFrame;
use super::stores::{BakedStoreInfo, SceneStores};
use crate::accel::{DeviceBvh, SceneBvh};
use crate::image_texture::{DeviceImages, ImageSet};
use crate::kernels::render::PATH_TRACE;
use crate::normal_map::pyramid::VmfPyramid;
use crate::output::Film;
use crate::scene::{Environment, NormalFilter, RenderSettings, Scene, MAX_DEPTH};
use crate::shader_constants::{
    IMAGE_CTREES_ID, IMAGE_NONE, NORMAL_FILTER_MIP, NORMAL_FILTER_NONE, NORMAL_FILTER_VMF,
    PATH_TRACE_MATERIAL_KINDS_ID, PATH_TRACE_NORMAL_MAPS_ID, PATH_TRACE_STORE_KINDS_ID,
    PATH_TRACE_TEXTURE_KINDS_ID, PATH_TRACE_VMF_LOBES_ID,
};
use crate::shading::{GpuEnvironment, GpuLight, GpuMaterial};
use bytemuck::Zeroable;
use lazysolid_compute::gpu::{DeviceRecords, Gpu, GpuBuffer, Kernel};
use std::sync::Arc;
use std::time::{Duration, Instant};

lazysolid_compute::push_block! {
    /// Push block of `path_trace.comp`.
    #[derive(Clone, Copy)]
    pub(crate) struct PathTracePush {
        sample_index: u32,
        first_pixel: u32,
        pixel_count: u32,
    }
}

/// What one pass did.
#[derive(Clone, Copy, Debug)]
pub struct PassReport {
    /// Samples per pixel accumulated so far.
    pub samples: u32,
    /// Rays traced by the pass (camera, bounce and shadow rays).
    pub rays: u64,
    /// Wall time of the pass.
    pub time: Duration,
}

/// Facts about the prepared scene, for messages and benchmarks.
#[derive(Clone, Copy, Debug)]
pub struct RenderStats {
    /// Time to build every mesh BVH.
    pub blas_time: Duration,
    /// Time to build the instance BVH.
    pub tlas_time: Duration,
    /// Triangles over all instances.
    pub instanced_triangles: u64,
    /// GPU bytes of the BVHs.
    pub bvh_bytes: u64,
    /// Time to fit the vMF pyramids of the scene's normal maps (CPU, every core).
    pub vmf_fit_time: Duration,
    /// GPU bytes of the image textures, normal maps and vMF lobes.
    pub image_bytes: u64,
}

/// A scene on the device with its film.
pub struct PathTracer {
    gpu: Gpu,
    kernel: Arc<Kernel>,
    scene_bvh: SceneBvh,
    bvh: DeviceBvh,
    frame: GpuFrame,
    frame_buf: GpuBuffer<GpuFrame>,
    materials: GpuBuffer<GpuMaterial>,
    lights: GpuBuffer<GpuLight>,
    /// The `Environment` record; it holds the environment's tables.
    environment: DeviceRecords,
    stores: SceneStores,
    glints: crate::glint::SceneGlints,
    images: DeviceImages,
    film: GpuBuffer<[f32; 4]>,
    aovs: GpuBuffer<[f32; 4]>,
    ray_count: GpuBuffer<u32>,
    settings: RenderSettings,
    samples: u32,
    stats: RenderStats,
}

impl PathTracer {
    /// Builds the BVHs and uploads everything the kernel reads.
    ///
    /// # Errors
    /// Device failures and limits, or shading data that cannot be prepared (an unreadable
    /// environment map).
    pub fn new(gpu: &Gpu, scene: &Scene) -> Result<PathTracer, RenderError> {
        check_scene(scene)?;
        let settings = scene.render;
        let scene_bvh = SceneBvh::from_scene(scene);
        let bvh = DeviceBvh::upload(gpu, &scene_bvh)?;
        let stores = SceneStores::build(gpu, scene)?;
        let glints = crate::glint::SceneGlints::build(gpu, scene)?;
        let vmf_start = Instant::now();
        let pyramids = vmf_pyramids(scene)?;
        let vmf_fit_time = vmf_start.elapsed();
        let vmf_lobes = pyramids
            .iter()
            .flatten()
            .map(|p| p.lobes_per_texel)
            .max()
            .unwrap_or(0);
        let mut image_set = ImageSet::with_vmf_stride(vmf_lobes);
        let mut materials = Vec::with_capacity(scene.materials.len());
        for ((m, &glint), pyramid) in scene.materials.iter().zip(&glints.slots).zip(&pyramids) {
            let mut add = |image: &crate::image_texture::ImageTexture| {
                image_set
                    .add(image)
                    .map_err(|e| RenderError::Settings(format!("material {:?}: {e}", m.name)))
            };
            let albedo_image = match &m.albedo_map {
                Some(a) => match &a.ctree {
                    Some((_, trees)) => image_set.add_ctree(&a.image, trees),
                    None => add(&a.image)?,
                },
                None => IMAGE_NONE,
            };
            let normal_image = match &m.normal_map {
                Some(n) => image_set
                    .add_normal_map(&n.image, normal_filter_code(n.filter), pyramid.as_ref())
                    .map_err(|e| RenderError::Settings(format!("material {:?}: {e}", m.name)))?,
                None => IMAGE_NONE,
            };
            materials.push(GpuMaterial {
                glint,
                albedo_image,
                normal_image,
                ..GpuMaterial::from(m)
            });
        }
        let image_ctrees = image_set.has_ctrees();
        let images = image_set.upload(gpu)?;
        let lights: Vec<GpuLight> = scene.lights.iter().map(GpuLight::from).collect();
        // A binding cannot be empty: a scene without lights still gets one (unused) record.
        let light_records = if lights.is_empty() {
            vec![GpuLight::zeroed()]
        } else {
            lights.clone()
        };
        let environment = GpuEnvironment::from_scene(gpu, &scene.environment)?;
        let env_sampled = match &scene.environment {
            Environment::Constant(c) => c.max_element() > 0.0,
            Environment::LatLong { .. } => true,
        };
        let frame = GpuFrame::new(&scene.camera, &settings, lights.len() as u32, env_sampled);
        let pixels = settings.width as usize * settings.height as usize;
        let stats = RenderStats {
            blas_time: scene_bvh.blas_time,
            tlas_time: scene_bvh.tlas_time,
            instanced_triangles: scene_bvh.instanced_triangles(),
            bvh_bytes: bvh.bytes(),
            vmf_fit_time,
            image_bytes: images.bytes(),
        };
        Ok(PathTracer {
            gpu: gpu.clone(),
            kernel: crate::accel::ray_queries::cwbvh_kernel(
                gpu,
                &PATH_TRACE,
                &[
                    (PATH_TRACE_STORE_KINDS_ID, stores.kinds_mask()),
                    (
                        PATH_TRACE_MATERIAL_KINDS_ID,
                        super::kinds_mask(materials.iter().map(|m| m.kind)),
                    ),
                    (
                        PATH_TRACE_TEXTURE_KINDS_ID,
                        super::kinds_mask(materials.iter().map(|m| m.texture_kind)),
                    ),
                    (
                        PATH_TRACE_NORMAL_MAPS_ID,
                        materials.iter().any(|m| m.normal_image != IMAGE_NONE) as u32
                            | ((vmf_lobes > 0) as u32) << 1,
                    ),
                    (PATH_TRACE_VMF_LOBES_ID, vmf_lobes.max(1) as u32),
                    (IMAGE_CTREES_ID, image_ctrees as u32),
                ],
            )?,
            frame_buf: GpuBuffer::from_slice(gpu, "render frame", &[frame])?,
            materials: GpuBuffer::from_slice(gpu, "render materials", &materials)?,
            lights: GpuBuffer::from_slice(gpu, "render lights", &light_records)?,
            environment: DeviceRecords::new(gpu, "render environment", &[environment.params()])?,
            film: GpuBuffer::zeroed(gpu, "render film", pixels)?,
            aovs: GpuBuffer::zeroed(gpu, "render aovs", 2 * pixels)?,
            ray_count: GpuBuffer::zeroed(gpu, "render ray count", 1)?,
            bvh,
            scene_bvh,
            stores,
            glints,
            images,
            frame,
            settings,
            samples: 0,
            stats,
        })
    }

    /// Adds one sample to every pixel.
    ///
    /// # Errors
    /// Device failures.
    pub fn pass(&mut self) -> Result<PassReport, RenderError> {
        let start = Instant::now();
        let aovs = self.samples == 0;
        if aovs != (self.frame.aovs != 0) {
            self.frame.aovs = aovs as u32;
            self.frame_buf.write(0, &[self.frame])?;
        }
        let tiles =
            self.settings.width.div_ceil(8) as u64 * self.settings.height.div_ceil(8) as u64;
        let invocations = tiles * 64;
        let push = PathTracePush {
            sample_index: self.samples,
            first_pixel: 0,
            pixel_count: invocations as u32,
        };
        self.ray_count.write(0, &[0])?;
        let [b0, b1, b2, b3, b4] = self.bvh.bindings();
        let [s0, s1] = self.stores.bindings();
        let [i0, i1, i2] = self.images.bindings();
        let [v0, v1] = self.images.vmf_bindings();
        let bindings = [
            s0,
            s1,
            i0,
            i1,
            i2,
            v0,
            v1,
            self.bvh.uv_binding(),
            b0,
            b1,
            b2,
            b3,
            b4,
            ("FrameBlock", self.frame_buf.arg()),
            ("Materials", self.materials.arg()),
            ("Lights", self.lights.arg()),
            ("EnvironmentBlock", self.environment.arg()),
            ("Film", self.film.arg()),
            ("Aovs", self.aovs.arg()),
            ("RayCount", self.ray_count.arg()),
            ("GlintRecords", self.glints.records.arg()),
        ];
        self.gpu.submit(|rec| {
            rec.dispatch(
                &self.kernel,
                self.kernel.groups_for(invocations),
                &bindings,
                &push,
            )
        })?;
        self.samples += 1;
        let rays = self.ray_count.read()?[0] as u64;
        Ok(PassReport {
            samples: self.samples,
            rays,
            time: start.elapsed(),
        })
    }

    /// Moves the instances to where they are at `time` (seconds; see
    /// [`Scene::instance_transform`]) and starts the picture over. Only the top level of the
    /// BVH is rebuilt; meshes, stores and their texels stay, so an animation synthesizes
    /// nothing after its first frame.
    ///
    /// # Errors
    /// Device failures.
    pub fn set_time(&mut self, scene: &Scene, time: f32) -> Result<(), RenderError> {
        let transforms: Vec<_> = (0..scene.instances.len())
            .map(|i| scene.instance_transform(i, time))
            .collect();
        self.scene_bvh.set_transforms(&transforms);
        self.bvh = DeviceBvh::upload(&self.gpu, &self.scene_bvh)?;
        self.stats.tlas_time = self.scene_bvh.tlas_time;
        self.restart()
    }

    /// Renders at `settings` (size, samples, seed, depths) from now on: the film and the frame
    /// record are made anew, the BVH, the stores and their texels stay — how one run renders a
    /// large still and a small animation without baking twice.
    ///
    /// # Errors
    /// Device failures.
    pub fn set_settings(
        &mut self,
        scene: &Scene,
        settings: RenderSettings,
    ) -> Result<(), RenderError> {
        check_settings(&scene.source, &settings)?;
        let env_sampled = match &scene.environment {
            Environment::Constant(c) => c.max_element() > 0.0,
            Environment::LatLong { .. } => true,
        };
        self.frame = GpuFrame::new(
            &scene.camera,
            &settings,
            scene.lights.len() as u32,
            env_sampled,
        );
        self.frame_buf = GpuBuffer::from_slice(&self.gpu, "render frame", &[self.frame])?;
        let pixels = settings.width as usize * settings.height as usize;
        self.film = GpuBuffer::zeroed(&self.gpu, "render film", pixels)?;
        self.aovs = GpuBuffer::zeroed(&self.gpu, "render aovs", 2 * pixels)?;
        self.settings = settings;
        self.samples = 0;
        Ok(())
    }

    /// Starts the picture over (film and sample count cleared), e.g. after texels were
    /// inserted into the scene's stores and the records refreshed.
    ///
    /// # Errors
    /// Device failures.
    pub fn restart(&mut self) -> Result<(), RenderError> {
        self.film.write(0, &vec![[0.0f32; 4]; self.film.len()])?;
        self.samples = 0;
        Ok(())
    }

    /// Renders the remaining samples of the scene's `spp`, calling `on_pass` after each.
    ///
    /// # Errors
    /// Device failures.
    pub fn render(&mut self, mut on_pass: impl FnMut(&PassReport)) -> Result<Film, RenderError> {
        while self.samples < self.settings.spp {
            let report = self.pass()?;
            on_pass(&report);
        }
        self.film()
    }

    /// The film so far: mean radiance per pixel, with albedo, normal and depth of the first
    /// sample's primary hit.
    ///
    /// # Errors
    /// Readback failures; a film without samples.
    pub fn film(&self) -> Result<Film, RenderError> {
        if self.samples == 0 {
            return Err(RenderError::Settings("no sample was rendered yet".into()));
        }
        let sums = self.film.read()?;
        let aovs = self.aovs.read()?;
        let color = sums
            .iter()
            .map(|s| {
                let n = s[3].max(1.0);
                [s[0] / n, s[1] / n, s[2] / n]
            })
            .collect();
        let albedo = aovs
            .chunks(2)
            .map(|a| [a[0][0], a[0][1], a[0][2]])
            .collect();
        let normal = aovs
            .chunks(2)
            .map(|a| [a[1][0], a[1][1], a[1][2]])
            .collect();
        let depth = aovs.chunks(2).map(|a| a[1][3]).collect();
        Ok(Film::new(self.settings.width, self.settings.height, color)?
            .with_albedo(albedo)?
            .with_normal(normal)?
            .with_depth(depth)?)
    }

    /// Samples per pixel so far.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// The render settings.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// The sparse stores baked for the scene's textures.
    pub fn stores(&self) -> &[BakedStoreInfo] {
        self.stores.info()
    }

    /// The baked stores, to read matter from (an export's bake).
    pub fn scene_stores(&self) -> &SceneStores {
        &self.stores
    }

    /// The baked stores themselves, to insert texels (new surface) into; refresh them
    /// ([`SceneStores::refresh`]) before the next pass.
    pub fn scene_stores_mut(&mut self) -> &mut SceneStores {
        &mut self.stores
    }

    /// Facts about the prepared scene.
    pub fn stats(&self) -> RenderStats {
        self.stats
    }
}

/// What [`SceneBvh`] and the kernel rely on, for scenes built in code rather than loaded (the
/// loader checks all of it with line numbers).
/// Checks render settings against what the kernel and film can take.
fn check_settings(source: &std::path::Path, s: &RenderSettings) -> Result<(), RenderError> {
    let file = source.display();
    let bad = |problem: String| Err(RenderError::Settings(format!("{file}: {problem}")));
    if s.width == 0 || s.height == 0 || s.spp == 0 {
        return bad(format!(
            "render settings {}x{}, {} spp (each must be at least 1)",
            s.width, s.height, s.spp
        ));
    }
    if s.max_depth > MAX_DEPTH {
        return bad(format!(
            "render max_depth {} is more than {MAX_DEPTH}",
            s.max_depth
        ));
    }
    if s.width as u64 * s.height as u64 > 1 << 26 {
        return bad(format!("{}x{} pixels is more than 2^26", s.width, s.height));
    }
    Ok(())
}

/// The vMF pyramid of every material whose normal map is filtered by vMF, fitted once per map
/// file and lobe count (materials sharing one map share it).
fn vmf_pyramids(scene: &Scene) -> Result<Vec<Option<VmfPyramid>>, RenderError> {
    let mut fitted: Vec<(&std::path::Path, usize, VmfPyramid)> = Vec::new();
    let mut out = Vec::with_capacity(scene.materials.len());
    for m in &scene.materials {
        let Some(n) = m
            .normal_map
            .as_ref()
            .filter(|n| n.filter == NormalFilter::Vmf)
        else {
            out.push(None);
            continue;
        };
        if let Some((_, _, p)) = fitted
            .iter()
            .find(|(f, j, _)| *f == n.source.as_path() && *j == n.lobes)
        {
            out.push(Some(p.clone()));
            continue;
        }
        let p = VmfPyramid::build(&n.example, n.lobes).map_err(|e| {
            RenderError::Settings(format!(
                "material {:?}: {}: {e}",
                m.name,
                n.source.display()
            ))
        })?;
        fitted.push((n.source.as_path(), n.lobes, p.clone()));
        out.push(Some(p));
    }
    Ok(out)
}

/// The device code of a normal filter.
fn normal_filter_code(f: NormalFilter) -> u32 {
    match f {
        NormalFilter::None => NORMAL_FILTER_NONE,
        NormalFilter::Mip => NORMAL_FILTER_MIP,
        NormalFilter::Vmf => NORMAL_FILTER_VMF,
    }
}

fn check_scene(scene: &Scene) -> Result<(), RenderError> {
    check_settings(&scene.source, &scene.render)?;
    let file = scene.source.display();
    let bad = |problem: String| Err(RenderError::Settings(format!("{file}: {problem}")));
    if scene.instances.is_empty() {
        return bad("the scene has no instance".into());
    }

    for (i, inst) in scene.instances.iter().enumerate() {
        if inst.mesh >= scene.meshes.len() || inst.material >= scene.materials.len() {
            return bad(format!(
                "instance {i} refers to mesh {} of {} / material {} of {}",
                inst.mesh,
                scene.meshes.len(),
                inst.material,
                scene.materials.len()
            ));
        }
        if inst.transform.matrix3.determinant().abs() < 1e-12 {
            return bad(format!("instance {i} has a singular transform"));
        }
    }
    Ok(())
}
