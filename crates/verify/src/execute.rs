//! One line parsed and executed by the machine model, and the note of a stock model that
//! cannot run: shared by the first reading (`stream.rs`) and the second (`reread.rs`). An
//! xCAM `.NCC` line goes to its reader (`ncc.rs`) instead of the G-code parser.

use crate::machine::{Machine, Raw};
use crate::{parse, FindingKind, Severity, StockSkip, SyntaxError};

/// One line (without its `\r`) parsed and executed by `m` as line `no`; `adjust` changes
/// the parsed words first (an adjusted program's heights).
pub(crate) fn execute(
    m: &mut Machine,
    no: usize,
    l: &str,
    max_line_len: usize,
    adjust: impl FnOnce(&mut parse::Block),
) {
    if m.dialect() == crate::Dialect::Xcam {
        return ncc_line(m, no, l, max_line_len);
    }
    let parsed = if l.len() > max_line_len {
        Err(FindingKind::Syntax(SyntaxError::LineTooLong(max_line_len)))
    } else {
        parse::parse_line(l)
    };
    match parsed {
        Ok(mut b) => {
            adjust(&mut b);
            m.exec(no, &b)
        }
        Err(kind) => {
            if m.ended {
                // the controller does not read past the end
                m.after_end(no);
            } else {
                m.findings.push(Raw {
                    line: Some(no),
                    kind,
                    severity: Severity::Error,
                });
            }
        }
    }
}

/// One line of an xCAM `.NCC` file: the reader's blocks executed at the lines they belong
/// to, its findings kept; the program may end after any line that leaves nothing pending.
fn ncc_line(m: &mut Machine, no: usize, l: &str, max_line_len: usize) {
    if l.len() > max_line_len {
        m.findings.push(Raw {
            line: Some(no),
            kind: FindingKind::Syntax(SyntaxError::LineTooLong(max_line_len)),
            severity: Severity::Error,
        });
        m.last_code_ends = false;
        return;
    }
    let (steps, found) = m.ncc.line(no, l);
    m.findings
        .extend(found.into_iter().map(|(line, kind, severity)| Raw {
            line: Some(line),
            kind,
            severity,
        }));
    for (line, block) in &steps {
        m.exec(*line, block);
    }
    m.last_code_ends = m.ncc.complete();
}

/// The stock model cannot run: top or tool unknown.
pub(crate) fn missing_params(top: Option<f64>, tool: Option<f64>) -> Raw {
    Raw {
        line: None,
        kind: FindingKind::StockSkipped(StockSkip::MissingParams {
            top: top.is_none(),
            tool: tool.is_none(),
        }),
        severity: Severity::Note,
    }
}
