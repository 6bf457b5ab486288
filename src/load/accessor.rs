//! glTF vertex accessors read as floats whatever their component type: floats as stored, and
//! the integer types `KHR_mesh_quantization` allows (bytes and shorts, signed or not,
//! normalised or not) converted as glTF 2.0 §3.11 says — `max(c / 127, −1)` for a normalised
//! signed byte, `c / 255` for an unsigned one, likewise with 32767 and 65535 for shorts, and
//! the plain value when not normalised (the node transform then scales it).

use gltf::accessor::{DataType, Item, Iter};

use super::accessor_rules::{AccessorUse, check_accessor};
use crate::read::FileKind;

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
        }
    }
}

/// Every element of `accessor` as `N` floats (sparse accessors included), once it passes the
/// rules for `use_` ([`check_accessor`]; `document` is the accessor's).
pub fn read_vectors<const N: usize>(
    document: &gltf::Document,
    accessor: gltf::Accessor,
    use_: AccessorUse,
    buffers: &[Vec<u8>],
) -> Result<Vec<[f32; N]>, AccessorProblem>
where
    [f32; N]: Item,
    [i8; N]: Item,
    [u8; N]: Item,
    [i16; N]: Item,
    [u16; N]: Item,
{
    check_accessor(document.as_json(), accessor.index(), use_, buffers)?;
    let found = accessor.dimensions().multiplicity();
    if found != N {
        return Err(AccessorProblem::Components { expected: N, found });
    }
    let normalized = accessor.normalized();
    let get = |buffer: gltf::Buffer| buffers.get(buffer.index()).map(Vec::as_slice);
    fn convert<'a, 's, T: Item + Copy, const N: usize>(
        accessor: gltf::Accessor<'a>,
        get: impl Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
        to_float: impl Fn(T) -> f32,
    ) -> Result<Vec<[f32; N]>, AccessorProblem>
    where
        [T; N]: Item,
    {
        let iter = Iter::<[T; N]>::new(accessor, get).ok_or(AccessorProblem::OutsideBuffer)?;
        Ok(iter.map(|v| v.map(&to_float)).collect())
    }
    let unit = |scale: f32| move |c: f32| if normalized { (c / scale).max(-1.0) } else { c };
    match accessor.data_type() {
        DataType::F32 => convert::<f32, N>(accessor, get, |c| c),
        DataType::I8 => convert::<i8, N>(accessor, get, |c| unit(127.0)(c as f32)),
        DataType::U8 => convert::<u8, N>(accessor, get, |c| unit(255.0)(c as f32)),
        DataType::I16 => convert::<i16, N>(accessor, get, |c| unit(32767.0)(c as f32)),
        DataType::U16 => convert::<u16, N>(accessor, get, |c| unit(65535.0)(c as f32)),
        data_type => Err(AccessorProblem::ComponentType { data_type, normalized, use_ }),
    }
}
