//! Throughput of the bake's parts on a 4096² 8-bit height map (the size the nvcompress
//! comparison uses): the per-texel reference kernel (how the report timed kernels before),
//! the row kernels to float normals and to 8-bit RGB, and the Frankot–Chellappa solve at
//! 1024². Run: `cargo bench --no-default-features --bench bake`. Throughput is texels per
//! second; compare ratios within one run (the machine is shared).

use bumpview::height::derivative::Derivative;
use bumpview::height::integrate::{Slopes, integrate};
use bumpview::height::rows::{Channels, HeightGrid, MapFormat, Samples, encode_normal_map, normals};
use bumpview::height::{Border, HeightField, Kernel};
use bumpview::names::Named;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// A `side²` 8-bit height map of overlapping sine bumps (no constant runs, like real relief).
fn height_bytes(side: usize) -> Vec<u8> {
    (0..side * side)
        .map(|i| {
            let (x, y) = ((i % side) as f32, (i / side) as f32);
            (127.5 + 60.0 * (x * 0.031).sin() * (y * 0.017).cos() + 60.0 * (x * 0.11 + y * 0.07).sin()) as u8
        })
        .collect()
}

fn kernels(c: &mut Criterion) {
    let side = 4096;
    let bytes = height_bytes(side);
    let grid = HeightGrid { width: side, height: side, samples: Samples::U8(&bytes), slope_scale: 40.96, depth: false };
    let mut group = c.benchmark_group("kernel 4096²");
    group.sample_size(10);
    group.throughput(Throughput::Elements((side * side) as u64));
    let field = HeightField {
        width: side as u32,
        height: side as u32,
        samples: bytes.iter().map(|&b| b as f32 / 255.0).collect(),
        range_m: 0.01,
        texel_size_m: 1.0 / side as f32,
    };
    group.bench_function("central, per texel (reference)", |b| {
        b.iter(|| {
            let (w, h) = (side as i64, side as i64);
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| field.normal(Kernel::CentralDifference, Border::Wrap, x, y))
                .collect::<Vec<_>>()
        })
    });
    for kernel in [Kernel::CentralDifference, Kernel::Sobel3, Kernel::Sobel5] {
        group.bench_function(format!("{}, rows → f32 normals", kernel.name()), |b| {
            b.iter(|| normals(&grid, kernel, Border::Wrap))
        });
    }
    let rgb8 = MapFormat { sixteen_bit: false, channels: Channels::Rgb, green_down: false };
    group.bench_function("central, rows → RGB8", |b| {
        b.iter(|| encode_normal_map(&grid, Kernel::CentralDifference, Border::Wrap, rgb8))
    });
    group.finish();
}

fn frankot_chellappa(c: &mut Criterion) {
    let side = 1024;
    let bytes = height_bytes(side);
    let field = HeightField {
        width: side as u32,
        height: side as u32,
        samples: bytes.iter().map(|&b| b as f32 / 255.0).collect(),
        range_m: 1.0,
        texel_size_m: 1.0,
    };
    let (mut dx, mut dy_up) = (vec![], vec![]);
    for y in 0..side as i64 {
        for x in 0..side as i64 {
            let (a, b) = field.slope(Kernel::CentralDifference, Border::Wrap, x, y);
            dx.push(a);
            dy_up.push(b);
        }
    }
    let slopes = Slopes { width: side, height: side, dx, dy_up };
    let mut group = c.benchmark_group("Frankot–Chellappa 1024²");
    group.sample_size(10);
    group.throughput(Throughput::Elements((side * side) as u64));
    group.bench_function("wrap", |b| {
        b.iter(|| integrate(&slopes, Derivative::Kernel(Kernel::CentralDifference), Border::Wrap))
    });
    group.finish();
}

criterion_group!(benches, kernels, frankot_chellappa);
criterion_main!(benches);
