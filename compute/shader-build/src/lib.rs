//! Compiles lazysolid's GLSL kernels to SPIR-V and reflects their interface, at build time.
//!
//! Each crate that owns kernels calls [`build_kernels`] from its `build.rs` with a
//! [`KernelSet`]: every `*.comp` in the set's folders becomes one `KernelDef` constant (embedded
//! SPIR-V words, descriptor bindings by name, the push-constant block's size and members) in a
//! generated Rust module per folder, which also lists them all in `ALL`. Kernels are thereby Rust
//! identifiers, never file-name strings, and their bindings and push blocks are checked against
//! the GLSL when they are dispatched. Shared includes live in `<glsl root>/include` and are
//! usable by every crate's kernels.

mod push_members;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The kernels one crate owns, and how to compile them.
#[derive(Clone, Debug)]
pub struct KernelSet {
    /// The GLSL root: kernels are named by their path below it, includes are searched in
    /// `include/` below it.
    pub glsl_root: PathBuf,
    /// The folders below `glsl_root` whose `*.comp` files this crate owns (one generated module
    /// per folder, nested folders joined by `_`).
    pub folders: Vec<String>,
    /// Files whose `pub const NAME: u32 = LITERAL;` lines become `#define NAME LITERAL` for every
    /// kernel of the set (a crate passes its own constants and those of the crates whose
    /// includes it uses).
    pub constants: Vec<PathBuf>,
    /// Rust path of the module that defines `KernelDef`, `BindingDef` and `BindingKind` as the
    /// generated code sees it: `crate::gpu` inside `lazysolid-compute`,
    /// `lazysolid_compute::gpu` elsewhere.
    pub gpu_module: String,
}

/// Runs `set` from a build script: tells cargo what to watch, writes the generated module to
/// `$OUT_DIR/kernels.rs` (to be `include!`d), and fails the build with every GLSL error (file
/// and line) otherwise.
pub fn build_kernels(set: &KernelSet) {
    let include = "include".to_string();
    for folder in set.folders.iter().chain([&include]) {
        println!(
            "cargo:rerun-if-changed={}",
            set.glsl_root.join(folder).display()
        );
    }
    for constants in &set.constants {
        println!("cargo:rerun-if-changed={}", constants.display());
    }
    let out =
        PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("kernels.rs");
    match generate(set) {
        Ok(source) => {
            if let Err(e) = std::fs::write(&out, source) {
                panic!("{}: {e}", out.display());
            }
        }
        Err(e) => {
            eprintln!("{e}");
            panic!("{e}");
        }
    }
}

/// Hands the constants files `set` was compiled with to the build scripts of the crates that
/// depend on this one directly (Cargo's `links` metadata: the crate's `links = "NAME"` key makes
/// them `DEP_NAME_CONSTANTS`), so a dependent's kernels, which may include this crate's GLSL,
/// get the same `#define`s without naming another crate's files by path.
pub fn export_constants(set: &KernelSet) {
    let joined = std::env::join_paths(&set.constants)
        .unwrap_or_else(|e| panic!("constants paths cannot be joined: {e}"));
    println!("cargo::metadata=constants={}", joined.to_string_lossy());
}

/// The constants files the dependency whose `links` key is `links` exported with
/// [`export_constants`]. Panics (failing the build with the variable's name) when it exported
/// none: the dependency is then not a direct one, or has no `links` key.
pub fn dependency_constants(links: &str) -> Vec<PathBuf> {
    let var = format!("DEP_{}_CONSTANTS", links.to_uppercase().replace('-', "_"));
    let value = std::env::var_os(&var).unwrap_or_else(|| {
        panic!("{var} is not set: `{links}` must be a direct dependency with `links = \"{links}\"`")
    });
    std::env::split_paths(&value).collect()
}

