//! Byte offsets ↔ (line, UTF-16 column), as editors count.

#[derive(Debug, Clone)]
pub struct LineIndex {
    starts: Vec<usize>,
    text: String,
}

/// A 0-based line and UTF-16 column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Pos {
    pub line: u32,
    pub col: u32,
}

impl LineIndex {
    pub fn new(text: &str) -> LineIndex {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex {
            starts,
            text: text.to_string(),
        }
    }

    pub fn pos(&self, offset: usize) -> Pos {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let start = self.starts[line];
        let mut end = offset;
        while !self.text.is_char_boundary(end) {
            end -= 1;
        }
        let col = self.text[start..end].encode_utf16().count();
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
        let mut units = 0u32;
        for (i, c) in self.text[start..line_end].char_indices() {
            if units >= pos.col {
                return start + i;
            }
            units += c.len_utf16() as u32;
        }
        line_end
    }

    pub fn line_count(&self) -> usize {
        self.starts.len()
    }
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
}
