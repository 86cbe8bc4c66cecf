/// Every edit of every kind at every place of every shipped machine: each is made or refused
/// with a reason, never a panic, and what it makes still reads as a machine.
#[test]
fn every_edit_everywhere_reads_back() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../machines");
    for behaviour in std::fs::read_dir(&root).unwrap() {
        let dir = behaviour.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        for file in std::fs::read_dir(&dir).unwrap() {
            let path = file.unwrap().path();
            if path.extension().is_none_or(|e| e != "machine") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let (states, _) = view_native(&text).unwrap();
            let mut edits = vec![Edit::AddState { name: "NEW".into() }];
            for (i, s) in states.iter().enumerate() {
                let n = s.transitions.len();
                edits.extend([
                    Edit::RenameState {
                        state: i,
                        to: format!("{}_2", s.name),
                    },
                    Edit::DeleteState { state: i },
                    Edit::SetInitial { state: i },
                    Edit::MakeFinal { state: i },
                    Edit::AddTransition {
                        state: i,
                        label: "x && y".into(),
                        target: (i + 1) % states.len(),
                    },
                ]);
                for section in [Section::Entry, Section::Exit, Section::Internal] {
                    edits.push(Edit::SetActivity {
                        state: i,
                        section,
                        text: "n = n + 1;\nSay: hello".into(),
                    });
                    edits.push(Edit::SetActivity {
                        state: i,
                        section,
                        text: String::new(),
                    });
                }
                for t in 0..=n {
                    edits.push(Edit::DeleteTransition {
                        state: i,
                        transition: t,
                    });
                    edits.push(Edit::SetLabel {
                        state: i,
                        transition: t,
                        label: "!z".into(),
                    });
                    for to in 0..n {
                        edits.push(Edit::MoveTransition {
                            state: i,
                            from: t,
                            to,
                        });
                    }
                }
            }
            for edit in edits {
                if let Ok(edited) = edit_native("m.machine", &text, &edit) {
                    assert!(
                        view_native(&edited.text).is_ok(),
                        "{}: {edit:?}\n{}",
                        path.display(),
                        edited.text
                    );
                }
            }
        }
    }
}
