//! What glTF 2.0 allows an accessor for the use a primitive makes of it, checked on the JSON
//! and the buffers before the `gltf` crate's readers see the accessor: those readers assume a
//! valid file and panic (`unreachable!`, slice bounds, subtraction overflow) on an index
//! accessor of floats, a stride shorter than an element, a count of 0 or a sparse index type
//! that is not unsigned.
//!
//! Component types (glTF 2.0 §3.7.2.1, and `KHR_mesh_quantization` for the integer vertex
//! attributes, accepted whether or not the file lists the extension):
//!
//! | use      | type   | float     | byte / short (signed or not) | unsigned int |
//! |----------|--------|-----------|------------------------------|--------------|
//! | indices  | SCALAR | —         | unsigned, not normalised     | not normalised |
//! | POSITION | VEC3   | not norm. | either                       | —            |
//! | NORMAL   | VEC3   | not norm. | signed, normalised           | —            |
//! | TANGENT  | VEC4   | not norm. | signed, normalised           | —            |
//! | TEXCOORD | VEC2   | not norm. | either                       | —            |
//!
//! Layout (§3.6.2.4, §3.6.2.3): a count of at least 1; the offset is a multiple of the component size, in the view
//! and in the buffer; a view's stride is at least one element; every element (and every
//! sparse index and value) lies inside its view and the view inside its buffer's bytes;
//! sparse indices are unsigned, strictly increasing and below the accessor's count.

use gltf::accessor::{DataType, Dimensions};
use gltf::json::validation::Checked;

use crate::read::FileKind;

/// What a primitive reads an accessor as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccessorUse {
    Indices,
    Positions,
    Normals,
    Tangents,
    TexCoords,
}

impl AccessorUse {
    /// The use as glTF names it.
    pub fn name(self) -> &'static str {
        match self {
            AccessorUse::Indices => "indices",
            AccessorUse::Positions => "POSITION",
            AccessorUse::Normals => "NORMAL",
            AccessorUse::Tangents => "TANGENT",
            AccessorUse::TexCoords => "TEXCOORD",
        }
    }

    /// The accessor type this use needs.
    pub fn dimensions(self) -> Dimensions {
        match self {
            AccessorUse::Indices => Dimensions::Scalar,
            AccessorUse::TexCoords => Dimensions::Vec2,
            AccessorUse::Positions | AccessorUse::Normals => Dimensions::Vec3,
            AccessorUse::Tangents => Dimensions::Vec4,
        }
    }

    /// Whether glTF (with `KHR_mesh_quantization`) allows components of `data_type`,
    /// normalised or not, for this use (the table in the module doc).
    pub fn allows(self, data_type: DataType, normalized: bool) -> bool {
        use DataType::{F32, I8, I16, U8, U16, U32};
        match (self, data_type) {
            (AccessorUse::Indices, U8 | U16 | U32) => !normalized,
            (AccessorUse::Indices, _) => false,
            (_, F32) => !normalized,
            (_, U32) => false,
            (AccessorUse::Positions | AccessorUse::TexCoords, I8 | U8 | I16 | U16) => true,
            (AccessorUse::Normals | AccessorUse::Tangents, I8 | I16) => normalized,
            (AccessorUse::Normals | AccessorUse::Tangents, U8 | U16) => false,
        }
    }
}

