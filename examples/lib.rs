//! The worked examples of texrtl's user guide (see the README): `cargo run --example
//! saturating_accumulator` models a unit of your own, checks it against a golden model with a
//! testbench of the framework, and writes its waveform.
