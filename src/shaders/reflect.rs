//! Reads struct layouts (member names, `Offset` and `ArrayStride` decorations) out of SPIR-V, so
//! tests and hot reload can check the GLSL header against the Rust mirrors in `sim::gpu_types`.

use std::collections::HashMap;

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_STRUCT: u32 = 30;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_RUNTIME_ARRAY: u32 = 29;
const OP_DECORATE: u32 = 71;
const OP_MEMBER_DECORATE: u32 = 72;
const DECORATION_ARRAY_STRIDE: u32 = 6;
const DECORATION_OFFSET: u32 = 35;

/// One struct type as the SPIR-V lays it out.
#[derive(Debug, Clone, PartialEq)]
pub struct StructLayout {
    pub name: String,
    /// (member name, byte offset) in declaration order.
    pub members: Vec<(String, u32)>,
    /// Strides of arrays whose element is this struct (std430: the struct's size).
    pub array_strides: Vec<u32>,
}

/// Every named struct type in the module that carries explicit offsets.
pub fn struct_layouts(words: &[u32]) -> Vec<StructLayout> {
    let mut names: HashMap<u32, String> = HashMap::new();
    let mut member_names: HashMap<(u32, u32), String> = HashMap::new();
    let mut offsets: HashMap<(u32, u32), u32> = HashMap::new();
    let mut strides: HashMap<u32, u32> = HashMap::new();
    let mut structs: Vec<(u32, usize)> = Vec::new(); // (id, member count)
    let mut arrays: Vec<(u32, u32)> = Vec::new(); // (array id, element type id)

    let mut at = 5;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let op = words[at] & 0xffff;
        if count == 0 || at + count > words.len() {
            break;
        }
        let args = &words[at + 1..at + count];
        match op {
            OP_NAME if !args.is_empty() => {
                names.insert(args[0], literal_string(&args[1..]));
            }
            OP_MEMBER_NAME if args.len() >= 2 => {
                member_names.insert((args[0], args[1]), literal_string(&args[2..]));
            }
            OP_MEMBER_DECORATE if args.len() >= 4 && args[2] == DECORATION_OFFSET => {
                offsets.insert((args[0], args[1]), args[3]);
            }
            OP_DECORATE if args.len() >= 3 && args[1] == DECORATION_ARRAY_STRIDE => {
                strides.insert(args[0], args[2]);
            }
            OP_TYPE_STRUCT if !args.is_empty() => structs.push((args[0], args.len() - 1)),
            OP_TYPE_ARRAY | OP_TYPE_RUNTIME_ARRAY if args.len() >= 2 => arrays.push((args[0], args[1])),
            _ => {}
        }
        at += count;
    }

    structs
        .into_iter()
        .filter_map(|(id, n)| {
            let name = names.get(&id)?.clone();
            let members = (0..n as u32)
                .map(|m| {
                    let member = member_names.get(&(id, m)).cloned().unwrap_or_default();
                    Some((member, *offsets.get(&(id, m))?))
                })
                .collect::<Option<Vec<_>>>()?;
            let array_strides = arrays
                .iter()
                .filter(|(_, elem)| *elem == id)
                .filter_map(|(arr, _)| strides.get(arr).copied())
                .collect();
            Some(StructLayout { name, members, array_strides })
        })
        .collect()
}

fn literal_string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|b| *b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}
