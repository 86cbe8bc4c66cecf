//! Theories built into the binary, so the quick start runs with no files: `proclaim table offside`.

/// `(name, file name, text)`
pub const THEORIES: [(&str, &str, &str); 8] = [
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
