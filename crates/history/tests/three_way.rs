//! The three-way merge of texts (`merge_texts`) on small texts whose merges are known: what
//! merges, what conflicts and how a conflict is written; and the compile check.

use millpath_history::merge::{broken_paths, merge_texts, ConflictKind};

const BASE: &str = "\
# two slots
path 2001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (30, 0)
  sweep (0, 0) -> (5, 0)
  mill (5, 0) -> (25, 0)
  sweep (25, 0) -> (30, 0)
}

path 2002.1P {
  start (0, 20)  M10x3 O2 T3 I1,5 B-0,2
  end (30, 20)
  sweep (0, 20) -> (5, 20)
  mill (5, 20) -> (25, 20)
  sweep (25, 20) -> (30, 20)
}
";

fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from} not in the text");
    text.replacen(from, to, 1)
}

#[test]
fn one_side_unchanged_gives_the_other_as_it_is() {
    let theirs = edit(BASE, "B-0,2", "B-0,3");
    let m = merge_texts(BASE, BASE, &theirs);
    assert_eq!(m.text, theirs);
    assert!(m.conflicts.is_empty());
    assert_eq!(merge_texts(BASE, &theirs, BASE).text, theirs);
}

#[test]
fn edits_in_different_paths_merge() {
    let ours = edit(
        BASE,
        "start (0, 0)  M10x3 O2 T3 I1,5 B-0,2",
        "start (0, 0)  M10x3 O2 T3 I1,5 B-0,4",
    );
    let theirs = edit(
        BASE,
        "mill (5, 20) -> (25, 20)",
        "mill (5, 20) -> (25, 20)  B-0,3",
    );
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty(), "{:?}", m.conflicts);
    let both = edit(
        &ours,
        "mill (5, 20) -> (25, 20)",
        "mill (5, 20) -> (25, 20)  B-0,3",
    );
    assert_eq!(m.text, both);
}

#[test]
fn different_elements_and_fields_of_one_path_merge() {
    // ours: the start's parameters and the mill's comment; theirs: the start moved, the
    // mill's parameters, a line added at the end
    let ours = edit(BASE, "I1,5 B-0,2\n  end (30, 0)", "I1 B-0,2\n  end (30, 0)");
    let ours = edit(
        &ours,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  # the slot",
    );
    let theirs = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,3",
    );
    let theirs = edit(
        &theirs,
        "  sweep (25, 0) -> (30, 0)\n",
        "  sweep (25, 0) -> (30, 0)\n  mark (0, 5) -> (30, 5)\n",
    );
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty(), "{:?}", m.conflicts);
    assert!(
        m.text.contains("start (0, 0)  M10x3 O2 T3 I1 B-0,2\n"),
        "{}",
        m.text
    );
    assert!(
        m.text
            .contains("  mill (5, 0) -> (25, 0)  B-0,3  # the slot\n"),
        "{}",
        m.text
    );
    assert!(
        m.text
            .contains("  sweep (25, 0) -> (30, 0)\n  mark (0, 5) -> (30, 5)\n}"),
        "{}",
        m.text
    );
}

#[test]
fn the_same_element_changed_both_ways_is_a_conflict_with_markers() {
    let ours = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,1",
    );
    let theirs = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,3",
    );
    // and a clean change elsewhere, kept beside the conflict
    let theirs = edit(
        &theirs,
        "mill (5, 20) -> (25, 20)",
        "mill (5, 20) -> (25, 20)  B-0,5",
    );
    let m = merge_texts(BASE, &ours, &theirs);
    assert_eq!(m.conflicts.len(), 1, "{:?}", m.conflicts);
    let c = &m.conflicts[0];
    assert_eq!(c.path, "2001.1P");
    assert_eq!(c.kind, ConflictKind::BothChanged);
    assert_eq!(c.element.as_deref(), Some("mill (5, 0) -> (25, 0)"));
    let want = "  sweep (0, 0) -> (5, 0)\n<<<<<<< ours\n  mill (5, 0) -> (25, 0)  B-0,1\n=======\n  mill (5, 0) -> (25, 0)  B-0,3\n>>>>>>> theirs\n  sweep (25, 0) -> (30, 0)\n";
    assert!(m.text.contains(want), "{}", m.text);
    assert_eq!(m.text.lines().nth(c.line - 1), Some("<<<<<<< ours"));
    assert!(m.text.contains("mill (5, 20) -> (25, 20)  B-0,5"));
}

