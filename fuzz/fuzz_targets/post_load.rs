//! The post loader on any text: a post or a located error, never a panic; a post that loads
//! renders every event with any values in bounded time and space.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath_post::{Event, Globals, LineWriter, Value, Var};

fuzz_target!(|src: &str| {
    let Ok(post) = millpath_post::load("fuzz.toml", src) else {
        return;
    };
    let g = Globals {
        file_name: "a(b)!.dxf",
        program_name: "1.1P",
        tool_diameter: 2.0,
        clearance: 10.0,
        stock_top: 1.0,
        stock_bottom: -1.0,
        program_feed: 300.0,
    };
    let vars: Vec<(Var, Value)> = Var::ALL
        .iter()
        .map(|v| (*v, Value::Num(-1e300)))
        .collect();
    let mut w = LineWriter::new(&post);
    for e in Event::ALL {
        let text = post.text(e, &vars, &g);
        assert!(text.len() <= millpath_post::template::MAX_TEMPLATE * 400);
        for line in text.lines() {
            let _ = w.line(line);
        }
    }
    let _ = post.comment(4, &"MSG, ä(?)".repeat(100), &g);
});
