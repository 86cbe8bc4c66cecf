//! The standard scalable defeasible-logic theories of `docs/spec/benchmarks.md` (Maher, Rock,
//! Antoniou, Billington and Miller, 2001), written in `.dl` or SPINdle's `.dfl` so the same
//! files can be timed here and by other reasoners, with the answer each must give.

use std::fmt;
use std::io::{self, Write};

/// One benchmark theory with its size parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Chain(u64),
    Chains(u64),
    Circle(u64),
    Circles(u64),
    Levels(u64),
    LevelsMinus(u64),
    Teams(u64),
    Tree(u64, u64),
    Dag(u64, u64),
    Mix(u64, u64, u64),
    /// `Di: => ai`, `Ai: a(i+1 mod n) => ~ai`: a simple cycle of attacks.
    AttackRing(u64),
    /// `=> ai`, `=> bi`, `ai => ~bi`, `bi => ~ai`, `bi => ~a(i+1 mod n)`.
    PairsRing(u64),
    /// Support and attack around a ring, decided by priorities (benchmarks.md).
    PriorityRing(u64),
    /// `=> a0`; `ai => a(i+1 mod n)`; `a(i+2 mod n) ~> ~ai`.
    DefeaterRing(u64),
    /// `=> ai` for each i; `aj => ~ai` for every i ≠ j.
    Clique(u64),
    /// 2k layers closed in a cycle, alternating attack layers and support-and-attack layers.
    Ladder(u64),
    /// `=> c0`; clause facts `\/{~ci, c(i+1)}` for i < n; query `cn`.
    ClauseChain(u64),
}

/// The output language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Dl,
    Dfl,
}

/// What a correct reasoner answers on a family: `+alg lit` when `proved`, else `-alg lit`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expectation {
    pub algorithm: &'static str,
    pub literal: String,
    pub proved: bool,
}

impl fmt::Display for Expectation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sign = if self.proved { '+' } else { '-' };
        write!(f, "{sign}{} {}", self.algorithm, self.literal)
    }
}

/// A family name or its parameters were wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FamilyError(pub String);

impl fmt::Display for FamilyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for FamilyError {}

/// How a family of one number is made from it.
type MakeFamily = fn(u64) -> Family;

/// The families of one number, by name: each name stands once, with what it makes (a name
/// missing here is an unknown family, never another family).
const ONE_NUMBER: [(&str, MakeFamily); 14] = [
    ("chain", Family::Chain),
    ("chains", Family::Chains),
    ("circle", Family::Circle),
    ("circles", Family::Circles),
    ("levels", Family::Levels),
    ("levels-", Family::LevelsMinus),
    ("teams", Family::Teams),
    ("attack-ring", Family::AttackRing),
    ("pairs-ring", Family::PairsRing),
    ("priority-ring", Family::PriorityRing),
    ("defeater-ring", Family::DefeaterRing),
    ("clique", Family::Clique),
    ("ladder", Family::Ladder),
    ("clause-chain", Family::ClauseChain),
];

pub const NAMES: [&str; 17] = [
    "chain",
    "chains",
    "circle",
    "circles",
    "levels",
    "levels-",
    "teams",
    "tree",
    "dag",
    "mix",
    "attack-ring",
    "pairs-ring",
    "priority-ring",
    "defeater-ring",
    "clique",
    "ladder",
    "clause-chain",
];

