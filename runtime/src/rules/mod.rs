//! Flow-sensitive rules: their metadata (one file per rule, same doc format
//! as the analyzer's static rules) and, for the rules that look at a block
//! against the state before it, the check beside the doc (a function over
//! `check::Cx`, called in order from `interp/checks.rs`). The other rules are
//! part of executing the block, in the interpreter. Every diagnostic is made from
//! its rule's static (`ZERO_FEED.error(span, msg)`, `cx.out.diag(&ZERO_FEED, …)`),
//! so the code it carries is the one the rule declares
//! (`runtime/tests/rule_codes.rs` checks).

use analyzer::rules::RuleMeta;

/// The rule of a run stopped by its step, motion or output budget.
pub use step_budget::STEP_BUDGET;

pub(crate) mod after_end;
pub(crate) mod arc_corrected;
pub(crate) mod arc_ill_conditioned;
pub(crate) mod arc_no_center;
pub(crate) mod arc_polar_ijk;
pub(crate) mod arc_radius_mismatch;
pub(crate) mod arc_radius_too_small;
pub(crate) mod arc_same_end_r;
pub(crate) mod arc_uvw_plane;
pub(crate) mod arc_words;
pub(crate) mod call_depth;
pub(crate) mod check;
pub(crate) mod comp_conflict;
pub(crate) mod comp_motion;
pub(crate) mod context_restore;
pub(crate) mod coord_during_rotation;
pub(crate) mod coordinate_mode;
pub(crate) mod cycle_hygiene;
pub(crate) mod cycle_missing;
pub(crate) mod cycle_q;
pub(crate) mod cycle_spindle;
pub(crate) mod cycle_state;
pub(crate) mod cycle_still_active;
pub(crate) mod dlacc_incompatible;
pub(crate) mod dlacc_tcp;
pub(crate) mod expression;
pub(crate) mod feed_spindle_off;
pub(crate) mod flow;
pub(crate) mod interp;
pub(crate) mod inverse_time;
pub(crate) mod involute;
pub(crate) mod lathe_cycle;
pub(crate) mod macro_alarm;
pub(crate) mod missing_end;
pub(crate) mod mode_left_on;
pub(crate) mod no_effect;
pub(crate) mod nurbs_block;
pub(crate) mod offset_number;
pub(crate) mod polar_interp;
pub(crate) mod probe_state;
pub(crate) mod rapid_no_motion;
pub(crate) mod rigid_tap;
pub(crate) mod rigid_tap_feed;
pub(crate) mod rotary_only_feed;
pub(crate) mod scaling_magnification;
pub(crate) mod smoothing_time;
pub(crate) mod spindle_stopped;
pub(crate) mod step_budget;
pub(crate) mod sub_not_found;
pub(crate) mod subprogram_file;
pub(crate) mod thread_lead;
pub(crate) mod tlc_type;
pub(crate) mod tool_offset_state;
pub(crate) mod tool_table;
pub(crate) mod travel_limit;
pub(crate) mod trc_lookahead;
pub(crate) mod unknown_code;
pub(crate) mod unknown_tool;
pub(crate) mod unknown_user_m;
pub(crate) mod vacant_read;
pub(crate) mod vacant_word;
pub(crate) mod var_file;
pub(crate) mod word_unused;
pub(crate) mod zero_feed;

/// Metadata of every runtime rule, in code order.
pub static REGISTRY: &[&RuleMeta] = &[
    &arc_radius_mismatch::ARC_RADIUS_MISMATCH,
    &arc_radius_too_small::ARC_RADIUS_TOO_SMALL,
    &arc_corrected::ARC_CORRECTED_R,
    &arc_corrected::ARC_CORRECTED_IJK,
    &arc_no_center::ARC_NO_CENTER,
    &arc_same_end_r::ARC_SAME_END_R,
    &arc_polar_ijk::ARC_POLAR_IJK,
    &zero_feed::ZERO_FEED,
    &sub_not_found::SUB_NOT_FOUND,
    &call_depth::CALL_DEPTH,
    &step_budget::STEP_BUDGET,
    &after_end::AFTER_END,
    &missing_end::MISSING_END,
    &flow::FLOW,
    &unknown_tool::UNKNOWN_TOOL,
    &cycle_missing::CYCLE_MISSING,
    &cycle_q::CYCLE_Q,
    &cycle_state::CYCLE_STATE,
    &rigid_tap::RIGID_TAP,
    &dlacc_incompatible::DLACC_INCOMPATIBLE,
    &dlacc_tcp::DLACC_TCP,
    &coord_during_rotation::COORD_DURING_ROTATION,
    &travel_limit::TRAVEL_LIMIT,
    &expression::EXPRESSION,
    &unknown_code::UNKNOWN_CODE,
    &interp::INTERP,
    &macro_alarm::MACRO_ALARM,
    &vacant_word::VACANT_WORD,
    &no_effect::NO_EFFECT,
    &arc_ill_conditioned::ARC_ILL_CONDITIONED,
    &arc_words::ARC_WORDS,
    &probe_state::PROBE_STATE,
    &comp_motion::COMP_MOTION,
    &coordinate_mode::COORDINATE_MODE,
    &tool_offset_state::TOOL_OFFSET_STATE,
    &cycle_hygiene::CYCLE_HYGIENE,
    &comp_conflict::COMP_CONFLICT,
    &cycle_spindle::CYCLE_SPINDLE,
    &spindle_stopped::SPINDLE_STOPPED,
    &inverse_time::INVERSE_TIME,
    &mode_left_on::MODE_LEFT_ON,
    &word_unused::WORD_UNUSED,
    &unknown_user_m::UNKNOWN_USER_M,
    &context_restore::CONTEXT_RESTORE,
    &nurbs_block::NURBS_BLOCK,
    &lathe_cycle::LATHE_CYCLE,
    &arc_uvw_plane::ARC_UVW_PLANE,
    &rapid_no_motion::RAPID_NO_MOTION,
    &feed_spindle_off::FEED_SPINDLE_OFF,
    &cycle_still_active::CYCLE_STILL_ACTIVE,
    &tlc_type::TLC_TYPE,
    &smoothing_time::SMOOTHING_TIME,
    &rotary_only_feed::ROTARY_ONLY_FEED,
    &trc_lookahead::TRC_LOOKAHEAD,
    &subprogram_file::SUBPROGRAM_FILE,
    &vacant_read::VACANT_READ,
    &involute::INVOLUTE,
    &polar_interp::POLAR_INTERP,
    &thread_lead::THREAD_LEAD,
    &rigid_tap_feed::RIGID_TAP_FEED,
    &offset_number::OFFSET_NUMBER,
    &scaling_magnification::SCALING_MAGNIFICATION,
    &tool_table::TOOL_TABLE,
    &var_file::VAR_FILE,
];

/// Looks a runtime rule up by code or name.
pub fn lookup(code: &str) -> Option<&'static RuleMeta> {
    REGISTRY
        .iter()
        .copied()
        .find(|r| r.code.eq_ignore_ascii_case(code) || r.name.eq_ignore_ascii_case(code))
}
