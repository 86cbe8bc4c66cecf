//! The order of different machines' clocks ([`crate::clocks`]) in SPIN's model: its arrays,
//! what an arrival, a move and a new round write, and the condition a snapshot's due tests
//! must meet, as Promela text the writer (`promela.rs`) places.
//!
//! Arrays, one entry a machine (only where some machine's clocks are ordered): `arr`
//! ([`crate::world::Control::arrived`]), `ord` (its row of [`crate::world::Control::order`]),
//! `ldue` and `lwait` (what it left with, [`crate::clocks::left`]).

use crate::clocks::{bounds, heard_later, implied, number, ordered};
use crate::model::StateModel;
use crate::search::Search;

/// Whether any machine's clocks are ordered (else nothing of this is written).
pub(crate) fn any(model: &Search) -> bool {
    model.clock_ranks.iter().any(Option::is_some)
}

/// The arrays' declarations.
pub(crate) fn declarations(model: &Search) -> String {
    let n = model.machines.len();
    format!(
        "bit arr[{n}]; /* arrived this round in a state whose clocks are ordered */\n\
         byte ord[{n}]; /* bit r: arrived no later than the machine of clock rank r */\n\
         byte ldue[{n}]; /* left this round: its longest due test of its arrival's clocks */\n\
         byte lwait[{n}]; /* left this round: its shortest test not due */"
    )
}

/// What machine `k`'s arrival into state `s` writes ([`crate::clocks::arrive`]).
pub(crate) fn arrival(model: &Search, k: usize, s: usize) -> Option<String> {
    let rank = model.clock_ranks[k]?;
    let takes_part = ordered(&model.machines[k].states[s]);
    let mut out = String::new();
    let mut row = Vec::new();
    for (j, r) in model.clock_ranks.iter().enumerate() {
        let Some(r) = *r else { continue };
        if j == k {
            continue;
        }
        if takes_part {
            out.push_str(&format!("ord[{j}] = ord[{j}] | {}; ", 1 << rank));
            row.push(format!("(arr[{j}] << {r})"));
        } else {
            out.push_str(&format!("ord[{j}] = ord[{j}] & {}; ", 255 ^ (1 << rank)));
        }
    }
    let row = if row.is_empty() || !takes_part {
        "0".to_string()
    } else {
        row.join(" | ")
    };
    let arrived = takes_part && heard_later(&model.clock_ranks, k);
    out.push_str(&format!(
        "ord[{k}] = {row}; arr[{k}] = {};",
        u8::from(arrived)
    ));
    Some(out)
}

/// What a new round clears.
pub(crate) fn new_round(model: &Search) -> String {
    (model.clock_ranks.iter().enumerate())
        .filter(|(_, r)| r.is_some())
        .map(|(k, _)| format!(" arr[{k}] = 0; ldue[{k}] = 0; lwait[{k}] = 0;"))
        .collect()
}

/// What machine `k` leaving `state` keeps for the round, from its due bits then.
pub(crate) fn leaving(model: &Search, k: usize, state: &StateModel) -> Option<String> {
    if !heard_later(&model.clock_ranks, k) {
        return None;
    }
    let number = |d| number(&model.clock_durations, Some(d));
    let constant: Vec<(usize, u64)> = (state.time_tests.iter().enumerate())
        .filter_map(|(i, t)| Some((i, t.micros?)))
        .collect();
    // Longest due first, among the arrival's clocks.
    let mut due: Vec<(usize, u64)> = (constant.iter().copied())
        .filter(|&(i, _)| state.arrival_starts(state.time_tests[i].clock))
        .collect();
    due.sort_by_key(|&(_, d)| std::cmp::Reverse(d));
    let longest = due.iter().rev().fold("0".to_string(), |rest, &(i, d)| {
        format!("(((due[{k}] >> {i}) & 1) -> {} : {rest})", number(d))
    });
    // Shortest not due first.
    let mut waiting = constant;
    waiting.sort_by_key(|&(_, d)| std::cmp::Reverse(d));
    let shortest = waiting.iter().fold("0".to_string(), |rest, &(i, d)| {
        format!("(((due[{k}] >> {i}) & 1) -> {rest} : {})", number(d))
    });
    Some(format!("ldue[{k}] = {longest}; lwait[{k}] = {shortest};"))
}