impl Family {
    /// `chain 1000`, `tree 12 3`, `mix 10 5 4` as on the command line.
    pub fn parse(name: &str, args: &[u64]) -> Result<Family, FamilyError> {
        let want = |n: usize| -> Result<(), FamilyError> {
            if args.len() == n {
                Ok(())
            } else {
                Err(FamilyError(format!(
                    "`{name}` takes {n} number{}, got {}",
                    if n == 1 { "" } else { "s" },
                    args.len()
                )))
            }
        };
        let family = match name {
            _ if ONE_NUMBER.iter().any(|(n, _)| *n == name) => {
                want(1)?;
                let make = ONE_NUMBER
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map(|(_, make)| *make)
                    .ok_or_else(|| FamilyError(format!("unknown family `{name}`")))?;
                make(args[0])
            }
            "tree" | "dag" => {
                want(2)?;
                if args[1] < 2 && name == "tree" {
                    return Err(FamilyError("a tree needs k of at least 2".into()));
                }
                if name == "tree" {
                    Family::Tree(args[0], args[1])
                } else {
                    Family::Dag(args[0], args[1])
                }
            }
            "mix" => {
                want(3)?;
                Family::Mix(args[0], args[1], args[2])
            }
            _ => {
                return Err(FamilyError(format!(
                    "unknown family `{name}`; the families are {}",
                    NAMES.join(", ")
                )))
            }
        };
        match family {
            Family::Circle(0) | Family::Circles(0) => {
                Err(FamilyError("a circle needs at least one rule".into()))
            }
            Family::AttackRing(n)
            | Family::PairsRing(n)
            | Family::PriorityRing(n)
            | Family::DefeaterRing(n)
                if n < 3 =>
            {
                Err(FamilyError(format!("{family} needs a ring of at least 3")))
            }
            Family::Clique(n) | Family::Ladder(n) if n < 1 => {
                Err(FamilyError(format!("{family} needs a size of at least 1")))
            }
            _ if !family.is_valid() => Err(FamilyError(format!("{family} is too large to write"))),
            _ if family.rule_count() > 1 << 32 => Err(FamilyError(format!(
                "{family} would have {} rules, more than this generator writes",
                family.rule_count()
            ))),
            _ => Ok(family),
        }
    }

    /// Rules the theory has (facts not counted, as in the literature).
    pub fn rule_count(&self) -> u128 {
        let pow = |k: u64, n: u64| (k as u128).checked_pow(n as u32).unwrap_or(u128::MAX / 8);
        match *self {
            Family::Chain(n) | Family::Chains(n) | Family::Circle(n) | Family::Circles(n) => {
                n as u128
            }
            Family::Levels(n) | Family::LevelsMinus(n) => 4 * n as u128 + 5,
            Family::Teams(n) => 4 * (0..=n).map(|i| pow(4, i)).sum::<u128>(),
            Family::Tree(n, _) if !self.is_valid() => n as u128,
            Family::Tree(n, k) => (pow(k, n) - 1) / (k as u128 - 1),
            Family::Dag(n, k) => n as u128 * k as u128 + 1,
            Family::Mix(m, n, k) => 2 * m as u128 + 2 * (m * n * k) as u128,
            Family::AttackRing(n) => 2 * n as u128,
            Family::PairsRing(n) => 5 * n as u128,
            Family::PriorityRing(n) => 1 + 4 * n as u128,
            Family::DefeaterRing(n) => 1 + 2 * n as u128,
            Family::Clique(n) => n as u128 * n as u128,
            Family::Ladder(k) => 10 * k as u128,
            Family::ClauseChain(_) => 1,
        }
    }

    /// Clause facts the theory has (each becomes two strict rules of the checked theory).
    pub fn clause_count(&self) -> u128 {
        match *self {
            Family::ClauseChain(n) => n as u128,
            _ => 0,
        }
    }

