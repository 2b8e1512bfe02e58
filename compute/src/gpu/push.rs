//! Push-constant blocks with a declared layout, checked member by member against the GLSL.
//!
//! A host push block is declared with [`push_block!`](crate::push_block): an ordinary struct
//! whose fields are laid out as GLSL's scalar block layout lays out the members of the same
//! types in the same order (each at the next multiple of its alignment). The macro records
//! every field's name, offset and GLSL type; [`check_push_block`] compares them with the
//! members `lazysolid-shader-build` reflected from the kernel's SPIR-V. Names must be
//! identical (snake_case in both languages; nested structs give dotted names such as
//! `store.cells`). [`Recorder::dispatch`](super::Recorder::dispatch) runs the check in debug
//! builds, and a test runs it for every kernel through the crates' push-block registries.

use super::address::DeviceAddress;
use super::keep_alive::KeepAlive;
use super::kernel::KernelDef;

/// One leaf member of a GLSL push-constant block, as reflected from SPIR-V.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PushFieldDef {
    /// Dotted member name.
    pub name: &'static str,
    /// Byte offset from the start of the block.
    pub offset: u32,
    /// GLSL type, such as `uint`, `uint64_t` or `vec3`.
    pub ty: &'static str,
}

/// One leaf field of a host push block, as its declaration lays it out.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HostField {
    /// Dotted field name.
    pub name: String,
    /// Byte offset from the start of the block.
    pub offset: u32,
    /// The GLSL type the field's Rust type stands for (`T[N]` for arrays and vectors).
    pub ty: String,
}

/// A value that can sit in a push block or a device record: its scalar-layout alignment and
/// size, its leaf fields and its bytes.
pub trait PushValue {
    /// Alignment in GLSL's scalar block layout (that of the largest scalar component).
    const ALIGN: u32;
    /// Size in bytes (a struct ends at its last member's end, as in the scalar layout).
    const SIZE: u32;
    /// Appends the leaf fields, named below `prefix` and placed from `offset`.
    fn fields(prefix: &str, offset: u32, out: &mut Vec<HostField>);
    /// Writes the value's bytes to `out[..SIZE]`.
    fn write(&self, out: &mut [u8]);
    /// Makes `keep` hold the memory of every buffer the value's device addresses point into.
    fn keep_alive(&self, _keep: &mut KeepAlive) {}
}

/// A whole push-constant block: declared with [`push_block!`](crate::push_block), or `()` for
/// a kernel without one. Bare scalars are not blocks, so every member has a checked name.
pub trait PushBlock: PushValue {}

impl PushValue for () {
    const ALIGN: u32 = 1;
    const SIZE: u32 = 0;
    fn fields(_: &str, _: u32, _: &mut Vec<HostField>) {}
    fn write(&self, _: &mut [u8]) {}
}

impl PushBlock for () {}

macro_rules! scalar_push_values {
    ($($ty:ty => $glsl:literal;)*) => {$(
        impl PushValue for $ty {
            const ALIGN: u32 = size_of::<$ty>() as u32;
            const SIZE: u32 = size_of::<$ty>() as u32;
            fn fields(prefix: &str, offset: u32, out: &mut Vec<HostField>) {
                out.push(HostField { name: prefix.to_string(), offset, ty: $glsl.into() });
            }
            fn write(&self, out: &mut [u8]) {
                out[..size_of::<$ty>()].copy_from_slice(&self.to_le_bytes());
            }
        }

        /// `[T; N]` stands for GLSL's `T name[N]`, and equally for the vector `TvecN` (the
        /// scalar layout places both alike).
        impl<const N: usize> PushValue for [$ty; N] {
            const ALIGN: u32 = size_of::<$ty>() as u32;
            const SIZE: u32 = (N * size_of::<$ty>()) as u32;
            fn fields(prefix: &str, offset: u32, out: &mut Vec<HostField>) {
                out.push(HostField { name: prefix.to_string(), offset, ty: format!("{}[{N}]", $glsl) });
            }
            fn write(&self, out: &mut [u8]) {
                for (i, v) in self.iter().enumerate() {
                    v.write(&mut out[i * size_of::<$ty>()..]);
                }
            }
        }
    )*};
}

scalar_push_values! {
    u32 => "uint";
    i32 => "int";
    f32 => "float";
    u64 => "uint64_t";
    i64 => "int64_t";
}

