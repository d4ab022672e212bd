//! Reads struct layouts out of SPIR-V (member names, `Offset`, `ArrayStride` and `MatrixStride`
//! decorations, and every member's type down to its scalars), and which structs the module's
//! buffers and push constants hold, so tests and hot reload can check the GLSL header against
//! the Rust mirrors in `sim::gpu_types` whatever the shader calls its types.

use crate::sim::gpu_types::GpuScalar;
use std::collections::HashMap;

/// A scalar as the module has it: one the host has a type for, or `None` (another width).
pub type Scalar = Option<GpuScalar>;

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_INT: u32 = 21;
const OP_TYPE_FLOAT: u32 = 22;
const OP_TYPE_VECTOR: u32 = 23;
const OP_TYPE_MATRIX: u32 = 24;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_RUNTIME_ARRAY: u32 = 29;
const OP_TYPE_STRUCT: u32 = 30;
const OP_TYPE_POINTER: u32 = 32;
const OP_CONSTANT: u32 = 43;
const OP_VARIABLE: u32 = 59;
const OP_DECORATE: u32 = 71;
const OP_MEMBER_DECORATE: u32 = 72;
const DECORATION_ARRAY_STRIDE: u32 = 6;
const DECORATION_ROW_MAJOR: u32 = 4;
const DECORATION_MATRIX_STRIDE: u32 = 7;
const DECORATION_BINDING: u32 = 33;
const DECORATION_OFFSET: u32 = 35;
const STORAGE_UNIFORM: u32 = 2;
const STORAGE_PUSH_CONSTANT: u32 = 9;
const STORAGE_STORAGE_BUFFER: u32 = 12;

/// One struct type as the SPIR-V lays it out.
#[derive(Debug, Clone, PartialEq)]
pub struct StructLayout {
    pub name: String,
    /// (member name, byte offset) in declaration order.
    pub members: Vec<(String, u32)>,
    /// Every scalar of the struct, (byte offset, kind), in member order (arrays and matrices
    /// unrolled by their strides).
    pub scalars: Vec<(u32, Scalar)>,
    /// Strides of arrays whose element is this struct (std430: the struct's size).
    pub array_strides: Vec<u32>,
}

#[derive(Clone)]
enum Type {
    Scalar(Scalar),
    Vector(u32, u32),
    Matrix(u32, u32),
    Array(u32, u32),
    RuntimeArray(u32),
    Struct(Vec<u32>),
    /// The pointee.
    Pointer(u32),
}

/// The module's types and decorations, by id.
#[derive(Default)]
struct Module {
    names: HashMap<u32, String>,
    member_names: HashMap<(u32, u32), String>,
    offsets: HashMap<(u32, u32), u32>,
    matrix_strides: HashMap<(u32, u32), u32>,
    row_major: std::collections::HashSet<(u32, u32)>,
    strides: HashMap<u32, u32>,
    constants: HashMap<u32, u32>,
    types: HashMap<u32, Type>,
    /// In declaration order.
    structs: Vec<u32>,
    bound: HashMap<u32, u32>,
    /// (variable type, storage class, variable id)
    variables: Vec<(u32, u32, u32)>,
}

