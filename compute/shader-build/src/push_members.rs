//! The members of a kernel's push-constant block, read from an unoptimized SPIR-V module (the
//! optimizer strips member names). Nested structs are flattened into dotted names
//! (`store.cells`) with offsets from the start of the block, so the host side can be compared
//! member by member whatever its nesting.

use std::collections::HashMap;

/// One leaf member of the push-constant block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PushMember {
    /// Dotted GLSL member name (`n`, `store.cells`).
    pub name: String,
    /// Byte offset from the start of the block.
    pub offset: u32,
    /// GLSL type (`uint`, `uint64_t`, `vec3`, `uvec4`, `uint[4]`).
    pub ty: String,
}

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_BOOL: u32 = 20;
const OP_TYPE_INT: u32 = 21;
const OP_TYPE_FLOAT: u32 = 22;
const OP_TYPE_VECTOR: u32 = 23;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_STRUCT: u32 = 30;
const OP_TYPE_POINTER: u32 = 32;
const OP_CONSTANT: u32 = 43;
const OP_VARIABLE: u32 = 59;
const OP_MEMBER_DECORATE: u32 = 72;
const DECORATION_OFFSET: u32 = 35;
const STORAGE_PUSH_CONSTANT: u32 = 9;

enum Type {
    Scalar(&'static str),
    Vector(u32, u32),
    Array(u32, u32),
    Struct(Vec<u32>),
    Other(u32),
}

#[derive(Default)]
struct Module {
    names: HashMap<u32, String>,
    member_names: HashMap<(u32, u32), String>,
    offsets: HashMap<(u32, u32), u32>,
    types: HashMap<u32, Type>,
    constants: HashMap<u32, u32>,
    pointees: HashMap<u32, (u32, u32)>,
    push_variable_type: Option<u32>,
}

fn string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .take_while(|&b| b != 0)
        .collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

fn parse(words: &[u32]) -> Module {
    let mut m = Module::default();
    let mut i = 5;
    while i < words.len() {
        let count = (words[i] >> 16) as usize;
        let op = words[i] & 0xffff;
        if count == 0 || i + count > words.len() {
            break;
        }
        let a = &words[i + 1..i + count];
        match op {
            OP_NAME if a.len() >= 2 => {
                m.names.insert(a[0], string(&a[1..]));
            }
            OP_MEMBER_NAME if a.len() >= 3 => {
                m.member_names.insert((a[0], a[1]), string(&a[2..]));
            }
            OP_MEMBER_DECORATE if a.len() == 4 && a[2] == DECORATION_OFFSET => {
                m.offsets.insert((a[0], a[1]), a[3]);
            }
            OP_TYPE_BOOL => {
                m.types.insert(a[0], Type::Scalar("bool"));
            }
            OP_TYPE_INT if a.len() == 3 => {
                let ty = match (a[1], a[2]) {
                    (32, 0) => "uint",
                    (32, _) => "int",
                    (64, 0) => "uint64_t",
                    (64, _) => "int64_t",
                    (16, 0) => "uint16_t",
                    (16, _) => "int16_t",
                    (8, 0) => "uint8_t",
                    _ => "int8_t",
                };
                m.types.insert(a[0], Type::Scalar(ty));
            }
            OP_TYPE_FLOAT if a.len() >= 2 => {
                let ty = match a[1] {
                    64 => "double",
                    16 => "float16_t",
                    _ => "float",
                };
                m.types.insert(a[0], Type::Scalar(ty));
            }
            OP_TYPE_VECTOR if a.len() == 3 => {
                m.types.insert(a[0], Type::Vector(a[1], a[2]));
            }
            OP_TYPE_ARRAY if a.len() == 3 => {
                m.types.insert(a[0], Type::Array(a[1], a[2]));
            }
            OP_TYPE_STRUCT if !a.is_empty() => {
                m.types.insert(a[0], Type::Struct(a[1..].to_vec()));
            }
            OP_TYPE_POINTER if a.len() == 3 => {
                m.pointees.insert(a[0], (a[1], a[2]));
                m.types.insert(a[0], Type::Other(op));
            }
            OP_CONSTANT if a.len() >= 3 => {
                m.constants.insert(a[1], a[2]);
            }
            OP_VARIABLE if a.len() >= 3 && a[2] == STORAGE_PUSH_CONSTANT => {
                m.push_variable_type = m.pointees.get(&a[0]).map(|&(_, t)| t);
            }
            // Every other type declaration (OpTypeVoid..OpTypeForwardPointer and the rest of
            // the type range), including the guarded ones above whose guard failed.
            other if (OP_TYPE_BOOL..=39).contains(&other) => {
                m.types.insert(a[0], Type::Other(op));
            }
            _ => {}
        }
        i += count;
    }
    m
}

impl Module {
    /// The GLSL spelling of a non-struct type.
    fn leaf(&self, id: u32) -> Result<String, String> {
        match self.types.get(&id) {
            Some(Type::Scalar(s)) => Ok((*s).to_string()),
            Some(Type::Vector(component, n)) => {
                let prefix = match self.leaf(*component)?.as_str() {
                    "float" => "",
                    "double" => "d",
                    "int" => "i",
                    "uint" => "u",
                    "bool" => "b",
                    "uint64_t" => "u64",
                    "int64_t" => "i64",
                    other => return Err(format!("vectors of {other} are not supported")),
                };
                Ok(format!("{prefix}vec{n}"))
            }
            Some(Type::Array(element, length)) => {
                let n = self
                    .constants
                    .get(length)
                    .ok_or("an array whose length is a specialization constant")?;
                Ok(format!("{}[{n}]", self.leaf(*element)?))
            }
            Some(Type::Struct(_)) => Err("arrays of structs are not supported".into()),
            Some(Type::Other(op)) => Err(format!(
                "a member of SPIR-V type opcode {op} (only scalars, vectors, arrays of them and structs)"
            )),
            None => Err(format!("unknown type id {id}")),
        }
    }

    fn flatten(
        &self,
        ty: u32,
        prefix: &str,
        base: u32,
        out: &mut Vec<PushMember>,
    ) -> Result<(), String> {
        let Some(Type::Struct(members)) = self.types.get(&ty) else {
            out.push(PushMember {
                name: prefix.to_string(),
                offset: base,
                ty: self.leaf(ty)?,
            });
            return Ok(());
        };
        for (i, &member) in members.iter().enumerate() {
            let i = i as u32;
            let name = self.member_names.get(&(ty, i)).cloned().unwrap_or_default();
            let struct_name = self.names.get(&ty).map_or("", String::as_str);
            if name.is_empty() {
                return Err(format!("member {i} of {struct_name} has no name"));
            }
            let offset = *self
                .offsets
                .get(&(ty, i))
                .ok_or_else(|| format!("member {name} of {struct_name} has no offset"))?;
            let path = if prefix.is_empty() {
                name
            } else {
                format!("{prefix}.{name}")
            };
            self.flatten(member, &path, base + offset, out)?;
        }
        Ok(())
    }
}

/// The leaf members of the push-constant block of `words` (empty when there is none), in
/// declaration order.
pub fn reflect(words: &[u32]) -> Result<Vec<PushMember>, String> {
    let module = parse(words);
    let mut out = Vec::new();
    if let Some(block) = module.push_variable_type {
        module.flatten(block, "", 0, &mut out)?;
    }
    Ok(out)
}