impl PushValue for DeviceAddress<'_> {
    const ALIGN: u32 = 8;
    const SIZE: u32 = 8;
    fn fields(prefix: &str, offset: u32, out: &mut Vec<HostField>) {
        u64::fields(prefix, offset, out)
    }
    fn write(&self, out: &mut [u8]) {
        self.raw().write(out)
    }
    fn keep_alive(&self, keep: &mut KeepAlive) {
        DeviceAddress::keep_alive(*self, keep)
    }
}

macro_rules! glam_push_values {
    ($($ty:ty => $array:ty;)*) => {$(
        impl PushValue for $ty {
            const ALIGN: u32 = <$array as PushValue>::ALIGN;
            const SIZE: u32 = <$array as PushValue>::SIZE;
            fn fields(prefix: &str, offset: u32, out: &mut Vec<HostField>) {
                <$array>::fields(prefix, offset, out)
            }
            fn write(&self, out: &mut [u8]) {
                self.to_array().write(out)
            }
        }
    )*};
}

glam_push_values! {
    glam::Vec2 => [f32; 2];
    glam::Vec3 => [f32; 3];
    glam::Vec4 => [f32; 4];
    glam::UVec2 => [u32; 2];
    glam::UVec3 => [u32; 3];
    glam::UVec4 => [u32; 4];
    glam::IVec3 => [i32; 3];
}

/// `offset` rounded up to a multiple of `align`.
pub const fn align_up(offset: u32, align: u32) -> u32 {
    offset.div_ceil(align) * align
}

/// The leaf fields of `P` as its declaration lays them out.
pub fn host_fields<P: PushValue>() -> Vec<HostField> {
    let mut out = Vec::new();
    P::fields("", 0, &mut out);
    out
}

/// `P`'s bytes, to hand to `vkCmdPushConstants` or to upload as a record.
pub fn push_bytes<P: PushValue>(value: &P) -> Vec<u8> {
    let mut bytes = vec![0; P::SIZE as usize];
    value.write(&mut bytes);
    bytes
}

/// A GLSL type with vectors spelled as arrays (`uvec3` as `uint[3]`), which is how the scalar
/// layout treats them and how host arrays are described.
fn canonical(ty: &str) -> String {
    let Some((prefix, n)) = ty.split_once("vec") else {
        return ty.to_string();
    };
    let scalar = match prefix {
        "" => "float",
        "d" => "double",
        "i" => "int",
        "u" => "uint",
        "b" => "bool",
        "u64" => "uint64_t",
        "i64" => "int64_t",
        _ => return ty.to_string(),
    };
    format!("{scalar}[{n}]")
}

/// Compares a host block's fields with the kernel's reflected push-constant members: same
/// count, and member for member the same name, offset and GLSL type.
///
/// # Errors
/// The first difference, naming the host type, the member and both sides.
pub fn check_fields(def: &KernelDef, host_type: &str, host: &[HostField]) -> Result<(), String> {
    let glsl = def.push_fields;
    let show = |name: &str, offset: u32, ty: &str| format!("`{ty} {name}` at byte {offset}");
    for i in 0..host.len().max(glsl.len()) {
        match (host.get(i), glsl.get(i)) {
            (Some(h), Some(g))
                if h.name == g.name && h.offset == g.offset && h.ty == canonical(g.ty) => {}
            (h, g) => {
                let h = h.map_or("nothing".into(), |h| show(&h.name, h.offset, &h.ty));
                let g = g.map_or("nothing".into(), |g| show(g.name, g.offset, g.ty));
                return Err(format!(
                    "push block {host_type} differs from the GLSL block of {}: member {i} is {h} on the host but {g} in GLSL",
                    def.name
                ));
            }
        }
    }
    Ok(())
}

/// [`check_fields`] for the block type `P`.
///
/// # Errors
/// See [`check_fields`].
pub fn check_push_block<P: PushBlock>(def: &KernelDef) -> Result<(), String> {
    check_fields(def, std::any::type_name::<P>(), &host_fields::<P>())
}

/// A kernel and the host block its dispatches push: one entry of a crate's registry, which a
/// test checks in full (and which must name every kernel that has a push block).
#[derive(Clone, Copy)]
pub struct PushRegistration {
    /// The kernel.
    pub kernel: &'static KernelDef,
    /// The host block's type name.
    pub host_type: &'static str,
    /// The host block's size in bytes.
    pub host_bytes: u32,
    /// The host block's fields.
    pub host_fields: fn() -> Vec<HostField>,
}