    /// The answers a correct reasoner gives.
    pub fn expected(&self) -> Vec<Expectation> {
        let e = |algorithm, literal: String, proved| Expectation {
            algorithm,
            literal,
            proved,
        };
        match *self {
            Family::Chain(n) => vec![
                e("beta", format!("a{n}"), true),
                e("pi", format!("a{n}"), true),
            ],
            Family::Chains(n) => vec![e("mu", format!("a{n}"), true)],
            Family::Circle(_) => vec![e("beta", "a0".into(), false), e("pi", "a0".into(), false)],
            Family::Circles(_) => vec![e("mu", "a0".into(), false)],
            Family::Levels(_) | Family::Teams(_) | Family::Tree(..) | Family::Dag(..) => {
                vec![e("beta", "a0".into(), true), e("pi", "a0".into(), true)]
            }
            Family::LevelsMinus(_) => {
                vec![e("beta", "a0".into(), true), e("pi", "a0".into(), false)]
            }
            Family::Mix(..) => vec![e("beta", "p".into(), false), e("pi", "p".into(), false)],
            Family::AttackRing(n) | Family::Clique(n) => vec![e("beta", "a0".into(), n % 2 == 1)],
            Family::PairsRing(_) => vec![e("beta", "a0".into(), false)],
            Family::PriorityRing(_) | Family::DefeaterRing(_) => vec![e("beta", "a0".into(), true)],
            Family::Ladder(_) => vec![e("beta", "t0".into(), true)],
            Family::ClauseChain(n) => vec![
                e("beta", format!("c{n}"), true),
                e("pi", format!("c{n}"), true),
                e("mu", format!("c{n}"), false),
            ],
        }
    }

    /// Whether the sizes make a theory (`parse` only builds such families).
    pub fn is_valid(&self) -> bool {
        match *self {
            Family::Tree(n, k) => {
                k >= 2
                    && (k as u128)
                        .checked_pow(n as u32)
                        .is_some_and(|l| l < 1 << 40)
            }
            Family::Circle(n) | Family::Circles(n) => n > 0,
            Family::AttackRing(n)
            | Family::PairsRing(n)
            | Family::PriorityRing(n)
            | Family::DefeaterRing(n) => n >= 3,
            Family::Clique(n) => (1..=1 << 16).contains(&n),
            Family::Ladder(k) => k >= 1,
            _ => true,
        }
    }

