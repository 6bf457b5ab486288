//! glTF vertex accessors read as floats whatever their component type: floats as stored, and
//! the integer types `KHR_mesh_quantization` allows (bytes and shorts, signed or not,
//! normalised or not) converted as glTF 2.0 §3.11 says — `max(c / 127, −1)` for a normalised
//! signed byte, `c / 255` for an unsigned one, likewise with 32767 and 65535 for shorts, and
//! the plain value when not normalised (the node transform then scales it).

use gltf::accessor::{DataType, Item, Iter};

use super::accessor_rules::{AccessorProblem, AccessorUse, check_accessor};
use super::budget::try_vec;

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
        let count = accessor.count();
        let iter = Iter::<[T; N]>::new(accessor, get).ok_or(AccessorProblem::OutsideBuffer)?;
        let mut vectors = try_vec(count).ok_or(AccessorProblem::NoMemory { count: count as u64 })?;
        vectors.extend(iter.map(|v| v.map(&to_float)));
        Ok(vectors)
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
