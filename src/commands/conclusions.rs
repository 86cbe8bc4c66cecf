//! Every conclusion of a theory written out, a line (or a JSON object) per answer: `prove` with
//! no query and SPINdle's format. A 10^6-literal theory is millions of lines, so each line is
//! written as bytes into one buffer, the algorithm's tag and the atom's name copied, never
//! formatted line by line.

use proclaim_cdl::{Algorithm, Atom, Lit, ProofOutcome, Session, Theory, Undecided};
use std::io::{self, Write};

/// How a line writes a negated literal: `~a` in proclaim's own forms, `-a` in SPINdle's.
#[derive(Clone, Copy)]
pub enum Negation {
    Tilde,
    Minus,
}

/// Writes `lit` as `a`, `~a` or `-a`.
pub fn write_lit(
    out: &mut impl Write,
    theory: &Theory,
    lit: Lit,
    negation: Negation,
) -> io::Result<()> {
    if lit.is_negated() {
        out.write_all(match negation {
            Negation::Tilde => b"~",
            Negation::Minus => b"-",
        })?;
    }
    out.write_all(theory.atom_name(lit.atom()).as_bytes())
}

/// `+beta q`, `-beta q`, or `?beta q  (undecided: …)`: the line of one answer.
pub fn write_line<W: Write>(
    out: &mut W,
    alg: Algorithm,
    query: impl FnOnce(&mut W) -> io::Result<()>,
    answer: &Result<bool, Undecided>,
) -> io::Result<()> {
    out.write_all(match answer {
        Ok(true) => b"+",
        Ok(false) => b"-",
        Err(_) => b"?",
    })?;
    out.write_all(alg.name().as_bytes())?;
    out.write_all(b" ")?;
    query(out)?;
    if let Err(undecided) = answer {
        write!(out, "  (undecided: {})", reason(undecided))?;
    }
    out.write_all(b"\n")
}

/// `{"algorithm":"beta","proved":true,"query":"q"}`, the keys in the order serde_json sorts
/// them, so the array is the one `serde_json` would print for the same answers.
pub fn write_json_item<W: Write>(
    out: &mut W,
    alg: Algorithm,
    query: impl FnOnce(&mut W) -> io::Result<()>,
    answer: &Result<bool, Undecided>,
) -> io::Result<()> {
    out.write_all(b"{\"algorithm\":\"")?;
    out.write_all(alg.name().as_bytes())?;
    out.write_all(match answer {
        Ok(true) => b"\",\"proved\":true,\"query\":".as_slice(),
        Ok(false) => b"\",\"proved\":false,\"query\":",
        Err(_) => b"\",\"proved\":null,\"query\":",
    })?;
    query(out)?;
    if let Err(undecided) = answer {
        out.write_all(b",\"undecided\":")?;
        write_json_string(out, &undecided.to_string())?;
    }
    out.write_all(b"}")
}

/// A JSON string, escaped by serde_json.
pub fn write_json_string(out: &mut impl Write, text: &str) -> io::Result<()> {
    serde_json::to_writer(out, text).map_err(io::Error::from)
}

/// A literal as a JSON string: its name copied as it is when nothing in it needs escaping (an
/// atom name, nearly always).
fn write_json_lit(out: &mut impl Write, theory: &Theory, lit: Lit) -> io::Result<()> {
    let name = theory.atom_name(lit.atom());
    if name.bytes().any(|b| b == b'"' || b == b'\\' || b < 0x20) {
        return write_json_string(out, &theory.show(lit).to_string());
    }
    out.write_all(b"\"")?;
    write_lit(out, theory, lit, Negation::Tilde)?;
    out.write_all(b"\"")
}

/// The undecided answer's reason, short enough for the end of an answer line.
pub fn reason(undecided: &Undecided) -> String {
    let origin = if undecided.stalled_at == undecided.goal {
        String::new()
    } else {
        format!(" through `{}`", undecided.stalled_at)
    };
    format!(
        "search budget of {} steps spent in an attack cycle of {} goals{origin}; raise it with --budget",
        undecided.steps, undecided.component
    )
}

/// Every literal each algorithm proves or leaves undecided (not the ones it does not prove),
/// algorithm by algorithm in literal order, as lines or as one JSON array. Returns whether any
/// was undecided.
pub fn write_every<W: Write>(
    out: &mut W,
    session: &mut Session,
    algorithms: &[Algorithm],
    json: bool,
) -> io::Result<bool> {
    let engine = session.engine().clone();
    let theory = engine.theory();
    let mut any_undecided = false;
    let mut first = true;
    if json {
        out.write_all(b"[")?;
    }
    for &alg in algorithms {
        for (lit, verdict) in (0..).map(Lit).zip(session.answers(alg)) {
            let answer = match verdict {
                ProofOutcome::NotProved => continue,
                ProofOutcome::Proved => Ok(true),
                ProofOutcome::Undecided => {
                    any_undecided = true;
                    session.decide(alg, lit)
                }
            };
            if json {
                if !first {
                    out.write_all(b",")?;
                }
                first = false;
                let query = |out: &mut W| write_json_lit(out, theory, lit);
                write_json_item(out, alg, query, &answer)?;
            } else {
                let query = |out: &mut W| write_lit(out, theory, lit, Negation::Tilde);
                write_line(out, alg, query, &answer)?;
            }
        }
    }
    if json {
        out.write_all(b"]\n")?;
    }
    Ok(any_undecided)
}

