//! Property tests with a small deterministic generator: the parser never panics on random
//! or mutated input, and formatting is idempotent and preserves the tree.

use millpath_syntax::parser::parse_without_shortcut;
use millpath_syntax::{format, parse, Item, PathItem};

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[(self.next() % items.len() as u64) as usize]
    }
    fn num(&mut self) -> String {
        let v = (self.next() % 20000) as f64 / 7.0 - 1000.0;
        format!("{v}")
    }
}

fn random_file(r: &mut Rng) -> String {
    let mut s = String::new();
    for p in 0..(1 + r.next() % 3) {
        if r.next().is_multiple_of(3) {
            s.push_str("# a comment ü\n");
        }
        s.push_str(&format!("path {}.{}P {{\n", 1000 + p, r.next() % 9));
        for _ in 0..(r.next() % 12) {
            let kind = r.pick(&[
                "start",
                "end",
                "turn",
                "probe",
                "noprobe",
                "mill",
                "mark",
                "bars",
                "sub",
                "sweep",
                "move",
                "skip",
                "drill",
                "helix",
                "mark helix",
                "bars helix",
                "raw CENTER",
            ]);
            let geom = match kind {
                "start" | "end" | "turn" | "probe" | "noprobe" => {
                    format!("({}, {})", r.num(), r.num())
                }
                "drill" | "helix" | "mark helix" | "bars helix" => format!(
                    "({},{}) d{}",
                    r.num(),
                    r.num(),
                    (r.next() % 90) as f64 / 7.0 + 0.1
                ),
                _ if r.next().is_multiple_of(3) => format!(
                    "arc ({}, {}) r {} from {} to {}",
                    r.num(),
                    r.num(),
                    (r.next() % 90 + 1) as f64 / 3.0,
                    r.next() % 360,
                    r.next() % 360
                ),
                _ => format!("({}, {})->({},{})", r.num(), r.num(), r.num(), r.num()),
            };
            let params = (0..(r.next() % 5))
                .map(|_| {
                    r.pick(&[
                        "T2", "O2", "B-0,3", ">8998.2P", ":B1", "B=B", "\"#5\"", "Q:x#y", "N1",
                        "I1,2",
                    ])
                })
                .collect::<Vec<_>>()
                .join("  ");
            let comment = if r.next().is_multiple_of(4) {
                "   # note"
            } else {
                ""
            };
            s.push_str(&format!(
                "{}{kind} {geom}  {params}{comment}\n",
                " ".repeat((r.next() % 5) as usize)
            ));
            if r.next().is_multiple_of(5) {
                s.push('\n');
            }
        }
        s.push_str("}\n");
    }
    s
}

fn mutate(r: &mut Rng, s: &str) -> String {
    let mut chars: Vec<char> = s.chars().collect();
    for _ in 0..(1 + r.next() % 4) {
        if chars.is_empty() {
            break;
        }
        let i = (r.next() as usize) % chars.len();
        match r.next() % 3 {
            0 => {
                chars.remove(i);
            }
            1 => chars.insert(
                i,
                r.pick(&[
                    "(", ")", ",", "{", "}", "#", "\"", "\n", "-", ">", "x", "é", "\\",
                ])
                .chars()
                .next()
                .unwrap(),
            ),
            _ => chars.truncate(i),
        }
    }
    chars.into_iter().collect()
}

fn elements(f: &millpath_syntax::File) -> Vec<(String, String, Vec<String>)> {
    f.items
        .iter()
        .filter_map(|i| match i {
            Item::Path(p) => Some(p),
            _ => None,
        })
        .flat_map(|p| {
            p.items.iter().filter_map(|i| match i {
                PathItem::Element(e) => Some((
                    format!("{:?}", e.kind.value),
                    format!("{:?}", e.geometry.value),
                    e.params.iter().map(|p| p.value.clone()).collect(),
                )),
                _ => None,
            })
        })
        .collect()
}

