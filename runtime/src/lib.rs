//! Partscope runtime: interpreter, interpolator and motion planner. Pure: no IO.
