//! `millpath post list` and `millpath post show NAME`: the built-in posts, and one printed as
//! an editable post file (loading that file gives the built-in post, byte for byte).

use millpath_core::Lang;

pub fn list(lang: Lang) -> u8 {
    for name in millpath_post::builtin::NAMES {
        let Some(post) = millpath_post::builtin::get(name) else {
            continue;
        };
        println!(
            "{:<10} {:<7} {}",
            post.name,
            post.family.name(),
            post.description
        );
    }
    let hint = match lang {
        Lang::De => "(`millpath post show NAME` gibt einen als Datei zum Anpassen aus)",
        _ => "(`millpath post show NAME` prints one as a file to adapt)",
    };
    println!("{hint}");
    0
}

pub fn show(name: &str, lang: Lang) -> u8 {
    match millpath_post::builtin::source(name) {
        Some(text) => {
            print!("{text}");
            0
        }
        None => {
            let known = millpath_post::builtin::NAMES.join(", ");
            match lang {
                Lang::De => eprintln!("error: kein eingebauter Post `{name}` (eingebaut: {known})"),
                _ => eprintln!("error: no built-in post `{name}` (built in: {known})"),
            }
            2
        }
    }
}
