//! Tangent generation on the built-in torus at 1M triangles (1000 × 500 quads): bevy_mikktspace
//! against meshoptimizer's MikkTSpace-compatible generator and "auto" (what a mesh without
//! tangents gets, [`resolve`] with no choice). Run: `cargo bench --no-default-features --bench
//! tangents`; compare the ratio within one run (the machine is shared).

use bumpview::names::Named;
use bumpview::scene::builtin::torus_mesh;
use bumpview::tangent::{TangentMethod, resolve, tangents};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

fn million_triangles(c: &mut Criterion) {
    let mut mesh = torus_mesh(1000, 500);
    mesh.analytic_tangents = None;
    let triangles = mesh.indices.len() / 3;
    assert_eq!(triangles, 1_000_000);
    let mut group = c.benchmark_group("tangents, torus 1M triangles");
    group.sample_size(10);
    group.throughput(Throughput::Elements(triangles as u64));
    for method in [TangentMethod::MikkTSpace, TangentMethod::Meshopt] {
        group.bench_function(method.name(), |b| b.iter(|| tangents(&mesh, method)));
    }
    group.bench_function("auto", |b| b.iter(|| resolve(&mesh, None)));
    group.finish();
}

criterion_group!(benches, million_triangles);
criterion_main!(benches);
