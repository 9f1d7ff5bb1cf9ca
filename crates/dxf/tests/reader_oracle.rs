//! The reader against a frozen copy of itself: `tests/oracle/` holds the reader as it was
//! before its hot loop was rewritten for speed (commit 1bf6505: `reader.rs`, `tokens.rs`,
//! `decode.rs`, `extra.rs`, `blocks.rs` and the public types of `lib.rs`, unit tests left
//! out). Both read the same bytes; the drawings (or errors: kind, message, line) must be
//! identical, compared through `Debug` and, for the entities' numbers, bit by bit (`Debug`
//! prints every NaN alike).
//!
//! Inputs: every shared drawing (`../shared`, skipped with a message when absent), the
//! repository's own DXFs, and generated ones: small drawings with every section, table and
//! entity kind the reader knows, written with unusual group-code lines, line ends and code
//! pages, windows of pairs cut out of the real drawings, all mutated at the byte and line
//! level (truncated, bytes flipped/inserted/deleted, lines dropped/doubled/swapped).
//! `MILLPATH_ORACLE_CASES=N` sets the number of generated inputs (default 12,000, a few
//! seconds in a debug build); `MILLPATH_ORACLE_SEED` another seed.
//!
//! When the reader changes behaviour on purpose, change the copy in `tests/oracle/` with it.

#![allow(dead_code)]

#[path = "oracle/blocks.rs"]
mod blocks;
#[path = "oracle/decode.rs"]
mod decode;
#[path = "oracle/extra.rs"]
mod extra;
#[path = "oracle/reader.rs"]
mod reader;
#[path = "oracle/tokens.rs"]
mod tokens;
#[path = "oracle/types.rs"]
mod types;

use std::path::{Path, PathBuf};
use types::*;

/// The bits of every number of the model-space and block entities and `$TEXTSIZE`, for a
/// drawing of either type set (`$m`: the module that has `EntityKind`, `Text`, `MText`).
macro_rules! float_bits {
    ($d:expr, $m:path) => {{
        use $m as m;
        let d = $d;
        let mut v = vec![d.text_size.to_bits()];
        let entities = d
            .entities
            .iter()
            .chain(d.blocks.values().flat_map(|b| b.entities.iter()));
        for e in entities {
            let mut fs: Vec<f64> = vec![e.linetype_scale];
            fs.extend(e.extrusion);
            match &e.kind {
                m::EntityKind::Line { start, end } => {
                    fs.extend(start);
                    fs.extend(end);
                }
                m::EntityKind::Circle { center, radius } => {
                    fs.extend(center);
                    fs.push(*radius);
                }
                m::EntityKind::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                } => {
                    fs.extend(center);
                    fs.extend([*radius, *start_angle, *end_angle]);
                }
                m::EntityKind::Text(t) => {
                    fs.extend(t.first);
                    fs.extend(t.second.unwrap_or_default());
                    fs.extend([t.height, t.rotation]);
                }
                m::EntityKind::MText(t) => {
                    fs.extend(t.insert);
                    fs.extend(t.direction.unwrap_or_default());
                    fs.extend([t.height, t.rotation.unwrap_or_default()]);
                }
            }
            v.extend(fs.iter().map(|f| f.to_bits()));
        }
        v
    }};
}

