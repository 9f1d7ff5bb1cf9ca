//! Reading and compiling drawings: our example, and every drawing of ../shared when present.

use criterion::{criterion_group, criterion_main, Criterion};
use millpath_core::{compile_file, OsFileSystem, Session, Settings};
use std::path::{Path, PathBuf};

fn drawings() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut v = vec![root.join("examples/plate/1234.1P.dxf")];
    let fixtures = root.join("../shared/conformance/fixtures");
    if let Ok(rd) = std::fs::read_dir(&fixtures) {
        let mut more: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
        more.sort();
        v.extend(more);
    } else {
        eprintln!("../shared is absent: benchmarking the example only");
    }
    v
}

fn bench(c: &mut Criterion) {
    let files = drawings();
    let bytes: Vec<Vec<u8>> = files.iter().map(|f| std::fs::read(f).unwrap()).collect();
    c.bench_function(&format!("read {} drawings", files.len()), |b| {
        b.iter(|| {
            for data in &bytes {
                let _ = millpath_dxf::read_dxf(data);
            }
        })
    });
    c.bench_function(&format!("check-compile {} drawings", files.len()), |b| {
        b.iter(|| {
            for f in &files {
                let fs = OsFileSystem;
                let settings = Settings {
                    check: true,
                    ..Settings::default()
                };
                let mut s = Session::new(settings, &fs).unwrap();
                compile_file(&mut s, f, "bench");
            }
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
