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

fn json(table: &Table) -> serde_json::Value {
    let rows: Vec<_> = table
        .rows
        .iter()
        .map(|row| {
            let inputs: serde_json::Map<_, _> = table
                .inputs
                .iter()
                .zip(&row.inputs)
                .map(|(n, v)| (n.clone(), (*v).into()))
                .collect();
            let outputs = row.outputs.as_ref().map(|outputs| {
                table
                    .columns
                    .iter()
                    .zip(outputs)
                    .map(|(c, v)| (c.heading.clone(), (*v).into()))
                    .collect::<serde_json::Map<_, _>>()
            });
            serde_json::json!({"inputs": inputs, "outputs": outputs})
        })
        .collect();
    let columns: Vec<_> = table
        .columns
        .iter()
        .map(|c| {
            serde_json::json!({
                "heading": c.heading,
                "algorithm": c.algorithm.name(),
                "description": c.description,
            })
        })
        .collect();
    serde_json::json!({"inputs": table.inputs, "outputs": columns, "rows": rows})
}