impl Module {
    fn read(words: &[u32]) -> Self {
        let mut m = Module::default();
        let mut at = 5;
        while at < words.len() {
            let count = (words[at] >> 16) as usize;
            let op = words[at] & 0xffff;
            if count == 0 || at + count > words.len() {
                break;
            }
            let a = &words[at + 1..at + count];
            match op {
                OP_NAME if !a.is_empty() => {
                    m.names.insert(a[0], literal_string(&a[1..]));
                }
                OP_MEMBER_NAME if a.len() >= 2 => {
                    m.member_names.insert((a[0], a[1]), literal_string(&a[2..]));
                }
                OP_MEMBER_DECORATE if a.len() >= 4 && a[2] == DECORATION_OFFSET => {
                    m.offsets.insert((a[0], a[1]), a[3]);
                }
                OP_MEMBER_DECORATE if a.len() >= 4 && a[2] == DECORATION_MATRIX_STRIDE => {
                    m.matrix_strides.insert((a[0], a[1]), a[3]);
                }
                OP_MEMBER_DECORATE if a.len() >= 3 && a[2] == DECORATION_ROW_MAJOR => {
                    m.row_major.insert((a[0], a[1]));
                }
                OP_DECORATE if a.len() >= 3 && a[1] == DECORATION_ARRAY_STRIDE => {
                    m.strides.insert(a[0], a[2]);
                }
                OP_DECORATE if a.len() >= 3 && a[1] == DECORATION_BINDING => {
                    m.bound.insert(a[0], a[2]);
                }
                OP_CONSTANT if a.len() >= 3 => {
                    m.constants.insert(a[1], a[2]);
                }
                OP_TYPE_INT if a.len() >= 3 => {
                    let kind = match (a[1], a[2]) {
                        (32, 0) => Some(GpuScalar::U32),
                        (32, _) => Some(GpuScalar::I32),
                        _ => None,
                    };
                    m.types.insert(a[0], Type::Scalar(kind));
                }
                OP_TYPE_FLOAT if a.len() >= 2 => {
                    let kind = (a[1] == 32).then_some(GpuScalar::F32);
                    m.types.insert(a[0], Type::Scalar(kind));
                }
                OP_TYPE_VECTOR if a.len() >= 3 => {
                    m.types.insert(a[0], Type::Vector(a[1], a[2]));
                }
                OP_TYPE_MATRIX if a.len() >= 3 => {
                    m.types.insert(a[0], Type::Matrix(a[1], a[2]));
                }
                OP_TYPE_ARRAY if a.len() >= 3 => {
                    m.types.insert(a[0], Type::Array(a[1], a[2]));
                }
                OP_TYPE_RUNTIME_ARRAY if a.len() >= 2 => {
                    m.types.insert(a[0], Type::RuntimeArray(a[1]));
                }
                OP_TYPE_STRUCT if !a.is_empty() => {
                    m.types.insert(a[0], Type::Struct(a[1..].to_vec()));
                    m.structs.push(a[0]);
                }
                OP_TYPE_POINTER if a.len() >= 3 => {
                    m.types.insert(a[0], Type::Pointer(a[2]));
                }
                OP_VARIABLE if a.len() >= 3 => m.variables.push((a[0], a[2], a[1])),
                _ => {}
            }
            at += count;
        }
        m
    }

    /// Appends the scalars of a value of type `id` at byte `base`, in column order for a
    /// matrix; `matrix`: a matrix member's (or array of matrices') stride and whether it is
    /// row-major. `None` when a size or stride is not known (no explicit layout, or an array
    /// length that is a specialization constant).
    fn flatten(
        &self,
        id: u32,
        base: u32,
        matrix: Option<(u32, bool)>,
        out: &mut Vec<(u32, Scalar)>,
    ) -> Option<()> {
        match self.types.get(&id)? {
            Type::Scalar(s) => out.push((base, *s)),
            Type::Vector(c, n) => {
                for k in 0..*n {
                    self.flatten(*c, base + 4 * k, None, out)?;
                }
            }
            Type::Matrix(col, n) => {
                let (stride, row_major) = matrix?;
                let Some(Type::Vector(c, rows)) = self.types.get(col) else { return None };
                for k in 0..*n {
                    for r in 0..*rows {
                        let at =
                            if row_major { base + r * stride + 4 * k } else { base + k * stride + 4 * r };
                        self.flatten(*c, at, None, out)?;
                    }
                }
            }
            Type::Array(e, len) => {
                let stride = *self.strides.get(&id)?;
                for k in 0..*self.constants.get(len)? {
                    self.flatten(*e, base + stride * k, matrix, out)?;
                }
            }
            Type::RuntimeArray(e) => self.flatten(*e, base, matrix, out)?,
            Type::Struct(members) => {
                for k in 0..members.len() as u32 {
                    let offset = *self.offsets.get(&(id, k))?;
                    let matrix =
                        self.matrix_strides.get(&(id, k)).map(|s| (*s, self.row_major.contains(&(id, k))));
                    self.flatten(members[k as usize], base + offset, matrix, out)?;
                }
            }
            Type::Pointer(..) => return None,
        }
        Some(())
    }

