//! bumpview: the tested core of a viewer and teaching tool for bump and normal mapping.
//!
//! The library holds scene data, the built-in teaching scene, loaders for glTF, OBJ and
//! images ([`load`]), the height→normal step, tangent frames, a CPU reference of the shading
//! and the wgpu renderer. It has no egui or winit dependency; the `bumpview` binary is a thin
//! eframe layer over it.
//!
//! # Conventions
//!
//! Every module follows these; they are cited where they are used.
//!
//! - **World**: right-handed, +Y up, units are metres.
//! - **Texture coordinates** are stored as glTF and wgpu use them: origin at the image's
//!   top-left texel, `u` to the right, `v` *down* the image.
//! - **Tangents** are MikkTSpace `vec4`: `xyz` is the direction of ∂P/∂u, `w = ±1` is the
//!   handedness, and the bitangent is `B = w · cross(N, T)` (the glTF 2.0 rule). `B` points
//!   *up* the image (towards −v), which is where a tangent-space normal map's green (+Y)
//!   points. MikkTSpace is therefore fed `(u, 1 − v)`; see [`tangent`]. Tangents a file supplies
//!   are used; missing ones are made MikkTSpace-compatible by meshoptimizer ([`tangent::resolve`]).
//! - **Normal maps** are tangent-space, OpenGL convention (+Y = green = up the image),
//!   linear (never sampled through an sRGB view), decoded as `n = normalize(2·rgb − 1)`,
//!   unless the material's [`scene::NormalConvention`] says DirectX (green negated),
//!   two-channel (`z = sqrt(max(0, 1 − x² − y²))`) or object space (a model-space normal
//!   taken to world space by the normal matrix; no tangents). See [`shading::decode_normal`].
//! - **Bump strength** `s` follows glTF `normalTexture.scale`: `normalize(n · (s, s, 1))`;
//!   `s = 0` is flat and a negative `s` inverts the relief.
//! - **Colour**: base-colour textures are sRGB; shading happens in linear RGB; the render
//!   targets encode sRGB, so PNGs hold sRGB values.
//! - **Height maps**: white = high; a height map has a unit, metres per full range, so that
//!   slopes are right in world space ([`height`]).
//! - **Normal transform**: normals by the inverse-transpose of the model matrix, tangents by
//!   the model matrix, and `w *= sign(det(model))`. Back faces of double-sided materials
//!   flip `N`, and with it the frame.
//! - **Debug views** show a unit world-space vector `v` as the stored colour `0.5·v + 0.5`
//!   (so a PNG byte is `255 · (0.5·v + 0.5)`, not gamma-encoded again).
//! - **No NaN**: directions are normalised through [`math::normalize_or`], which falls back
//!   to a valid vector; degenerate UV triangles fall back to a valid orthonormal frame.

pub mod atomic;
pub mod bake;
pub mod chain;
pub mod check;
pub mod counters;
pub mod error;
pub mod frame;
pub mod height;
pub mod lessons;
pub mod load;
pub mod math;
pub mod names;
pub mod prepare;
pub mod probe;
pub mod read;
pub mod render;
pub mod report;
pub mod scene;
pub mod shading;
pub mod state;
pub mod tangent;
pub mod texture;

pub use counters::WorkCounters;
pub use error::{LoadError, RenderError};
