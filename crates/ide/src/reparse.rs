//! Incremental parsing for keystrokes: when an edit stays inside one element line of an
//! error-free document, only that line is parsed again and the rest of the previous tree is
//! kept (its spans shifted). Anything else (new lines, braces, other items, syntax errors
//! before or after) parses the whole text. The result is always what [`parse`] gives; a
//! differential test checks that on random edits.

use millpath_syntax::{parse, File, Item, PathItem, Span, SyntaxError};

/// The previous version of a document: its text and tree, parsed without syntax errors.
pub struct Previous<'a> {
    pub src: &'a str,
    pub ast: &'a File,
}

/// Where an incremental parse changed the previous tree: one element line, the rest kept
/// (the editor reuses what it made of the other elements, see `incremental.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Splice {
    /// The path: its index in [`File::items`].
    pub item: usize,
    /// The element: its index in the path's items.
    pub element: usize,
    /// The start of the edited line (the same in both texts).
    pub line_start: usize,
    /// The end of the edited line in the previous text (its `\n`): every offset from here on
    /// moved by `delta`.
    pub old_line_end: usize,
    pub delta: isize,
}

impl Splice {
    /// Where a previous offset is now (offsets inside the edited line are not asked).
    pub fn moved(&self, offset: usize) -> usize {
        if offset >= self.old_line_end {
            offset.saturating_add_signed(self.delta)
        } else {
            offset
        }
    }
}

/// Parses `new`, reusing `prev` when the change is confined to one element line.
pub fn reparse(prev: Option<Previous<'_>>, new: &str) -> (File, Vec<SyntaxError>) {
    let (ast, errors, _) = reparse_spliced(prev, new);
    (ast, errors)
}

/// [`reparse`] that says which element it parsed again (`None`: the whole text was parsed).
pub fn reparse_spliced(
    prev: Option<Previous<'_>>,
    new: &str,
) -> (File, Vec<SyntaxError>, Option<Splice>) {
    if let Some(p) = prev {
        if let Some((ast, splice)) = one_line(&p, new) {
            return (ast, Vec::new(), Some(splice));
        }
    }
    let (ast, errors) = parse(new);
    (ast, errors, None)
}

const MINI_HEAD: &str = "path 0000.0P {\n";

fn one_line(prev: &Previous<'_>, new: &str) -> Option<(File, Splice)> {
    let old = prev.src;
    // the changed region: common prefix and suffix
    let mut pre = common_prefix(old.as_bytes(), new.as_bytes());
    while !old.is_char_boundary(pre) || !new.is_char_boundary(pre) {
        pre -= 1;
    }
    let max_suf = old.len().min(new.len()) - pre;
    let mut suf = common_suffix(&old.as_bytes()[pre..], &new.as_bytes()[pre..]).min(max_suf);
    while !old.is_char_boundary(old.len() - suf) || !new.is_char_boundary(new.len() - suf) {
        suf -= 1;
    }
    let (old_end, new_end) = (old.len() - suf, new.len() - suf);
    if old[pre..old_end].contains('\n') || new[pre..new_end].contains('\n') {
        return None;
    }
    let line_start = old[..pre].rfind('\n').map_or(0, |i| i + 1);
    let old_line_end = old[pre..].find('\n').map_or(old.len(), |i| pre + i);
    if old_end > old_line_end || old_line_end == old.len() {
        return None;
    }
    let delta = new.len() as isize - old.len() as isize;
    let new_line_end = (old_line_end as isize + delta) as usize;
    let line = &new[line_start..new_line_end];
    if line.contains(['{', '}', '\r']) {
        return None;
    }
    // the element of that line in the previous tree
    let (pi, ei) = prev.ast.items.iter().enumerate().find_map(|(pi, it)| {
        let Item::Path(p) = it else { return None };
        if !(p.span.start < line_start && old_line_end < p.span.end) {
            return None;
        }
        p.items
            .iter()
            .position(|i| {
                matches!(i, PathItem::Element(e)
                    if line_start <= e.span.start && e.span.end <= old_line_end + 1)
            })
            .map(|ei| (pi, ei))
    })?;
    // the new line on its own
    let mini = format!("{MINI_HEAD}{line}\n}}\n");
    let (m, errors) = parse(&mini);
    if !errors.is_empty() || m.items.len() != 1 {
        return None;
    }
    let Item::Path(mp) = m.items.into_iter().next()? else {
        return None;
    };
    let [PathItem::Element(mut el)] = <[PathItem; 1]>::try_from(mp.items).ok()? else {
        return None;
    };
    let base = line_start as isize - MINI_HEAD.len() as isize;
    shift_element(&mut el, |x| (x as isize + base) as usize);
    // the previous tree, the element replaced, everything after it shifted
    let mut ast = prev.ast.clone();
    let after = |x: usize| {
        if x >= old_line_end {
            (x as isize + delta) as usize
        } else {
            x
        }
    };
    for (i, it) in ast.items.iter_mut().enumerate() {
        if i < pi {
            continue;
        }
        match it {
            Item::Blank => {}
            Item::Comment(c) => c.span = span(&c.span, after),
            Item::Error(s) => *s = span(s, after),
            Item::Path(p) => {
                p.span = span(&p.span, after);
                if i > pi {
                    p.name.span = span(&p.name.span, after);
                    if let Some(c) = &mut p.comment {
                        c.span = span(&c.span, after);
                    }
                }
                let from = if i == pi { ei + 1 } else { 0 };
                for pit in p.items.iter_mut().skip(from) {
                    match pit {
                        PathItem::Blank => {}
                        PathItem::Comment(c) => c.span = span(&c.span, after),
                        PathItem::Error(s) => *s = span(s, after),
                        PathItem::Element(e) => shift_element(e, after),
                    }
                }
            }
        }
    }
    if let Item::Path(p) = &mut ast.items[pi] {
        p.items[ei] = PathItem::Element(el);
    }
    let splice = Splice {
        item: pi,
        element: ei,
        line_start,
        old_line_end,
        delta,
    };
    Some((ast, splice))
}

