//! Push-constant blocks: every kernel's GLSL block against the host block its dispatches use,
//! member by member (name, offset, GLSL type), and the checks' own failures. No device needed.

use lazysolid_compute::gpu::{check_push_block, DeviceAddress};
use lazysolid_compute::kernels::{self, prims};

#[test]
fn every_kernel_push_block_matches_its_host_block() {
    let registry = lazysolid_tests::push_registry();
    // Each crate compiles its own kernels: the compute crate's, the synthesizer's, the
    // renderer's and the tests' own.
    let kernels: Vec<_> = kernels::ALL
        .iter()
        .chain(lazysolid_synth::kernels::ALL)
        .chain(lazysolid_renderer::kernels::ALL)
        .chain(lazysolid_tests::kernels::ALL)
        .flat_map(|m| m.iter())
        .collect();
    let mut problems = Vec::new();
    for kernel in &kernels {
        let entries: Vec<_> = registry
            .iter()
            .filter(|r| r.kernel.name == kernel.name)
            .collect();
        if entries.is_empty() && kernel.push_constant_bytes > 0 {
            problems.push(format!(
                "{} has a {}-byte push block but no registered host block",
                kernel.name, kernel.push_constant_bytes
            ));
        }
        if entries.len() > 1 {
            problems.push(format!(
                "{} is registered {} times",
                kernel.name,
                entries.len()
            ));
        }
        for entry in entries {
            if let Err(e) = entry.check() {
                problems.push(e);
            }
        }
    }
    for entry in &registry {
        if !kernels.iter().any(|k| k.name == entry.kernel.name) {
            problems.push(format!(
                "{} is registered but not compiled",
                entry.kernel.name
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // Every kernel with a push block was looked at, the nested ones included.
    let with_push = kernels.iter().filter(|k| k.push_constant_bytes > 0).count();
    assert!(with_push >= 50, "only {with_push} kernels with push blocks");
    assert!(kernels::store::HASH_LOOKUP
        .push_fields
        .iter()
        .any(|f| f.name == "store.fastmod_m" && f.ty == "uint64_t"));
}

lazysolid_compute::push_block! {
    struct CopyInOrder<'a> {
        src: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        n: u32,
    }
}

lazysolid_compute::push_block! {
    struct CopySwapped<'a> {
        dst: DeviceAddress<'a>,
        src: DeviceAddress<'a>,
        n: u32,
    }
}

lazysolid_compute::push_block! {
    struct CopyWrongType<'a> {
        src: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        n: f32,
    }
}

lazysolid_compute::push_block! {
    struct CopyMisplaced<'a> {
        n: u32,
        src: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
    }
}

lazysolid_compute::push_block! {
    struct CopyShort<'a> {
        src: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
    }
}

#[test]
fn reordered_retyped_or_missing_fields_are_refused() {
    let def = &prims::COPY_VEC4;
    check_push_block::<CopyInOrder>(def).unwrap();
    let swapped = check_push_block::<CopySwapped>(def).unwrap_err();
    assert!(
        swapped.contains(
            "member 0 is `uint64_t dst` at byte 0 on the host but `uint64_t src` at byte 0 in GLSL"
        ) && swapped.contains("prims/copy_vec4.comp"),
        "{swapped}"
    );
    let retyped = check_push_block::<CopyWrongType>(def).unwrap_err();
    assert!(retyped.contains("`float n` at byte 16"), "{retyped}");
    // A 32-bit field first puts the 64-bit ones at byte 8 (scalar layout), not 4.
    let misplaced = check_push_block::<CopyMisplaced>(def).unwrap_err();
    assert!(
        misplaced.contains("member 0 is `uint n` at byte 0"),
        "{misplaced}"
    );
    let short = check_push_block::<CopyShort>(def).unwrap_err();
    assert!(
        short.contains("member 2 is nothing on the host but `uint n` at byte 16"),
        "{short}"
    );
}
