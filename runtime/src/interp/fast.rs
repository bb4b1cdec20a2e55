//! The fast path for plain motion blocks: RS274/NGC lines that hold only X, Y, Z
//! and F numbers under a modal G0 or G1, the bulk of CAM output. Such a line needs
//! none of the general executor's code, mode, comment, call and stop handling, so it
//! builds its words straight from the items, runs the same state checks and moves.
//!
//! Every precondition below names a piece of `exec_block`/`exec_words` that would
//! act on the line; anything else goes the general way. The differential test
//! `runtime/tests/fast_path.rs` runs both paths over the conformance programs.

use analyzer::syntax::Item;

use super::*;

impl Interp<'_, '_> {
    /// Runs `items` (the non-empty items of the current block) if the block qualifies;
    /// `None` leaves it to the general path, with nothing changed.
    pub(super) fn fast_motion_block(
        &mut self,
        items: &[Item],
        bspan: Span,
    ) -> Option<Result<Flow, Diagnostic>> {
        if !self.fast_path
            || self.dialect != Dialect::Rs274ngc
            || self.canon.is_some()
            || self.st.ended
            || !matches!(self.st.modal.motion, 0 | 10)
            // Cutter compensation holds moves back and offsets them.
            || self.st.modal.comp != 400
            // Inverse time and per-revolution feeds read F differently.
            || self.st.modal.feed_mode != 940
            // Diameter mode halves X as the line is read.
            || self.st.modal.diameter
            || self.st.g66.is_some()
        {
            return None;
        }
        // Taken out of `self` for the call (an `Option` move, no allocation).
        let mut w = self.fast_words.take().unwrap_or_default();
        let r = if fill_plain_words(&mut w, items) {
            Some(self.fast_motion(&w, bspan))
        } else {
            None
        };
        // Only these four letters are ever written here; everything else in the
        // kept words stays as `Words::default()` left it.
        for c in [b'X', b'Y', b'Z', b'F'] {
            let i = (c - b'A') as usize;
            w.v[i] = None;
            w.span[i] = Span::default();
            w.point[i] = false;
        }
        self.fast_words = Some(w);
        r
    }

    /// What `exec_block` and `exec_words` do with a qualifying line, in their order.
    fn fast_motion(&mut self, w: &Words, bspan: Span) -> Result<Flow, Diagnostic> {
        self.inv_rate_set = false;
        self.block_exact = false;
        self.plain_motion_checks(w, bspan);
        if let Some(f) = w.get(b'F') {
            self.st.feed = f * self.unit();
        }
        let t = self.target(w);
        if self.st.modal.motion == 0 {
            self.rapid_to(t);
        } else {
            self.feed_to(t, bspan)?;
        }
        Ok(Flow::Next)
    }
}

/// Reads a plain motion line's words into `w` (whose X, Y, Z and F are empty):
/// false when the line is not one (another item or letter, a repeated letter, an
/// expression, no axis word), with possibly some of the four letters written.
fn fill_plain_words(w: &mut Words, items: &[Item]) -> bool {
    let mut axes = false;
    for it in items {
        let ItemKind::Word(word) = &it.kind else {
            return false;
        };
        let WordValue::Num(n) = word.value else {
            return false;
        };
        if word.comma {
            return false;
        }
        let c = word.letter;
        if !matches!(c, b'X' | b'Y' | b'Z' | b'F') {
            return false;
        }
        let i = (c - b'A') as usize;
        // A repeated letter: the general path decides which one counts.
        if w.v[i].is_some() {
            return false;
        }
        axes |= c != b'F';
        w.v[i] = Some(n.value);
        w.span[i] = it.span;
        w.point[i] = n.has_point;
    }
    axes
}
