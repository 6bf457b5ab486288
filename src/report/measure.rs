//! Angular errors and run times of the tangent methods and height kernels on the reference
//! surfaces, as report rows.

use glam::{DVec3, Vec3};

use super::surfaces::{Reference, Region, SineBumps};
use super::timing::{Repeats, median_seconds};
use crate::height::{Border, HeightField, Kernel};
use crate::names::Named;
use crate::scene::Mesh;
use crate::tangent::{AngleStats, TangentMethod, bitangent, tangents};

/// What a row measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Study {
    /// Tangent frames on meshes; throughput in triangles per second.
    Tangents,
    /// Height→normal kernels on height fields; throughput in texels per second.
    Kernels,
}

impl Study {
    /// What the throughput counts.
    pub fn unit(self) -> &'static str {
        match self {
            Study::Tangents => "triangles",
            Study::Kernels => "texels",
        }
    }
}

/// The direction whose angular error a statistic describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Vector {
    /// The tangent `T`.
    Tangent,
    /// The bitangent `B = w · cross(N, T)`, so a wrong handedness shows as 180°.
    Bitangent,
    /// The tangent-space normal of a height field.
    Normal,
}

/// One line of the report: a method on a surface at a resolution, restricted to a region.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub study: Study,
    /// [`TangentMethod::name`] or [`Kernel::name`].
    pub method: &'static str,
    /// `sphere`, `torus`, `plane`, `plane 8-bit`, `plane 16-bit` or `plane clamp`.
    pub surface: String,
    /// Segments around (sphere, torus) or texels per period (plane): the number that doubles.
    pub resolution: u32,
    /// The resolution as printed, e.g. `256x128` or `32 texels/period`.
    pub resolution_label: String,
    pub region: Region,
    /// Angular error statistics in degrees, per measured vector.
    pub errors: Vec<(Vector, AngleStats)>,
    /// Median wall-clock seconds of one run over the whole surface.
    pub seconds: f64,
    /// Triangles or texels one run handles.
    pub items: usize,
}

impl Row {
    pub fn error(&self, vector: Vector) -> Option<AngleStats> {
        self.errors.iter().find(|(v, _)| *v == vector).map(|&(_, stats)| stats)
    }

    /// Items per second.
    pub fn throughput(&self) -> f64 {
        self.items as f64 / self.seconds.max(1e-12)
    }
}

/// The angle between two directions in degrees, as `atan2(|a × b|, a · b)` in f64: exact
/// down to rounding even for tiny angles, unlike `acos` of an f32 dot product, which cannot
/// tell angles below about 0.02° from zero.
pub fn angle_degrees(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

/// Mean T and B errors (degrees) of `method` over `region`, measured the naive way: `acos`
/// of an f32 dot product, which rounds angles below about 0.01° to 0 or 0.0198°. Shown beside
/// the exact measurement to explain a published figure of that size.
pub fn acos_f32_means(method: TangentMethod, reference: &Reference, region: Region) -> Option<(f32, f32)> {
    let mesh = &reference.mesh;
    let (frames, exact) = (tangents(mesh, method)?, mesh.analytic_tangents.as_ref()?);
    let acos_f32 = |a: Vec3, b: Vec3| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees();
    let mut sums = [0.0f64; 2];
    let mut count = 0usize;
    for (((&n, f), r), _) in
        mesh.normals.iter().zip(&frames).zip(exact).zip(&reference.regions).filter(|&(_, &g)| g == region)
    {
        sums[0] += acos_f32(f.truncate(), r.truncate()) as f64;
        sums[1] += acos_f32(bitangent(n, *f), bitangent(n, *r)) as f64;
        count += 1;
    }
    (count > 0).then(|| ((sums[0] / count as f64) as f32, (sums[1] / count as f64) as f32))
}

/// A surface at one resolution, as it appears in the rows.
#[derive(Debug, Clone, Copy)]
pub struct Sample<'a> {
    pub surface: &'a str,
    pub resolution: u32,
    pub resolution_label: &'a str,
}

