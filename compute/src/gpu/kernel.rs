//! Compute pipelines built from the SPIR-V that a crate's `build.rs` embeds, with their
//! interface checked at dispatch against the reflected GLSL bindings and push-constant block.
//! Pipelines are built only through the device's kernel cache ([`Gpu::kernel`]), once per
//! (kernel, workgroup size, specialization constants), and shared.

use super::context::{Gpu, GpuInner};
use super::error::{GpuError, GpuResult, VkContext};
use crate::shader_constants::DEFAULT_WORKGROUP_SIZE;
use ash::vk;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// Kind of a reflected descriptor binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BindingKind {
    /// `layout(binding = N) buffer`.
    StorageBuffer,
    /// `layout(binding = N) uniform`.
    UniformBuffer,
}

/// One descriptor binding of a kernel, as reflected from its SPIR-V.
#[derive(Clone, Copy, Debug)]
pub struct BindingDef {
    /// The GLSL block's instance name (or its type name when anonymous).
    pub name: &'static str,
    /// `binding = N` in set 0.
    pub binding: u32,
    /// Storage or uniform buffer.
    pub kind: BindingKind,
}

/// A kernel as compiled at build time: generated in each owning crate's `kernels` module.
#[derive(Clone, Copy, Debug)]
pub struct KernelDef {
    /// Path of the GLSL file below `glsl/`, used in every message about the kernel and as its
    /// name in the kernel cache.
    pub name: &'static str,
    /// SPIR-V words.
    pub spirv: &'static [u32],
    /// Descriptor bindings of set 0.
    pub bindings: &'static [BindingDef],
    /// Size of the push-constant block in bytes (0 when there is none).
    pub push_constant_bytes: u32,
    /// Leaf members of the push-constant block in declaration order (nested structs
    /// flattened into dotted names), which host blocks are checked against.
    pub push_fields: &'static [super::PushFieldDef],
}

/// Specialization constant id that every kernel uses for its workgroup width
/// (`layout(local_size_x_id = 0) in;`).
pub const WORKGROUP_SIZE_ID: u32 = 0;

const _: () = assert!(DEFAULT_WORKGROUP_SIZE <= super::DESIGN_WORKGROUP_INVOCATIONS);

/// A compute pipeline with its layouts, shared through the device's kernel cache: get it with
/// [`Gpu::kernel`] or [`Gpu::kernel_with`], dispatch it as often as needed.
pub struct Kernel {
    pub(crate) gpu: Arc<GpuInner>,
    pub(crate) def: &'static KernelDef,
    module: vk::ShaderModule,
    pub(crate) set_layout: vk::DescriptorSetLayout,
    pub(crate) pipeline_layout: vk::PipelineLayout,
    pub(crate) pipeline: vk::Pipeline,
    workgroup_size: u32,
}

impl Gpu {
    /// `def` with the default workgroup size (256), from the device's kernel cache: the
    /// pipeline is built at the first request and shared by every later one.
    ///
    /// # Errors
    /// Shader-module or pipeline creation failures.
    pub fn kernel(&self, def: &'static KernelDef) -> GpuResult<Arc<Kernel>> {
        self.kernel_with(def, DEFAULT_WORKGROUP_SIZE, &[])
    }

    /// `def` with a workgroup width and further specialization constants `(id, value)`, from
    /// the device's kernel cache (one pipeline per distinct width and constants).
    ///
    /// # Errors
    /// A workgroup size outside the device's limit, two different kernels under one name,
    /// shader-module or pipeline creation failures.
    pub fn kernel_with(
        &self,
        def: &'static KernelDef,
        workgroup_size: u32,
        constants: &[(u32, u32)],
    ) -> GpuResult<Arc<Kernel>> {
        self.kernels
            .get(&self.inner, def, workgroup_size, constants)
    }