/// Compiles every kernel of `set` and returns the generated Rust source.
///
/// # Errors
/// A missing folder or constants file, and every compile error, each with the file and line
/// shaderc reports.
pub fn generate(set: &KernelSet) -> Result<String, String> {
    let glsl_root = set.glsl_root.as_path();
    let mut defines = Vec::new();
    for file in &set.constants {
        defines.extend(read_constants(file)?);
    }
    let mut kernels = Vec::new();
    for folder in &set.folders {
        let dir = glsl_root.join(folder);
        if !dir.is_dir() {
            return Err(format!("{}: kernel folder not found", dir.display()));
        }
        collect_kernels(&dir, &mut kernels);
    }
    kernels.sort();

    let compiler =
        shaderc::Compiler::new().map_err(|e| format!("cannot create the shaderc compiler: {e}"))?;
    let mut modules: BTreeMap<String, Vec<(String, String)>> = BTreeMap::new();
    let mut failures = Vec::new();
    for path in &kernels {
        let rel = path.strip_prefix(glsl_root).unwrap();
        let module = rel
            .parent()
            .map(|p| p.to_string_lossy().replace(['/', '-'], "_"))
            .unwrap_or_default();
        let stem = rel
            .file_name()
            .unwrap()
            .to_string_lossy()
            .trim_end_matches(".comp")
            .replace('.', "_");
        // Reflection reads an unoptimized module: the optimizer strips the names bindings are
        // matched by. The embedded module is the optimized one; its layout is a subset.
        let built = compile(&compiler, glsl_root, path, &defines, true)
            .and_then(|words| Ok((words, compile(&compiler, glsl_root, path, &defines, false)?)))
            .and_then(|(words, plain)| describe(&rel.to_string_lossy(), &stem, &words, &plain));
        match built {
            Ok(item) => modules.entry(module).or_default().push(item),
            Err(e) => failures.push(e),
        }
    }
    if !failures.is_empty() {
        return Err(format!(
            "{} GLSL kernel(s) failed to compile:\n{}",
            failures.len(),
            failures.join("\n")
        ));
    }
    let mut out = String::from("// Generated by lazysolid-shader-build from glsl/. Do not edit.\n");
    let folders: Vec<String> = modules.keys().map(|m| format!("{m}::ALL")).collect();
    let _ = writeln!(
        out,
        "/// Every kernel, folder by folder.\npub const ALL: &[&[&{}::KernelDef]] = &[{}];",
        set.gpu_module,
        folders.join(", ")
    );
    for (module, items) in &modules {
        let _ = writeln!(
            out,
            "/// Kernels compiled from `glsl/{module}/`.\npub mod {module} {{\n    #[allow(unused_imports)]\n    use {}::{{BindingDef, BindingKind, KernelDef, PushFieldDef}};",
            set.gpu_module
        );
        let mut all = String::new();
        for (ident, item) in items {
            out.push_str(item);
            let _ = write!(all, "&{ident}, ");
        }
        let _ = writeln!(
            out,
            "    /// Every kernel of this folder.\n    pub const ALL: &[&KernelDef] = &[{all}];\n}}"
        );
    }
    Ok(out)
}

/// Reads `pub const NAME: u32 = VALUE;` lines: the constants shared with GLSL.
fn read_constants(path: &Path) -> Result<Vec<(String, String)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut defines = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let Some(rest) = line.trim().strip_prefix("pub const ") else {
            continue;
        };
        // Only scalar u32 constants become #defines; arrays and other types stay Rust-only.
        if !rest.contains(": u32 =") {
            continue;
        }
        let parsed = rest.split_once(':').and_then(|(name, rest)| {
            Some((
                name.trim(),
                rest.split_once('=')?.1.trim().trim_end_matches(';').trim(),
            ))
        });
        match parsed {
            Some((name, value))
                if !value.is_empty() && value.chars().all(|c| c.is_ascii_digit() || c == '_') =>
            {
                defines.push((name.to_string(), value.replace('_', "")))
            }
            _ => {
                return Err(format!(
                    "{}:{}: shared constants must read `pub const NAME: u32 = LITERAL;`",
                    path.display(),
                    n + 1
                ))
            }
        }
    }
    Ok(defines)
}

fn collect_kernels(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect_kernels(&path, out);
        } else if path.extension().is_some_and(|e| e == "comp") {
            out.push(path);
        }
    }
}

fn compile(
    compiler: &shaderc::Compiler,
    root: &Path,
    path: &Path,
    defines: &[(String, String)],
    optimize: bool,
) -> Result<Vec<u32>, String> {
    let source = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut options = shaderc::CompileOptions::new()
        .map_err(|e| format!("cannot create shaderc options: {e}"))?;
    options.set_target_env(
        shaderc::TargetEnv::Vulkan,
        shaderc::EnvVersion::Vulkan1_2 as u32,
    );
    options.set_target_spirv(shaderc::SpirvVersion::V1_5);
    options.set_optimization_level(if optimize {
        shaderc::OptimizationLevel::Performance
    } else {
        shaderc::OptimizationLevel::Zero
    });
    for (name, value) in defines {
        options.add_macro_definition(name, Some(value));
    }
    let include_root = root.join("include");
    options.set_include_callback(move |requested, kind, requester, _depth| {
        let mut candidates = vec![include_root.join(requested)];
        if kind == shaderc::IncludeType::Relative {
            candidates.insert(
                0,
                Path::new(requester)
                    .parent()
                    .unwrap_or(Path::new(""))
                    .join(requested),
            );
        }
        for c in candidates {
            if let Ok(content) = std::fs::read_to_string(&c) {
                return Ok(shaderc::ResolvedInclude {
                    resolved_name: c.display().to_string(),
                    content,
                });
            }
        }
        Err(format!(
            "#include \"{requested}\" not found next to {requester} nor in glsl/include"
        ))
    });
    let artifact = compiler
        .compile_into_spirv(
            &source,
            shaderc::ShaderKind::Compute,
            &path.display().to_string(),
            "main",
            Some(&options),
        )
        .map_err(|e| e.to_string())?;
    Ok(artifact.as_binary().to_vec())
}