/// The condition machine `k` in state `s` may have `mask` due on, as the other machines'
/// clocks stand ([`crate::clocks::agrees`]); `None` where nothing constrains it.
pub(crate) fn agrees(model: &Search, k: usize, state: &StateModel, mask: u16) -> Option<String> {
    let rank = model.clock_ranks[k]?;
    let mut broken = Vec::new();
    for (j, r) in model.clock_ranks.iter().enumerate() {
        let Some(r) = *r else { continue };
        if j == k {
            continue;
        }
        let mine_older = format!("((ord[{k}] >> {r}) & 1)");
        let theirs_older = format!("((ord[{j}] >> {rank}) & 1)");
        let settled = settled_broken(model, k, j, state, mask, &mine_older, &theirs_older);
        let left = left_broken(model, j, state, mask, &mine_older, &theirs_older);
        if settled.is_none() && left.is_none() {
            continue;
        }
        let moved = format!("(ldue[{j}] != 0 || lwait[{j}] != 0)");
        let settled = settled.map_or("0".to_string(), |b| {
            format!("(mode[{j}] == 0 && !je[{j}] && ({b}))")
        });
        let left = left.unwrap_or_else(|| "0".to_string());
        broken.push(format!("({moved} -> ({left}) : {settled})"));
    }
    (!broken.is_empty()).then(|| format!("!({})", broken.join(" || ")))
}

/// [`agrees`] against machine `j` in its state: a due test of `j`'s arrival implies one of
/// `k` not in `mask`, or (`j` rang before `k`) one in `mask` implies one of `j` not due.
fn settled_broken(
    model: &Search,
    k: usize,
    j: usize,
    state: &StateModel,
    mask: u16,
    mine_older: &str,
    theirs_older: &str,
) -> Option<String> {
    let mut any = Vec::new();
    for (t, other) in model.machines[j].states.iter().enumerate() {
        let forcing = implied(state, other)
            .filter(|&(_, x)| mask & (1 << x) == 0)
            .fold(0u32, |m, (y, _)| m | 1 << y);
        let needed = match j < k {
            true => implied(other, state)
                .filter(|&(y, _)| mask & (1 << y) != 0)
                .fold(0u32, |m, (_, x)| m | 1 << x),
            false => 0,
        };
        let mut here = Vec::new();
        if forcing != 0 {
            here.push(format!("({mine_older} && (due[{j}] & {forcing}) != 0)"));
        }
        if needed != 0 {
            here.push(format!(
                "({theirs_older} && (due[{j}] & {needed}) != {needed})"
            ));
        }
        if !here.is_empty() {
            any.push(format!("(st[{j}] == {t} && ({}))", here.join(" || ")));
        }
    }
    (!any.is_empty()).then(|| any.join(" || "))
}

/// [`agrees`] against machine `j` that left its state in this round, by what it kept.
fn left_broken(
    model: &Search,
    j: usize,
    state: &StateModel,
    mask: u16,
    mine_older: &str,
    theirs_older: &str,
) -> Option<String> {
    let number = |d| number(&model.clock_durations, Some(d));
    let (due, not_due) = bounds(state, mask);
    let mut any = Vec::new();
    if let Some(d) = not_due {
        any.push(format!("({mine_older} && ldue[{j}] >= {})", number(d)));
    }
    if let Some(d) = due {
        any.push(format!(
            "({theirs_older} && lwait[{j}] != 0 && lwait[{j}] <= {})",
            number(d)
        ));
    }
    (!any.is_empty()).then(|| any.join(" || "))
}