/// `None` when both readers agree on `bytes`, else what differs.
fn differs(bytes: &[u8]) -> Option<String> {
    let old = reader::read_dxf(bytes);
    // a panic is a difference too (the input is then written out like any other)
    let new = match std::panic::catch_unwind(|| millpath_dxf::read_dxf(bytes)) {
        Ok(new) => new,
        Err(_) => return Some("the reader panicked".into()),
    };
    let (o, n) = (format!("{old:?}"), format!("{new:?}"));
    if o != n {
        let at = o
            .bytes()
            .zip(n.bytes())
            .position(|(a, b)| a != b)
            .unwrap_or(o.len().min(n.len()));
        let from = at.saturating_sub(120);
        let window = |s: &str| {
            let cut: String = s.get(from..).unwrap_or("").chars().take(240).collect();
            cut
        };
        return Some(format!("old: …{}\nnew: …{}", window(&o), window(&n)));
    }
    if let (Ok(o), Ok(n)) = (&old, &new) {
        if float_bits!(o, crate::types) != float_bits!(n, millpath_dxf) {
            return Some("same Debug, different float bits".into());
        }
    }
    if let (Err(o), Err(n)) = (&old, &new) {
        if o.to_string() != n.to_string() {
            return Some(format!("messages: {o} / {n}"));
        }
    }
    None
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn dxf_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf")))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// The shared drawings (empty with a message when ../shared is absent) and ours.
fn real_drawings() -> Vec<(String, Vec<u8>)> {
    let shared = repo().join("../shared");
    let mut files = Vec::new();
    if shared.join("conformance/fixtures").is_dir() {
        files.extend(dxf_files(&shared.join("conformance/fixtures")));
        files.extend(dxf_files(&shared.join("samples")));
    } else {
        eprintln!("../shared is absent: comparing our own and generated drawings only");
    }
    let listed = std::process::Command::new("git")
        .args(["ls-files", "*.dxf", "*.DXF"])
        .current_dir(repo())
        .output();
    match listed {
        Ok(out) if out.status.success() => {
            for l in String::from_utf8_lossy(&out.stdout).lines() {
                files.push(repo().join(l));
            }
        }
        _ => eprintln!("git ls-files failed: the repository's own DXFs are not compared"),
    }
    files
        .into_iter()
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            (p.display().to_string(), bytes)
        })
        .collect()
}

/// xorshift64*: deterministic, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn percent(&mut self, p: usize) -> bool {
        self.below(100) < p
    }
    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }
}

const NUMBERS: &[&[u8]] = &[
    b"0",
    b"1.5",
    b"-2.25",
    b"10",
    b"  3.125  ",
    b"0.0",
    b"-0",
    b"-0.0",
    b"1e3",
    b"1E-2",
    b"+3",
    b".5",
    b"5.",
    b"nan",
    b"NaN",
    b"-nan",
    b"inf",
    b"-infinity",
    b"\xc2\xa02.5\xc2\xa0",
    b"123456789012345",
    b"1234567890123456789",
    b"0.000000000000001",
    b"-3e9",
    b"4.9",
    b"2147483648",
    b"-2147483649",
    b"\t7\x0b",
    b"1e400",
    b"99999999999999999999.5",
    b"12.000000000000000001",
];

/// Values that are no number (an error where the reader reads one).
const NOT_NUMBERS: &[&[u8]] = &[
    b"abc", b"", b" ", b"1.\xfc5", b"0x10", b"1.2.3", b"--1", b"1,5",
];

fn number(rng: &mut Rng) -> &'static [u8] {
    if rng.percent(3) {
        rng.pick(NOT_NUMBERS)
    } else {
        rng.pick(NUMBERS)
    }
}

const NAMES: &[&[u8]] = &[
    b"0",
    b"P1",
    b"1234_1P",
    b"1234_1P~A",
    b"SCHL\xdcSSEL",
    b"Gr\xc3\xbcn",
    b"\xef\xbb\xbfP1",
    b"\xc2\xa0P1",
    b"P1 ",
    b" P1",
    b"\xcf1",
    b"a\\U+00E4b",
    b"\\U+00E4",
    b"x\\u+00e4yz",
    b"\\PB-0,1\\PS5",
    b"Continuous",
    b"DASHED",
    b"",
    b"\xe2\x80\x83",
    b"\xc3",
    b"\xe2\x82",
    b"Layer with spaces",
    b"\x00\x01",
    b"*Model_Space",
    b"*Paper_Space0",
    b"$MODEL_SPACE",
    b"BLK1",
];

