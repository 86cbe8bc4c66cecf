//! `proclaim table`: the truth table of the declared outputs over the declared inputs.

use crate::cli::TableFormat;
use crate::failure::Failure;
use crate::load;
use proclaim_cdl::{truth_table, Engine, Table};
use std::process::ExitCode;
use std::sync::Arc;

pub fn run(theory_name: &str, format: TableFormat) -> Result<ExitCode, Failure> {
    let (_, theory) = load::theory(theory_name)?;
    let table =
        truth_table(Arc::new(Engine::new(theory))).map_err(|e| Failure::Argument(e.to_string()))?;
    if table.default_columns {
        eprintln!(
            "note: the theory declares no output{{}}; tabling every non-input atom with beta"
        );
    }
    print!(
        "{}",
        match format {
            TableFormat::Text => text(&table),
            TableFormat::Csv => csv(&table),
            TableFormat::Markdown => markdown(&table),
            TableFormat::Json => format!("{}\n", json(&table)),
        }
    );
    Ok(ExitCode::SUCCESS)
}

/// Header and body cells: inputs first, then one column per output.
fn cells(table: &Table) -> (Vec<String>, Vec<Vec<String>>) {
    let header = table
        .inputs
        .iter()
        .cloned()
        .chain(table.columns.iter().map(|c| c.heading.clone()))
        .collect();
    let rows = table
        .rows
        .iter()
        .map(|row| {
            let mut cells: Vec<String> = row.inputs.iter().map(|v| v.to_string()).collect();
            match &row.outputs {
                Some(outputs) => cells.extend(outputs.iter().map(|v| v.to_string())),
                None => cells.extend(table.columns.iter().map(|_| "inconsistent".to_string())),
            }
            cells
        })
        .collect();
    (header, rows)
}

fn text(table: &Table) -> String {
    let (header, rows) = cells(table);
    let widths: Vec<usize> = (0..header.len())
        .map(|i| {
            rows.iter()
                .map(|r| r[i].len())
                .chain([header[i].len()])
                .max()
                .unwrap_or(0)
                // Padding past this point reads no better, and `format!` panics past u16::MAX.
                .min(80)
        })
        .collect();
    let split = table.inputs.len();
    let line = |cells: &[String]| {
        let mut out = String::new();
        for (i, cell) in cells.iter().enumerate() {
            if i == split && split > 0 {
                out.push_str("| ");
            }
            out.push_str(&format!("{cell:<w$}  ", w = widths[i]));
        }
        out.trim_end().to_string() + "\n"
    };
    let mut out = line(&header);
    for row in &rows {
        out.push_str(&line(row));
    }
    for column in table.columns.iter().filter(|c| c.description.is_some()) {
        out.push_str(&format!(
            "{}: {}\n",
            column.heading,
            column.description.as_deref().unwrap_or_default()
        ));
    }
    out
}

fn csv(table: &Table) -> String {
    let quote = |s: &str| {
        if s.contains([',', '"', '\n']) {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s.to_string()
        }
    };
    let (header, rows) = cells(table);
    std::iter::once(header)
        .chain(rows)
        .map(|r| r.iter().map(|c| quote(c)).collect::<Vec<_>>().join(",") + "\n")
        .collect()
}

fn markdown(table: &Table) -> String {
    let (header, rows) = cells(table);
    let mut out = format!("| {} |\n", header.join(" | "));
    out.push_str(&format!("|{}\n", "---|".repeat(header.len())));
    for row in rows {
        out.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    out
}

/// The table as one JSON object, written straight into text: a `serde_json::Value` of a table
/// with a column for each of a million atoms is a million map entries. Keys come in the order
/// serde_json's maps keep them (sorted, the last of equal keys kept), so the text is the one
/// serde_json would print.
fn json(table: &Table) -> String {
    let mut out = String::from("{\"inputs\":[");
    for (i, name) in table.inputs.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        push_json_str(&mut out, name);
    }
    out.push_str("],\"outputs\":[");
    for (i, c) in table.columns.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str("{\"algorithm\":");
        push_json_str(&mut out, c.algorithm.name());
        out.push_str(",\"description\":");
        match &c.description {
            Some(d) => push_json_str(&mut out, d),
            None => out.push_str("null"),
        }
        out.push_str(",\"heading\":");
        push_json_str(&mut out, &c.heading);
        out.push('}');
    }
    out.push_str("],\"rows\":[");
    let inputs = map_order(&table.inputs);
    let headings: Vec<&String> = table.columns.iter().map(|c| &c.heading).collect();
    let columns = map_order(&headings);
    let push_map = |out: &mut String, keys: &[&String], order: &[usize], values: &[bool]| {
        out.push('{');
        for (n, &i) in order.iter().enumerate() {
            if n > 0 {
                out.push(',');
            }
            push_json_str(out, keys[i]);
            out.push_str(if values[i] { ":true" } else { ":false" });
        }
        out.push('}');
    };
    let input_names: Vec<&String> = table.inputs.iter().collect();
    for (r, row) in table.rows.iter().enumerate() {
        if r > 0 {
            out.push(',');
        }
        out.push_str("{\"inputs\":");
        push_map(&mut out, &input_names, &inputs, &row.inputs);
        out.push_str(",\"outputs\":");
        match &row.outputs {
            Some(outputs) => push_map(&mut out, &headings, &columns, outputs),
            None => out.push_str("null"),
        }
        out.push('}');
    }
    out.push_str("]}");
    out
}

/// The order in which a JSON map holds these keys: sorted, and of equal keys only the last.
fn map_order<K: Ord>(keys: &[K]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by(|&a, &b| keys[a].cmp(&keys[b]));
    let mut kept: Vec<usize> = Vec::with_capacity(order.len());
    for i in order {
        match kept.last_mut() {
            Some(last) if keys[*last] == keys[i] => *last = i,
            _ => kept.push(i),
        }
    }
    kept
}

fn push_json_str(out: &mut String, text: &str) {
    out.push_str(&serde_json::to_string(text).unwrap_or_default());
}