    /// The struct an array type (or a nest of them) holds, or the struct itself.
    fn element_struct(&self, id: u32) -> Option<u32> {
        match self.types.get(&id)? {
            Type::Struct(_) => Some(id),
            Type::Array(e, _) | Type::RuntimeArray(e) => self.element_struct(*e),
            _ => None,
        }
    }
}

/// What the layout check reads from a module.
pub struct Reflection {
    /// Every named struct type in the module that carries explicit offsets.
    pub layouts: Vec<StructLayout>,
    /// The structs that the module's buffers, uniforms and push constants hold (`bound_structs`).
    pub bound: Vec<(String, String)>,
}

/// Reads `words` once for both.
pub fn reflect(words: &[u32]) -> Reflection {
    let m = Module::read(words);
    Reflection { layouts: struct_layouts(&m), bound: bound_structs(&m) }
}

fn struct_layouts(m: &Module) -> Vec<StructLayout> {
    m.structs
        .iter()
        .filter_map(|&id| {
            let Some(Type::Struct(member_types)) = m.types.get(&id) else { return None };
            let name = m.names.get(&id)?.clone();
            let members = (0..member_types.len() as u32)
                .map(|k| {
                    let member = m.member_names.get(&(id, k)).cloned().unwrap_or_default();
                    Some((member, *m.offsets.get(&(id, k))?))
                })
                .collect::<Option<Vec<_>>>()?;
            let mut scalars = Vec::new();
            m.flatten(id, 0, None, &mut scalars)?;
            let array_strides = m
                .types
                .iter()
                .filter(|(_, t)| matches!(t, Type::Array(e, _) | Type::RuntimeArray(e) if *e == id))
                .filter_map(|(arr, _)| m.strides.get(arr).copied())
                .collect();
            Some(StructLayout { name, members, scalars, array_strides })
        })
        .collect()
}

/// The structs that the module's buffers, uniforms and push constants hold, inside their
/// blocks: (where, e.g. "binding 2", the struct's name in the module, "" when it has none).
/// A push-constant block is listed itself (its own name is the shared struct) unless it holds
/// only uint words, as the compute passes' do.
fn bound_structs(m: &Module) -> Vec<(String, String)> {
    let mut found = Vec::new();
    for &(pointer, storage, var) in &m.variables {
        if ![STORAGE_UNIFORM, STORAGE_STORAGE_BUFFER, STORAGE_PUSH_CONSTANT].contains(&storage) {
            continue;
        }
        let Some(Type::Pointer(pointee)) = m.types.get(&pointer) else { continue };
        // (an array of blocks: a batched shader's per-object bindings)
        let Some(block) = m.element_struct(*pointee) else { continue };
        let block = &block;
        let Some(Type::Struct(members)) = m.types.get(block) else { continue };
        let place = match m.bound.get(&var) {
            Some(b) => format!("binding {b}"),
            None => "the push constants".to_string(),
        };
        let name = |id: &u32| m.names.get(id).cloned().unwrap_or_default();
        if storage == STORAGE_PUSH_CONSTANT {
            // The compute passes push plain uint words (`Recorder::push`); anything else is a
            // shared struct.
            let mut scalars = Vec::new();
            let words = m.flatten(*block, 0, None, &mut scalars).is_some()
                && scalars.iter().all(|(_, s)| *s == Some(GpuScalar::U32));
            if !words {
                found.push((place.clone(), name(block)));
            }
        }
        for s in members.iter().filter_map(|t| m.element_struct(*t)) {
            found.push((place.clone(), name(&s)));
        }
    }
    found
}

fn literal_string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|b| *b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}
