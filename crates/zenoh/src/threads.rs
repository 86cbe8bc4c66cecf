//! How many threads Zenoh runs: by default five runtimes' worth, and every message crosses
//! several of them. Handing them all to one runtime shortens a round trip on a small machine, at
//! the median and more so at the tail (`cargo bench --features zenoh --bench network` measures it).

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
