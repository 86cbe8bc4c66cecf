//! How C99 writes the code tree (`code.rs`): the world behind a pointer, unsigned literals,
//! `switch` with `break`, and each parameter marked used for `-Wall -Wextra -Werror`.

use crate::code::{Expr, Function, Spelling, Type};
use std::fmt::Write;

pub(crate) struct C;

fn type_name(t: Type) -> &'static str {
    match t {
        Type::Truth => "int",
        Type::Index => "unsigned",
        Type::Ms => "uint64_t",
        Type::Text => "const char *",
    }
}

/// A whole number as a C expression of type `int64_t`.
fn whole(i: i64) -> String {
    if i == i64::MIN {
        "(-INT64_C(9223372036854775807) - 1)".into()
    } else {
        format!("INT64_C({i})")
    }
}

impl C {
    fn with_world(&self, name: &str, args: &[Expr]) -> String {
        let mut all = vec!["w".to_string()];
        all.extend(args.iter().map(|a| self.expr(a)));
        format!("{name}({})", all.join(", "))
    }
}

impl Spelling for C {
    fn expr(&self, e: &Expr) -> String {
        match e {
            Expr::World(field) => format!("w->{field}"),
            Expr::Index(table, at) => format!("{}[{}]", self.expr(table), self.expr(at)),
            Expr::Table(name) => (*name).to_string(),
            Expr::Name(name) => name.clone(),
            Expr::Whole(i) => whole(*i),
            Expr::Count(n) => format!("{n}u"),
            Expr::Number(n) => n.to_string(),
            Expr::Truth(b) => u8::from(*b).to_string(),
            Expr::Text(s) => format!("\"{}\"", esc(s)),
            Expr::Call(name, args) => self.with_world(name, args),
            Expr::Buffer(name, args) => self.with_world(name, args),
            Expr::Pure(name, args) => format!("{name}({})", self.list(args)),
            Expr::Report(name, args) => self.with_world(&format!("w->cb.{name}"), args),
            Expr::Not(e) => format!("!{}", self.expr(e)),
            Expr::Binary(..) => format!("({})", self.bare(e)),
            Expr::Label(label) => self.expr(label),
            Expr::Decide {
                theory,
                output,
                offset,
            } => format!("{theory}_answer({output}u, w->input + {offset})"),
        }
    }

    fn head(&self, f: &Function) -> (String, Vec<String>) {
        let world = if f.writes {
            "struct world *w"
        } else {
            "const struct world *w"
        };
        let mut params = vec![world.to_string()];
        let mut used = vec!["(void)w;".to_string()];
        for (name, t) in &f.params {
            let spaced = if matches!(t, Type::Text) { "" } else { " " };
            params.push(format!("{}{spaced}{name}", type_name(*t)));
            used.push(format!("(void){name};"));
        }
        let head = format!(
            "static {} {}({})\n{{",
            type_name(f.returns),
            f.name,
            params.join(", ")
        );
        (head, used)
    }

    fn test(&self, keyword: &str, condition: &Expr) -> String {
        format!("{keyword} ({}) {{", self.bare(condition))
    }

    fn local(&self, name: &str, t: Type, value: &Expr) -> String {
        format!("{} {name} = {};", type_name(t), self.expr(value))
    }

    fn counter(&self, name: &str) -> String {
        format!("uint32_t {name} = 0;")
    }

    fn increment(&self, name: &str) -> String {
        format!("{name}++;")
    }

    fn call_statement(&self, call: &Expr) -> Vec<String> {
        vec![format!("{};", self.expr(call))]
    }

    fn switch(&self, on: &Expr) -> String {
        format!("switch ({}) {{", self.expr(on))
    }

    fn arm(&self, numbers: &[i64]) -> Vec<String> {
        let last = numbers.len().saturating_sub(1);
        numbers
            .iter()
            .enumerate()
            .map(|(i, n)| {
                if i == last {
                    format!("case {n}: {{")
                } else {
                    format!("case {n}:")
                }
            })
            .collect()
    }

    fn otherwise(&self) -> String {
        "default: {".into()
    }

    fn arm_breaks(&self) -> bool {
        true
    }
}

/// Text as a C string literal's inside.
pub(crate) fn esc(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '?' => out.push_str("\\?"),
            c if (c as u32) < 0x20 || (c as u32) > 0x7e => {
                let mut buf = [0u8; 4];
                for b in c.encode_utf8(&mut buf).bytes() {
                    let _ = write!(out, "\\{b:03o}");
                }
            }
            c => out.push(c),
        }
    }
    out
}
