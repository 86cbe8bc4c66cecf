//! Behaviours of the shapes real gufsm users verify, written out by code so that tests, benches
//! and the command line check the same files: `sensors N` (N sensor machines each following
//! its own free input and mirroring it in a shared variable, a controller raising an alarm
//! when all are on), `press` (eight machines: a controller, a motor, a plunger, a button, three
//! position sensors and an operator over shared variables, five free inputs) and `minepump`
//! (four machines: the water and methane sensors, the pump and its controller).

use std::path::Path;

/// A behaviour's files: machines (name, text) in manifest order, and its properties as
/// manifest lines.
struct Files {
    machines: Vec<(String, String)>,
}

impl Files {
    fn write(&self, dir: &Path) {
        std::fs::create_dir_all(dir).expect("the folder can be made");
        let mut manifest = String::new();
        for (name, text) in &self.machines {
            std::fs::write(dir.join(format!("{name}.machine")), text).expect("write");
            manifest.push_str(&format!("[[machine]]\nfile = \"{name}.machine\"\n\n"));
        }
        std::fs::write(dir.join("behaviour.toml"), manifest).expect("write");
    }
}

/// A two-state machine that follows free input `input` and mirrors it in `variable`.
fn follower(name: &str, input: &str, variable: &str) -> String {
    format!(
        "machine {name}\ninitial OFF\n\
         state OFF {{\n  entry {{ {variable} = 0; }}\n  when {input} -> ON\n}}\n\
         state ON {{\n  entry {{ {variable} = 1; }}\n  when !{input} -> OFF\n}}\n"
    )
}

/// `sensors N`: machines `S0`..`S{N-1}` following inputs `in0`.. into `s0`..; `Controller`
/// goes from `Idle` to `Alarm` (setting `alarm`) when every `s` is 1, and back when one is not.
pub fn write_sensors(dir: &Path, n: usize) {
    let mut machines: Vec<(String, String)> = (0..n)
        .map(|i| {
            (
                format!("S{i}"),
                follower(&format!("S{i}"), &format!("in{i}"), &format!("s{i}")),
            )
        })
        .collect();
    let all = (0..n)
        .map(|i| format!("s{i} == 1"))
        .collect::<Vec<_>>()
        .join(" && ");
    machines.push((
        "Controller".into(),
        format!(
            "machine Controller\ninitial Idle\n\
             state Idle {{\n  entry {{ alarm = 0; }}\n  when {all} -> Alarm\n}}\n\
             state Alarm {{\n  entry {{ alarm = 1; }}\n  when !({all}) -> Idle\n}}\n"
        ),
    ));
    Files { machines }.write(dir);
}

/// `press`: a press after the Griffith team's gufsm behaviours. The operator must be present
/// and the button pressed to close; the motor drives the press down to the bottom sensor,
/// the plunger stamps for a while, and the motor brings it back up to the top sensor. The
/// operator stepping away while closing reopens it.
pub fn write_press(dir: &Path) {
    let machines = vec![
        ("Button".to_string(), follower("Button", "buttonPressed", "pressed")),
        ("Operator".to_string(), follower("Operator", "operatorPresent", "guard")),
        ("Top".to_string(), follower("Top", "atTop", "top")),
        ("Middle".to_string(), follower("Middle", "atMiddle", "middle")),
        ("Bottom".to_string(), follower("Bottom", "atBottom", "bottom")),
        (
            "Controller".to_string(),
            "machine Controller\ninitial Open\n\
             state Open {\n  entry { motorCmd = 0; plunge = 0; }\n  when pressed == 1 && guard == 1 -> Closing\n}\n\
             state Closing {\n  entry { motorCmd = 1; }\n  when guard == 0 -> Opening\n  when bottom == 1 -> PressClosed\n}\n\
             state PressClosed {\n  entry { motorCmd = 0; plunge = 1; }\n  when timeout(2s) -> Opening\n}\n\
             state Opening {\n  entry { plunge = 0; motorCmd = 2; }\n  when top == 1 -> Open\n}\n"
                .to_string(),
        ),
        (
            "Motor".to_string(),
            "machine Motor\ninitial Stopped\n\
             state Stopped {\n  entry { running = 0; }\n  when motorCmd == 1 -> Down\n  when motorCmd == 2 -> Up\n}\n\
             state Down {\n  entry { running = 1; }\n  when motorCmd != 1 -> Stopped\n}\n\
             state Up {\n  entry { running = 2; }\n  when motorCmd != 2 -> Stopped\n}\n"
                .to_string(),
        ),
        (
            "Plunger".to_string(),
            "machine Plunger\ninitial Retracted\n\
             state Retracted {\n  when plunge == 1 && running == 0 -> Extended\n}\n\
             state Extended {\n  when plunge == 0 -> Retracted\n}\n"
                .to_string(),
        ),
    ];
    Files { machines }.write(dir);
}

/// `minepump`: the water level (`high`) and methane sensors follow free inputs; the controller
/// runs the pump while the water is high and there is no methane; the pump follows it.
pub fn write_minepump(dir: &Path) {
    let machines = vec![
        ("Water".to_string(), follower("Water", "waterHigh", "high")),
        (
            "Methane".to_string(),
            follower("Methane", "methanePresent", "methane"),
        ),
        (
            "Controller".to_string(),
            "machine Controller\ninitial Off\n\
             state Off {\n  entry { pumpCmd = 0; }\n  when high == 1 && methane == 0 -> On\n}\n\
             state On {\n  entry { pumpCmd = 1; }\n  when methane == 1 || high == 0 -> Off\n}\n"
                .to_string(),
        ),
        (
            "Pump".to_string(),
            "machine Pump\ninitial Stopped\n\
             state Stopped {\n  entry { pumping = 0; }\n  when pumpCmd == 1 -> Pumping\n}\n\
             state Pumping {\n  entry { pumping = 1; }\n  when pumpCmd == 0 -> Stopped\n}\n"
                .to_string(),
        ),
    ];
    Files { machines }.write(dir);
}