#[test]
fn the_same_change_on_both_sides_is_no_conflict() {
    let ours = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,1",
    );
    let ours = edit(
        &ours,
        "mill (5, 20) -> (25, 20)",
        "mill (5, 20) -> (25, 20)  B-0,3",
    );
    let theirs = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,1",
    );
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty());
    assert_eq!(m.text, ours);
}

#[test]
fn deleted_on_one_side_changed_on_the_other_is_a_conflict() {
    let ours = edit(BASE, "  mill (5, 0) -> (25, 0)\n", "");
    let theirs = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,3",
    );
    let m = merge_texts(BASE, &ours, &theirs);
    assert_eq!(m.conflicts.len(), 1);
    assert_eq!(m.conflicts[0].kind, ConflictKind::DeletedByOurs);
    assert!(m
        .text
        .contains("<<<<<<< ours\n=======\n  mill (5, 0) -> (25, 0)  B-0,3\n>>>>>>> theirs\n"));
    // deleted on one side, unchanged on the other: gone
    let theirs = edit(BASE, "B-0,2\n  end (30, 20)", "B-0,4\n  end (30, 20)");
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty());
    assert!(!m.text.contains("mill (5, 0) -> (25, 0)"));
    assert!(m.text.contains("start (0, 20)  M10x3 O2 T3 I1,5 B-0,4"));
}

#[test]
fn a_path_deleted_on_purpose_goes_and_paths_added_on_both_sides_stay() {
    let second = BASE.find("path 2002.1P").unwrap();
    let ours = BASE[..second - 1].to_string();
    let added = "\npath 2003.1P {\n  start (0, 40)  M10x3 O2 T3 B-0,2\n  end (5, 40)\n  mill (0, 40) -> (5, 40)\n}\n";
    let theirs = format!("{BASE}{added}");
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty(), "{:?}", m.conflicts);
    assert!(!m.text.contains("2002.1P"));
    assert!(m.text.contains("path 2003.1P"));
    assert!(m.text.contains("path 2001.1P"));
}

#[test]
fn a_reordered_text_with_an_edit_merges() {
    // theirs writes the second path first and its lines reversed (another writer's order)
    let second = BASE.find("path 2002.1P").unwrap();
    let reversed = |block: &str| {
        let lines: Vec<&str> = block.trim_end().lines().collect();
        let (head, body) = (lines[0], &lines[1..lines.len() - 1]);
        let mut s = format!("{head}\n");
        for l in body.iter().rev() {
            s.push_str(l);
            s.push('\n');
        }
        s.push_str("}\n");
        s
    };
    let theirs = format!(
        "{}\n# two slots\n{}",
        reversed(&BASE[second..]),
        reversed(&BASE[12..second - 1])
    );
    let ours = edit(
        BASE,
        "mill (5, 0) -> (25, 0)",
        "mill (5, 0) -> (25, 0)  B-0,3",
    );
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty(), "{:?}\n{}", m.conflicts, m.text);
    assert!(
        m.text.contains("mill (5, 0) -> (25, 0)  B-0,3"),
        "{}",
        m.text
    );
}

#[test]
fn add_add_from_an_empty_base() {
    let m = merge_texts("", BASE, BASE);
    assert_eq!(m.text, BASE);
    let theirs = edit(BASE, "B-0,2", "B-0,3");
    let m = merge_texts("", BASE, &theirs);
    assert_eq!(m.conflicts.len(), 1);
    assert_eq!(m.conflicts[0].kind, ConflictKind::AddedBoth);
    assert_eq!(m.conflicts[0].element, None);
}

#[test]
fn a_merge_that_breaks_a_path_while_both_sides_compile_is_found() {
    // ours moves the end marker and the last sweep to 40; theirs edits the sweep's end to
    // 35: each side compiles, the merge (end at 40, sweep to 35) leaves a gap
    let ours = edit(BASE, "end (30, 0)", "end (40, 0)");
    let ours = edit(
        &ours,
        "sweep (25, 0) -> (30, 0)",
        "sweep (25, 0) -> (40, 0)",
    );
    let theirs = edit(
        BASE,
        "  sweep (25, 0) -> (30, 0)\n",
        "  sweep (25, 0) -> (30, 0)\n  sweep (30, 0) -> (40, 0)\n",
    );
    let theirs = edit(&theirs, "end (30, 0)", "end (40, 0)");
    let settings = millpath_core::Settings::default();
    assert!(broken_paths(&ours, &theirs, &ours, &settings).is_empty());
    let m = merge_texts(BASE, &ours, &theirs);
    assert!(m.conflicts.is_empty(), "{:?}", m.conflicts);
    assert_eq!(
        broken_paths(&ours, &theirs, &m.text, &settings),
        ["2001.1P"],
        "{}",
        m.text
    );
}
