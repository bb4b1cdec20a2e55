//! Times a full analysis and an incremental update after a one-character
//! insertion in the middle of FILE: `cargo run --release -p analyzer --example incremental_speed FILE [--syntax-only]`.

use std::sync::Arc;
use std::time::Instant;

use analyzer::incremental::Incremental;
use analyzer::{Dialect, Settings};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: incremental_speed FILE [--syntax-only]");
    let syntax_only = args.next().is_some_and(|a| a == "--syntax-only");
    let text = std::fs::read(&path).expect("read FILE");
    let settings = Settings::new(Dialect::Rs274ngc);
    let t = Instant::now();
    let mut inc = Incremental::new(Arc::from(&text[..]), &settings, syntax_only);
    println!("full: {:?}", t.elapsed());
    let mut times = Vec::new();
    for k in 0..10 {
        let mut edited = text.clone();
        let at = text.len() / 11 * (k + 1);
        let at = at + text[at..].iter().position(|b| *b == b'\n').unwrap_or(0) + 4;
        edited.insert_str_at(at, if k % 2 == 0 { "A " } else { "" });
        let t = Instant::now();
        inc = inc.update_owned(Arc::from(&edited[..]), &settings, syntax_only);
        times.push(t.elapsed());
    }
    println!("updates: {times:?}");
}

trait InsertAt {
    fn insert_str_at(&mut self, at: usize, s: &str);
}

impl InsertAt for Vec<u8> {
    fn insert_str_at(&mut self, at: usize, s: &str) {
        let tail = self.split_off(at.min(self.len()));
        self.extend_from_slice(s.as_bytes());
        self.extend_from_slice(&tail);
    }
}
