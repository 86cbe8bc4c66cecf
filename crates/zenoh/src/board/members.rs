//! Who is on the board, through Zenoh's liveliness tokens: each process holds one for itself
//! (`@alive/<process>`) and one per type it declared a signal or data (`@kind/<type>/<kind>/
//! <since>/<process>`). A process that is gone loses its tokens, so its types turn stale and its
//! claims to consume signals pass to the next claimant; nothing else stops.

use super::*;
use zenoh::sample::SampleKind;

/// How long the set of linked processes must stay the same before a joining process counts
/// itself meshed with every other (the one it connected to tells it of the rest).
const SETTLED: Duration = Duration::from_millis(250);
/// How long a joining process waits for the mesh at most before it goes on with what it has.
const MESH_PATIENCE: Duration = Duration::from_secs(3);

/// How long a scouting process, or one of a mesh, looks for others before it goes on alone
/// (Zenoh scouts every few hundred milliseconds; a mesh dials every 100 ms).
const SCOUTING_PATIENCE: Duration = Duration::from_secs(1);

/// Waits, as `role` needs, until this process is linked to the others it can find.
pub(super) async fn meet(session: &zenoh::Session, role: &Role) -> Result<(), NetworkError> {
    match role {
        Role::Listen(_) => Ok(()),
        Role::Connect(endpoint) => wait_for_the_mesh(session, endpoint, MESH_PATIENCE, true).await,
        // A robot up before its teammates goes on alone; its dials go on.
        Role::Mesh { listen, .. } => {
            wait_for_the_mesh(session, listen, SCOUTING_PATIENCE, false).await
        }
        // The first robot on the network finds nobody, and is a board of its own until others
        // come.
        Role::Scout => {
            wait_for_the_mesh(session, "multicast scouting", SCOUTING_PATIENCE, false).await
        }
    }
}

/// Waits until this process is linked to the one at `endpoint` and to every process that one
/// knows: postings go straight from poster to reader, so a process must be linked to a poster
/// to hear it.
async fn wait_for_the_mesh(
    session: &zenoh::Session,
    endpoint: &str,
    patience: Duration,
    must_find: bool,
) -> Result<(), NetworkError> {
    let started = tokio::time::Instant::now();
    let mut linked = Vec::new();
    let mut since = started;
    loop {
        let mut now: Vec<String> = session
            .info()
            .peers_zid()
            .await
            .map(|z| z.to_string())
            .collect();
        now.sort();
        if now != linked {
            linked = now;
            since = tokio::time::Instant::now();
        } else if !linked.is_empty() && since.elapsed() >= SETTLED {
            return Ok(());
        }
        if started.elapsed() >= patience {
            return if linked.is_empty() && must_find {
                Err(NetworkError::NoBoard {
                    board: None,
                    endpoint: endpoint.to_string(),
                })
            } else {
                Ok(())
            };
        }
        tokio::time::sleep(Duration::from_millis(25)).await;
    }
}

/// Declares this process alive and follows the others' tokens.
pub(super) async fn watch(peer: &Arc<Peer>, weak: &PeerRef) -> Result<Vec<Serving>, NetworkError> {
    let session = &peer.session;
    let alive_key = peer.keys.alive(&peer.me);
    let token = session
        .liveliness()
        .declare_token(alive_key.clone())
        .await
        .map_err(|e| NetworkError::zenoh(format!("cannot declare {alive_key}"), e))?;
    peer.net.lock().alive.insert(peer.me.clone());
    let processes = follow_tokens(peer, weak, peer.keys.every_alive(), |peer, key, kind| {
        let Some(process) = key.rsplit('/').next() else {
            return;
        };
        match kind {
            SampleKind::Put => peer.arrived(process),
            SampleKind::Delete => peer.gone(process),
        }
    })
    .await?;
    let kinds = follow_tokens(peer, weak, peer.keys.every_kind(), |peer, key, kind| {
        let Some(declared) = Declared::parse(key) else {
            tracing::debug!(key, "unreadable kind declaration");
            return;
        };
        match kind {
            SampleKind::Put => peer.declared(declared),
            SampleKind::Delete => peer.undeclared(declared),
        }
    })
    .await?;
    Ok(vec![
        Serving::Token(token),
        Serving::Subscriber(processes),
        Serving::Subscriber(kinds),
    ])
}