const KINDS: &[&[u8]] = &[
    b"LINE",
    b"ARC",
    b"CIRCLE",
    b"TEXT",
    b"MTEXT",
    b"POINT",
    b"LWPOLYLINE",
    b"POLYLINE",
    b"VERTEX",
    b"SEQEND",
    b"INSERT",
    b"ATTRIB",
    b"ELLIPSE",
    b"SPLINE",
    b"HATCH",
    b" LINE",
    b"LINE ",
    b"line",
    b"\xc2\xa0LINE",
];

const ENTITY_CODES: &[i32] = &[
    1, 2, 3, 5, 6, 8, 10, 20, 30, 11, 21, 31, 40, 41, 42, 43, 44, 45, 48, 50, 51, 62, 66, 67, 70,
    71, 72, 73, 90, 100, 210, 220, 230, 330, 1001, 1000, 999, -1, 102,
];

/// A generated drawing as pairs (code, value).
fn synth_pairs(rng: &mut Rng) -> Vec<(i32, Vec<u8>)> {
    let mut v: Vec<(i32, Vec<u8>)> = Vec::new();
    let mut push = |code: i32, value: &[u8]| v.push((code, value.to_vec()));
    if rng.percent(85) {
        push(0, b"SECTION");
        push(2, b"HEADER");
        for _ in 0..rng.below(6) {
            match rng.below(6) {
                0 => {
                    push(9, b"$ACADVER");
                    let ver = rng.pick(&[
                        &b"AC1009"[..],
                        b"AC1015",
                        b"AC1018",
                        b"AC1021",
                        b"AC1024",
                        b"AC1032",
                        b"",
                        b"ACxyz",
                        b" AC1015 ",
                    ]);
                    push(1, ver);
                }
                1 => {
                    push(9, b"$DWGCODEPAGE");
                    let cp = rng.pick(&[
                        &b"ANSI_1252"[..],
                        b"ANSI_1251",
                        b"ansi_1253",
                        b"ANSI_932",
                        b"DOS850",
                        b"UTF-8",
                        b"nonsense",
                        b"",
                    ]);
                    push(3, cp);
                }
                2 => {
                    push(9, b"$TEXTSIZE");
                    push(40, number(rng));
                }
                3 => {
                    push(9, b"$INSUNITS");
                    push(70, number(rng));
                }
                4 => {
                    push(9, b"$EXTMIN");
                    push(10, number(rng));
                    push(20, number(rng));
                }
                _ => {
                    push(
                        9,
                        rng.pick(&[&b" $ACADVER"[..], b"$acadver", b"$TEXTSIZE "]),
                    );
                    push(rng.pick(&[1, 3, 40, 70]), number(rng));
                }
            }
        }
        push(0, b"ENDSEC");
    }
    if rng.percent(80) {
        push(0, b"SECTION");
        push(2, b"TABLES");
        for table in [&b"LTYPE"[..], b"LAYER", b"STYLE"] {
            if rng.percent(20) {
                continue;
            }
            push(0, b"TABLE");
            push(2, table);
            for _ in 0..rng.below(5) {
                push(0, if rng.percent(90) { table } else { b"LAYER" });
                for _ in 0..rng.below(5) {
                    match rng.below(5) {
                        0 | 1 => push(2, rng.pick(NAMES)),
                        2 => push(6, rng.pick(NAMES)),
                        3 => push(62, number(rng)),
                        _ => push(70, number(rng)),
                    }
                }
            }
            push(0, b"ENDTAB");
        }
        push(0, b"ENDSEC");
    }
    let entities = |v: &mut Vec<(i32, Vec<u8>)>, rng: &mut Rng, n: usize| {
        for _ in 0..n {
            v.push((0, rng.pick(KINDS).to_vec()));
            for _ in 0..rng.below(12) {
                let code = rng.pick(ENTITY_CODES);
                let value = match code {
                    1 | 2 | 3 | 5 | 6 | 8 | 100 | 330 | 1000 | 1001 | 102 => rng.pick(NAMES),
                    67 if rng.percent(50) => &b"1"[..],
                    _ => number(rng),
                };
                v.push((code, value.to_vec()));
            }
        }
    };
    if rng.percent(50) {
        v.push((0, b"SECTION".to_vec()));
        v.push((2, b"BLOCKS".to_vec()));
        for _ in 0..rng.below(3) {
            v.push((0, b"BLOCK".to_vec()));
            v.push((2, rng.pick(NAMES).to_vec()));
            v.push((10, number(rng).to_vec()));
            let n = rng.below(4);
            entities(&mut v, rng, n);
            v.push((0, b"ENDBLK".to_vec()));
        }
        v.push((0, b"ENDSEC".to_vec()));
    }
    if rng.percent(90) {
        v.push((0, b"SECTION".to_vec()));
        v.push((2, b"ENTITIES".to_vec()));
        let n = rng.below(10);
        entities(&mut v, rng, n);
        v.push((0, b"ENDSEC".to_vec()));
    }
    if rng.percent(40) {
        v.push((0, b"SECTION".to_vec()));
        v.push((2, b"OBJECTS".to_vec()));
        for _ in 0..rng.below(6) {
            let code = rng.pick(ENTITY_CODES);
            v.push((code, rng.pick(NAMES).to_vec()));
        }
        v.push((0, b"ENDSEC".to_vec()));
    }
    if rng.percent(90) {
        v.push((0, b"EOF".to_vec()));
    }
    v
}

