//! Partscope runtime: interpreter, interpolator and motion planner. Pure: no IO.

#![forbid(unsafe_code)]

pub mod canon;
pub mod dryrun;
pub mod interp;
pub mod machine;
pub mod plan;
pub mod rules;

pub use interp::{default_motion_budget, default_step_budget};
pub use interp::{
    rerun, run, run_checkpointed, run_streaming, run_streaming_owned, run_with_snapshots,
    BlockSnapshot, Checkpoints, Event, EventKind, Motion, MotionKind, NoResolver, ResolvedFile,
    Resolver, RunInput, RunOutput, Stopped, CANCEL_POLL_STEPS, CANON_FILE_NAME,
};
// Editors ask a run for the values its expressions took (`interp::values`).
pub use interp::values::{ValueLimits, ValueRecord, ValueSeries};
pub use interp::{run_checkpointed_observed, run_checkpointed_recording};