/// Statistics of `angles` (degrees) over `All` and over each region that occurs, in region order.
fn by_region(regions: &[Region], angles: &[Vec<f64>]) -> Vec<(Region, Vec<AngleStats>)> {
    let mut present: Vec<Region> = regions.to_vec();
    present.sort();
    present.dedup();
    present.retain(|&r| r != Region::All);
    std::iter::once(Region::All)
        .chain(present)
        .map(|region| {
            let stats = angles
                .iter()
                .map(|values| {
                    let selected = values.iter().zip(regions).filter(|&(_, &r)| region == Region::All || r == region);
                    AngleStats::of(selected.map(|(&a, _)| a as f32))
                })
                .collect();
            (region, stats)
        })
        .collect()
}

/// Frames of `method` on `reference` against its analytic frame, T and B per region, timed.
/// Per-face frames are measured on the unwelded mesh, where they are exact per triangle.
pub fn tangent_rows(method: TangentMethod, reference: &Reference, sample: Sample, repeats: Repeats) -> Vec<Row> {
    let unwelded;
    let (mesh, regions): (&Mesh, Vec<Region>) = if method == TangentMethod::PerFace {
        unwelded = reference.mesh.unwelded();
        (&unwelded, reference.mesh.indices.iter().map(|&i| reference.regions[i as usize]).collect())
    } else {
        (&reference.mesh, reference.regions.clone())
    };
    let (seconds, frames) = median_seconds(repeats, || tangents(mesh, method));
    let frames = frames.expect("reference meshes carry analytic frames");
    let exact = mesh.analytic_tangents.as_ref().expect("reference meshes carry analytic frames");
    let (mut t_angles, mut b_angles) = (vec![], vec![]);
    for ((&n, &f), &e) in mesh.normals.iter().zip(&frames).zip(exact) {
        let (t, te) = (f.truncate().as_dvec3(), e.truncate().as_dvec3());
        t_angles.push(angle_degrees(t, te));
        b_angles.push(angle_degrees(bitangent(n, f).as_dvec3(), bitangent(n, e).as_dvec3()));
    }
    by_region(&regions, &[t_angles, b_angles])
        .into_iter()
        .map(|(region, stats)| Row {
            study: Study::Tangents,
            method: method.name(),
            surface: sample.surface.to_owned(),
            resolution: sample.resolution,
            resolution_label: sample.resolution_label.to_owned(),
            region,
            errors: vec![(Vector::Tangent, stats[0]), (Vector::Bitangent, stats[1])],
            seconds,
            items: mesh.indices.len() / 3,
        })
        .collect()
}

/// Every texel's normal by `kernel`, rows top to bottom.
pub fn kernel_normals(field: &HeightField, kernel: Kernel, border: Border) -> Vec<Vec3> {
    let (width, height) = (field.width as i64, field.height as i64);
    (0..height).flat_map(|y| (0..width).map(move |x| field.normal(kernel, border, x, y))).collect()
}

/// Normals of `kernel` on `field` (made from `bumps`) against the exact normals, timed; with a
/// clamped border also split into interior and border texels.
pub fn kernel_rows(
    kernel: Kernel,
    bumps: &SineBumps,
    field: &HeightField,
    border: Border,
    sample: Sample,
    repeats: Repeats,
) -> Vec<Row> {
    let (seconds, normals) = median_seconds(repeats, || kernel_normals(field, kernel, border));
    let side = bumps.side();
    let texels = || (0..side).flat_map(|j| (0..side).map(move |i| (i, j)));
    let angles: Vec<f64> =
        texels().zip(&normals).map(|((i, j), n)| angle_degrees(n.as_dvec3(), bumps.normal(i, j))).collect();
    let regions: Vec<Region> = match border {
        Border::Wrap => vec![Region::All; angles.len()],
        Border::Clamp => texels().map(|(i, j)| bumps.region(i, j)).collect(),
    };
    by_region(&regions, &[angles])
        .into_iter()
        .map(|(region, stats)| Row {
            study: Study::Kernels,
            method: kernel.name(),
            surface: sample.surface.to_owned(),
            resolution: sample.resolution,
            resolution_label: sample.resolution_label.to_owned(),
            region,
            errors: vec![(Vector::Normal, stats[0])],
            seconds,
            items: normals.len(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_angles_are_resolved() {
        let a = DVec3::X;
        let b = DVec3::new(1.0, 1e-7, 0.0);
        assert!((angle_degrees(a, b) - 1e-7f64.to_degrees()).abs() < 1e-12);
        assert!((angle_degrees(a, -a) - 180.0).abs() < 1e-9);
    }
}
