//! Clocked modules, their hierarchy and the visitor that tracing and checks walk it with.

use super::signal::{Reg, Signal};
use crate::fx::Narrowing;

/// What a traced signal is to its module.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Dir {
    /// Driven from outside the module.
    Input,
    /// Driven by the module.
    Output,
    /// A register's current value.
    Reg,
    /// An internal combinational value worth seeing.
    Wire,
}

/// Walks a module hierarchy: every instance, then every port, register and wire in it.
///
/// Tracing, the schedule check and any other tool that needs to see "every signal" use this,
/// so a signal is declared once (in [`Module::visit`]) and appears everywhere.
pub trait Visitor {
    /// Enters an instance `instance` of module type `kind`.
    fn enter(&mut self, instance: &str, kind: &str);
    /// Leaves the instance entered last.
    fn leave(&mut self);
    /// A signal of the current instance.
    fn signal(&mut self, dir: Dir, s: &Signal);
    /// A register of the current instance: its current value `q` (what is traced) and the
    /// next value its edge will commit.
    fn register(&mut self, q: &Signal, next: u64) {
        let _ = next;
        self.signal(Dir::Reg, q);
    }
    /// A [`Reg`] of the current instance, visited as [`Visitor::register`].
    fn reg(&mut self, r: &Reg) {
        self.register(r.q(), r.next_bits());
    }
    /// A named narrowing of the current instance: for numeric coverage; by default its
    /// overflow flag is a wire of the instance (so tracing shows it).
    fn narrowing(&mut self, n: &Narrowing) {
        self.signal(Dir::Wire, n.flag());
    }
}

/// A clocked hardware module in two-process style.
///
/// * [`eval`](Module::eval) is the combinational process: from the inputs and the registers'
///   current values it computes the outputs and the registers' next values. It must not change
///   any register's current value, and evaluating it twice must give the same result (the
///   simulator checks this when asked: see [`crate::kernel::Sim::check_schedule`]).
/// * [`tick`](Module::tick) is the clock edge: every register commits its next value, or its
///   reset value when the synchronous reset is asserted.
///
/// A parent module's `eval` is the static schedule of its children: it copies its inputs to
/// the children's inputs and evaluates them in dataflow order, each exactly once. Everything is
/// static dispatch, so the compiler inlines across module boundaries.
pub trait Module {
    /// The instance name (unique among its siblings); by default the kind's (a numbered unit
    /// is named after its kind: `blend_adjust_153`).
    fn instance(&self) -> &str {
        self.kind()
    }
    /// The module type's name, e.g. `blend_adjust`.
    fn kind(&self) -> &'static str;
    /// Combinational process.
    fn eval(&mut self);
    /// Clock edge with synchronous reset.
    fn tick(&mut self, reset: bool);
    /// Declares the instance's signals and children: call `v.enter`, list every port and
    /// register, visit the children, `v.leave`.
    fn visit(&self, v: &mut dyn Visitor);
    /// The bits of every signal [`Module::visit`] lists, in the same order: what a tracer
    /// samples and the schedule check compares each cycle. By default it walks `visit`;
    /// `#[derive(Module)]` writes it field by field, statically dispatched, so a tracer's
    /// per-signal work inlines into one loop-free pass over the design.
    #[inline]
    fn visit_bits<F: FnMut(u64)>(&self, f: &mut F)
    where
        Self: Sized,
    {
        self.visit(&mut BitsOf(f));
    }
}

/// A visitor handing each signal's bits to a function: the default [`Module::visit_bits`],
/// and the default of the declared traits' `bits_*` methods.
pub struct BitsOf<'a, F>(pub &'a mut F);

impl<F: FnMut(u64)> Visitor for BitsOf<'_, F> {
    fn enter(&mut self, _: &str, _: &str) {}
    fn leave(&mut self) {}
    #[inline]
    fn signal(&mut self, _: Dir, s: &Signal) {
        (self.0)(s.bits());
    }
}

/// Lists signals of a module for [`Module::visit`]:
/// `signals!(v; Input: self.a, self.b; Output: self.y; Reg: self.r)`.
#[macro_export]
macro_rules! signals {
    ($v:expr; $($dir:ident : $($s:expr),+ );+ $(;)?) => {
        $( $( $crate::signals!(@one $v, $dir, $s); )+ )+
    };
    (@one $v:expr, Reg, $s:expr) => { $v.reg(&$s) };
    (@one $v:expr, $dir:ident, $s:expr) => { $v.signal($crate::kernel::Dir::$dir, &$s) };
}

/// The check behind a clock enable (`#[module(enable = ...)]`), run by the derived edge in
/// debug builds each time the enable skips it: no register below `m` (a [`Reg`] or a
/// `RegOf`; a `Regs` type of your own commits as its `tick_regs` says) may hold a next value
/// other than its current one. `eval` writing a register while its module's enable is low
/// would have that write commit at some later edge, silently; this panics instead, naming the
/// register.
pub fn check_gated_edge(m: &dyn Module) {
    /// Counts signals in visit order up to the first register with a pending next value.
    #[derive(Default)]
    struct Pending {
        seen: usize,
        found: Option<(usize, u64, u64)>,
    }
    impl Visitor for Pending {
        fn enter(&mut self, _: &str, _: &str) {}
        fn leave(&mut self) {}
        fn signal(&mut self, _: Dir, _: &Signal) {
            self.seen += 1;
        }
        fn register(&mut self, q: &Signal, next: u64) {
            if self.found.is_none() && next != q.bits() {
                self.found = Some((self.seen, q.bits(), next));
            }
            self.seen += 1;
        }
    }
    let mut p = Pending::default();
    m.visit(&mut p);
    if let Some((i, q, next)) = p.found {
        let path = super::signal_paths(m).swap_remove(i);
        panic!(
            "clock enable of '{}': the edge was skipped while '{path}' holds {q:#x} with the \
             next value {next:#x} pending (eval wrote it while the enable was low; it would \
             commit at a later edge)",
            m.instance()
        );
    }
}
