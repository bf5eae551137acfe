//! Criterion benches of the lab's everyday families (the demo scenes, the
//! random families and the tilings of the `--quick` corpus): every method,
//! every peer and the bounds, on the same passes the lab times.
//! `cargo bench -p lab`; one benchmark is `FAMILY/CONTENDER`. The lab itself
//! is built for the machine's CPU; for figures comparable with it, build
//! the same way (on x86-64): `RUSTFLAGS='-C target-cpu=native -C
//! llvm-args=-x86-branches-within-32B-boundaries' cargo bench -p lab
//! --target-dir target/native`. Criterion draws no plots here: they need a
//! system font the machine may not have.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use lab::corpus::{self, Budget, Group};
use lab::measure;
use lab::Bound;
use lab::Contender;
use raster::Polygon;

fn families(c: &mut Criterion) {
    let contenders = Contender::all();
    let everyday =
        corpus::build(Budget::QUICK).expect("the corpus builds").into_iter().filter(|f| f.group != Group::Stress);
    for family in everyday {
        // Judging finds the polygons each contender fails on, which the
        // lab leaves out of its timing too, and the exact spans.
        let judged = measure::quietly(|| measure::judge(&family, &contenders, &|| {}));
        let mut group = c.benchmark_group(family.name);
        for (i, contender) in contenders.iter().enumerate() {
            if judged.tallies[i].is_none() {
                continue;
            }
            let polygons: Vec<&Polygon> = judged.timed[i].iter().map(|&p| &family.polygons[p]).collect();
            group.throughput(Throughput::Elements(polygons.len() as u64));
            let mut pass = contender.pass(&polygons);
            group.bench_function(contender.name(), |b| b.iter(&mut pass));
        }
        let exact: Vec<&[lab::Span]> = judged.exact.iter().map(Vec::as_slice).collect();
        group.throughput(Throughput::Elements(exact.len() as u64));
        for bound in Bound::ALL {
            let mut pass = bound.pass(&exact);
            group.bench_function(bound.name(), |b| b.iter(&mut pass));
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().without_plots().sample_size(20).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    targets = families
}
criterion_main!(benches);
