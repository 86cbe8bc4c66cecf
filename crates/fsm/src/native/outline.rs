//! Where each part of a native machine file is written: the byte spans an edit patches, so that
//! everything it does not touch (comments, order, spacing) stays as the person wrote it.
//!
//! Read from the same tokens as the grammar, but kept apart from the syntax tree: the tree
//! holds what things mean, the outline where they are.

use super::ast::{Ref, Section};
use super::lexer::{MachineLexer, MachineToken};
use std::ops::Range;

/// A native file's parts and their places, in file order.
#[derive(Clone, Debug)]
pub struct Outline {
    /// The end of the machine's name: where an `initial` line goes when there is none.
    pub header_end: usize,
    /// `initial TARGET`, when written.
    pub initial: Option<RefAt>,
    pub states: Vec<StateAt>,
}

/// A reference to a state (`NAME` or `#id`) and where it is written.
#[derive(Clone, Debug)]
pub struct RefAt {
    pub reference: Ref,
    pub span: Range<usize>,
}

#[derive(Clone, Debug)]
pub struct StateAt {
    pub name: String,
    pub id: Option<i64>,
    /// The `state` keyword.
    pub start: usize,
    pub name_span: Range<usize>,
    /// The block's closing `}`.
    pub close: usize,
    pub activities: Vec<ActivityAt>,
    pub whens: Vec<WhenAt>,
    /// The outcome it announces (`outcome landed`): it is final.
    pub outcome: Option<String>,
}

#[derive(Clone, Debug)]
pub struct ActivityAt {
    pub section: Section,
    /// The section's keyword.
    pub start: usize,
    pub open: usize,
    pub close: usize,
}

/// `when LABEL -> TARGET`.
#[derive(Clone, Debug)]
pub struct WhenAt {
    pub start: usize,
    pub label: Range<usize>,
    pub target: RefAt,
}

/// Why a text has no outline: the first token that is not where the format wants it.
#[derive(Clone, Debug)]
pub struct Unreadable {
    pub at: usize,
    pub message: String,
}

impl Outline {
    /// The outline of `text`, or where it stops reading as a machine.
    pub fn read(text: &str) -> Result<Outline, Unreadable> {
        let mut tokens = Vec::new();
        for token in MachineLexer::new(text) {
            match token {
                Ok(t) => tokens.push(t),
                Err(e) => {
                    return Err(Unreadable {
                        at: e.at,
                        message: e.message,
                    })
                }
            }
        }
        Reader {
            tokens,
            next: 0,
            end: text.len(),
        }
        .file()
    }

    /// Every state's id as the reader gives it: as written, the others numbered from 1 skipping
    /// those taken (the reader's own rule, `number` in `native/mod.rs`).
    pub fn ids(&self) -> Vec<i64> {
        let mut taken: Vec<i64> = self.states.iter().filter_map(|s| s.id).collect();
        let mut next = 1;
        self.states
            .iter()
            .map(|s| {
                s.id.unwrap_or_else(|| {
                    while taken.contains(&next) {
                        next += 1;
                    }
                    taken.push(next);
                    next
                })
            })
            .collect()
    }

    /// The state a reference means, by its position in the file, when it means exactly one.
    pub fn resolve(&self, reference: &Ref) -> Option<usize> {
        match reference {
            Ref::Id(id) => self.ids().iter().position(|i| i == id),
            Ref::Name(name) => {
                let mut found = self
                    .states
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| &s.name == name);
                match (found.next(), found.next()) {
                    (Some((i, _)), None) => Some(i),
                    _ => None,
                }
            }
        }
    }
}

struct Reader<'t> {
    tokens: Vec<(usize, MachineToken<'t>, usize)>,
    next: usize,
    end: usize,
}

impl<'t> Reader<'t> {
    fn peek(&self) -> Option<&(usize, MachineToken<'t>, usize)> {
        self.tokens.get(self.next)
    }

    fn take(&mut self, wanted: &str) -> Result<(usize, MachineToken<'t>, usize), Unreadable> {
        match self.tokens.get(self.next) {
            Some(t) => {
                self.next += 1;
                Ok(t.clone())
            }
            None => Err(Unreadable {
                at: self.end,
                message: format!("the file ends where {wanted} was expected"),
            }),
        }
    }

