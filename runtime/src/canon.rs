//! LinuxCNC canonical-machining-function output, in the format the standalone
//! `rs274` driver prints (without its output-line counter): one line per
//! call, ` N..... NAME(args)` (or ` N10    NAME(args)` when the block had an
//! N word), reals with four decimals, coordinates in program units and in
//! the current coordinate system.

/// Collects canonical lines.
#[derive(Debug, Clone, Default)]
pub struct Canon {
    pub lines: Vec<String>,
    /// The N word of the block being executed, as written (`0010`).
    pub line_number: Option<String>,
}

/// `%.4f`.
pub fn f4(v: f64) -> String {
    format!("{v:.4}")
}

impl Canon {
    fn prefix(&self) -> String {
        match &self.line_number {
            Some(n) => format!(" N{n:<6}"),
            None => " N..... ".to_string(),
        }
    }

    /// The ` N….. ` prefix of the current block.
    pub fn current_prefix(&self) -> String {
        self.prefix()
    }

    /// Emits one call line.
    pub fn call(&mut self, text: impl AsRef<str>) {
        let line = format!("{}{}", self.prefix(), text.as_ref());
        self.lines.push(line);
    }

    /// Emits a raw line (no prefix), as `(print,…)` does.
    pub fn raw(&mut self, text: impl Into<String>) {
        self.lines.push(text.into());
    }

    pub fn six(v: &[f64; 6]) -> String {
        v.iter().map(|x| f4(*x)).collect::<Vec<_>>().join(", ")
    }

    pub fn preamble(&mut self, g5x_index: usize, g5x: &[f64; 6], g92: &[f64; 6], rotation: f64) {
        self.call("USE_LENGTH_UNITS(CANON_UNITS_MM)");
        self.call(format!(
            "SET_G5X_OFFSET({}, {})",
            g5x_index,
            Canon::six(g5x)
        ));
        self.call(format!("SET_G92_OFFSET({})", Canon::six(g92)));
        self.call(format!("SET_XY_ROTATION({})", f4(rotation)));
        self.call("SET_FEED_REFERENCE(CANON_XYZ)");
        self.call("ON_RESET()");
    }

    pub fn comment(&mut self, text: &str) {
        self.call(format!("COMMENT(\"{text}\")"));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prefixes() {
        let mut c = Canon::default();
        c.call("ON_RESET()");
        c.line_number = Some("10".into());
        c.call("ON_RESET()");
        assert_eq!(
            c.lines,
            vec![
                " N..... ON_RESET()".to_string(),
                " N10    ON_RESET()".to_string()
            ]
        );
        assert_eq!(f4(-0.00001), "-0.0000");
    }
}
