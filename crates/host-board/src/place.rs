//! Which whiteboard a run is on: its own, or one shared over Zenoh, as `--listen` and
//! `--connect` say.

use proclaim_board::Whiteboard;
use proclaim_runtime::host::Place;

/// The whiteboard `place` names: this process's own, or one shared over Zenoh.
pub(crate) async fn whiteboard(place: &Place) -> Result<Whiteboard, String> {
    if !place.shared() {
        return Ok(Whiteboard::local());
    }
    shared(place).await
}

#[cfg(feature = "network")]
async fn shared(place: &Place) -> Result<Whiteboard, String> {
    let (role, said) = match (&place.listen, &place.connect) {
        (Some(endpoint), _) => (
            proclaim_zenoh::Role::Listen(endpoint.clone()),
            format!("listening on {endpoint}"),
        ),
        (_, Some(endpoint)) => (
            proclaim_zenoh::Role::Connect(endpoint.clone()),
            format!("connected to {endpoint}"),
        ),
        _ => return Ok(Whiteboard::local()),
    };
    let name = place.board.as_deref().unwrap_or("proclaim");
    let settings = proclaim_zenoh::Settings {
        config_file: None,
        low_latency: false,
        lease: None,
        dial: None,
    };
    let board = proclaim_zenoh::whiteboard(&role, name, &settings)
        .await
        .map_err(|e| e.to_string())?;
    eprintln!("  on whiteboard `{name}`, {said}");
    Ok(board)
}

#[cfg(not(feature = "network"))]
async fn shared(_: &Place) -> Result<Whiteboard, String> {
    Err("--listen/--connect: this program was built without the whiteboard across processes; build it with `cargo build --release --features network`".into())
}

#[cfg(all(test, not(feature = "network")))]
mod tests {
    use super::*;

    #[test]
    fn a_shared_whiteboard_without_the_network_feature_is_refused_with_the_way_to_get_it() {
        let place = Place {
            connect: Some("tcp/127.0.0.1:1".into()),
            ..Place::default()
        };
        let runtime = tokio::runtime::Builder::new_current_thread()
            .build()
            .unwrap();
        let error = runtime.block_on(whiteboard(&place)).err().expect("refused");
        assert!(error.contains("--features network"), "{error}");
    }
}
