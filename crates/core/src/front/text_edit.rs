//! The drawn objects of a text after an edit inside one element line (the editor's
//! keystroke), from those of the previous version instead of from the whole tree.
//!
//! An element's object reads only the element, its path's name and where the element is
//! (the line and column of its spans: [`element_object`]). An edit inside one element line
//! changes no other element, no path name and no line or column of another element (the
//! line holds that element alone); it moves the offsets after it. So every other object is
//! the previous one with its offsets moved, and only the edited element's object is made
//! again. When the previous objects came without a diagnostic, that is exactly what
//! [`objects_of`](crate::front::text::objects_of) gives for the new tree, diagnostics and
//! abort included (test below, on random edits of every kind of element).

use crate::diag::{Diagnostic, Diags, FileRef, Origin};
use crate::front::drawing::DrawnObject;
use crate::front::text::{declared_drill, element_object, span_of, ElementNames, TextDrawing};
use millpath_syntax::{File, Item, PathItem, Span};
use std::sync::Arc;

/// An edit confined to one element line: the element (its path's index in
/// [`File::items`], its index in the path's items, in the new tree), the edited line's
/// start, its end in the previous text and how far the offsets after it moved.
#[derive(Debug, Clone, Copy)]
pub struct LineEdit {
    pub item: usize,
    pub element: usize,
    pub line_start: usize,
    pub old_line_end: usize,
    pub delta: isize,
}

impl LineEdit {
    fn moved(&self, offset: u32) -> u32 {
        if offset as usize >= self.old_line_end {
            let moved = (offset as i64 + self.delta as i64).max(0);
            u32::try_from(moved).unwrap_or(u32::MAX)
        } else {
            offset
        }
    }
}

/// The previous version's drawn objects and declared kinds (a [`TextDrawing`]'s, borrowed).
#[derive(Clone, Copy)]
pub struct PrevObjects<'a> {
    pub objects: &'a [DrawnObject],
    pub declared: &'a [(usize, bool)],
}

/// The objects of `ast` (the new tree, without syntax errors) after `edit`, made from
/// `prev` (the objects of the previous tree, which gave no diagnostic: one per element).
/// `None` when the previous objects do not fit the tree (the caller makes them all).
pub fn objects_after_edit(
    prev: PrevObjects<'_>,
    ast: &File,
    edit: &LineEdit,
    src: &str,
    file: &Arc<FileRef>,
    diags: &mut Diags,
) -> Option<Result<TextDrawing, Diagnostic>> {
    // the edited element, its index among all elements and their number
    let mut total = 0;
    let mut found = None;
    for (i, item) in ast.items.iter().enumerate() {
        let Item::Path(p) = item else { continue };
        if i == edit.item {
            let PathItem::Element(el) = p.items.get(edit.element)? else {
                return None;
            };
            let before = p.items[..edit.element]
                .iter()
                .filter(|it| matches!(it, PathItem::Element(_)))
                .count();
            found = Some((total + before, el, &p.name.value));
        }
        total += p.elements().count();
    }
    let (at, el, path_name) = found?;
    if prev.objects.len() != total || el.span.start < edit.line_start {
        return None;
    }
    let old = &prev.objects[at];
    let Origin::Span { line, .. } = old.origin else {
        return None;
    };
    if *old.path != **path_name {
        return None;
    }
    // the edited element on its line: the line is the previous one's, the column counted
    let line_start = edit.line_start;
    let origin_of = |span: &Span| -> Origin {
        let mut end = span.start.clamp(line_start, src.len());
        while !src.is_char_boundary(end) {
            end -= 1;
        }
        let col = src[line_start..end].chars().count() + 1;
        span_of(file, span, line as usize, col)
    };
    let mut names = ElementNames::default();
    let object = match element_object(el, &old.path, &mut names, &origin_of, diags) {
        Ok(o) => o,
        Err(abort) => return Some(Err(abort)),
    };
    let mut objects = Vec::with_capacity(total);
    objects.extend(prev.objects[..at].iter().cloned());
    objects.push(object);
    objects.extend(prev.objects[at + 1..].iter().map(|o| {
        let mut o = o.clone();
        if edit.delta != 0 {
            move_origin(&mut o.origin, edit);
            if let Some(t) = &mut o.text {
                move_origin(&mut t.origin, edit);
            }
        }
        o
    }));
    let mut declared: Vec<(usize, bool)> = prev
        .declared
        .iter()
        .copied()
        .filter(|(i, _)| *i != at)
        .collect();
    if let Some(drill) = declared_drill(el) {
        let pos = declared.partition_point(|(i, _)| *i < at);
        declared.insert(pos, (at, drill));
    }
    Some(Ok(TextDrawing { objects, declared }))
}