#[test]
fn formatting_is_idempotent_and_keeps_the_tree() {
    let mut r = Rng(0x2545F4914F6CDD1D);
    for _ in 0..500 {
        let src = random_file(&mut r);
        let (tree, errors) = parse(&src);
        assert!(errors.is_empty(), "{errors:?}\n{src}");
        let once = format(&tree, &src);
        let (tree2, errors2) = parse(&once);
        assert!(errors2.is_empty(), "{errors2:?}\n{once}");
        assert_eq!(elements(&tree), elements(&tree2), "{src}\n---\n{once}");
        assert_eq!(format(&tree2, &once), once);
    }
}

#[test]
fn random_and_mutated_input_never_panics() {
    let mut r = Rng(0x9E3779B97F4A7C15);
    for _ in 0..2000 {
        let base = random_file(&mut r);
        let src = mutate(&mut r, &base);
        let (tree, errors) = parse(&src);
        for e in &errors {
            assert!(
                e.span.start <= e.span.end && e.span.end <= src.len(),
                "{e:?}"
            );
        }
        let _ = format(&tree, &src);
    }
    for _ in 0..500 {
        let bytes: Vec<u8> = (0..(r.next() % 200))
            .map(|_| (r.next() % 128) as u8)
            .collect();
        let src = String::from_utf8_lossy(&bytes);
        let _ = parse(&src);
    }
}

/// Inserts whole words where the short-cut for plain segment lines must hand over to the
/// full grammar (`ccw around`, a second geometry, a missing arrow).
fn mutate_words(r: &mut Rng, s: &str) -> String {
    let mut lines: Vec<String> = s.lines().map(str::to_string).collect();
    for _ in 0..(1 + r.next() % 3) {
        if lines.is_empty() {
            break;
        }
        let i = (r.next() as usize) % lines.len();
        let word = r.pick(&[
            " ccw around (1, 2)",
            " cw around (3,4)",
            " cw",
            " ccw",
            " (1, 2)",
            " -> (5, 6)",
            " mill",
            " x1",
            "\r",
            " # c",
            " \"q\"",
            " {",
            " }",
        ]);
        let line = &mut lines[i];
        let at = line
            .char_indices()
            .map(|(k, _)| k)
            .nth((r.next() as usize) % line.chars().count().max(1))
            .unwrap_or(line.len());
        line.insert_str(at, word);
    }
    let mut out = lines.join("\n");
    if r.next().is_multiple_of(2) {
        out.push('\n');
    }
    out
}

#[test]
fn the_shortcut_for_plain_segments_gives_the_full_grammars_tree_and_errors() {
    let mut r = Rng(0xD1B54A32D192ED03);
    let check = |src: &str| {
        let fast = parse(src);
        let full = parse_without_shortcut(src);
        assert_eq!(fast, full, "{src:?}");
    };
    for _ in 0..1500 {
        let base = random_file(&mut r);
        check(&base);
        check(&mutate(&mut r, &base));
        check(&mutate_words(&mut r, &base));
    }
    for src in [
        "path 1P {\n  mill (0, 0) -> (1, 1)",
        "path 1P {\n  mill (0, 0) -> (1, 1)  T2 # c",
        "path 1P {\n  mill (0, 0) -> (1, 1)\r\n}\r\n",
        "path 1P {\n  mill (0, 0) -> (1, 1) ccw around (0, 1)\n}\n",
        "path 1P {\n  mill (0, 0) -> (1, 1) cw\n}\n",
        "path 1P {\n  mill (0, 0) -> (1, 1) (2, 2)\n}\n",
        "path 1P {\n  mill (0, 0) -> (1, x)\n}\n",
        "path 1P {\n  mill (0, 0) -> (1, 1e999)\n}\n",
        "path 1P {\n  mill (0, 0) -> (1, 1) }\n",
        "path 1P {\n  mill (0,0)->(1,1)T2\n}\n",
        "path 1P {\n  mill\n}\n",
        "path 1P {\n  mill (0, 0)\n}\n",
        "path 1P {\n  mil (0, 0) -> (1, 1)\n}\n",
    ] {
        check(src);
    }
    // the repository's drawings
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut dirs = vec![root.join("examples"), root.join("tests"), root.join("docs")];
    let mut seen = 0;
    while let Some(d) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "mpath") {
                if let Ok(src) = std::fs::read_to_string(&p) {
                    check(&src);
                    seen += 1;
                }
            }
        }
    }
    assert!(seen > 0, "no .mpath file found under {}", root.display());
}