/// Follows the liveliness tokens under `key`, those already declared included: `on` hears each
/// token's key as it comes (`Put`) and goes (`Delete`), while the peer lives.
pub(super) async fn follow_tokens(
    peer: &Arc<Peer>,
    weak: &PeerRef,
    key: String,
    on: impl Fn(&Arc<Peer>, &str, SampleKind) + Send + Sync + 'static,
) -> Result<Subscriber<()>, NetworkError> {
    let weak = weak.clone();
    peer.session
        .liveliness()
        .declare_subscriber(key.clone())
        .history(true)
        .callback(move |sample| {
            if let Some(peer) = weak.upgrade() {
                on(&peer, sample.key_expr().as_str(), sample.kind());
            }
        })
        .await
        .map_err(|e| NetworkError::zenoh(format!("cannot follow {key}"), e))
}

/// A kind declaration read from its token's key.
struct Declared {
    ty: String,
    kind: Kind,
    since: u64,
    process: String,
}

impl Declared {
    fn parse(key: &str) -> Option<Declared> {
        let mut chunks = key.rsplit('/');
        let process = chunks.next()?.to_string();
        let since = chunks.next()?.parse().ok()?;
        let kind = WireKind::parse(chunks.next()?)?.into();
        let ty = chunks.next()?.to_string();
        Some(Declared {
            ty,
            kind,
            since,
            process,
        })
    }
}

impl Peer {
    fn arrived(self: &Arc<Self>, process: &str) {
        if process == self.me || !self.net.lock().alive.insert(process.to_string()) {
            return;
        }
        // A process seen for the first time may hold values this one has not heard (this one
        // restarted, or the two were apart): ask it, off Zenoh's receiving thread.
        let peer = Arc::clone(self);
        let process = process.to_string();
        let asking = std::thread::Builder::new()
            .name("proclaim-zenoh-catch-up".into())
            .spawn(move || peer.catch_up_with(&process));
        if let Err(e) = asking {
            tracing::warn!(error = %e, "cannot ask a new process for its values");
        }
    }

    fn gone(&self, process: &str) {
        let mut net = self.net.lock();
        if !net.alive.remove(process) {
            return;
        }
        let orphaned: Vec<String> = net
            .current
            .iter()
            .filter(|(_, (meta, _))| meta.process.as_deref() == Some(process))
            .map(|(ty, _)| ty.clone())
            .collect();
        let module = gone_module(process);
        for ty in orphaned {
            if net.stale.insert(ty.clone()) {
                tracing::info!(ty, process, "stale: its poster is gone");
                self.mark_stale(&ty, true, &module);
            }
        }
        for claims in net.claims.values_mut() {
            claims.retain(|(_, p)| p != process);
        }
    }

    fn declared(&self, d: Declared) {
        if d.process == self.me {
            return;
        }
        let mut net = self.net.lock();
        let claims = net.claims.entry(d.ty.clone()).or_default();
        claims.retain(|(_, p)| *p != d.process);
        if d.kind == Kind::Signal {
            claims.insert((d.since, d.process));
        }
        if !net.declared_here.contains_key(&d.ty) && self.board.kind(&d.ty) != d.kind {
            self.board.declare_observed(&d.ty, d.kind);
        }
    }

    fn undeclared(&self, d: Declared) {
        if let Some(claims) = self.net.lock().claims.get_mut(&d.ty) {
            claims.remove(&(d.since, d.process));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::keys::Keys;

    #[test]
    fn a_kind_declaration_is_read_back_from_its_key() {
        let key = Keys::new("team18").kind("kick", WireKind::Signal, 1_700, "ab12");
        let declared = Declared::parse(&key).unwrap();
        assert_eq!(declared.ty, "kick");
        assert_eq!(declared.kind, Kind::Signal);
        assert_eq!(declared.since, 1_700);
        assert_eq!(declared.process, "ab12");
    }

    #[test]
    fn a_key_that_is_no_kind_declaration_is_ignored() {
        for key in [
            "proclaim/team18/@kind/kick/loud/1700/ab12",
            "proclaim/team18/@kind/kick/signal/soon/ab12",
            "ab12",
        ] {
            assert!(Declared::parse(key).is_none(), "{key}");
        }
    }
}