    /// Writes the theory; sizes that make none are an `InvalidInput` error.
    pub fn write(&self, out: &mut impl Write, format: Format) -> io::Result<()> {
        if !self.is_valid() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{self} is not a theory"),
            ));
        }
        if format == Format::Dfl && self.clause_count() > 0 {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{self} is written with clause facts, which SPINdle's .dfl cannot say"),
            ));
        }
        let mut w = Writer { out, format };
        match *self {
            Family::Chain(n) | Family::Chains(n) => {
                let arrow = if matches!(self, Family::Chain(_)) {
                    "=>"
                } else {
                    "->"
                };
                w.fact("a0")?;
                for i in 1..=n {
                    w.rule(i, &[&format!("a{}", i - 1)], arrow, &format!("a{i}"))?;
                }
            }
            Family::Circle(n) | Family::Circles(n) => {
                let arrow = if matches!(self, Family::Circle(_)) {
                    "=>"
                } else {
                    "->"
                };
                for i in 0..n {
                    w.rule(i, &[&format!("a{i}")], arrow, &format!("a{}", (i + 1) % n))?;
                }
            }
            Family::Levels(n) | Family::LevelsMinus(n) => {
                write_levels(&mut w, n, matches!(self, Family::Levels(_)))?
            }
            Family::Teams(n) => write_teams(&mut w, n)?,
            Family::Tree(n, k) => write_tree(&mut w, n, k)?,
            Family::Dag(n, k) => write_dag(&mut w, n, k)?,
            Family::Mix(m, n, k) => write_mix(&mut w, m, n, k)?,
            _ => self.write_attack_family(&mut w)?,
        }
        Ok(())
    }

    /// The attack-cycle families of benchmarks.md ("Attack cycles"): one short arm per family,
    /// each arm that family's definition.
    fn write_attack_family<W: Write>(&self, w: &mut Writer<'_, W>) -> io::Result<()> {
        let a = |i: u64| format!("a{i}");
        let mut label = 0u64;
        let mut rule = |w: &mut Writer<'_, W>, body: &[&str], arrow: &str, head: &str| {
            label += 1;
            w.rule(label - 1, body, arrow, head).map(|_| label - 1)
        };
        match *self {
            Family::AttackRing(n) => {
                for i in 0..n {
                    rule(w, &[], "=>", &a(i))?;
                    rule(w, &[&a((i + 1) % n)], "=>", &w.neg(&a(i)))?;
                }
            }
            Family::PairsRing(n) => {
                for i in 0..n {
                    let (ai, bi) = (a(i), format!("b{i}"));
                    rule(w, &[], "=>", &ai)?;
                    rule(w, &[], "=>", &bi)?;
                    rule(w, &[&ai], "=>", &w.neg(&bi))?;
                    rule(w, &[&bi], "=>", &w.neg(&ai))?;
                    rule(w, &[&bi], "=>", &w.neg(&a((i + 1) % n)))?;
                }
            }
            Family::PriorityRing(n) => write_priority_ring(w, n)?,
            Family::DefeaterRing(n) => {
                rule(w, &[], "=>", &a(0))?;
                for i in 0..n {
                    rule(w, &[&a(i)], "=>", &a((i + 1) % n))?;
                    rule(w, &[&a((i + 2) % n)], "~>", &w.neg(&a(i)))?;
                }
            }
            Family::Clique(n) => {
                for i in 0..n {
                    rule(w, &[], "=>", &a(i))?;
                    for j in (0..n).filter(|&j| j != i) {
                        rule(w, &[&a(j)], "=>", &w.neg(&a(i)))?;
                    }
                }
            }
            Family::Ladder(k) => {
                let layers = 2 * k;
                let at = |name: &str, i: u64| format!("{name}{}", i % layers);
                for i in 0..layers {
                    if i % 2 == 0 {
                        for x in ["t", "u"] {
                            rule(w, &[], "=>", &at(x, i))?;
                            rule(w, &[&at("f", i + 1)], "=>", &w.neg(&at(x, i)))?;
                            rule(w, &[&at("g", i + 1)], "=>", &w.neg(&at(x, i)))?;
                        }
                    } else {
                        for x in ["f", "g"] {
                            rule(w, &[&at("t", i + 1)], "=>", &at(x, i))?;
                            rule(w, &[&at("u", i + 1)], "=>", &w.neg(&at(x, i)))?;
                        }
                    }
                }
            }
            Family::ClauseChain(n) => {
                rule(w, &[], "=>", "c0")?;
                for i in 0..n {
                    writeln!(w.out, "\\/{{~c{i}, c{}}}.", i + 1)?;
                }
            }
            _ => unreachable!("write handles the other families"),
        }
        Ok(())
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Family::Chain(n) => write!(f, "chain({n})"),
            Family::Chains(n) => write!(f, "chains({n})"),
            Family::Circle(n) => write!(f, "circle({n})"),
            Family::Circles(n) => write!(f, "circles({n})"),
            Family::Levels(n) => write!(f, "levels({n})"),
            Family::LevelsMinus(n) => write!(f, "levels-({n})"),
            Family::Teams(n) => write!(f, "teams({n})"),
            Family::Tree(n, k) => write!(f, "tree({n}, {k})"),
            Family::Dag(n, k) => write!(f, "dag({n}, {k})"),
            Family::Mix(m, n, k) => write!(f, "mix({m}, {n}, {k})"),
            Family::AttackRing(n) => write!(f, "attack-ring({n})"),
            Family::PairsRing(n) => write!(f, "pairs-ring({n})"),
            Family::PriorityRing(n) => write!(f, "priority-ring({n})"),
            Family::DefeaterRing(n) => write!(f, "defeater-ring({n})"),
            Family::Clique(n) => write!(f, "clique({n})"),
            Family::Ladder(k) => write!(f, "ladder({k})"),
            Family::ClauseChain(n) => write!(f, "clause-chain({n})"),
        }
    }
}

