//! glTF vertex accessors read as floats whatever their component type: floats as stored, and
//! the integer types `KHR_mesh_quantization` allows (bytes and shorts, signed or not,
//! normalised or not) converted as glTF 2.0 §3.11 says — `max(c / 127, −1)` for a normalised
//! signed byte, `c / 255` for an unsigned one, likewise with 32767 and 65535 for shorts, and
//! the plain value when not normalised (the node transform then scales it).

use gltf::accessor::{DataType, Item, Iter};

/// Why an accessor could not be read as vectors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccessorProblem {
    /// Its type has another number of components than the attribute needs.
    Components { expected: usize, found: usize },
    /// Its component type is not one a vertex attribute may have (e.g. 32-bit integers).
    ComponentType(DataType),
    /// Its data lies outside its buffer.
    OutsideBuffer,
}

impl std::fmt::Display for AccessorProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AccessorProblem::Components { expected, found } => {
                write!(f, "has {found} components per vertex, {expected} expected")
            }
            AccessorProblem::ComponentType(t) => {
                write!(f, "has component type {t:?}, which no vertex attribute may have")
            }
            AccessorProblem::OutsideBuffer => write!(f, "lies outside its buffer"),
        }
    }
}

/// Every element of `accessor` as `N` floats (sparse accessors included).
pub fn read_vectors<const N: usize>(
    accessor: gltf::Accessor,
    buffers: &[Vec<u8>],
) -> Result<Vec<[f32; N]>, AccessorProblem>
where
    [f32; N]: Item,
    [i8; N]: Item,
    [u8; N]: Item,
    [i16; N]: Item,
    [u16; N]: Item,
{
    let found = accessor.dimensions().multiplicity();
    if found != N {
        return Err(AccessorProblem::Components { expected: N, found });
    }
    if accessor.count() == 0 {
        return Ok(vec![]);
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
        other => Err(AccessorProblem::ComponentType(other)),
    }
}
