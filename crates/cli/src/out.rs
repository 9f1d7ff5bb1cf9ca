//! Writing to standard output without panicking when the reader goes away.
//!
//! `millpath check … | head -1` closes the pipe early. `println!` would panic ("failed
//! printing to stdout: Broken pipe", exit 101); here a closed pipe ends the program quietly
//! with status 141 (128 + SIGPIPE, what a shell reports for a command killed by SIGPIPE).
//! Any other write error ends it with status 1 and a message on standard error.

use std::io::Write;

/// The exit status after standard output was closed by its reader.
pub const BROKEN_PIPE_STATUS: i32 = 141;

/// Writes `s` to standard output; never returns when the output is gone.
pub fn write(s: &str) {
    write_bytes(s.as_bytes());
}

/// [`write`] for bytes (a DXF file in its own code page).
pub fn write_bytes(b: &[u8]) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(b).and_then(|()| out.flush()) {
        gone(&e);
    }
}

/// Writes `s` and a newline to standard output.
pub fn line(s: &str) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out
        .write_all(s.as_bytes())
        .and_then(|()| out.write_all(b"\n"))
    {
        gone(&e);
    }
}

fn gone(e: &std::io::Error) -> ! {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        std::process::exit(BROKEN_PIPE_STATUS);
    }
    let _ = writeln!(
        std::io::stderr(),
        "error: cannot write to standard output: {e}"
    );
    std::process::exit(1);
}

/// `println!` that stops quietly on a closed pipe.
macro_rules! outln {
    ($($t:tt)*) => { crate::out::line(&format!($($t)*)) };
}