/// Why an accessor cannot be read for its use ([`super::accessor_rules`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccessorProblem {
    /// It, its buffer view or its buffer does not exist.
    Missing,
    /// Its component type or type is not one glTF defines.
    Invalid,
    /// Its type has another number of components than the use needs.
    Components { expected: usize, found: usize },
    /// Its component type (normalised or not) is not one glTF allows for the use.
    ComponentType { data_type: DataType, normalized: bool, use_: AccessorUse },
    /// A count of 0 (glTF requires at least 1).
    Empty,
    /// Neither a buffer view nor sparse values.
    NoData,
    /// Without a buffer view, more elements than fit in a buffer's cap once read as floats.
    TooMany { count: u64 },
    /// Its buffer view's stride is shorter than one element.
    Stride { stride: u64, element: u64 },
    /// Its offset is not a multiple of its component size.
    Misaligned { offset: u64, component: u64 },
    /// Its data lies outside its buffer view or buffer.
    OutsideBuffer,
    /// Its sparse count is 0 or above its count.
    SparseCount { sparse: u64, count: u64 },
    /// Its sparse indices are not unsigned integers.
    SparseIndexType(DataType),
    /// Its sparse indices are not strictly increasing below its count.
    SparseIndices,
    /// The system refused the memory for its elements.
    NoMemory { count: u64 },
}

impl std::fmt::Display for AccessorProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AccessorProblem::Missing => write!(f, "names a buffer view or buffer that does not exist"),
            AccessorProblem::Invalid => write!(f, "has a component type or type glTF does not define"),
            AccessorProblem::Components { expected, found } => {
                write!(f, "has {found} components per element, {expected} expected")
            }
            AccessorProblem::ComponentType { data_type, normalized, use_ } => {
                let normalized = if *normalized { "normalised " } else { "" };
                write!(f, "has {normalized}component type {data_type:?}, which glTF does not allow for {}", use_.name())
            }
            AccessorProblem::Empty => write!(f, "has a count of 0 (glTF requires at least 1)"),
            AccessorProblem::NoData => write!(f, "has neither a bufferView nor sparse values"),
            AccessorProblem::TooMany { count } => {
                let mib = FileKind::Buffer.cap() >> 20;
                write!(f, "has {count} elements and no bufferView: more than the {mib} MiB a buffer may hold once read")
            }
            AccessorProblem::Stride { stride, element } => {
                write!(f, "has a byteStride of {stride} bytes, shorter than its {element}-byte elements")
            }
            AccessorProblem::Misaligned { offset, component } => {
                write!(f, "starts at byte {offset}, not a multiple of its {component}-byte components")
            }
            AccessorProblem::OutsideBuffer => write!(f, "lies outside its buffer view or buffer"),
            AccessorProblem::SparseCount { sparse, count } => {
                write!(f, "has a sparse count of {sparse} for {count} elements (1 to {count} allowed)")
            }
            AccessorProblem::SparseIndexType(t) => {
                write!(f, "has sparse indices of component type {t:?} (unsigned byte, short or int allowed)")
            }
            AccessorProblem::SparseIndices => {
                write!(f, "has sparse indices that are not strictly increasing below its count")
            }
            AccessorProblem::NoMemory { count } => write!(f, "has {count} elements, more than the memory left holds"),
        }
    }
}

