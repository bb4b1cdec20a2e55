//! Partscope runtime: interpreter, interpolator and motion planner. Pure: no IO.

pub mod machine;
pub mod plan;
