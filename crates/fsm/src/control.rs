//! The control protocol of machines: the words posted to a machine's name, the activity
//! functions that post them, and the message types a machine posts about itself. The one place
//! these words are spelled; the readers, the drawing, the liveness compiler and the runner all
//! use it.

use std::fmt;

/// A command posted to a machine's name (`Placer: On`). gufsm's `SuspensibleMachine` semantics:
/// `On` and `resume` do nothing to a running machine, `restart` starts it again from its
/// initial state, `suspend` parks it remembering its state, `resume` re-enters that state (its
/// OnEntry runs again), `Off` makes it dormant (a later `On` starts from the initial state).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    On,
    Off,
    Suspend,
    Resume,
    Restart,
    /// Read the machine's file again and start from its initial state.
    Reload,
    /// Read the machine's file again and stay in the current state when it still exists.
    Reread,
}

impl Command {
    pub const ALL: [Command; 7] = [
        Command::On,
        Command::Off,
        Command::Suspend,
        Command::Resume,
        Command::Restart,
        Command::Reload,
        Command::Reread,
    ];

    /// The word as posted.
    pub fn word(self) -> &'static str {
        match self {
            Command::On => "On",
            Command::Off => "Off",
            Command::Suspend => "suspend",
            Command::Resume => "resume",
            Command::Restart => "restart",
            Command::Reload => "reload",
            Command::Reread => "reread",
        }
    }

    /// The activity function that posts the command (`suspend("Placer")`; `start`/`stop` for
    /// `On`/`Off`), as gufsm's activity language spells them.
    pub fn from_function(function: &str) -> Option<Command> {
        match function {
            "start" => Some(Command::On),
            "stop" => Some(Command::Off),
            "suspend" => Some(Command::Suspend),
            "resume" => Some(Command::Resume),
            "restart" => Some(Command::Restart),
            _ => None,
        }
    }

    /// Reads a posted word; `on`/`off` in any case, as the team wrote them.
    pub fn parse(word: &str) -> Option<Command> {
        let word = word.trim();
        Command::ALL
            .into_iter()
            .find(|c| c.word() == word || c.word().eq_ignore_ascii_case(word))
    }
}

impl fmt::Display for Command {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.word())
    }
}

/// The type a machine posts its running state to (`PlacerIsRunning`: true or false).
pub fn running_type(machine: &str) -> String {
    format!("{machine}IsRunning")
}

/// The machine a `NameIsRunning` type speaks of.
pub fn machine_of_running_type(ty: &str) -> Option<&str> {
    ty.strip_suffix("IsRunning").filter(|m| !m.is_empty())
}
