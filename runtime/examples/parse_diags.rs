//! Prints the parser's diagnostics for an RS274/NGC file (developer aid).
fn main() {
    let path = std::env::args().nth(1).unwrap_or_default();
    let text = std::fs::read(&path).unwrap_or_default();
    let settings = analyzer::Settings::new(analyzer::Dialect::Rs274ngc);
    let a = analyzer::analyze(text, &settings);
    for d in a.program.diagnostics {
        println!("{} {:?} {} {:?}", d.code, d.severity, d.message, d.span);
    }
}
