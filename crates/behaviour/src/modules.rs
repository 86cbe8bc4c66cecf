//! Every module of a behaviour with its declaration (what it posts, reads, waits on and
//! answers), without starting anything: the dictionary that `check`, `deps` and `--launch` read.

use crate::loaded::Behaviour;
use crate::manifest::SensorKind;
use proclaim_board::ModuleDecl;
use proclaim_experts::{
    ButtonWrapper, FallWrapper, GameControllerReceiver, ReasonerExpert, ReceiverConfig,
};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ModuleKind {
    /// A machine of the behaviour; `start` is false for a sub-machine.
    Machine {
        file: String,
        start: bool,
        /// Its subsumption layer (the manifest's `priority`).
        priority: u32,
        /// The suppressed types it posts (the manifest's `[suppress]`), with their holds.
        holds: Vec<(String, std::time::Duration)>,
    },
    Theory {
        file: String,
    },
    Sensor(SensorKind),
    /// A `[[prolog]]` knowledge base (its file) or an `[[expert]]` program (`None`).
    Program {
        file: Option<String>,
    },
    Impersonator,
    /// Declared in the manifest or its dictionary; not started by the behaviour.
    Outside,
}

#[derive(Clone, Debug)]
pub struct Module {
    pub decl: ModuleDecl,
    pub kind: ModuleKind,
}

/// The modules of `behaviour`, machines first, in manifest order.
pub fn modules(behaviour: &Behaviour) -> Vec<Module> {
    let mut out = Vec::new();
    let shared = behaviour.shared_variables();
    for m in &behaviour.machines {
        let decl = proclaim_runner::declaration(&m.machine, &m.machine.name, &shared);
        let holds = behaviour
            .suppress
            .iter()
            .filter(|(ty, _)| decl.posts.contains(ty))
            .cloned()
            .collect();
        out.push(Module {
            decl,
            kind: ModuleKind::Machine {
                file: m.file.clone(),
                start: m.start,
                priority: m.priority,
                holds,
            },
        });
    }
    for t in &behaviour.theories {
        let expert = ReasonerExpert::new(&t.name, t.theory.clone(), &t.mapping);
        out.push(Module {
            decl: expert.declaration(),
            kind: ModuleKind::Theory {
                file: t.file.clone(),
            },
        });
    }
    for p in &behaviour.programs {
        let file = match &p.kind {
            crate::programs::ProgramKind::Prolog { file, .. } => Some(file.clone()),
            crate::programs::ProgramKind::Command { .. } => None,
        };
        out.push(Module {
            decl: p.declaration(),
            kind: ModuleKind::Program { file },
        });
    }
    for s in &behaviour.sensors {
        let kind = s.entry.kind;
        let decls = match kind {
            SensorKind::Gamecontroller => {
                vec![GameControllerReceiver::declaration_for(
                    &ReceiverConfig::default(),
                )]
            }
            SensorKind::ChestButton => vec![ButtonWrapper::chest().declaration()],
            SensorKind::FootBumpers => vec![
                ButtonWrapper::foot(true).declaration(),
                ButtonWrapper::foot(false).declaration(),
            ],
            SensorKind::Fall => vec![FallWrapper::default().declaration()],
        };
        out.extend(decls.into_iter().map(|decl| Module {
            decl,
            kind: ModuleKind::Sensor(kind),
        }));
    }
    if let Some(script) = &behaviour.script {
        let atoms = script.atoms();
        out.push(Module {
            decl: ModuleDecl::new("impersonator")
                .posts(atoms.clone())
                .answers(atoms),
            kind: ModuleKind::Impersonator,
        });
    }
    for o in &behaviour.outside {
        out.push(Module {
            decl: ModuleDecl::new(&o.name)
                .posts(o.posts.clone())
                .reads(o.reads.clone())
                .answers(o.answers.clone()),
            kind: ModuleKind::Outside,
        });
    }
    out
}