/// Checks accessor `index` of `root` for `use_` against the rules of the module doc, with
/// `buffers` the bytes of the document's buffers.
pub fn check_accessor(
    root: &gltf::json::Root,
    index: usize,
    use_: AccessorUse,
    buffers: &[Vec<u8>],
) -> Result<(), AccessorProblem> {
    let accessor = root.accessors.get(index).ok_or(AccessorProblem::Missing)?;
    let (Checked::Valid(data_type), Checked::Valid(dimensions)) = (accessor.component_type, accessor.type_) else {
        return Err(AccessorProblem::Invalid);
    };
    let data_type = data_type.0;
    if dimensions != use_.dimensions() {
        let (expected, found) = (use_.dimensions().multiplicity(), dimensions.multiplicity());
        return Err(AccessorProblem::Components { expected, found });
    }
    if !use_.allows(data_type, accessor.normalized) {
        return Err(AccessorProblem::ComponentType { data_type, normalized: accessor.normalized, use_ });
    }
    let count = accessor.count.0;
    if count == 0 {
        return Err(AccessorProblem::Empty);
    }
    let element = (data_type.size() * dimensions.multiplicity()) as u64;
    let offset = accessor.byte_offset.map_or(0, |o| o.0);
    match accessor.buffer_view {
        Some(view) => {
            check_run(root, view.value(), offset, count, element, data_type.size() as u64, buffers)?;
        }
        // No view: `count` zeros under the sparse values, read as 4-byte numbers (floats or
        // u32 indices): at most a buffer's cap of them, however small the file.
        None if accessor.sparse.is_some() => {
            if count > FileKind::Buffer.cap() / (4 * dimensions.multiplicity() as u64) {
                return Err(AccessorProblem::TooMany { count });
            }
        }
        None => return Err(AccessorProblem::NoData),
    }
    if let Some(sparse) = &accessor.sparse {
        let sparse_count = sparse.count.0;
        if sparse_count == 0 || sparse_count > count {
            return Err(AccessorProblem::SparseCount { sparse: sparse_count, count });
        }
        let index_type = match sparse.indices.component_type {
            Checked::Valid(t) if matches!(t.0, DataType::U8 | DataType::U16 | DataType::U32) => t.0,
            Checked::Valid(t) => return Err(AccessorProblem::SparseIndexType(t.0)),
            Checked::Invalid => return Err(AccessorProblem::Invalid),
        };
        let index_size = index_type.size() as u64;
        let (indices_view, values_view) = (sparse.indices.buffer_view.value(), sparse.values.buffer_view.value());
        let (indices, stride) =
            check_run(root, indices_view, sparse.indices.byte_offset.0, sparse_count, index_size, index_size, buffers)?;
        let values_offset = sparse.values.byte_offset.0;
        check_run(root, values_view, values_offset, sparse_count, element, data_type.size() as u64, buffers)?;
        let mut previous = None;
        for i in 0..sparse_count as usize {
            let bytes = &indices[i * stride as usize..];
            let at = match index_type {
                DataType::U8 => bytes[0] as u64,
                DataType::U16 => u16::from_le_bytes([bytes[0], bytes[1]]) as u64,
                _ => u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]) as u64,
            };
            if at >= count || previous.is_some_and(|p| at <= p) {
                return Err(AccessorProblem::SparseIndices);
            }
            previous = Some(at);
        }
    }
    Ok(())
}

/// Checks `count` elements of `element` bytes (of components of `component` bytes) from
/// `offset` in buffer view `view`, at the view's stride or packed; returns the bytes from the
/// first element's start to the last one's end, and the stride.
fn check_run<'b>(
    root: &gltf::json::Root,
    view: usize,
    offset: u64,
    count: u64,
    element: u64,
    component: u64,
    buffers: &'b [Vec<u8>],
) -> Result<(&'b [u8], u64), AccessorProblem> {
    let view = root.buffer_views.get(view).ok_or(AccessorProblem::Missing)?;
    let view_offset = view.byte_offset.map_or(0, |o| o.0);
    // The gltf crate reads a stride of 0 as none.
    let stride = match view.byte_stride.map_or(0, |s| s.0 as u64) {
        0 => element,
        stride => stride,
    };
    if stride < element {
        return Err(AccessorProblem::Stride { stride, element });
    }
    if !offset.is_multiple_of(component) || !view_offset.wrapping_add(offset).is_multiple_of(component) {
        return Err(AccessorProblem::Misaligned { offset, component });
    }
    let buffer = buffers.get(view.buffer.value()).ok_or(AccessorProblem::Missing)?;
    let end = (count - 1).checked_mul(stride).and_then(|s| s.checked_add(offset)).and_then(|s| s.checked_add(element));
    let view_end = view_offset.checked_add(view.byte_length.0);
    match (end, view_end) {
        (Some(end), Some(view_end)) if end <= view.byte_length.0 && view_end <= buffer.len() as u64 => {
            Ok((&buffer[(view_offset + offset) as usize..(view_offset + end) as usize], stride))
        }
        _ => Err(AccessorProblem::OutsideBuffer),
    }
}