/// A group code line: mostly as CAD programs write it, sometimes not.
fn code_line(rng: &mut Rng, code: i32) -> Vec<u8> {
    match rng.below(40) {
        // `+-1`, `00-1`: not group codes, one is enough
        1 | 2 | 7 if code < 0 && rng.percent(90) => format!("{code:>3}").into_bytes(),
        0 => format!("{code}").into_bytes(),
        1 => format!("{code:010}").into_bytes(),
        2 => format!("+{code}").into_bytes(),
        3 => format!("\t{code}").into_bytes(),
        4 => format!("{code:>3}  ").into_bytes(),
        5 => format!("\x0b{code}").into_bytes(),
        6 => format!("{code:>3}\t").into_bytes(),
        7 => format!("00{code}").into_bytes(),
        8 => format!("{code:>12}").into_bytes(),
        9 => format!("\u{a0}{code:>3}").into_bytes(),
        10 => format!("{code:>3} \x0c").into_bytes(),
        _ => format!("{code:>3}").into_bytes(),
    }
}

/// The pairs as a file, with the line ends of one CAD program or another, and an unusual
/// end of file now and then.
fn render(rng: &mut Rng, pairs: &[(i32, Vec<u8>)]) -> Vec<u8> {
    let mut out = render_pairs(rng, pairs);
    match rng.below(16) {
        0 => {
            out.pop();
        }
        1 => out.extend(b"\n\n"),
        2 => out.extend(b"\r\n \t\r\n"),
        3 => out.extend(b"\n\x0b\n"),
        _ => {}
    }
    out
}

fn render_pairs(rng: &mut Rng, pairs: &[(i32, Vec<u8>)]) -> Vec<u8> {
    let eol: &[u8] = rng.pick(&[&b"\n"[..], b"\r\n", b"\n", b"\r\n", b"\r\r\n"]);
    let mut out = Vec::new();
    for (code, value) in pairs {
        out.extend(code_line(rng, *code));
        out.extend(if rng.percent(2) { b"\r\n" } else { eol });
        out.extend(value);
        out.extend(if rng.percent(2) { b"\r\r\n" } else { eol });
    }
    out
}

