//! One line parsed and executed by the machine model, and the note of a stock model that
//! cannot run: shared by the first reading (`stream.rs`) and the second (`reread.rs`).

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