fn describe(
    rel: &str,
    stem: &str,
    words: &[u32],
    plain: &[u32],
) -> Result<(String, String), String> {
    let bytes: Vec<u8> = plain.iter().flat_map(|w| w.to_le_bytes()).collect();
    let reflection = rspirv_reflect::Reflection::new_from_spirv(&bytes)
        .map_err(|e| format!("{rel}: reflection failed: {e:?}"))?;
    let sets = reflection
        .get_descriptor_sets()
        .map_err(|e| format!("{rel}: descriptor reflection failed: {e:?}"))?;
    let mut bindings = String::new();
    for (set, infos) in &sets {
        if *set != 0 {
            return Err(format!(
                "{rel}: descriptor set {set} used; kernels use set 0 only"
            ));
        }
        for (binding, info) in infos {
            let kind = match info.ty {
                rspirv_reflect::DescriptorType::STORAGE_BUFFER => "StorageBuffer",
                rspirv_reflect::DescriptorType::UNIFORM_BUFFER => "UniformBuffer",
                other => {
                    return Err(format!(
                        "{rel}: binding {binding} ({}) has unsupported descriptor type {other:?}",
                        info.name
                    ))
                }
            };
            let name = if info.name.is_empty() {
                block_type_name(plain, *binding).unwrap_or_default()
            } else {
                info.name.clone()
            };
            if name.is_empty() {
                return Err(format!(
                    "{rel}: binding {binding} has no name; kernels are bound by name"
                ));
            }
            let _ = write!(
                bindings,
                "BindingDef {{ name: {name:?}, binding: {binding}, kind: BindingKind::{kind} }}, "
            );
        }
    }
    let push = reflection
        .get_push_constant_range()
        .map_err(|e| format!("{rel}: push-constant reflection failed: {e:?}"))?
        .map(|p| p.offset + p.size)
        .unwrap_or(0);
    let mut push_fields = String::new();
    for m in push_members::reflect(plain).map_err(|e| format!("{rel}: push constants: {e}"))? {
        let _ = write!(
            push_fields,
            "PushFieldDef {{ name: {:?}, offset: {}, ty: {:?} }}, ",
            m.name, m.offset, m.ty
        );
    }
    let ident = stem.to_uppercase();
    let mut spirv = String::new();
    for chunk in words.chunks(12) {
        spirv.push_str("           ");
        for w in chunk {
            let _ = write!(spirv, " {w:#010x},");
        }
        spirv.push('\n');
    }
    let item = format!(
        "    /// Kernel `glsl/{rel}`.\n    pub const {ident}: KernelDef = KernelDef {{\n        name: {rel:?},\n        spirv: &[\n{spirv}        ],\n        bindings: &[{bindings}],\n        push_constant_bytes: {push},\n        push_fields: &[{push_fields}],\n    }};\n"
    );
    Ok((ident, item))
}

/// The block type name of the variable decorated `Binding = binding` (for anonymous blocks,
/// whose variable has an empty name): `buffer Src { ... };` is bound as "Src".
fn block_type_name(words: &[u32], binding: u32) -> Option<String> {
    const OP_NAME: u32 = 5;
    const OP_TYPE_POINTER: u32 = 32;
    const OP_VARIABLE: u32 = 59;
    const OP_DECORATE: u32 = 71;
    const DECORATION_BINDING: u32 = 33;
    let mut names = std::collections::HashMap::new();
    let mut pointee = std::collections::HashMap::new();
    let mut var_type = std::collections::HashMap::new();
    let mut var = None;
    let mut i = 5;
    while i < words.len() {
        let count = (words[i] >> 16) as usize;
        let op = words[i] & 0xffff;
        if count == 0 || i + count > words.len() {
            break;
        }
        let args = &words[i + 1..i + count];
        match op {
            OP_NAME if args.len() >= 2 => {
                let bytes: Vec<u8> = args[1..]
                    .iter()
                    .flat_map(|w| w.to_le_bytes())
                    .take_while(|&b| b != 0)
                    .collect();
                names.insert(args[0], String::from_utf8_lossy(&bytes).into_owned());
            }
            OP_TYPE_POINTER if args.len() == 3 => {
                pointee.insert(args[0], args[2]);
            }
            OP_VARIABLE if args.len() >= 2 => {
                var_type.insert(args[1], args[0]);
            }
            OP_DECORATE
                if args.len() == 3 && args[1] == DECORATION_BINDING && args[2] == binding =>
            {
                var = Some(args[0])
            }
            _ => {}
        }
        i += count;
    }
    let block = pointee.get(var_type.get(&var?)?)?;
    names.get(block).cloned()
}
