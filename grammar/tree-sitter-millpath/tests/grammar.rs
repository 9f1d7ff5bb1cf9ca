//! The tree-sitter grammar (compiled from the committed parser.c, no CLI needed) and the
//! TextMate grammar, checked against their corpus and against the real parser.

use millpath_syntax::ast::{Kind, Style};
use std::path::{Path, PathBuf};
use tree_sitter::{Node, Parser};

fn parser() -> Parser {
    let mut p = Parser::new();
    p.set_language(&tree_sitter_millpath::LANGUAGE.into())
        .expect("language version");
    p
}

fn normalise(sexp: &str) -> String {
    let no_fields = regex::Regex::new(r"\w+: ").unwrap().replace_all(sexp, "");
    no_fields
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace("( ", "(")
        .replace(" )", ")")
}

#[test]
fn corpus() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("test/corpus");
    let mut count = 0;
    let header = regex::Regex::new(r"(?m)^=+\n(.*)\n=+\n").unwrap();
    for f in std::fs::read_dir(&dir).unwrap() {
        let text = std::fs::read_to_string(f.unwrap().path()).unwrap();
        let starts: Vec<(usize, usize, String)> = header
            .captures_iter(&text)
            .map(|c| {
                (
                    c.get(0).unwrap().start(),
                    c.get(0).unwrap().end(),
                    c[1].to_string(),
                )
            })
            .collect();
        for (i, (_, body_start, name)) in starts.iter().enumerate() {
            let end = starts.get(i + 1).map_or(text.len(), |s| s.0);
            let body = &text[*body_start..end];
            let (input, expected) = body.split_once("\n---\n").expect("--- separator");
            let input = input.trim_start_matches('\n');
            let input = format!("{}\n", input.trim_end_matches('\n'));
            let tree = parser().parse(&input, None).unwrap();
            assert_eq!(
                normalise(&tree.root_node().to_sexp()),
                normalise(expected),
                "corpus case {name}"
            );
            count += 1;
        }
    }
    assert!(count >= 3);
}

fn mpath_files() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut out = Vec::new();
    for d in std::fs::read_dir(&root).unwrap() {
        let d = d.unwrap().path();
        if d.is_dir() {
            for f in std::fs::read_dir(&d).unwrap() {
                let f = f.unwrap().path();
                if f.extension().is_some_and(|e| e == "mpath") {
                    out.push(f);
                }
            }
        }
    }
    out.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("test/all-kinds.mpath"));
    out.sort();
    out
}

fn collect_kinds<'a>(n: Node<'a>, src: &'a str, out: &mut Vec<String>) {
    if n.kind() == "element" {
        let k = n.child_by_field_name("kind").unwrap();
        out.push(
            src[k.byte_range()]
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" "),
        );
    }
    let mut c = n.walk();
    for ch in n.children(&mut c) {
        collect_kinds(ch, src, out);
    }
}

#[test]
fn tree_sitter_and_the_parser_agree_on_every_example() {
    let files = mpath_files();
    assert!(files.len() >= 4);
    for f in files {
        let src = std::fs::read_to_string(&f).unwrap();
        let tree = parser().parse(&src, None).unwrap();
        assert!(
            !tree.root_node().has_error(),
            "{}: {}",
            f.display(),
            tree.root_node().to_sexp()
        );
        let (ast, errors) = millpath_syntax::parse(&src);
        assert!(errors.is_empty(), "{}: {errors:?}", f.display());
        let mut ts_kinds = Vec::new();
        collect_kinds(tree.root_node(), &src, &mut ts_kinds);
        let ours: Vec<String> = ast
            .paths()
            .flat_map(|p| {
                p.elements()
                    .map(|e| e.kind.value.words())
                    .collect::<Vec<_>>()
            })
            .collect();
        assert_eq!(ts_kinds, ours, "{}", f.display());
    }
}

fn all_kinds() -> Vec<Kind> {
    let mut v = vec![
        Kind::Start,
        Kind::End,
        Kind::Turn,
        Kind::Probe,
        Kind::NoProbe,
        Kind::Mill,
        Kind::Mark,
        Kind::Bars,
        Kind::Sub,
        Kind::Sweep,
        Kind::Move,
        Kind::Skip,
    ];
    for s in [Style::Mill, Style::Mark, Style::Bars] {
        v.push(Kind::Drill(s));
        v.push(Kind::Helix(s));
    }
    v.push(Kind::Raw("CENTER".into()));
    v
}

#[test]
fn textmate_grammar_knows_every_element_kind() {
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../millpath.tmLanguage.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let begin = json["repository"]["element"]["begin"].as_str().unwrap();
    let re = regex::Regex::new(begin).unwrap();
    for k in all_kinds() {
        let line = format!("  {} (0, 0)", k.words());
        let m = re.captures(&line).unwrap_or_else(|| panic!("{line}"));
        let words = k.words();
        let expected = words
            .split(' ')
            .take(if matches!(k, Kind::Raw(_)) { 1 } else { 2 })
            .collect::<Vec<_>>()
            .join(" ");
        assert_eq!(
            m[1].split_whitespace().collect::<Vec<_>>().join(" "),
            expected,
            "{line}"
        );
    }
    let path = regex::Regex::new(json["patterns"][1]["begin"].as_str().unwrap()).unwrap();
    assert_eq!(&path.captures("path 1234.1P {").unwrap()[2], "1234.1P");
    let comment = json["repository"]["comment"]["match"].as_str().unwrap();
    assert!(comment.contains('#'));
}

#[test]
fn the_test_file_covers_every_kind() {
    let src =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("test/all-kinds.mpath"))
            .unwrap();
    let (ast, errors) = millpath_syntax::parse(&src);
    assert!(errors.is_empty());
    let kinds: Vec<Kind> = ast
        .paths()
        .flat_map(|p| {
            p.elements()
                .map(|e| e.kind.value.clone())
                .collect::<Vec<_>>()
        })
        .collect();
    for k in all_kinds() {
        assert!(
            kinds
                .iter()
                .any(|x| std::mem::discriminant(x) == std::mem::discriminant(&k)
                    && (!matches!(k, Kind::Drill(_) | Kind::Helix(_)) || *x == k)),
            "{k:?} missing"
        );
    }
}

#[test]
fn neovim_uses_the_same_highlight_queries() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ours = std::fs::read_to_string(root.join("queries/highlights.scm")).unwrap();
    let nvim =
        std::fs::read_to_string(root.join("../../editors/neovim/queries/millpath/highlights.scm"))
            .unwrap();
    assert_eq!(ours, nvim, "copy grammar/tree-sitter-millpath/queries/highlights.scm to editors/neovim/queries/millpath/");
    // and the queries compile against the grammar
    tree_sitter::Query::new(&tree_sitter_millpath::LANGUAGE.into(), &ours)
        .expect("highlight query");
}
