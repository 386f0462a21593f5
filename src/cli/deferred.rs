//! Subcommands whose arguments clap builds only when they are used.
//!
//! clap's derive builds the whole command tree, every argument of every subcommand,
//! before it parses anything: for `singdist` about 0.2 ms of a 2 ms `solve` of a small
//! system. [`Deferred`] hands a subcommand's arguments to [`clap::Command::defer`], so
//! only the subcommand named on the command line (or whose help is asked for) builds
//! them; names, descriptions, parsing and help are unchanged.

use clap::{ArgMatches, Args, Command, FromArgMatches, Subcommand};

/// The arguments (or nested subcommands) `T` of a subcommand, built when the
/// subcommand is.
#[derive(Debug)]
pub struct Deferred<T>(pub T);

impl<T: FromArgMatches> FromArgMatches for Deferred<T> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        T::from_arg_matches(matches).map(Deferred)
    }

    fn from_arg_matches_mut(matches: &mut ArgMatches) -> Result<Self, clap::Error> {
        T::from_arg_matches_mut(matches).map(Deferred)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        self.0.update_from_arg_matches(matches)
    }

    fn update_from_arg_matches_mut(&mut self, matches: &mut ArgMatches) -> Result<(), clap::Error> {
        self.0.update_from_arg_matches_mut(matches)
    }
}

impl<T: Args> Args for Deferred<T> {
    fn group_id() -> Option<clap::Id> {
        T::group_id()
    }

    fn augment_args(cmd: Command) -> Command {
        cmd.defer(|cmd| keeping_descriptions(cmd, T::augment_args))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        cmd.defer(|cmd| keeping_descriptions(cmd, T::augment_args_for_update))
    }
}

/// `augment(cmd)` with the descriptions `cmd` has: the subcommand's own (its doc
/// comment where it is declared), which the derive applies after the arguments' and
/// which the arguments' doc comment must not replace when they are built later.
fn keeping_descriptions(cmd: Command, augment: fn(Command) -> Command) -> Command {
    let about = cmd.get_about().cloned();
    let long_about = cmd.get_long_about().cloned();
    let cmd = augment(cmd);
    let cmd = match about {
        Some(text) => cmd.about(text),
        None => cmd.about(None::<&str>),
    };
    match long_about {
        Some(text) => cmd.long_about(text),
        None => cmd.long_about(None::<&str>),
    }
}

impl<T: Subcommand> Subcommand for Deferred<T> {
    fn augment_subcommands(cmd: Command) -> Command {
        cmd.defer(|cmd| keeping_descriptions(cmd, T::augment_subcommands))
    }

    fn augment_subcommands_for_update(cmd: Command) -> Command {
        cmd.defer(|cmd| keeping_descriptions(cmd, T::augment_subcommands_for_update))
    }

    fn has_subcommand(name: &str) -> bool {
        T::has_subcommand(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    /// The arguments' own description.
    #[derive(Parser, Debug)]
    struct Inner {
        /// An option.
        #[arg(long, default_value_t = 3)]
        count: u32,
    }

    #[derive(clap::Subcommand, Debug)]
    enum Nested {
        /// A nested subcommand.
        Leaf(Inner),
    }

    #[derive(Parser, Debug)]
    enum Outer {
        /// Uses the inner arguments.
        Use(Deferred<Inner>),
        /// Has subcommands of its own.
        #[command(subcommand)]
        Group(Deferred<Nested>),
    }

    /// A deferred subcommand parses its arguments and nested subcommands, applies
    /// defaults and refuses unknown ones, as the subcommand itself does.
    #[test]
    fn a_deferred_subcommand_parses_as_the_subcommand_itself() {
        let count = |args: &[&str]| match Outer::try_parse_from(args) {
            Ok(Outer::Use(Deferred(inner))) | Ok(Outer::Group(Deferred(Nested::Leaf(inner)))) => {
                Some(inner.count)
            }
            Err(_) => None,
        };
        assert_eq!(count(&["outer", "use", "--count", "7"]), Some(7));
        assert_eq!(count(&["outer", "use"]), Some(3));
        assert_eq!(count(&["outer", "group", "leaf", "--count", "5"]), Some(5));
        assert_eq!(count(&["outer", "group", "other"]), None);
        assert!(Outer::try_parse_from(["outer", "use", "--other"]).is_err());
        let help = Outer::try_parse_from(["outer", "use", "--help"])
            .unwrap_err()
            .to_string();
        assert!(help.contains("--count"), "{help}");
        assert!(help.starts_with("Uses the inner arguments"), "{help}");
        assert!(!help.contains("own description"), "{help}");
    }
}