/// A window of whole pairs (from a group-code line on) of a real drawing, in a section of
/// its own after a generated header.
fn window(rng: &mut Rng, real: &[(String, Vec<u8>)]) -> Vec<u8> {
    let (_, file) = &real[rng.below(real.len())];
    let starts: Vec<usize> = std::iter::once(0)
        .chain(
            file.iter()
                .enumerate()
                .filter(|(_, &b)| b == b'\n')
                .map(|(i, _)| i + 1),
        )
        .collect();
    let lines = starts.len();
    let first = rng.below(lines / 2) * 2;
    let last = (first + 2 * (1 + rng.below(200))).min((lines - 1) / 2 * 2);
    let body = &file[starts[first]..starts[last]];
    let mut header = synth_pairs(rng);
    header.truncate(header.iter().position(|p| p.1 == b"ENTITIES").unwrap_or(0));
    header.truncate(
        header
            .iter()
            .rposition(|p| p.1 == b"ENDSEC")
            .map_or(0, |i| i + 1),
    );
    let section = rng.pick(&[&b"ENTITIES"[..], b"BLOCKS", b"TABLES", b"OBJECTS"]);
    header.push((0, b"SECTION".to_vec()));
    header.push((2, section.to_vec()));
    let mut out = render_pairs(rng, &header);
    out.extend(body);
    out.extend(b"  0\nENDSEC\n  0\nEOF\n");
    out
}

const BYTES: &[u8] = b"\r\n \t\x0b\x0c0123456789-+.\\\xfc\xc3\xa0\xef\x00AZ";

/// Byte and line level damage, `n` times.
fn mutate(rng: &mut Rng, mut b: Vec<u8>, n: usize) -> Vec<u8> {
    for _ in 0..n {
        let at = rng.below(b.len() + 1);
        match rng.below(9) {
            0 => b.truncate(at),
            1 if at < b.len() => b[at] ^= 1 << rng.below(8),
            2 => b.insert(at, rng.pick(BYTES)),
            3 if at < b.len() => {
                b.remove(at);
            }
            4 if at < b.len() => b[at] = rng.pick(BYTES),
            // a whole line dropped, doubled, or swapped with the next
            5..=7 => {
                let start = b[..at]
                    .iter()
                    .rposition(|&c| c == b'\n')
                    .map_or(0, |i| i + 1);
                let Some(len) = b[start..].iter().position(|&c| c == b'\n') else {
                    continue;
                };
                let line = b[start..start + len + 1].to_vec();
                match rng.below(3) {
                    0 => {
                        b.drain(start..start + len + 1);
                    }
                    1 => {
                        b.splice(start..start, line);
                    }
                    _ => {
                        let next = start + len + 1;
                        if let Some(l2) = b[next..].iter().position(|&c| c == b'\n') {
                            let second = b[next..next + l2 + 1].to_vec();
                            b.splice(start..next + l2 + 1, second.into_iter().chain(line));
                        }
                    }
                }
            }
            _ => {
                // a random code line in place of a value or code
                let start = b[..at]
                    .iter()
                    .rposition(|&c| c == b'\n')
                    .map_or(0, |i| i + 1);
                let code = rng.pick(ENTITY_CODES);
                let line = code_line(rng, code);
                b.splice(start..start, line.into_iter().chain(*b"\n"));
            }
        }
    }
    b
}

