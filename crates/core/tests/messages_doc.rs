//! The codes in the manual's message list (`docs/src/messages.md`) name the messages they
//! explain. Codes are indexes into `Msg::ALL`, so a message added in the wrong place, or two
//! branches appending at once, shift them: each entry's quoted text must share most of its
//! words with the message its code names today.

use millpath_core::{Lang, Msg};

/// Words of four letters or more, lower case.
fn words(s: &str) -> Vec<String> {
    s.split(|c: char| !c.is_alphabetic())
        .filter(|w| w.chars().count() >= 4)
        .map(str::to_lowercase)
        .collect()
}

/// `(text, code)` of every entry: ``**`text`** (MP012)`` or ``(warning MP012)``.
fn entries(doc: &str) -> Vec<(String, usize)> {
    let re = regex::Regex::new(r"\*\*`+ ?(.*?) ?`+\*\*\s*\((?:warning )?MP(\d+)\)").unwrap();
    re.captures_iter(doc)
        .map(|c| (c[1].to_string(), c[2].parse().unwrap()))
        .collect()
}

#[test]
fn every_documented_code_names_its_message() {
    let doc = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/src/messages.md"),
    )
    .unwrap();
    let entries = entries(&doc);
    assert!(entries.len() >= 30, "{} entries found", entries.len());
    let mut wrong = Vec::new();
    for (text, code) in entries {
        let Some(msg) = code.checked_sub(1).and_then(|i| Msg::ALL.get(i)) else {
            wrong.push(format!("MP{code:03}: no such message ({text})"));
            continue;
        };
        // the longest literal run of the entry (`…` stands for arguments)
        let run = text.split('…').max_by_key(|r| r.len()).unwrap_or_default();
        let ours = words(run);
        let templates = format!(
            "{} {}",
            msg.template(Lang::En),
            msg.human_template(Lang::En)
        )
        .to_lowercase();
        let shared = ours
            .iter()
            .filter(|w| templates.contains(w.as_str()))
            .count();
        if !ours.is_empty() && shared * 2 < ours.len() {
            wrong.push(format!(
                "MP{code:03} is {msg:?} (\"{}\"), but the manual says \"{text}\"",
                msg.template(Lang::En)
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn a_shifted_code_is_found() {
    // the entry of "No more segments …" given the code of the message before it
    let before = Msg::NoMoreSegments.code()[2..].parse::<usize>().unwrap() - 1;
    let doc = format!("**`No more segments found after location …`** (MP{before:03})\n");
    let (text, code) = entries(&doc).remove(0);
    let msg = Msg::ALL[code - 1];
    assert_eq!(msg, Msg::NotReached);
    let ours = words(&text);
    let shared = ours
        .iter()
        .filter(|w| msg.template(Lang::En).to_lowercase().contains(w.as_str()))
        .count();
    assert!(shared * 2 < ours.len(), "{shared} of {ours:?}");
}
