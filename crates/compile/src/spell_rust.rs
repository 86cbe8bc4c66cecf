//! How Rust writes the code tree (`code.rs`): the world borrowed, a label as a closure that
//! `proved` runs, `match` for a switch, and a value read from the world bound before the call
//! that changes it (the borrow checker's rule).

use crate::code::{Expr, Function, Spelling, Type};

pub(crate) struct Rust;

fn type_name(t: Type) -> &'static str {
    match t {
        Type::Truth => "bool",
        Type::Index => "usize",
        Type::Ms => "u64",
        Type::Text => "&str",
    }
}

impl Rust {
    fn with_world(&self, name: &str, args: &[Expr]) -> String {
        // The runtime's calls that read the behaviour's tables are generic over them.
        let tables = if proclaim_runtime::calls::GENERIC.contains(&name) {
            "::<Behaviour>"
        } else {
            ""
        };
        if args.is_empty() {
            format!("{name}{tables}(w)")
        } else {
            format!("{name}{tables}(w, {})", self.list(args))
        }
    }
}

impl Spelling for Rust {
    fn expr(&self, e: &Expr) -> String {
        match e {
            Expr::World(field) => format!("w.{field}"),
            Expr::Index(table, at) => format!("{}[{}]", self.expr(table), self.expr(at)),
            Expr::Table(name) => name.to_uppercase(),
            Expr::Name(name) => name.clone(),
            Expr::Whole(i) if *i == i64::MIN => "i64::MIN".into(),
            Expr::Whole(i) => i.to_string(),
            Expr::Count(n) => n.to_string(),
            Expr::Number(n) => n.to_string(),
            Expr::Truth(b) => b.to_string(),
            Expr::Text(s) => format!("{s:?}"),
            Expr::Call(name, args) => self.with_world(name, args),
            Expr::Pure(name, args) => format!("{name}({})", self.list(args)),
            Expr::Report(name, args) | Expr::Buffer(name, args) => {
                format!("w.{name}({})", self.list(args))
            }
            Expr::Not(e) => format!("!{}", self.expr(e)),
            Expr::Binary(..) => format!("({})", self.bare(e)),
            Expr::Label(label) => format!("|w| {}", self.bare(label)),
            Expr::Decide {
                theory,
                output,
                offset,
            } => format!("crate::theories::{theory}({output}, &w.input[{offset}..])"),
        }
    }

    fn head(&self, f: &Function) -> (String, Vec<String>) {
        let world = if f.writes { "&mut World" } else { "&World" };
        let mut params = vec![format!("w: {world}")];
        for (name, t) in &f.params {
            params.push(format!("mut {name}: {}", type_name(*t)));
        }
        let head = format!(
            "fn {}({}) -> {} {{",
            f.name,
            params.join(", "),
            type_name(f.returns)
        );
        (head, vec![])
    }

    fn test(&self, keyword: &str, condition: &Expr) -> String {
        format!("{keyword} {} {{", self.bare(condition))
    }

    fn local(&self, name: &str, t: Type, value: &Expr) -> String {
        format!("let mut {name}: {} = {};", type_name(t), self.expr(value))
    }

    fn counter(&self, name: &str) -> String {
        format!("let mut {name}: u32 = 0;")
    }

    fn increment(&self, name: &str) -> String {
        format!("{name} += 1;")
    }

    /// Each argument read from the world is bound first, as `value` (a call that changes the
    /// world cannot also lend it to its arguments).
    fn call_statement(&self, call: &Expr) -> Vec<String> {
        let Some(args) = call.arguments() else {
            return vec![format!("{};", self.expr(call))];
        };
        let mut lines = Vec::new();
        let mut bound = Vec::new();
        for (i, arg) in args.iter().enumerate() {
            if arg.reads_world() {
                let name = format!("value_{i}");
                lines.push(format!("let {name} = {};", self.expr(arg)));
                bound.push(Expr::Name(name));
            } else {
                bound.push(Expr::Name(self.expr(arg)));
            }
        }
        let call = call.with_arguments(bound);
        lines.push(format!("{};", self.expr(&call)));
        lines
    }

    fn switch(&self, on: &Expr) -> String {
        format!("match {} {{", self.expr(on))
    }

    fn arm(&self, numbers: &[i64]) -> Vec<String> {
        let shown: Vec<String> = numbers.iter().map(i64::to_string).collect();
        vec![format!("{} => {{", shown.join(" | "))]
    }

    fn otherwise(&self) -> String {
        "_ => {".into()
    }

    fn arm_breaks(&self) -> bool {
        false
    }
}
