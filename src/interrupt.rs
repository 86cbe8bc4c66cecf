//! Ctrl-C heard from the moment it is asked for: one that comes between two waits (while an
//! event is printed, say) is kept for the next wait, never lost, and the default of ending the
//! process at once is replaced from then on.

/// The run's Ctrl-C.
pub struct Interrupt {
    #[cfg(unix)]
    signal: Option<tokio::signal::unix::Signal>,
}

impl Interrupt {
    /// Listens from now on (inside the runtime).
    pub fn new() -> Interrupt {
        Interrupt {
            #[cfg(unix)]
            signal: tokio::signal::unix::signal(tokio::signal::unix::SignalKind::interrupt()).ok(),
        }
    }

    /// Waits for the next Ctrl-C (or one that came since the last wait).
    pub async fn next(&mut self) {
        #[cfg(unix)]
        if let Some(signal) = self.signal.as_mut() {
            signal.recv().await;
            return;
        }
        let _ = tokio::signal::ctrl_c().await;
    }
}