/// SPINdle's sign for `alg`'s answer about `lit`: `+`, `-`, or `?` for an undecided one, which
/// SPINdle does not have, explained on stderr.
fn spindle_sign(session: &mut Session, alg: Algorithm, lit: Lit, verdict: ProofOutcome) -> u8 {
    match verdict {
        ProofOutcome::Proved => b'+',
        ProofOutcome::NotProved => b'-',
        ProofOutcome::Undecided => {
            if let Err(undecided) = session.decide(alg, lit) {
                eprintln!("warning: {undecided}");
            }
            b'?'
        }
    }
}

/// SPINdle's conclusions for each literal given: `+D`/`-D` for μ, `+d`/`-d` for β, negation
/// written `-a`. SPINdle has no undecided answer: `?` marks one, explained on stderr. Returns
/// whether any was undecided.
pub fn write_spindle(
    out: &mut impl Write,
    session: &mut Session,
    lits: impl IntoIterator<Item = Lit>,
) -> io::Result<bool> {
    let engine = session.engine().clone();
    let theory = engine.theory();
    let mut any_undecided = false;
    for lit in lits {
        for (tag, alg) in [(b"D ", Algorithm::Mu), (b"d ", Algorithm::Beta)] {
            let verdict = session.verdict(alg, lit);
            let sign = spindle_sign(session, alg, lit, verdict);
            any_undecided |= sign == b'?';
            out.write_all(&[sign])?;
            out.write_all(tag)?;
            write_lit(out, theory, lit, Negation::Minus)?;
            out.write_all(b"\n")?;
        }
    }
    Ok(any_undecided)
}

/// Every atom of the theory in SPINdle's order: by name (byte order). The sort key leads with a
/// name's first eight bytes as a number, so nearly every comparison is one of integers rather
/// than of two names far apart in memory.
pub fn spindle_order(theory: &Theory) -> Vec<Atom> {
    let prefix = |name: &str| {
        let mut bytes = [0u8; 8];
        let n = name.len().min(8);
        bytes[..n].copy_from_slice(&name.as_bytes()[..n]);
        u64::from_be_bytes(bytes)
    };
    let mut atoms: Vec<(u64, u32)> = (0..theory.atom_count() as u32)
        .map(|a| (prefix(theory.atom_name(Atom(a))), a))
        .collect();
    // A name shorter than eight bytes is padded with zeros, which no name holds, so equal
    // prefixes are either the same short name or two long names that the full names decide.
    atoms.sort_unstable_by(|x, y| {
        x.0.cmp(&y.0)
            .then_with(|| theory.atom_name(Atom(x.1)).cmp(theory.atom_name(Atom(y.1))))
    });
    atoms.into_iter().map(|(_, a)| Atom(a)).collect()
}

/// SPINdle's conclusions for every atom, in SPINdle's order (`order` gives it, from
/// [`spindle_order`], once asked: it may still be being sorted on another thread):
/// `±D a`, `±d a`, `±D -a`, `±d -a`. Every answer is found first, in literal order, and the lines
/// are then written as bytes into one buffer, handed on a megabyte at a time. SPINdle has no
/// undecided answer: `?` marks one, explained on stderr. Returns whether any was undecided.
pub fn write_spindle_every(
    out: &mut impl Write,
    session: &mut Session,
    order: impl FnOnce() -> Vec<Atom>,
) -> io::Result<bool> {
    const CHUNK: usize = 1 << 20;
    let mu = session.answers(Algorithm::Mu);
    let beta = session.answers(Algorithm::Beta);
    let order = order();
    let engine = session.engine().clone();
    let theory = engine.theory();
    let mut any_undecided = false;
    let mut text = Vec::with_capacity(CHUNK + 4096);
    for &atom in &order {
        let name = theory.atom_name(atom).as_bytes();
        for negated in [false, true] {
            let lit = Lit::new(atom, negated);
            for (tag, alg, answers) in
                [(b"D ", Algorithm::Mu, &mu), (b"d ", Algorithm::Beta, &beta)]
            {
                let sign = spindle_sign(session, alg, lit, answers[lit.index()]);
                any_undecided |= sign == b'?';
                text.push(sign);
                text.extend_from_slice(tag);
                if negated {
                    text.push(b'-');
                }
                text.extend_from_slice(name);
                text.push(b'\n');
            }
        }
        if text.len() >= CHUNK {
            out.write_all(&text)?;
            text.clear();
        }
    }
    out.write_all(&text)?;
    Ok(any_undecided)
}