/// Levels of mutual defeat, each level's attack beaten by a priority (`Levels`) or not.
fn write_levels<W: Write>(w: &mut Writer<'_, W>, n: u64, with_priorities: bool) -> io::Result<()> {
    w.rule(0, &[], "=>", "a0")?;
    for i in 0..=n {
        let (even, odd, next) = (2 * i, 2 * i + 1, 2 * i + 2);
        w.rule(
            4 * i + 1,
            &[&format!("a{odd}")],
            "=>",
            &w.neg(&format!("a{even}")),
        )?;
        w.rule(4 * i + 2, &[], "=>", &format!("a{odd}"))?;
        w.rule(
            4 * i + 3,
            &[&format!("a{next}")],
            "=>",
            &w.neg(&format!("a{odd}")),
        )?;
        w.rule(4 * i + 4, &[], "=>", &format!("a{next}"))?;
        if with_priorities {
            w.priority(4 * i + 3, 4 * i + 2)?;
        }
    }
    Ok(())
}

/// Team defeat: a complete tree of blocks of four rules, two for each side.
fn write_teams<W: Write>(w: &mut Writer<'_, W>, n: u64) -> io::Result<()> {
    // Breadth first: block k's atom is a(k); its four fresh b's are the next atoms.
    let mut next_atom = 1u64;
    let mut rule = 0u64;
    let mut level = vec![0u64];
    for depth in (0..=n).rev() {
        let mut below = Vec::new();
        for p in level {
            let p = format!("a{p}");
            let np = w.neg(&p);
            let heads = [&p, &p, &np, &np];
            for (j, head) in heads.into_iter().enumerate() {
                if depth == 0 {
                    w.rule(rule + j as u64, &[], "=>", head)?;
                } else {
                    let b = next_atom + j as u64;
                    below.push(b);
                    w.rule(rule + j as u64, &[&format!("a{b}")], "=>", head)?;
                }
            }
            if depth > 0 {
                next_atom += 4;
            }
            w.priority(rule, rule + 2)?;
            w.priority(rule + 1, rule + 3)?;
            rule += 4;
        }
        level = below;
    }
    Ok(())
}

/// A complete `k`-ary tree of depth `n`: each rule needs its `k` children; leaves are facts.
fn write_tree<W: Write>(w: &mut Writer<'_, W>, n: u64, k: u64) -> io::Result<()> {
    let internal = ((k as u128).pow(n as u32) - 1) / (k as u128 - 1);
    let internal = internal as u64;
    for i in 0..internal {
        let children: Vec<String> = (1..=k).map(|c| format!("a{}", k * i + c)).collect();
        let refs: Vec<&str> = children.iter().map(String::as_str).collect();
        w.rule(i, &refs, "=>", &format!("a{i}"))?;
    }
    let leaves = (k as u128).pow(n as u32) as u64;
    for leaf in internal..internal + leaves {
        w.fact(&format!("a{leaf}"))?;
    }
    Ok(())
}

/// The priority ring of benchmarks.md ("Attack cycles"): `a(i) => a(i+1)`, attacked through
/// `b(i)`, the priorities alternating round the ring.
fn write_priority_ring<W: Write>(w: &mut Writer<'_, W>, n: u64) -> io::Result<()> {
    let a = |i: u64| format!("a{i}");
    let mut label = 0u64;
    let mut rule = |w: &mut Writer<'_, W>, body: &[&str], arrow: &str, head: &str| {
        label += 1;
        w.rule(label - 1, body, arrow, head).map(|_| label - 1)
    };
    rule(w, &[], "=>", &a(0))?;
    for i in 0..n {
        let (next, after) = (a((i + 1) % n), a((i + 2) % n));
        let bi = format!("b{i}");
        let p = rule(w, &[&a(i)], "=>", &next)?;
        let m = rule(w, &[&bi], "=>", &w.neg(&next))?;
        let b = rule(w, &[&next], "=>", &bi)?;
        let c = rule(w, &[&after], "=>", &w.neg(&bi))?;
        w.priority(p, m)?;
        if i % 2 == 0 {
            w.priority(b, c)?;
        } else {
            w.priority(c, b)?;
        }
    }
    Ok(())
}

