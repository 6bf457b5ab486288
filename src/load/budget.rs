//! The memory a model load may take, from the size of what it reads: counts in a file (glTF
//! accessor counts, OBJ corners) are charged against it before anything is allocated for
//! them, so a small file that declares a huge count is refused in one line instead of
//! allocating gigabytes. Allocations sized from the input are made fallibly
//! ([`try_vec`]): the system refusing memory is the same one line, not an abort.

use std::fmt;

/// Bytes every load may take whatever its size (a small model's meshes, tangents and GPU
/// streams fit many times over).
pub const BASE_BYTES: u64 = 64 << 20;

/// Bytes of meshes a load may make per byte it reads (model, buffers, material libraries):
/// a quantized glTF vertex (3 bytes of position) becomes 48 bytes of mesh, and a corner
/// shared by six triangles of a file without normals one vertex per triangle.
pub const BYTES_PER_INPUT_BYTE: u64 = 64;

/// Bytes of mesh per vertex as [`crate::scene::Mesh`] stores it: position, normal (12 bytes
/// each), UV (8) and tangent (16).
pub const VERTEX_BYTES: u64 = 48;

/// Bytes per index (`u32`).
pub const INDEX_BYTES: u64 = 4;

/// The memory a load may still take, in bytes.
#[derive(Debug, Clone)]
pub struct Budget {
    limit: u64,
    used: u64,
}

/// More memory asked than the budget has left.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OverBudget {
    /// Bytes this step asked for.
    pub wanted: u64,
    /// Bytes taken before it.
    pub used: u64,
    /// The budget, bytes.
    pub limit: u64,
}

impl fmt::Display for OverBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mib = |bytes: u64| bytes.div_ceil(1 << 20);
        write!(
            f,
            "needs {} MiB more memory (after {} MiB), over this model's budget of {} MiB ({} MiB plus {} bytes per byte read)",
            mib(self.wanted),
            mib(self.used),
            mib(self.limit),
            BASE_BYTES >> 20,
            BYTES_PER_INPUT_BYTE
        )
    }
}

impl Budget {
    /// The budget of a load that reads `input_bytes` bytes: [`BASE_BYTES`] plus
    /// [`BYTES_PER_INPUT_BYTE`] per byte.
    pub fn for_input(input_bytes: u64) -> Budget {
        Budget { limit: BASE_BYTES.saturating_add(input_bytes.saturating_mul(BYTES_PER_INPUT_BYTE)), used: 0 }
    }

    /// Takes `bytes` from the budget, or fails leaving it unchanged.
    pub fn charge(&mut self, bytes: u64) -> Result<(), OverBudget> {
        match self.used.checked_add(bytes).filter(|&total| total <= self.limit) {
            Some(total) => {
                self.used = total;
                Ok(())
            }
            None => Err(OverBudget { wanted: bytes, used: self.used, limit: self.limit }),
        }
    }
}

/// An empty vector with room for `count` elements, or `None` when the system refuses the
/// memory (or the size overflows).
pub fn try_vec<T>(count: usize) -> Option<Vec<T>> {
    let mut vec = Vec::new();
    vec.try_reserve_exact(count).ok()?;
    Some(vec)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charges_add_up_to_the_limit_and_a_refusal_takes_nothing() {
        let mut budget = Budget::for_input(1);
        assert_eq!(budget.limit, BASE_BYTES + BYTES_PER_INPUT_BYTE);
        budget.charge(BASE_BYTES).unwrap();
        let refused = budget.charge(BYTES_PER_INPUT_BYTE + 1).unwrap_err();
        assert_eq!((refused.used, refused.limit), (BASE_BYTES, BASE_BYTES + BYTES_PER_INPUT_BYTE));
        budget.charge(BYTES_PER_INPUT_BYTE).unwrap();
        assert_eq!(budget.used, budget.limit);
        assert!(budget.charge(u64::MAX).is_err());
        assert!(try_vec::<u64>(usize::MAX).is_none());
    }
}