fn cases() -> usize {
    std::env::var("MILLPATH_ORACLE_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12_000)
}

fn seed() -> u64 {
    std::env::var("MILLPATH_ORACLE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x6d69_6c6c_7061_7468)
}

fn report(what: &str, bytes: &[u8], diff: String) -> ! {
    let path = std::env::temp_dir().join("millpath-oracle-failure.dxf");
    let _ = std::fs::write(&path, bytes);
    panic!(
        "{what}: the readers differ (input written to {}):\n{diff}",
        path.display()
    );
}

#[test]
fn real_drawings_read_as_before() {
    let real = real_drawings();
    for (name, bytes) in &real {
        if let Some(d) = differs(bytes) {
            report(name, bytes, d);
        }
    }
    eprintln!("{} real drawings compared", real.len());
}

/// Inputs that once told the two apart, and the edges of the line-end masks.
#[test]
fn edge_cases_read_as_before() {
    let mut cases: Vec<Vec<u8>> = vec![
        // blank lines at the end of an open section: the pairs are read again after it
        b"  0\nSECTION\n  2\nENTITIES\n\n \n\n".to_vec(),
        b"  0\r\nSECTION\r\n  2\r\nHEADER\r\n \r\n\r\n".to_vec(),
        b"  0\nEOF\n\n\n".to_vec(),
        b"".to_vec(),
        b"\n".to_vec(),
        b"  0".to_vec(),
        b"  0\n".to_vec(),
        b"  0\nSECTION".to_vec(),
    ];
    // a pair around every block boundary, lines longer than a block
    let pair = b"  0\nLINE\n  8\nP1\n 10\n1.5\n";
    for pad in 0..70 {
        let mut v = b"  0\nSECTION\n  2\nENTITIES\n999\n".to_vec();
        v.extend(std::iter::repeat_n(b'x', pad));
        v.push(b'\n');
        for _ in 0..6 {
            v.extend(pair);
        }
        v.extend(b"  0\nENDSEC\n  0\nEOF");
        cases.push(v.clone());
        v.extend(b"\n\n  \n");
        cases.push(v);
    }
    for bytes in &cases {
        if let Some(d) = differs(bytes) {
            report(&format!("{:?}", String::from_utf8_lossy(bytes)), bytes, d);
        }
    }
}

#[test]
fn generated_and_mutated_drawings_read_as_before() {
    let real = real_drawings();
    let mut rng = Rng(seed() | 1);
    let n = cases();
    // what the inputs came to: drawings, or errors by kind
    let mut outcomes = std::collections::BTreeMap::<String, usize>::new();
    for i in 0..n {
        let base = match i % 4 {
            0 | 1 => {
                let pairs = synth_pairs(&mut rng);
                render(&mut rng, &pairs)
            }
            2 if !real.is_empty() => window(&mut rng, &real),
            _ => {
                let pairs = synth_pairs(&mut rng);
                render(&mut rng, &pairs)
            }
        };
        let damage = match rng.below(8) {
            0..=2 => 0,
            3..=5 => 1,
            _ => 1 + rng.below(4),
        };
        let mut bytes = mutate(&mut rng, base, damage);
        if rng.percent(1) {
            bytes.splice(0..0, b"AutoCAD Binary DXF\r\n\x1a\0".iter().copied());
        }
        if let Some(d) = differs(&bytes) {
            report(&format!("generated input {i}"), &bytes, d);
        }
        let outcome = match millpath_dxf::read_dxf(&bytes) {
            Ok(_) => "drawing".to_string(),
            Err(e) => format!("{:?}", e.kind)
                .chars()
                .take_while(|c| c.is_alphanumeric())
                .collect(),
        };
        *outcomes.entry(outcome).or_default() += 1;
    }
    eprintln!("{n} generated inputs compared: {outcomes:?}");
}

/// Whole real drawings, damaged: slow in a debug build, so a few by default.
#[test]
fn mutated_real_drawings_read_as_before() {
    let real = real_drawings();
    if real.is_empty() {
        return;
    }
    let mut rng = Rng(seed().rotate_left(17) | 1);
    let n = (cases() / 200).max(8);
    for i in 0..n {
        let (name, file) = &real[rng.below(real.len())];
        let damage = 1 + rng.below(3);
        let bytes = mutate(&mut rng, file.clone(), damage);
        if let Some(d) = differs(&bytes) {
            report(&format!("{name}, mutation {i}"), &bytes, d);
        }
    }
    eprintln!("{n} mutated real drawings compared");
}
