//! `proclaim gen`: writes a standard benchmark theory, its expected answers on stderr.

use crate::cli::GenArgs;
use crate::cli::TheoryFormat;
use crate::failure::Failure;
use proclaim_gen::{Family, Format};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `proclaim gen`.
pub fn command(args: GenArgs) -> Result<ExitCode, Failure> {
    run(
        &args.family,
        &args.sizes,
        args.format,
        args.output.as_deref(),
    )
}

pub fn run(
    family: &str,
    sizes: &[u64],
    format: TheoryFormat,
    output: Option<&Path>,
) -> Result<ExitCode, Failure> {
    let family = Family::parse(family, sizes).map_err(|e| Failure::Argument(e.to_string()))?;
    let format = match format {
        TheoryFormat::Dl => Format::Dl,
        TheoryFormat::Dfl => Format::Dfl,
    };
    let written = match output {
        Some(path) => std::fs::File::create(path)
            .and_then(|file| {
                let mut out = BufWriter::with_capacity(1 << 20, file);
                family.write(&mut out, format)?;
                out.flush()
            })
            .map_err(|error| Failure::Write {
                path: path.to_path_buf(),
                error,
            }),
        None => {
            let mut out = BufWriter::with_capacity(1 << 20, std::io::stdout().lock());
            match family.write(&mut out, format).and_then(|_| out.flush()) {
                // A closed pipe (`| head`) is the reader's choice, not an error.
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
                other => other.map_err(|error| Failure::Write {
                    path: PathBuf::from("<stdout>"),
                    error,
                }),
            }
        }
    };
    written?;
    let expected: Vec<String> = family.expected().iter().map(ToString::to_string).collect();
    eprintln!(
        "{family}: {} rules; expected: {}",
        family.rule_count(),
        expected.join(" ")
    );
    Ok(ExitCode::SUCCESS)
}
