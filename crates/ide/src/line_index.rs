//! Byte offsets ↔ (line, column), columns in UTF-16 code units (the LSP default) or in
//! UTF-8 bytes (when the client negotiated `positionEncoding: utf-8`).

#[derive(Debug, Clone)]
pub struct LineIndex {
    starts: Vec<usize>,
    text: String,
    utf8: bool,
}

/// A 0-based line and column (UTF-16 code units, or bytes for a UTF-8 index).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Pos {
    pub line: u32,
    pub col: u32,
}

impl LineIndex {
    pub fn new(text: &str) -> LineIndex {
        LineIndex::with_encoding(text, false)
    }

    /// An index counting columns in UTF-8 bytes (`utf8`) or UTF-16 code units.
    pub fn with_encoding(text: &str, utf8: bool) -> LineIndex {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex {
            starts,
            text: text.to_string(),
            utf8,
        }
    }

    /// The index of `text`, the previous version's (`prev`) after an edit that added or
    /// removed no line break: the same lines, those after the edited one (which ended at
    /// `old_line_end`) moved by `delta`. Not a scan of the whole text again.
    pub fn after_edit(
        prev: &LineIndex,
        text: &str,
        old_line_end: usize,
        delta: isize,
    ) -> LineIndex {
        let starts = prev
            .starts
            .iter()
            .map(|&s| {
                if s > old_line_end {
                    s.saturating_add_signed(delta)
                } else {
                    s
                }
            })
            .collect();
        LineIndex {
            starts,
            text: text.to_string(),
            utf8: prev.utf8,
        }
    }

    /// Columns count UTF-8 bytes.
    pub fn is_utf8(&self) -> bool {
        self.utf8
    }

    pub fn text(&self) -> &str {
        &self.text
    }

    pub fn pos(&self, offset: usize) -> Pos {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let start = self.starts[line];
        let mut end = offset;
        while !self.text.is_char_boundary(end) {
            end -= 1;
        }
        let col = if self.utf8 {
            end - start
        } else {
            self.text[start..end].encode_utf16().count()
        };
        Pos {
            line: line as u32,
            col: col as u32,
        }
    }

    pub fn offset(&self, pos: Pos) -> usize {
        let Some(&start) = self.starts.get(pos.line as usize) else {
            return self.text.len();
        };
        let line_end = self
            .starts
            .get(pos.line as usize + 1)
            .map_or(self.text.len(), |e| e - 1);
        column_offset(&self.text, start, line_end, pos.col, self.utf8)
    }

    /// [`LineIndex::offset`] in `text` without an index: its lines scanned up to `pos` only
    /// (one edit of a long document, where making the index would cost more than the edit).
    pub fn offset_in(text: &str, pos: Pos, utf8: bool) -> usize {
        let mut start = 0;
        for _ in 0..pos.line {
            match text[start..].find('\n') {
                Some(i) => start += i + 1,
                None => return text.len(),
            }
        }
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        column_offset(text, start, line_end, pos.col, utf8)
    }

    pub fn line_count(&self) -> usize {
        self.starts.len()
    }
}

/// The offset of column `col` (UTF-8 bytes or UTF-16 units) in the line `start..line_end`;
/// past its end, the line's end.
fn column_offset(text: &str, start: usize, line_end: usize, col: u32, utf8: bool) -> usize {
    let mut units = 0u32;
    for (i, c) in text[start..line_end].char_indices() {
        if units >= col {
            return start + i;
        }
        units += if utf8 { c.len_utf8() } else { c.len_utf16() } as u32;
    }
    line_end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_columns() {
        let idx = LineIndex::new("ab\nüx𝄞y\n");
        assert_eq!(idx.pos(4), Pos { line: 1, col: 0 }.max(idx.pos(3)));
        assert_eq!(idx.pos(3), Pos { line: 1, col: 0 });
        assert_eq!(idx.pos(5), Pos { line: 1, col: 1 });
        assert_eq!(idx.pos(10), Pos { line: 1, col: 4 });
        assert_eq!(idx.offset(Pos { line: 1, col: 4 }), 10);
        assert_eq!(idx.offset(Pos { line: 1, col: 1 }), 5);
        assert_eq!(idx.offset(Pos { line: 9, col: 0 }), 12);
        assert_eq!(idx.offset(Pos { line: 0, col: 99 }), 2);
    }

    /// An edit inside one line: the index moved from the previous one is the text's own.
    #[test]
    fn an_index_after_an_edit_equals_a_new_one() {
        let old = "ab\nüx𝄞y\n\nlast";
        for (at, end, ins) in [
            (5, 6, "zz"),
            (3, 5, ""),
            (0, 1, "😀"),
            (12, 12, "x"),
            (13, 17, ""),
        ] {
            let mut new = old.to_string();
            new.replace_range(at..end, ins);
            let old_line_end = old[at..].find('\n').map_or(old.len(), |i| at + i);
            let delta = new.len() as isize - old.len() as isize;
            for utf8 in [false, true] {
                let prev = LineIndex::with_encoding(old, utf8);
                let moved = LineIndex::after_edit(&prev, &new, old_line_end, delta);
                let fresh = LineIndex::with_encoding(&new, utf8);
                assert_eq!(moved.starts, fresh.starts, "{new:?}");
                assert_eq!(moved.text, fresh.text);
                assert_eq!(moved.utf8, fresh.utf8);
            }
        }
    }

    #[test]
    fn utf8_columns() {
        let idx = LineIndex::with_encoding("ab\nüx𝄞y\n", true);
        assert_eq!(idx.pos(5), Pos { line: 1, col: 2 });
        assert_eq!(idx.pos(10), Pos { line: 1, col: 7 });
        assert_eq!(idx.offset(Pos { line: 1, col: 7 }), 10);
        assert_eq!(idx.offset(Pos { line: 1, col: 2 }), 5);
        // inside a character: the next one
        assert_eq!(idx.offset(Pos { line: 1, col: 1 }), 5);
    }

    /// Without an index, the same offset for every position (inside, past a line's end, past
    /// the last line, inside a character), in both encodings, with CRLF and no final newline.
    #[test]
    fn an_offset_without_an_index_equals_the_indexed_one() {
        for text in ["ab\nüx𝄞y\n", "a\r\n😀b\r\n\nlast", "", "\n\n", "one line"] {
            for utf8 in [false, true] {
                let idx = LineIndex::with_encoding(text, utf8);
                for line in 0..6 {
                    for col in 0..10 {
                        let pos = Pos { line, col };
                        assert_eq!(
                            LineIndex::offset_in(text, pos, utf8),
                            idx.offset(pos),
                            "{text:?} {pos:?} utf8 {utf8}"
                        );
                    }
                }
            }
        }
    }
}
