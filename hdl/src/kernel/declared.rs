//! What `#[derive(Module)]` ticks and visits: a field marked `#[input]`, `#[output]` or
//! `#[wire]` is [`Signals`], `#[reg]` [`Regs`], `#[child]` [`Children`], `#[narrow]`
//! [`Narrowings`]; each is one item or a
//! collection of them (an array, a `Vec`, an `Option` of registers or children), so a bank of
//! registers or of sub-units is declared with one attribute, with no index kept in step by
//! hand. A port bundle (a struct of signals) is `Signals` by `#[derive(Signals)]`.

use super::module::{Dir, Module, Visitor};
use super::signal::{Reg, Signal};
use crate::fx::Narrowing;

/// Signals a module visits with one direction.
pub trait Signals {
    /// Visits every signal, in order.
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor);
}

impl Signals for Signal {
    #[inline]
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        v.signal(dir, self);
    }
}

impl<T: Signals, const N: usize> Signals for [T; N] {
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        self.iter().for_each(|s| s.visit_signals(dir, v));
    }
}

impl<T: Signals> Signals for Vec<T> {
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        self.iter().for_each(|s| s.visit_signals(dir, v));
    }
}

/// Ports a configuration may leave out (a trilinear unit's second level): visited when present.
impl<T: Signals> Signals for Option<T> {
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        self.iter().for_each(|s| s.visit_signals(dir, v));
    }
}

/// Registers: committed at the clock edge, visited as registers.
pub trait Regs {
    /// The clock edge of every register.
    fn tick_regs(&mut self, reset: bool);
    /// Visits every register, in order.
    fn visit_regs(&self, v: &mut dyn Visitor);
}

impl Regs for Reg {
    #[inline]
    fn tick_regs(&mut self, reset: bool) {
        self.tick(reset);
    }
    #[inline]
    fn visit_regs(&self, v: &mut dyn Visitor) {
        v.reg(self);
    }
}

/// Named narrowings ([`Narrowing`]): visited for numeric coverage (and their overflow flags
/// traced), never ticked.
pub trait Narrowings {
    /// Visits every narrowing, in order.
    fn visit_narrowings(&self, v: &mut dyn Visitor);
}

impl Narrowings for Narrowing {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        v.narrowing(self);
    }
}

impl<F: crate::fx::Fmt> Narrowings for crate::fx::NarrowingOf<F> {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        v.narrowing(self);
    }
}

impl<T: Narrowings, const N: usize> Narrowings for [T; N] {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        self.iter().for_each(|n| n.visit_narrowings(v));
    }
}

impl<T: Narrowings> Narrowings for Vec<T> {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        self.iter().for_each(|n| n.visit_narrowings(v));
    }
}

/// Child modules: their clock edge and their hierarchy.
pub trait Children {
    /// The clock edge of every child.
    fn tick_children(&mut self, reset: bool);
    /// Visits every child, in order.
    fn visit_children(&self, v: &mut dyn Visitor);
}

impl<M: Module> Children for M {
    #[inline]
    fn tick_children(&mut self, reset: bool) {
        self.tick(reset);
    }
    fn visit_children(&self, v: &mut dyn Visitor) {
        self.visit(v);
    }
}

/// `$trait` for arrays, `Vec`s and `Option`s of `$bound`: each item (an `Option` holds none
/// or one) ticked by `$tick` and visited by `$visit`, in order.
macro_rules! collections {
    ($trait:ident, $bound:ident, $tick_fn:ident => $tick:ident, $visit_fn:ident => $visit:ident) => {
        collections!(@one [T: $bound, const N: usize] [T; N], $trait, $tick_fn => $tick, $visit_fn => $visit);
        collections!(@one [T: $bound] Vec<T>, $trait, $tick_fn => $tick, $visit_fn => $visit);
        collections!(@one [T: $bound] Option<T>, $trait, $tick_fn => $tick, $visit_fn => $visit);
    };
    (@one [$($g:tt)*] $ty:ty, $trait:ident, $tick_fn:ident => $tick:ident, $visit_fn:ident => $visit:ident) => {
        impl<$($g)*> $trait for $ty {
            #[inline]
            fn $tick_fn(&mut self, reset: bool) {
                for x in self.iter_mut() {
                    x.$tick(reset);
                }
            }
            fn $visit_fn(&self, v: &mut dyn Visitor) {
                for x in self.iter() {
                    x.$visit(v);
                }
            }
        }
    };
}

collections!(Regs, Regs, tick_regs => tick_regs, visit_regs => visit_regs);
collections!(Children, Children, tick_children => tick_children, visit_children => visit_children);
