//! The options of the framework's commands, declared with clap's builder (no derive: a user
//! crate's first build does not compile `clap_derive`). An option's id is its long name.

use clap::builder::ValueParser;
use clap::{Arg, ArgAction, ArgMatches};
use std::path::PathBuf;

/// `--id VALUE`, once, parsed by `parser`.
pub(super) fn value(
    id: &'static str,
    name: &'static str,
    parser: impl Into<ValueParser>,
    help: &'static str,
) -> Arg {
    Arg::new(id)
        .long(id)
        .value_name(name)
        .value_parser(parser)
        .action(ArgAction::Set)
        .help(help)
}

/// `--id VALUE`, repeatable.
pub(super) fn values(
    id: &'static str,
    name: &'static str,
    parser: impl Into<ValueParser>,
    help: &'static str,
) -> Arg {
    value(id, name, parser, help).action(ArgAction::Append)
}

/// `--id FILE` (or folder).
pub(super) fn path(id: &'static str, name: &'static str, help: &'static str) -> Arg {
    value(id, name, clap::value_parser!(PathBuf), help)
}

/// `--id`, a switch.
pub(super) fn flag(id: &'static str, help: &'static str) -> Arg {
    Arg::new(id).long(id).action(ArgAction::SetTrue).help(help)
}

/// The value of `id`, which the command declares with type `T`.
pub(super) fn one<T: Clone + Send + Sync + 'static>(m: &ArgMatches, id: &str) -> Option<T> {
    m.get_one::<T>(id).cloned()
}

/// The value of an option with a default.
pub(super) fn given<T: Clone + Send + Sync + 'static>(m: &ArgMatches, id: &str) -> T {
    one(m, id).expect("an option with a default value")
}

/// Every value of a repeatable option, in order.
pub(super) fn all<T: Clone + Send + Sync + 'static>(m: &ArgMatches, id: &str) -> Vec<T> {
    m.get_many::<T>(id)
        .map(|v| v.cloned().collect())
        .unwrap_or_default()
}

/// `clap::Args` and `clap::FromArgMatches` for a command's options from its `augment(cmd)`
/// and `read(matches)`, so that a program's own derive can `#[command(flatten)]` them.
macro_rules! clap_args {
    ($t:ty) => {
        impl clap::FromArgMatches for $t {
            fn from_arg_matches(m: &clap::ArgMatches) -> Result<Self, clap::Error> {
                Ok(<$t>::read(m))
            }
            fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> Result<(), clap::Error> {
                *self = <$t>::read(m);
                Ok(())
            }
        }
        impl clap::Args for $t {
            fn augment_args(c: clap::Command) -> clap::Command {
                <$t>::augment(c)
            }
            fn augment_args_for_update(c: clap::Command) -> clap::Command {
                <$t>::augment(c)
            }
        }
    };
}
pub(super) use clap_args;
