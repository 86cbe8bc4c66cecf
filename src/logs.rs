//! The log subscriber: the crates' `tracing` spans and events (expert loops, machine rings,
//! queries, warnings) on stderr, filtered by `RUST_LOG` when set, else by `-v`/`-q`.

use crate::cli::LogFormat;
use tracing_subscriber::EnvFilter;

/// Installs the subscriber for the whole process. Warnings and errors show by default.
pub fn install(verbose: u8, quiet: bool, format: LogFormat) {
    let level = match (quiet, verbose) {
        (true, _) => "error",
        (false, 0) => "warn",
        (false, 1) => "info",
        (false, 2) => "debug",
        (false, _) => "trace",
    };
    // A RUST_LOG the filter cannot read falls back to the flags rather than failing the command.
    let filter = std::env::var("RUST_LOG")
        .ok()
        .and_then(|spec| EnvFilter::try_new(spec).ok())
        .unwrap_or_else(|| EnvFilter::new(level));
    let builder = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(crate::load::color());
    // Another subscriber (a test harness) may be in place; keep it.
    let _ = match format {
        LogFormat::Text => builder.try_init(),
        LogFormat::Json => builder
            .json()
            .with_current_span(true)
            .with_span_list(true)
            .try_init(),
    };
}
