//! The MillPath text language (`*.mpath`): one path per `path NAME { … }` block, one element
//! per line, parameters written exactly as in the drawing. See `docs/language.md`.

pub mod ast;
pub mod error;
pub mod format;
pub mod lexer;
pub mod parser;
mod tokens;

pub use ast::*;
pub use error::{ErrorKind, Expected, Found, SyntaxError};
pub use format::format;
pub use parser::parse;

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "\
# a part
path 1234.1P {  # key handle
  start (0, 0)  M3x40 O2 T3 I1,5 B-0,2
  end (80, 0)

  sweep (0, 0) -> (10, 10)
  mill (10, 10) -> (10, 30)  N1  # first
  mill arc (60, 11) r10 from 270 to 360
  helix (30, 20) d8  I0,5
  mark drill (60, 20) d2
  bars helix (1, 2) d 9
  sub (70, 11) -> (90, 11)  >8998.2P T2 :B=B \"#x\"
  raw DASHED2 (0, 0) -> (1, 1)
  raw PHANTOM (1, 1) d0.333
  probe (5, 5)
}
";

    #[test]
    fn parses_every_form() {
        let (file, errors) = parse(SAMPLE);
        assert!(errors.is_empty(), "{errors:?}");
        let p = file.paths().next().unwrap();
        assert_eq!(p.name.value, "1234.1P");
        let els: Vec<&Element> = p.elements().collect();
        assert_eq!(els.len(), 12);
        assert_eq!(els[0].kind.value, Kind::Start);
        assert_eq!(
            els[0]
                .params
                .iter()
                .map(|p| p.value.as_str())
                .collect::<Vec<_>>(),
            ["M3x40", "O2", "T3", "I1,5", "B-0,2"]
        );
        assert_eq!(&SAMPLE[els[0].params[3].span.clone()], "I1,5");
        assert_eq!(els[3].comment.as_ref().unwrap().value, "# first");
        assert_eq!(
            els[4].geometry.value,
            Geometry::Arc {
                c: Point { x: 60.0, y: 11.0 },
                r: 10.0,
                a0: 270.0,
                a1: 360.0
            }
        );
        assert_eq!(els[6].kind.value, Kind::Drill(Style::Mark));
        assert_eq!(
            els[7].geometry.value,
            Geometry::Circle {
                c: Point { x: 1.0, y: 2.0 },
                d: 9.0
            }
        );
        assert_eq!(els[8].params.last().unwrap().value, "#x");
        assert_eq!(els[9].kind.value, Kind::Raw("DASHED2".into()));
    }

    #[test]
    fn formatting_is_canonical_and_idempotent() {
        let (file, _) = parse(SAMPLE);
        let once = format(&file, SAMPLE);
        assert!(once.contains("  bars helix (1, 2) d9\n"), "{once}");
        assert!(once.contains("path 1234.1P {  # key handle\n"));
        let (again, errs) = parse(&once);
        assert!(errs.is_empty());
        assert_eq!(format(&again, &once), once);
        let messy = "path   X {\n\n\n   mill   (0,0)->(1,1)     B1    B2\n\n}\n\n\n";
        let (f, e) = parse(messy);
        assert!(e.is_empty(), "{e:?}");
        assert_eq!(
            format(&f, messy),
            "path X {\n  mill (0, 0) -> (1, 1)  B1 B2\n}\n"
        );
    }

    #[test]
    fn errors_are_reported_and_the_rest_is_parsed() {
        let src = "path A {\n  mill (0, 0) -> (1\n  start (0, 0)  T2\n  frobnicate 3\n  end (1, 1)\n}\nmill (0,0) -> (1,1)\npath B {\n  start (2, x)\n}\npath C {\n  end (0, 0)\n";
        let (file, errors) = parse(src);
        let paths: Vec<&PathBlock> = file.paths().collect();
        assert_eq!(
            paths
                .iter()
                .map(|p| p.name.value.as_str())
                .collect::<Vec<_>>(),
            ["A", "B", "C"],
            "{errors:?}"
        );
        assert_eq!(paths[0].elements().count(), 2);
        assert_eq!(paths[2].elements().count(), 1);
        let lines: Vec<usize> = errors
            .iter()
            .map(|e| src[..e.span.start].matches('\n').count() + 1)
            .collect();
        assert!(
            lines.contains(&2) && lines.contains(&4) && lines.contains(&7) && lines.contains(&9),
            "{errors:?}"
        );
        assert!(
            errors.iter().any(|e| e.message().contains("missing `}`")),
            "{errors:?}"
        );
        assert!(
            errors
                .iter()
                .any(|e| e.message().contains("`x` is not a number")),
            "{errors:?}"
        );
    }

    #[test]
    fn errors_carry_their_hint() {
        let src = "path X {\n  mil (0, 0) -> (1, 1)\n  mill (12,5, 0) -> (1, 1)\n  frobnicate (0, 0)\n  mill (0, x) -> (1, 1)\n}\n";
        let (_, errors) = parse(src);
        let kinds: Vec<&ErrorKind> = errors.iter().map(|e| &e.kind).collect();
        assert_eq!(
            kinds[0],
            &ErrorKind::UnknownKind {
                word: "mil".into(),
                suggestion: Some("mill")
            }
        );
        assert_eq!(
            kinds[1],
            &ErrorKind::DecimalComma {
                written: "12,5".into(),
                fixed: "12.5".into()
            }
        );
        assert_eq!(&src[errors[1].span.clone()], "12,5");
        assert_eq!(
            kinds[2],
            &ErrorKind::UnknownKind {
                word: "frobnicate".into(),
                suggestion: None
            }
        );
        assert_eq!(kinds[3], &ErrorKind::NotANumber("x".into()));
        assert_eq!(
            errors[0].message(),
            "`mil` is not an element kind: did you mean `mill`?"
        );
        assert_eq!(errors.len(), 4, "{errors:?}");
        let (_, errors) = parse("pat X {\n");
        assert_eq!(
            errors[0].kind,
            ErrorKind::DidYouMean {
                word: "pat".into(),
                suggestion: "path"
            }
        );
    }

    #[test]
    fn byte_order_marks_and_crlf_read_as_plain_text() {
        let plain = "path X {\n  start (0, 0)  T1 # c\n  mill (0, 0) -> (1, 1)  B1\n}\n";
        let (want, e) = parse(plain);
        assert!(e.is_empty());
        for src in [format!("\u{FEFF}{plain}"), plain.replace('\n', "\r\n")] {
            let (f, e) = parse(&src);
            assert!(e.is_empty(), "{e:?}");
            assert_eq!(format(&f, &src), format(&want, plain));
        }
    }

    #[test]
    fn arcs_by_end_points_and_centre() {
        let src = "path X {\n  mill (10, 0) -> (0, 10) ccw around (0, 0)\n  mill (0, 10) -> (10, 0) cw around (0, 0)\n}\n";
        let (f, e) = parse(src);
        assert!(e.is_empty(), "{e:?}");
        let els: Vec<&Element> = f.paths().next().unwrap().elements().collect();
        let quarter = Geometry::Arc {
            c: Point { x: 0.0, y: 0.0 },
            r: 10.0,
            a0: 0.0,
            a1: 90.0,
        };
        assert_eq!(els[0].geometry.value, quarter);
        // clockwise from (0,10) to (10,0) is the same counter-clockwise arc
        assert_eq!(els[1].geometry.value, quarter);
        // the formatter writes the exact form
        assert!(format(&f, src).contains("  mill arc (0, 0) r10 from 0 to 90\n"));
    }

    #[test]
    fn numbers_are_shortest_and_exact() {
        assert_eq!(format::num(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(format::num(-0.0), "-0");
        assert_eq!(format::num(57.687), "57.687");
        assert_eq!(format::num(1e-7), "0.0000001");
    }
}
