//! Theories built into the binary, so the quick start runs with no files: `proclaim table offside`.

/// `(name, file name, text)`
pub const THEORIES: [(&str, &str, &str); 9] = [
    (
        "offside",
        "offside.dl",
        include_str!("../theories/offside.dl"),
    ),
    (
        "microwave",
        "microwave.dl",
        include_str!("../theories/microwave.dl"),
    ),
    (
        "kickoff",
        "kickoff.dl",
        include_str!("../theories/kickoff.dl"),
    ),
    (
        "tweety",
        "classics/tweety.dl",
        include_str!("../theories/classics/tweety.dl"),
    ),
    (
        "nixon",
        "classics/nixon.dl",
        include_str!("../theories/classics/nixon.dl"),
    ),
    (
        "team-defeat",
        "classics/team-defeat.dl",
        include_str!("../theories/classics/team-defeat.dl"),
    ),
    (
        "blocking",
        "classics/blocking.dl",
        include_str!("../theories/classics/blocking.dl"),
    ),
    (
        "defeater",
        "classics/defeater.dl",
        include_str!("../theories/classics/defeater.dl"),
    ),
    (
        "loops",
        "classics/loops.dl",
        include_str!("../theories/classics/loops.dl"),
    ),
];

pub fn find(name: &str) -> Option<(&'static str, &'static str)> {
    THEORIES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, file, text)| (*file, *text))
}

pub fn names() -> String {
    THEORIES
        .iter()
        .map(|(n, _, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Behaviours built into the binary, so `proclaim run game_controller` works anywhere:
/// `(name, [(path relative to the behaviour, text)])`.
pub const BEHAVIOURS: [(&str, &[(&str, &str)]); 3] = [
    (
        "game_controller",
        &[
            (
                "behaviour.toml",
                include_str!("../machines/game_controller/behaviour.toml"),
            ),
            (
                "GameController.machine",
                include_str!("../machines/game_controller/GameController.machine"),
            ),
            (
                "Placer.machine",
                include_str!("../machines/game_controller/Placer.machine"),
            ),
            ("../nao.toml", include_str!("../machines/nao.toml")),
        ],
    ),
    (
        "microwave",
        &[
            (
                "behaviour.toml",
                include_str!("../machines/microwave/behaviour.toml"),
            ),
            (
                "Microwave.machine",
                include_str!("../machines/microwave/Microwave.machine"),
            ),
            (
                "kitchen.script",
                include_str!("../machines/microwave/kitchen.script"),
            ),
            (
                "../../theories/microwave.dl",
                include_str!("../theories/microwave.dl"),
            ),
        ],
    ),
    (
        "shootout",
        &[
            (
                "behaviour.toml",
                include_str!("../machines/shootout/behaviour.toml"),
            ),
            (
                "Kicker.machine",
                include_str!("../machines/shootout/Kicker.machine"),
            ),
            (
                "Keeper.machine",
                include_str!("../machines/shootout/Keeper.machine"),
            ),
            (
                "Scoreboard.machine",
                include_str!("../machines/shootout/Scoreboard.machine"),
            ),
            ("../nao.toml", include_str!("../machines/nao.toml")),
        ],
    ),
];

pub fn behaviour(name: &str) -> Option<&'static [(&'static str, &'static str)]> {
    BEHAVIOURS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, files)| *files)
}

pub fn behaviour_names() -> String {
    BEHAVIOURS
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}
