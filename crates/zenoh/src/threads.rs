//! How many threads Zenoh runs: by default five runtimes' worth, and every message crosses
//! several of them. Handing them all to one runtime cuts a round trip on a small machine by a
//! quarter (measured on 2 cores: a query answered in another process p50 ~390 → ~300 µs, p99
//! 1.3-1.7 ms → ~0.55 ms; `cargo bench --features zenoh --bench network`).

/// Zenoh's runtimes (receive, send, accept, network) handed over to its application runtime.
pub const FEW_THREADS: &str =
    "(rx: (handover: app), tx: (handover: app), net: (handover: app), acc: (handover: app))";

/// Runs Zenoh on [`FEW_THREADS`] unless the user chose otherwise in `ZENOH_RUNTIME`. Zenoh
/// reads that variable once, when it first starts, so call this first thing in `main`, before
/// any other thread exists (setting the environment is not thread-safe).
pub fn prefer_few_threads() {
    if std::env::var_os("ZENOH_RUNTIME").is_none() {
        std::env::set_var("ZENOH_RUNTIME", FEW_THREADS);
    }
}