fn move_origin(origin: &mut Origin, edit: &LineEdit) {
    if let Origin::Span { start, end, .. } = origin {
        *start = edit.moved(*start);
        *end = edit.moved(*end);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::text::objects_of;
    use millpath_syntax::parse;

    /// Every kind of element, texts where they belong and where they do not, a second path
    /// after the first, comments, non-ASCII text before and in lines.
    const SRC: &str = "# Größe 😀\npath 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  turn (3, 3)\n\n  sweep (0, 0) -> (5, 0)  # ä\n  mill (5, 0) -> (25, 0)  \"Grüße😀\" B-0,2 # ä😀\n  mill arc (0, 0) r5 from -90 to 90\n  drill (1, 2) d2\n  helix (4, 4) d6\n  mark (0, 1) -> (2, 1)\n  probe (8, 8)\n  sub (1, 1) -> (2, 2)\n  sweep (25, 0) -> (30, 0)\n}\n# tail\npath 2002.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  mill (0, 0) -> (30, 0) B-1\n  raw CENTER (0, 0) -> (1, 1)\n}\n";

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

    /// The edited line of a one-line edit of `old` into `new` found by hand (the editor's
    /// incremental parse finds it its own way): `None` unless one element line changed.
    fn line_edit(old: &str, new: &str, ast: &File) -> Option<LineEdit> {
        let mut pre = old
            .bytes()
            .zip(new.bytes())
            .take_while(|(a, b)| a == b)
            .count();
        while !old.is_char_boundary(pre) || !new.is_char_boundary(pre) {
            pre -= 1;
        }
        let line_start = old[..pre].rfind('\n').map_or(0, |i| i + 1);
        let old_line_end = line_start + old[line_start..].find('\n')?;
        let delta = new.len() as isize - old.len() as isize;
        let new_line_end = usize::try_from(old_line_end as isize + delta).ok()?;
        if new_line_end < line_start
            || old.as_bytes()[old_line_end..] != *new.as_bytes().get(new_line_end..)?
            || new.as_bytes()[line_start..new_line_end].contains(&b'\n')
        {
            return None;
        }
        for (item, it) in ast.items.iter().enumerate() {
            let Item::Path(p) = it else { continue };
            for (element, pit) in p.items.iter().enumerate() {
                if let PathItem::Element(e) = pit {
                    if line_start <= e.span.start && e.span.start < new_line_end {
                        return Some(LineEdit {
                            item,
                            element,
                            line_start,
                            old_line_end,
                            delta,
                        });
                    }
                }
            }
        }
        None
    }

    fn as_text(r: &Result<TextDrawing, Diagnostic>, d: &Diags) -> String {
        match r {
            Ok(t) => format!("{:?} {:?} {:?}", t.objects, t.declared, d.list),
            Err(e) => format!("abort {e:?} {:?}", d.list),
        }
    }

    /// Made from the previous objects or from the whole tree: the same objects (origins
    /// included), the same declared kinds, the same diagnostics or abort.
    #[test]
    fn objects_after_an_edit_equal_those_of_the_whole_tree() {
        let file = FileRef::new("a.mpath".into());
        let inserts = [
            "1", "-", ",", " ", "B", "T2", "\"x\"", "r", "0", "d", "😀", "ü", "", "Q", "raw",
        ];
        let (prev_ast, errs) = parse(SRC);
        assert!(errs.is_empty());
        let mut d = Diags::default();
        let prev = objects_of(&prev_ast, Vec::new(), SRC, &file, &mut d).unwrap();
        assert!(d.list.is_empty(), "{:?}", d.list);
        let mut rng = Rng(31);
        let (mut compared, mut differ) = (0, 0);
        for _ in 0..4000 {
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
            let (ast, errors) = parse(&new);
            if !errors.is_empty() {
                continue;
            }
            let Some(edit) = line_edit(SRC, &new, &ast) else {
                continue;
            };
            let (mut d1, mut d2) = (Diags::default(), Diags::default());
            let full = objects_of(&ast, Vec::new(), &new, &file, &mut d1);
            let prev_objects = PrevObjects {
                objects: &prev.objects,
                declared: &prev.declared,
            };
            let Some(reused) = objects_after_edit(prev_objects, &ast, &edit, &new, &file, &mut d2)
            else {
                continue;
            };
            let (a, b) = (as_text(&full, &d1), as_text(&reused, &d2));
            assert_eq!(a, b, "edit {at}..{end} → {new:?}");
            compared += 1;
            if a != as_text(&Ok(prev.clone()), &Diags::default()) {
                differ += 1;
            }
        }
        assert!(compared > 500, "only {compared} edits compared");
        assert!(differ > 300, "only {differ} edits changed the objects");
    }
}