/// Each atom needs the next `k`; the last `k` are facts.
fn write_dag<W: Write>(w: &mut Writer<'_, W>, n: u64, k: u64) -> io::Result<()> {
    for i in k * n + 1..=k * n + k {
        w.fact(&format!("a{i}"))?;
    }
    for i in 0..=n * k {
        let body: Vec<String> = (1..=k).map(|j| format!("a{}", i + j)).collect();
        let refs: Vec<&str> = body.iter().map(String::as_str).collect();
        w.rule(i, &refs, "=>", &format!("a{i}"))?;
    }
    Ok(())
}

/// `m` defeasible rules for `p` and `m` defeaters against it, each antecedent at the end of a
/// strict chain of length `k` from a fact.
fn write_mix<W: Write>(w: &mut Writer<'_, W>, m: u64, n: u64, k: u64) -> io::Result<()> {
    let mut rule = 0u64;
    for i in 1..=2 * m {
        let body: Vec<String> = (1..=n).map(|j| format!("a{i}_{j}")).collect();
        let refs: Vec<&str> = body.iter().map(String::as_str).collect();
        let (arrow, head) = if i <= m {
            ("=>", "p".to_string())
        } else {
            ("~>", w.neg("p"))
        };
        w.rule(rule, &refs, arrow, &head)?;
        rule += 1;
        for j in 1..=n {
            // A strict chain of length k from a fact to a(i, j).
            let link = |l: u64| {
                if l == k {
                    format!("a{i}_{j}")
                } else {
                    format!("a{i}_{j}_{l}")
                }
            };
            w.fact(&link(0))?;
            for l in 1..=k {
                w.rule(rule, &[&link(l - 1)], "->", &link(l))?;
                rule += 1;
            }
        }
    }
    Ok(())
}

struct Writer<'w, W: Write> {
    out: &'w mut W,
    format: Format,
}

impl<W: Write> Writer<'_, W> {
    fn neg(&self, atom: &str) -> String {
        match self.format {
            Format::Dl => format!("~{atom}"),
            Format::Dfl => format!("-{atom}"),
        }
    }

    fn fact(&mut self, lit: &str) -> io::Result<()> {
        match self.format {
            Format::Dl => writeln!(self.out, "{lit}."),
            Format::Dfl => writeln!(self.out, ">> {lit}"),
        }
    }

    fn rule(&mut self, label: u64, body: &[&str], arrow: &str, head: &str) -> io::Result<()> {
        let end = if self.format == Format::Dl { "." } else { "" };
        if body.is_empty() {
            writeln!(self.out, "r{label}: {arrow} {head}{end}")
        } else {
            writeln!(
                self.out,
                "r{label}: {} {arrow} {head}{end}",
                body.join(", ")
            )
        }
    }

    fn priority(&mut self, winner: u64, loser: u64) -> io::Result<()> {
        let end = if self.format == Format::Dl { "." } else { "" };
        writeln!(self.out, "r{winner} > r{loser}{end}")
    }
}

/// A theory only a search decides: ladder(6), whose layers alone would be decided without one,
/// with one rule read across them (`t2` attacked from `t0`), so its 24 goals are searched (`t0`
/// is proved, after about 110,000 steps). For tests of the search and its budget.
pub fn crossed_ladder() -> String {
    let mut text = Vec::new();
    // Writing to a vector cannot fail.
    let _ = Family::Ladder(6).write(&mut text, Format::Dl);
    String::from_utf8_lossy(&text).into_owned() + "x: t0 => ~t2.\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every family name makes that family and no other (a name once fell through to `teams`).
    #[test]
    fn every_name_makes_its_own_family() {
        for name in NAMES {
            let args: &[u64] = match name {
                "tree" | "dag" => &[3, 2],
                "mix" => &[3, 3, 2],
                _ => &[5],
            };
            let family = Family::parse(name, args).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(
                family.to_string().starts_with(&format!("{name}(")),
                "{name} made {family}"
            );
        }
        assert_eq!(
            ONE_NUMBER.len() + 3,
            NAMES.len(),
            "every name is in one table"
        );
        assert!(Family::parse("teamz", &[5]).is_err());
    }
}
