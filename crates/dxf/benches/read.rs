//! The DXF reader over our example and every drawing of ../shared (conformance fixtures and
//! samples) when present.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::path::{Path, PathBuf};

fn dxf_files_in(dir: &Path) -> Option<Vec<PathBuf>> {
    let rd = std::fs::read_dir(dir).ok()?;
    let mut v: Vec<PathBuf> = rd
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf")))
        .collect();
    v.sort();
    Some(v)
}

fn drawings() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut v = vec![root.join("examples/plate/1234.1P.dxf")];
    let shared = root.join("../shared");
    for sub in ["conformance/fixtures", "samples"] {
        match dxf_files_in(&shared.join(sub)) {
            Some(more) => v.extend(more),
            None => eprintln!("../shared/{sub} is absent: not benchmarked"),
        }
    }
    v
}

fn bench(c: &mut Criterion) {
    let files = drawings();
    let bytes: Vec<Vec<u8>> = files.iter().map(|f| std::fs::read(f).unwrap()).collect();
    let total: usize = bytes.iter().map(Vec::len).sum();
    let mut g = c.benchmark_group("read_dxf");
    g.throughput(Throughput::Bytes(total as u64));
    g.bench_function(format!("{} drawings", files.len()), |b| {
        b.iter(|| {
            for data in &bytes {
                let _ = std::hint::black_box(millpath_dxf::read_dxf(std::hint::black_box(data)));
            }
        })
    });
    g.finish();
    // The largest drawing alone, for a per-file figure.
    if let Some((i, _)) = bytes.iter().enumerate().max_by_key(|(_, b)| b.len()) {
        let name = files[i].file_name().unwrap().to_string_lossy().into_owned();
        let mut g = c.benchmark_group("read_dxf_largest");
        g.throughput(Throughput::Bytes(bytes[i].len() as u64));
        g.bench_function(name, |b| {
            b.iter(|| std::hint::black_box(millpath_dxf::read_dxf(std::hint::black_box(&bytes[i]))))
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