impl PushRegistration {
    /// The registration of `kernel` with the block `P`.
    pub fn of<P: PushBlock>(kernel: &'static KernelDef) -> Self {
        PushRegistration {
            kernel,
            host_type: std::any::type_name::<P>(),
            host_bytes: P::SIZE,
            host_fields: host_fields::<P>,
        }
    }

    /// The sizes, then [`check_fields`], for this pair.
    ///
    /// # Errors
    /// A size difference, or see [`check_fields`].
    pub fn check(&self) -> Result<(), String> {
        if self.host_bytes != self.kernel.push_constant_bytes {
            return Err(format!(
                "push block {} is {} bytes but the GLSL block of {} is {} bytes",
                self.host_type, self.host_bytes, self.kernel.name, self.kernel.push_constant_bytes
            ));
        }
        check_fields(self.kernel, self.host_type, &(self.host_fields)())
    }
}

/// Declares a struct usable as a push-constant block (and as a member of one, or as a device
/// record): the fields keep their declaration order, each placed at the next multiple of its
/// scalar-layout alignment, and the struct implements [`PushValue`] and [`PushBlock`].
/// Attributes (docs, derives) pass through; the struct may take one lifetime, for the buffers
/// its [`DeviceAddress`] fields borrow.
///
/// ```
/// use lazysolid_compute::gpu::{DeviceAddress, host_fields};
/// lazysolid_compute::push_block! {
///     /// The push block of a copy kernel.
///     pub struct CopyPush<'a> {
///         pub src: DeviceAddress<'a>,
///         pub dst: DeviceAddress<'a>,
///         pub n: u32,
///     }
/// }
/// let fields = host_fields::<CopyPush>();
/// assert_eq!((fields[2].name.as_str(), fields[2].offset), ("n", 16));
/// assert_eq!(fields[2].ty, "uint");
/// ```
#[macro_export]
macro_rules! push_block {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident $(<$lt:lifetime>)? {
            $($(#[$fmeta:meta])* $fvis:vis $field:ident : $ty:ty),* $(,)?
        }
    ) => {
        $(#[$meta])*
        $vis struct $name $(<$lt>)? {
            $($(#[$fmeta])* $fvis $field: $ty),*
        }

        impl $(<$lt>)? $crate::gpu::PushValue for $name $(<$lt>)? {
            const ALIGN: u32 = {
                let mut align = 1;
                $(
                    let a = <$ty as $crate::gpu::PushValue>::ALIGN;
                    if a > align {
                        align = a;
                    }
                )*
                align
            };
            const SIZE: u32 = {
                let mut end = 0;
                $(
                    end = $crate::gpu::align_up(end, <$ty as $crate::gpu::PushValue>::ALIGN)
                        + <$ty as $crate::gpu::PushValue>::SIZE;
                )*
                end
            };
            fn fields(prefix: &str, offset: u32, out: &mut Vec<$crate::gpu::HostField>) {
                let mut end = 0;
                $(
                    let at = $crate::gpu::align_up(end, <$ty as $crate::gpu::PushValue>::ALIGN);
                    let name = if prefix.is_empty() {
                        stringify!($field).to_string()
                    } else {
                        format!("{prefix}.{}", stringify!($field))
                    };
                    <$ty as $crate::gpu::PushValue>::fields(&name, offset + at, out);
                    end = at + <$ty as $crate::gpu::PushValue>::SIZE;
                )*
                let _ = end;
            }
            fn write(&self, out: &mut [u8]) {
                let mut end = 0;
                $(
                    let at = $crate::gpu::align_up(end, <$ty as $crate::gpu::PushValue>::ALIGN);
                    $crate::gpu::PushValue::write(&self.$field, &mut out[at as usize..]);
                    end = at + <$ty as $crate::gpu::PushValue>::SIZE;
                )*
                let _ = (end, out);
            }
            fn keep_alive(&self, keep: &mut $crate::gpu::KeepAlive) {
                $($crate::gpu::PushValue::keep_alive(&self.$field, keep);)*
                let _ = keep;
            }
        }

        impl $(<$lt>)? $crate::gpu::PushBlock for $name $(<$lt>)? {}
    };
}
