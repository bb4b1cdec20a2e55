//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Diagnostic;

use super::check::Cx;
use crate::interp::{is_cycle, is_group_1, letter_mask};

declare_rule! {
    /// ## What it does
    /// Flags (RS274/NGC) a D, H, I, J, L, P, Q or R word, or a `$` spindle selector, that no code of the line (or the modal motion) uses, and a `$` beyond the configured spindles (`machine.spindles`, default 1).
    ///
    ///
    /// Also flags axis words on a line with no motion code while no motion mode is
    /// active: after G80, or before the program's first G0/G1 (LinuxCNC starts in
    /// G80). G10, G28, G30, G52, G92 and G43.1/G43.2 on the line use them. The same
    /// words with an explicit G80 on the line are W004's.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses the line ("P word with no G2 G3 G4 … to use it") and stops the program; the word is usually a typo or belongs to another line.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1 P2
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G4 P2
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops as in LinuxCNC.
    ///
    /// Reported by W002, not this rule, when both see a D peck clearance LinuxCNC 2.9 does not accept on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC108, NGC110, NGC814
    pub static WORD_UNUSED = {
        code: "X008",
        name: "word-unused",
        summary: "A word that no code of the line uses",
        implements: &["NGC108", "NGC110", "NGC814"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// RS274/NGC: axis words with no code to take them, words no code of the line uses,
/// and `$` words.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    let modal = st.modal.motion;
    let gm = |codes: &[u32]| codes.iter().any(|c| w.has_g(*c));
    // Axis words with no motion code in the line while the modal motion is G80
    // (also at power on): LinuxCNC has nothing to give them to (enhance_block).
    // G10, G28, G30, G52 and G92 use them themselves; G43.1/G43.2 take them
    // as the offset.
    let group_1 = w.g().iter().any(|(g, _)| is_group_1(*g));
    if modal == 800
        && cx.motion.is_none()
        && !group_1
        && w.any_axis()
        && !gm(&[100, 280, 300, 520, 920, 431, 432])
    {
        let span = w.first_axis().map(|c| w.sp(c)).unwrap_or(cx.bspan);
        return Err(cx.out.err(
            &WORD_UNUSED,
            span,
            "cannot use axis values without a g code that uses them: no motion mode is active \
             (G80, or none yet since the program start), so LinuxCNC stops here; give G0 or G1 \
             on this line",
        ));
    }
    let mm = |codes: &[u32]| codes.iter().any(|c| w.has_m(*c));
    if w.has_any(letter_mask(b"DHIJLPQR")) {
        unused_words(cx)?;
    }
    if let Some(&(v, s)) = cx.items.dollar.first() {
        let takes = mm(&[30, 40, 50, 190, 510]) || gm(&[330, 331, 760, 950, 960, 970]);
        if !takes {
            return Err(cx.out.err(&WORD_UNUSED, s, "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G76, G95, G96 or G97 to use it: LinuxCNC stops here"));
        }
        let spindles = cx.input.machine.spindles.unwrap_or(1.0);
        if v != -1.0 && (v < 0.0 || v >= spindles || v.fract() != 0.0) {
            return Err(cx.out.err(&WORD_UNUSED, s, format!("${v} selects a spindle this machine does not have (spindles 0 to {}, or $-1 for all): LinuxCNC stops here", spindles - 1.0)));
        }
    }
    Ok(())
}

/// D, H, I, J, L, P, Q and R words that no code of the line uses (LinuxCNC's check
/// of other codes).
fn unused_words(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let w = cx.w;
    let gm = |codes: &[u32]| codes.iter().any(|c| w.has_g(*c));
    let mm = |codes: &[u32]| codes.iter().any(|c| w.has_m(*c));
    let user_m = w.m.iter().any(|(m, _)| (1000..=1990).contains(m));
    let mode = cx.motion_mode();
    let lathe_cycle = gm(&[700, 710, 711, 712, 720, 721, 722]);
    let cycle = is_cycle(mode);
    let unused: [(u8, bool, &str); 8] = [
        (b'D', gm(&[410, 411, 420, 421, 960]) || lathe_cycle, "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it"),
        (b'H', gm(&[430, 432, 760]), "H word with no G43 or G76 to use it"),
        (b'I', matches!(mode, 20 | 30 | 50 | 51 | 870 | 331 | 760) || gm(&[100, 710, 711, 712, 720, 721, 722]), "I word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it"),
        (b'J', matches!(mode, 20 | 30 | 50 | 51 | 870 | 331 | 760) || gm(&[100]), "J word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it"),
        (b'L', cycle || matches!(mode, 20 | 30 | 52 | 760) || gm(&[100, 410, 411, 420, 421]) || mm(&[660, 980]) || lathe_cycle, "L word with no G10, cutter compensation, canned cycle, digital/analog input, M98 or NURBS code"),
        (b'P', cycle || matches!(mode, 20 | 30 | 50 | 52 | 760) || gm(&[40, 100, 640]) || mm(&[190, 500, 510, 520, 530, 620, 630, 640, 650, 660, 980]) || user_m || lathe_cycle, "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 M63 M64 M65 M66 M98 or user M code to use it"),
        (b'Q', cycle || matches!(mode, 50 | 760) || gm(&[100, 640]) || mm(&[190, 610, 660, 670, 680]) || user_m || lathe_cycle, "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that uses it"),
        (b'R', cycle || matches!(mode, 20 | 30 | 760) || gm(&[100]) || mm(&[190]) || lathe_cycle, "R word with no g code that uses it"),
    ];
    for (c, used, msg) in unused {
        if w.has(c) && !used {
            return Err(cx.out.err(
                &WORD_UNUSED,
                w.sp(c),
                format!(
                    "{msg}: LinuxCNC stops here; remove the word or add the code it belongs to"
                ),
            ));
        }
    }
    Ok(())
}
