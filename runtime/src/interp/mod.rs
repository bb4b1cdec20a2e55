//! The interpreter: executes blocks of one dialect, tracking modal state,
//! coordinates, offsets, parameters, subprograms and canned cycles, and emits
//! motions, events, per-block snapshots, flow-sensitive diagnostics and (for
//! RS274/NGC) LinuxCNC canonical lines.
//!
//! Pure and bounded: files come through [`Resolver`], a step budget stops
//! runaway loops and a depth limit stops runaway recursion.

pub mod arc;
mod exec;
pub mod exponential;
pub mod expr;
pub mod files;
pub mod frame;
pub mod involute;
mod machine_cfg;
pub mod ndc;
pub mod rotary_feed;
mod state;
pub mod tcp;
mod types;
pub mod values;

pub use exec::{
    not_run_in_windows, rerun, run, run_checkpointed, run_checkpointed_observed,
    run_checkpointed_recording, run_streaming, run_streaming_owned, run_windowed,
    run_windowed_owned, run_with_snapshots, Checkpoints, MainFileFacts, MotionObserver, MotionSink,
    NextWindow, OwnedMotionSink, SNAPSHOT_LIMIT, STOP_SUFFIX,
};
pub use state::{Modal, State};
// What the rule checks in `crate::rules` read (`rules::check::Cx`).
pub(crate) use exec::{dist, letter_mask, target_of, tool_diameter_of, unit_of, Words};
pub(crate) use machine_cfg::MachineCfg;
pub(crate) use state::{is_cycle, is_group_1, moves_to_axis_words};
pub use types::*;