    /// The names of the kernels this device's kernel cache holds, sorted, once per kernel
    /// (whatever its specializations): what a piece of work has actually needed.
    pub fn cached_kernels(&self) -> Vec<&'static str> {
        let mut names: Vec<_> = self
            .kernels
            .kernels
            .lock()
            .unwrap()
            .keys()
            .map(|k| k.0)
            .collect();
        names.sort_unstable();
        names.dedup();
        names
    }

    /// How many pipelines this device's kernel cache has built so far (each request that
    /// found its kernel in the cache built none).
    pub fn pipelines_created(&self) -> u64 {
        self.kernels.created.load(Ordering::Relaxed)
    }

    /// Whether this handle owns the device alone, with its kernel cache: no other clone and no
    /// buffer, record or kernel made from it is alive. A device kept for reuse (the test
    /// suite's, whose pipelines would otherwise be built again for every test) is checked by
    /// this between uses, where a device used once is checked by its destruction.
    pub fn is_sole_owner(&self) -> bool {
        let cached = self.kernels.kernels.lock().unwrap();
        Arc::strong_count(&self.kernels) == 1
            && cached.values().all(|k| Arc::strong_count(k) == 1)
            && Arc::strong_count(&self.inner) == 1 + cached.len()
    }
}

/// Identity of a pipeline: kernel name, workgroup width, specialization constants.
type KernelKey = (&'static str, u32, Vec<(u32, u32)>);

/// The pipelines of one device. Owned by every clone of its [`Gpu`]; each [`Kernel`] holds the
/// device itself, so the cache may be dropped before the device or after it.
#[derive(Default)]
pub(crate) struct KernelCache {
    kernels: Mutex<HashMap<KernelKey, Arc<Kernel>>>,
    created: AtomicU64,
}

impl KernelCache {
    fn get(
        &self,
        gpu: &Arc<GpuInner>,
        def: &'static KernelDef,
        workgroup_size: u32,
        constants: &[(u32, u32)],
    ) -> GpuResult<Arc<Kernel>> {
        let key = (def.name, workgroup_size, constants.to_vec());
        // Held while building, so two threads asking for one kernel build it once.
        let mut kernels = self.kernels.lock().unwrap();
        if let Some(kernel) = kernels.get(&key) {
            if kernel.def.spirv != def.spirv {
                return Err(GpuError::KernelInterface {
                    kernel: def.name,
                    problem: "two different kernels have this name; kernels are cached by it"
                        .into(),
                });
            }
            return Ok(kernel.clone());
        }
        let kernel = Arc::new(Kernel::build(gpu, def, workgroup_size, constants)?);
        self.created.fetch_add(1, Ordering::Relaxed);
        kernels.insert(key, kernel.clone());
        Ok(kernel)
    }
}

impl Kernel {
    /// Builds the pipeline; only the cache calls this.
    fn build(
        inner: &Arc<GpuInner>,
        def: &'static KernelDef,
        workgroup_size: u32,
        constants: &[(u32, u32)],
    ) -> GpuResult<Kernel> {
        let inner = inner.clone();
        if workgroup_size == 0 || workgroup_size > inner.info.max_workgroup_invocations {
            return Err(GpuError::KernelInterface {
                kernel: def.name,
                problem: format!("workgroup size {workgroup_size} is outside 1..={} (maxComputeWorkGroupInvocations)", inner.info.max_workgroup_invocations),
            });
        }
        let device = &inner.device;
        let _layer = inner.layer();
        let module = unsafe {
            device
                .create_shader_module(&vk::ShaderModuleCreateInfo::default().code(def.spirv), None)
        }
        .vk("vkCreateShaderModule", def.name)?;
        let bindings: Vec<_> = def
            .bindings
            .iter()
            .map(|b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b.binding)
                    .descriptor_type(match b.kind {
                        BindingKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
                        BindingKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
                    })
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let set_info = vk::DescriptorSetLayoutCreateInfo::default()
            .flags(vk::DescriptorSetLayoutCreateFlags::PUSH_DESCRIPTOR_KHR)
            .bindings(&bindings);
        let set_layout = match unsafe { device.create_descriptor_set_layout(&set_info, None) } {
            Ok(l) => l,
            Err(result) => {
                unsafe { device.destroy_shader_module(module, None) };
                return Err(GpuError::Vulkan {
                    call: "vkCreateDescriptorSetLayout",
                    object: def.name.into(),
                    result,
                });
            }
        };
        let ranges = [vk::PushConstantRange::default()
            .stage_flags(vk::ShaderStageFlags::COMPUTE)
            .size(def.push_constant_bytes)];
        let set_layouts = [set_layout];
        let mut layout_info = vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts);
        if def.push_constant_bytes > 0 {
            layout_info = layout_info.push_constant_ranges(&ranges);
        }
        let pipeline_layout = match unsafe { device.create_pipeline_layout(&layout_info, None) } {
            Ok(l) => l,
            Err(result) => {
                unsafe {
                    device.destroy_descriptor_set_layout(set_layout, None);
                    device.destroy_shader_module(module, None);
                }
                return Err(GpuError::Vulkan {
                    call: "vkCreatePipelineLayout",
                    object: def.name.into(),
                    result,
                });
            }
        };
        let mut values = vec![workgroup_size];
        let mut entries = vec![vk::SpecializationMapEntry::default()
            .constant_id(WORKGROUP_SIZE_ID)
            .offset(0)
            .size(4)];
        for (i, (id, value)) in constants.iter().enumerate() {
            values.push(*value);
            entries.push(
                vk::SpecializationMapEntry::default()
                    .constant_id(*id)
                    .offset(4 * (i as u32 + 1))
                    .size(4),
            );
        }
        let data: &[u8] = bytemuck::cast_slice(&values);
        let spec = vk::SpecializationInfo::default()
            .map_entries(&entries)
            .data(data);
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(c"main")
            .specialization_info(&spec);
        let create = [vk::ComputePipelineCreateInfo::default()
            .stage(stage)
            .layout(pipeline_layout)];
        let kernel_parts = (module, set_layout, pipeline_layout);
        let pipeline = match unsafe {
            device.create_compute_pipelines(vk::PipelineCache::null(), &create, None)
        } {
            Ok(p) => p[0],
            Err((_, result)) => {
                unsafe {
                    device.destroy_pipeline_layout(kernel_parts.2, None);
                    device.destroy_descriptor_set_layout(kernel_parts.1, None);
                    device.destroy_shader_module(kernel_parts.0, None);
                }
                return Err(GpuError::Vulkan {
                    call: "vkCreateComputePipelines",
                    object: def.name.into(),
                    result,
                });
            }
        };
        inner.set_name(pipeline, def.name);
        Ok(Kernel {
            gpu: inner,
            def,
            module,
            set_layout,
            pipeline_layout,
            pipeline,
            workgroup_size,
        })
    }

    /// The kernel's GLSL file below `glsl/`.
    pub fn name(&self) -> &'static str {
        self.def.name
    }

    /// Workgroup width the pipeline was specialized with.
    pub fn workgroup_size(&self) -> u32 {
        self.workgroup_size
    }

    /// Workgroup counts that cover `count` invocations (rounded up), folded into a second
    /// dimension past `maxComputeWorkGroupCount[0]`. Kernels recover the linear group index
    /// with `group_index()` from `glsl/include/common.glsl`.
    pub fn groups_for(&self, count: u64) -> [u32; 3] {
        groups_for_blocks(
            count.div_ceil(self.workgroup_size as u64),
            self.gpu.info.max_workgroup_count,
        )
    }

    /// Workgroup counts for `blocks` workgroups, folded like [`Kernel::groups_for`].
    pub fn groups(&self, blocks: u64) -> [u32; 3] {
        groups_for_blocks(blocks, self.gpu.info.max_workgroup_count)
    }
}

fn groups_for_blocks(blocks: u64, max_x: u32) -> [u32; 3] {
    if blocks <= max_x as u64 {
        return [blocks as u32, 1, 1];
    }
    let x = max_x.min(65535) as u64;
    [x as u32, blocks.div_ceil(x) as u32, 1]
}

impl Drop for Kernel {
    fn drop(&mut self) {
        let _layer = self.gpu.layer();
        unsafe {
            let d = &self.gpu.device;
            d.destroy_pipeline(self.pipeline, None);
            d.destroy_pipeline_layout(self.pipeline_layout, None);
            d.destroy_descriptor_set_layout(self.set_layout, None);
            d.destroy_shader_module(self.module, None);
        }
    }
}
