//! The scalable family of the verifier's bench and of its SPIN comparison: `odometer N K`, N
//! machines each holding one digit (a global) of a base-K counter in its Internal activity,
//! each digit stepping when the one before it is 0, so all K^N readings are reached; the first
//! machine also fires on a free button, so every step has two environment choices.

use std::path::Path;

/// Writes the behaviour `odometer N K` (its machines and `behaviour.toml`) into `dir`.
pub fn write_odometer(dir: &Path, n: usize, k: usize) {
    std::fs::create_dir_all(dir).expect("the folder can be made");
    let mut manifest = String::new();
    for i in 0..n {
        let (step, label) = match i {
            0 => ("1".to_string(), "button && g0 == 0"),
            _ => (format!("(g{} == 0)", i - 1), "FALSE"),
        };
        let machine = format!(
            "machine D{i}\nstate RUN {{\n  internal {{ g{i} = (g{i} + {step}) % {k}; }}\n  when {label} -> RUN\n}}\n"
        );
        std::fs::write(dir.join(format!("D{i}.machine")), machine).expect("write");
        manifest.push_str(&format!("[[machine]]\nfile = \"D{i}.machine\"\n"));
    }
    std::fs::write(dir.join("behaviour.toml"), manifest).expect("write");
}
