//! What `#[derive(Module)]` ticks and visits: a field marked `#[input]`, `#[output]` or
//! `#[wire]` is [`Signals`], `#[reg]` [`Regs`], `#[child]` [`Children`], `#[narrow]`
//! [`Narrowings`]; each is one item or a
//! collection of them (an array, a `Vec`, an `Option` of registers or children), so a bank of
//! registers or of sub-units is declared with one attribute, with no index kept in step by
//! hand. A port bundle (a struct of signals) is `Signals` by `#[derive(Signals)]`.

use super::module::{BitsOf, Dir, Module, Visitor};
use super::signal::{Reg, Signal};
use crate::fx::Narrowing;

/// Signals a module visits with one direction.
pub trait Signals {
    /// Visits every signal, in order.
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor);
    /// Every signal's bits, in the order `visit_signals` visits them
    /// ([`Module::visit_bits`]); by default through `visit_signals`.
    #[inline]
    fn bits_signals<F: FnMut(u64)>(&self, f: &mut F)
    where
        Self: Sized,
    {
        self.visit_signals(Dir::Wire, &mut BitsOf(f));
    }
}

impl Signals for Signal {
    #[inline]
    fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
        v.signal(dir, self);
    }
    #[inline]
    fn bits_signals<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.bits());
    }
}

/// `Signals` for arrays, `Vec`s and `Option`s (ports a configuration may leave out, such as a
/// trilinear unit's second level): each item in order.
macro_rules! signal_collections {
    ($([$($g:tt)*] $ty:ty),*) => {$(
        impl<$($g)*> Signals for $ty {
            fn visit_signals(&self, dir: Dir, v: &mut dyn Visitor) {
                self.iter().for_each(|s| s.visit_signals(dir, v));
            }
            #[inline]
            fn bits_signals<F: FnMut(u64)>(&self, f: &mut F) {
                self.iter().for_each(|s| s.bits_signals(f));
            }
        }
    )*};
}

signal_collections!([T: Signals, const N: usize] [T; N], [T: Signals] Vec<T>, [T: Signals] Option<T>);

/// Registers: committed at the clock edge, visited as registers.
pub trait Regs {
    /// The clock edge of every register.
    fn tick_regs(&mut self, reset: bool);
    /// Visits every register, in order.
    fn visit_regs(&self, v: &mut dyn Visitor);
    /// Every register's current bits, in visit order ([`Module::visit_bits`]).
    #[inline]
    fn bits_regs<F: FnMut(u64)>(&self, f: &mut F)
    where
        Self: Sized,
    {
        self.visit_regs(&mut BitsOf(f));
    }
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
    #[inline]
    fn bits_regs<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.q().bits());
    }
}

/// Named narrowings ([`Narrowing`]): visited for numeric coverage (and their overflow flags
/// traced), never ticked.
pub trait Narrowings {
    /// Visits every narrowing, in order.
    fn visit_narrowings(&self, v: &mut dyn Visitor);
    /// Every narrowing's flag bits, in visit order ([`Module::visit_bits`]).
    #[inline]
    fn bits_narrowings<F: FnMut(u64)>(&self, f: &mut F)
    where
        Self: Sized,
    {
        self.visit_narrowings(&mut BitsOf(f));
    }
}

impl Narrowings for Narrowing {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        v.narrowing(self);
    }
    #[inline]
    fn bits_narrowings<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.flag().bits());
    }
}

impl<Q: crate::fx::Fmt> Narrowings for crate::fx::NarrowingOf<Q> {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        v.narrowing(self);
    }
    #[inline]
    fn bits_narrowings<F: FnMut(u64)>(&self, f: &mut F) {
        f(self.flag().bits());
    }
}

impl<T: Narrowings, const N: usize> Narrowings for [T; N] {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        self.iter().for_each(|n| n.visit_narrowings(v));
    }
    #[inline]
    fn bits_narrowings<F: FnMut(u64)>(&self, f: &mut F) {
        self.iter().for_each(|n| n.bits_narrowings(f));
    }
}

impl<T: Narrowings> Narrowings for Vec<T> {
    fn visit_narrowings(&self, v: &mut dyn Visitor) {
        self.iter().for_each(|n| n.visit_narrowings(v));
    }
    #[inline]
    fn bits_narrowings<F: FnMut(u64)>(&self, f: &mut F) {
        self.iter().for_each(|n| n.bits_narrowings(f));
    }
}

/// Child modules: their clock edge and their hierarchy.
pub trait Children {
    /// The clock edge of every child.
    fn tick_children(&mut self, reset: bool);
    /// Visits every child, in order.
    fn visit_children(&self, v: &mut dyn Visitor);
    /// Every child's signals' bits, in visit order ([`Module::visit_bits`]).
    #[inline]
    fn bits_children<F: FnMut(u64)>(&self, f: &mut F)
    where
        Self: Sized,
    {
        self.visit_children(&mut BitsOf(f));
    }
}

impl<M: Module> Children for M {
    #[inline]
    fn tick_children(&mut self, reset: bool) {
        self.tick(reset);
    }
    fn visit_children(&self, v: &mut dyn Visitor) {
        self.visit(v);
    }
    #[inline]
    fn bits_children<F: FnMut(u64)>(&self, f: &mut F) {
        self.visit_bits(f);
    }
}

/// `$trait` for arrays, `Vec`s and `Option`s of `$bound`: each item (an `Option` holds none
/// or one) ticked by `$tick` and visited by `$visit`, in order.
macro_rules! collections {
    ($trait:ident, $bound:ident, $tick_fn:ident => $tick:ident, $visit_fn:ident => $visit:ident, $bits_fn:ident) => {
        collections!(@one [T: $bound, const N: usize] [T; N], $trait, $tick_fn => $tick, $visit_fn => $visit, $bits_fn);
        collections!(@one [T: $bound] Vec<T>, $trait, $tick_fn => $tick, $visit_fn => $visit, $bits_fn);
        collections!(@one [T: $bound] Option<T>, $trait, $tick_fn => $tick, $visit_fn => $visit, $bits_fn);
    };
    (@one [$($g:tt)*] $ty:ty, $trait:ident, $tick_fn:ident => $tick:ident, $visit_fn:ident => $visit:ident, $bits_fn:ident) => {
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
            #[inline]
            fn $bits_fn<F: FnMut(u64)>(&self, f: &mut F) {
                for x in self.iter() {
                    x.$bits_fn(f);
                }
            }
        }
    };
}

collections!(Regs, Regs, tick_regs => tick_regs, visit_regs => visit_regs, bits_regs);
collections!(Children, Children, tick_children => tick_children, visit_children => visit_children, bits_children);