/// Bytes compared at once when looking for the changed region: equal blocks are compared
/// with `memcmp`, a keystroke in a 600 kB text costs microseconds instead of a byte loop.
const BLOCK: usize = 256;

/// The length of the common start of `a` and `b`.
fn common_prefix(a: &[u8], b: &[u8]) -> usize {
    let n = a.len().min(b.len());
    let mut i = 0;
    while i + BLOCK <= n && a[i..i + BLOCK] == b[i..i + BLOCK] {
        i += BLOCK;
    }
    i + a[i..n]
        .iter()
        .zip(&b[i..n])
        .take_while(|(x, y)| x == y)
        .count()
}

/// The length of the common end of `a` and `b`.
fn common_suffix(a: &[u8], b: &[u8]) -> usize {
    let n = a.len().min(b.len());
    let (a, b) = (&a[a.len() - n..], &b[b.len() - n..]);
    let mut k = 0;
    while k + BLOCK <= n && a[n - k - BLOCK..n - k] == b[n - k - BLOCK..n - k] {
        k += BLOCK;
    }
    k + a[..n - k]
        .iter()
        .rev()
        .zip(b[..n - k].iter().rev())
        .take_while(|(x, y)| x == y)
        .count()
}

fn span(s: &Span, f: impl Fn(usize) -> usize) -> Span {
    f(s.start)..f(s.end)
}

fn shift_element(e: &mut millpath_syntax::Element, f: impl Fn(usize) -> usize + Copy) {
    e.span = span(&e.span, f);
    e.kind.span = span(&e.kind.span, f);
    e.geometry.span = span(&e.geometry.span, f);
    for p in &mut e.params {
        p.span = span(&p.span, f);
    }
    if let Some(c) = &mut e.comment {
        c.span = span(&c.span, f);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SRC: &str = "# Größe 😀\npath 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n\n  sweep (0, 0) -> (5, 0)  # ä\n  mill (5, 0) -> (25, 0)  \"Grüße😀\" B-0,2 # ä😀\n  sweep (25, 0) -> (30, 0)\n}\n# tail\npath 2002.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  mill (0, 0) -> (30, 0)\n}\n";

    /// A tiny deterministic generator (no dependency).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self, n: usize) -> usize {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((self.0 >> 33) as usize) % n.max(1)
        }
    }

    #[test]
    fn incremental_equals_full_parse_on_random_edits() {
        let inserts = [
            "1", "-", ",", " ", "B", "T2", "#", "\"", "(", ")", "->", "x", "ü", "😀", "", "{",
        ];
        let mut rng = Rng(7);
        let mut reused = 0;
        for _ in 0..3000 {
            let (prev_ast, errs) = parse(SRC);
            assert!(errs.is_empty());
            let mut new = SRC.to_string();
            let mut at = rng.next(new.len());
            while !new.is_char_boundary(at) {
                at -= 1;
            }
            let mut end = (at + rng.next(4)).min(new.len());
            while !new.is_char_boundary(end) {
                end += 1;
            }
            new.replace_range(at..end, inserts[rng.next(inserts.len())]);
            let full = parse(&new);
            let prev = Previous {
                src: SRC,
                ast: &prev_ast,
            };
            if one_line(&prev, &new).is_some() {
                reused += 1;
            }
            let inc = reparse(Some(prev), &new);
            assert_eq!(inc, full, "edit {at}..{end} → {new:?}");
        }
        assert!(reused > 300, "only {reused} edits reused the tree");
    }

    /// The block-wise common prefix and suffix equal a byte-by-byte count, around and across
    /// block edges.
    #[test]
    fn common_prefix_and_suffix_equal_the_byte_count() {
        let mut rng = Rng(11);
        for _ in 0..2000 {
            let len = rng.next(3 * BLOCK + 7);
            let a: Vec<u8> = (0..len).map(|_| b'a' + rng.next(2) as u8).collect();
            let mut b = a.clone();
            // a few changes anywhere, sometimes none, sometimes a length change
            for _ in 0..rng.next(3) {
                if b.is_empty() {
                    break;
                }
                let at = rng.next(b.len());
                match rng.next(3) {
                    0 => b[at] = b'z',
                    1 => b.insert(at, b'y'),
                    _ => {
                        b.remove(at);
                    }
                }
            }
            let pre = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
            let suf = a
                .iter()
                .rev()
                .zip(b.iter().rev())
                .take_while(|(x, y)| x == y)
                .count();
            assert_eq!(common_prefix(&a, &b), pre, "{a:?} {b:?}");
            assert_eq!(common_suffix(&a, &b), suf, "{a:?} {b:?}");
        }
    }
}
