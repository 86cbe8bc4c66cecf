//! The behaviour both measuring examples compile: copies of the microwave's machine sharing its
//! theory, written to a folder.

use std::path::Path;

/// A behaviour folder of `machines` copies of the microwave's machine and its theory.
pub fn copies(root: &Path, folder: &Path, machines: usize) {
    let machine = std::fs::read_to_string(root.join("machines/microwave/Microwave.machine"))
        .expect("the microwave's machine");
    std::fs::copy(
        root.join("theories/microwave.dl"),
        folder.join("microwave.dl"),
    )
    .expect("the microwave's theory");
    let mut manifest = String::from("[[theory]]\nfile = \"microwave.dl\"\n");
    for i in 0..machines {
        let name = format!("Microwave{i}");
        std::fs::write(
            folder.join(format!("{name}.machine")),
            machine.replace("machine Microwave", &format!("machine {name}")),
        )
        .expect("a machine written");
        manifest.push_str(&format!("[[machine]]\nfile = \"{name}.machine\"\n"));
    }
    std::fs::write(folder.join("behaviour.toml"), manifest).expect("the manifest written");
}
