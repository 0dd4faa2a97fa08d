//! The RTL kernel: signals with declared formats, registers, two-process clocked modules,
//! hierarchy, and a cycle-based simulator.
//!
//! The design follows what makes cycle simulators fast (Verilator's choices): the schedule is
//! fixed in code (each parent's `eval` evaluates its children in dataflow order), values are
//! plain machine integers, every call is statically dispatched, nothing allocates per cycle,
//! and tracing is a single branch when it is off.

pub mod declared;
mod delay;
mod mem;
mod module;
mod signal;
mod sim;
mod stream;
mod typed;

pub use delay::Delay;
pub use mem::{Mem, MAX_SHOWN_WORDS};
pub use module::{check_gated_edge, BitsOf, Dir, Module, Visitor};
pub use signal::{Reg, Signal};
pub use sim::{
    instances, narrowings, panicked_in_cycle, signal_dirs, signal_paths, NoTrace, Sim, Trace,
};
pub use stream::{Payload, Stream};
/// Derives [`declared::Children`] for a group of sub-modules without a scope of its own.
pub use texrtl_hdl_derive::Group;
/// Derives [`Module`] from fields marked `#[input]`, `#[output]`, `#[wire]`, `#[reg]`,
/// `#[child]` (see [`declared`]); the behaviour is the type's own `fn eval(&mut self)`.
///
/// A register, signal, memory, delay line, narrowing or stream cannot be forgotten: a field
/// holding one (or an array, vector, option or tuple of them) without a mark does not compile,
/// since it would be neither committed at the edge, traced nor schedule-checked.
///
/// ```compile_fail
/// use hdl::kernel::{Module, Reg, Signal};
/// #[derive(Module)]
/// #[module(kind = "count")]
/// struct Count {
///     #[output]
///     q: Signal,
///     #[reg]
///     n: Reg,
///     carry: Reg, // added, but not marked
/// }
/// # impl Count { fn eval(&mut self) {} }
/// ```
///
/// ```compile_fail
/// use hdl::kernel::{Module, Reg, Signal};
/// #[derive(Module)]
/// #[module(kind = "count")]
/// struct Count {
///     #[output]
///     q: Signal,
///     taps: Vec<[Reg; 2]>, // the same inside a collection
/// }
/// # impl Count { fn eval(&mut self) {} }
/// ```
///
/// `#[skip]` leaves one out on purpose (and anything that is not the kernel's needs no mark):
///
/// ```
/// use hdl::kernel::{Module, Reg, Signal};
/// #[derive(Module)]
/// #[module(kind = "count")]
/// struct Count {
///     #[output]
///     q: Signal,
///     #[skip]
///     spare: Option<Reg>,
///     limit: u32,
/// }
/// # impl Count { fn eval(&mut self) {} }
/// ```
pub use texrtl_hdl_derive::Module;
/// Derives [`declared::Regs`] for a register bundle, a struct of registers ticked and visited
/// field by field.
pub use texrtl_hdl_derive::Regs;
/// Derives [`declared::Signals`] for a port bundle, a struct of signals visited field by field.
pub use texrtl_hdl_derive::Signals;
pub use typed::{Declare, DeclareTyped, RegOf, SignalOf};

#[cfg(test)]
mod tests;
