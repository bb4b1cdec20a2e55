//! Flow-sensitive rules: their metadata (one file per rule, same doc format
//! as the analyzer's static rules), the codes the interpreter emits and, for the
//! rules that look at a block against the state before it, the check beside the
//! doc (a function over `check::Cx`, called in order from `interp/checks.rs`).
//! The other rules are part of executing the block, in the interpreter.

use analyzer::rules::RuleMeta;

mod after_end;
mod arc_corrected;
mod arc_ill_conditioned;
mod arc_no_center;
mod arc_polar_ijk;
mod arc_radius_mismatch;
mod arc_radius_too_small;
mod arc_same_end_r;
pub(crate) mod arc_uvw_plane;
pub(crate) mod arc_words;
mod call_depth;
pub(crate) mod check;
pub(crate) mod comp_conflict;
pub(crate) mod comp_motion;
pub(crate) mod context_restore;
mod coord_during_rotation;
pub(crate) mod coordinate_mode;
pub(crate) mod cycle_hygiene;
mod cycle_missing;
mod cycle_q;
mod cycle_spindle;
mod cycle_state;
pub(crate) mod cycle_still_active;
mod dlacc_incompatible;
mod dlacc_tcp;
mod expression;
pub(crate) mod feed_spindle_off;
mod flow;
mod interp;
pub(crate) mod inverse_time;
pub(crate) mod involute;
pub(crate) mod lathe_cycle;
mod macro_alarm;
mod missing_end;
pub(crate) mod mode_left_on;
pub(crate) mod no_effect;
pub(crate) mod nurbs_block;
pub(crate) mod offset_number;
pub(crate) mod polar_interp;
pub(crate) mod probe_state;
pub(crate) mod rapid_no_motion;
mod rigid_tap;
pub(crate) mod rigid_tap_feed;
pub(crate) mod rotary_only_feed;
pub(crate) mod scaling_magnification;
pub(crate) mod smoothing_time;
pub(crate) mod spindle_stopped;
mod step_budget;
mod sub_not_found;
pub(crate) mod subprogram_file;
pub(crate) mod thread_lead;
pub(crate) mod tlc_type;
pub(crate) mod tool_offset_state;
pub(crate) mod tool_table;
mod travel_limit;
pub(crate) mod trc_lookahead;
mod unknown_code;
mod unknown_tool;
pub(crate) mod unknown_user_m;
pub(crate) mod vacant_read;
mod vacant_word;
pub(crate) mod var_file;
pub(crate) mod word_unused;
mod zero_feed;

/// Diagnostic codes emitted by the interpreter.
pub mod codes {
    pub const ARC_RADIUS_MISMATCH: &str = "A001";
    pub const ARC_RADIUS_TOO_SMALL: &str = "A002";
    pub const ARC_CORRECTED_R: &str = "A003";
    pub const ARC_CORRECTED_IJK: &str = "A004";
    pub const ARC_NO_CENTER: &str = "A005";
    pub const ARC_SAME_END_R: &str = "A006";
    pub const ARC_POLAR_IJK: &str = "A007";
    pub const ZERO_FEED: &str = "F001";
    pub const SUB_NOT_FOUND: &str = "F002";
    pub const CALL_DEPTH: &str = "F003";
    pub const STEP_BUDGET: &str = "F004";
    pub const AFTER_END: &str = "F005";
    pub const MISSING_END: &str = "F006";
    pub const FLOW: &str = "F007";
    pub const UNKNOWN_TOOL: &str = "T001";
    pub const CYCLE_MISSING: &str = "C001";
    pub const CYCLE_Q: &str = "C002";
    pub const CYCLE_STATE: &str = "C003";
    pub const RIGID_TAP: &str = "C004";
    pub const DLACC_INCOMPATIBLE: &str = "D001";
    pub const DLACC_TCP: &str = "D002";
    pub const COORD_DURING_ROTATION: &str = "K001";
    pub const TRAVEL_LIMIT: &str = "K002";
    pub const EXPRESSION: &str = "X001";
    pub const UNKNOWN_CODE: &str = "X002";
    pub const INTERP: &str = "X003";
    pub const MACRO_ALARM: &str = "X004";
    pub const VACANT_WORD: &str = "X005";
    pub const NO_EFFECT: &str = "F012";
    pub const ARC_ILL_CONDITIONED: &str = "A009";
    pub const ARC_WORDS: &str = "A008";
    pub const PROBE_STATE: &str = "F011";
    pub const COMP_MOTION: &str = "T004";
    pub const COORDINATE_MODE: &str = "K003";
    pub const TOOL_OFFSET_STATE: &str = "T003";
    pub const CYCLE_HYGIENE: &str = "C006";
    pub const COMP_CONFLICT: &str = "T002";
    pub const CYCLE_SPINDLE: &str = "C005";
    pub const SPINDLE_STOPPED: &str = "F010";
    pub const INVERSE_TIME: &str = "F009";
    pub const MODE_LEFT_ON: &str = "F008";
    pub const WORD_UNUSED: &str = "X008";
    pub const UNKNOWN_USER_M: &str = "X009";
    pub const CONTEXT_RESTORE: &str = "F013";
    pub const NURBS_BLOCK: &str = "A010";
    pub const LATHE_CYCLE: &str = "C007";
    pub const ARC_UVW_PLANE: &str = "A011";
    pub const RAPID_NO_MOTION: &str = "F014";
    pub const FEED_SPINDLE_OFF: &str = "F015";
    pub const CYCLE_STILL_ACTIVE: &str = "C008";
    pub const TLC_TYPE: &str = "T005";
    pub const SMOOTHING_TIME: &str = "D003";
    pub const ROTARY_ONLY_FEED: &str = "F016";
    pub const TRC_LOOKAHEAD: &str = "T006";
    pub const SUBPROGRAM_FILE: &str = "F017";
    pub const VACANT_READ: &str = "X010";
    pub const INVOLUTE: &str = "A012";
    pub const POLAR_INTERP: &str = "K004";
    pub const THREAD_LEAD: &str = "F018";
    pub const RIGID_TAP_FEED: &str = "C009";
    pub const OFFSET_NUMBER: &str = "T007";
    pub const SCALING_MAGNIFICATION: &str = "K005";
    pub const TOOL_TABLE: &str = "T008";
    pub const VAR_FILE: &str = "X011";
}

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