    fn unexpected<T>(
        token: &(usize, MachineToken<'t>, usize),
        wanted: &str,
    ) -> Result<T, Unreadable> {
        Err(Unreadable {
            at: token.0,
            message: format!("unexpected {}; expected {wanted}", token.1),
        })
    }

    fn file(mut self) -> Result<Outline, Unreadable> {
        let first = self.take("`machine`")?;
        if first.1 != MachineToken::Machine {
            return Self::unexpected(&first, "`machine`");
        }
        let (_, name_span) = self.name()?;
        let mut outline = Outline {
            header_end: name_span.end,
            initial: None,
            states: Vec::new(),
        };
        while let Some(token) = self.peek().cloned() {
            self.next += 1;
            match token.1 {
                MachineToken::Initial => outline.initial = Some(self.reference()?),
                MachineToken::Description => {
                    let text = self.take("the description")?;
                    if !matches!(text.1, MachineToken::Str(_)) {
                        return Self::unexpected(&text, "a quoted description");
                    }
                }
                MachineToken::State => outline.states.push(self.state(token.0)?),
                // A declaration is left as written: no edit touches it.
                MachineToken::Param | MachineToken::Outcome => {
                    self.take("what is declared")?;
                }
                _ => return Self::unexpected(&token, "`initial`, `description` or `state`"),
            }
        }
        Ok(outline)
    }

    fn name(&mut self) -> Result<(String, Range<usize>), Unreadable> {
        let token = self.take("a name")?;
        match &token.1 {
            MachineToken::Word(w) => Ok((w.to_string(), token.0..token.2)),
            MachineToken::Str(s) => Ok((s.clone(), token.0..token.2)),
            _ => Self::unexpected(&token, "a name"),
        }
    }

    fn reference(&mut self) -> Result<RefAt, Unreadable> {
        if self.peek().is_some_and(|t| t.1 == MachineToken::Hash) {
            let hash = self.take("`#`")?;
            let number = self.take("a state id")?;
            return match number.1 {
                MachineToken::Int(id) => Ok(RefAt {
                    reference: Ref::Id(id),
                    span: hash.0..number.2,
                }),
                _ => Self::unexpected(&number, "a state id"),
            };
        }
        let (name, span) = self.name()?;
        Ok(RefAt {
            reference: Ref::Name(name),
            span,
        })
    }

    fn brace(&mut self, wanted: MachineToken<'static>) -> Result<usize, Unreadable> {
        let token = self.take(&wanted.to_string())?;
        if token.1 == wanted {
            Ok(token.0)
        } else {
            Self::unexpected(&token, &wanted.to_string())
        }
    }

    fn state(&mut self, start: usize) -> Result<StateAt, Unreadable> {
        let (name, name_span) = self.name()?;
        let mut id = None;
        if self.peek().is_some_and(|t| t.1 == MachineToken::Hash) {
            match self.reference()?.reference {
                Ref::Id(n) => id = Some(n),
                Ref::Name(_) => unreachable!("a `#` reference is an id"),
            }
        }
        self.brace(MachineToken::LBrace)?;
        let mut state = StateAt {
            name,
            id,
            start,
            name_span,
            close: 0,
            activities: Vec::new(),
            whens: Vec::new(),
            outcome: None,
        };
        loop {
            let token = self.take("`}`")?;
            let section = match token.1 {
                MachineToken::RBrace => {
                    state.close = token.0;
                    return Ok(state);
                }
                MachineToken::When => {
                    let label = self.take("a label")?;
                    let MachineToken::LabelText(_) = label.1 else {
                        return Self::unexpected(&label, "a label");
                    };
                    self.brace(MachineToken::Arrow)?;
                    let target = self.reference()?;
                    state.whens.push(WhenAt {
                        start: token.0,
                        label: label.0..label.2,
                        target,
                    });
                    continue;
                }
                MachineToken::Outcome => {
                    if let MachineToken::Text(name) = self.take("the outcome")?.1 {
                        state.outcome = Some(name.to_string());
                    }
                    continue;
                }
                MachineToken::Entry => Section::Entry,
                MachineToken::Exit => Section::Exit,
                MachineToken::Internal => Section::Internal,
                _ => return Self::unexpected(&token, "`entry`, `exit`, `internal`, `when` or `}`"),
            };
            let open = self.brace(MachineToken::LBrace)?;
            // An activity's items hold no braces of their own: a statement's are inside its token.
            let close = loop {
                let item = self.take("the activity's `}`")?;
                match item.1 {
                    MachineToken::RBrace => break item.0,
                    MachineToken::LBrace
                    | MachineToken::State
                    | MachineToken::When
                    | MachineToken::Entry
                    | MachineToken::Exit => return Self::unexpected(&item, "the activity's `}`"),
                    _ => {}
                }
            };
            state.activities.push(ActivityAt {
                section,
                start: token.0,
                open,
                close,
            });
        }
    }
}
