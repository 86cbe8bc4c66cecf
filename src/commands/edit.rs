//! `proclaim edit BEHAVIOUR [ADDR]`: the behaviour's machines in the browser, edited in place
//! (the page is `proclaim_monitor::Editor`), under the monitor's access rules: open on
//! loopback, a token off it, nothing changed with `--read-only`.

use super::monitor::parse_addr;
use crate::behaviours::resolve;
use crate::failure::Failure;
use proclaim_behaviour::parse_manifest;
use proclaim_monitor::{Access, Editor, EditorFile};
use std::net::SocketAddr;
use std::process::ExitCode;

pub fn run(behaviour: &str, addr: &str, read_only: bool) -> Result<ExitCode, Failure> {
    let found = resolve(behaviour)?;
    let Some(folder) = found.files.folder().map(|f| f.to_path_buf()) else {
        return Err(Failure::Argument(format!(
            "{behaviour} is built into the binary and has no files to edit; edit it from its folder (machines/{behaviour} in the repository), or copy it out with `proclaim deps {behaviour} --launch MACHINE -o DIR/behaviour.toml`"
        )));
    };
    let manifest_text = found
        .files
        .read(&found.manifest)
        .map_err(|d| Failure::Argument(d.render(false)))?;
    let manifest = parse_manifest(&found.files.show(&found.manifest), &manifest_text)
        .map_err(|d| Failure::Argument(d.render(false)))?;
    let files = manifest
        .machines
        .iter()
        .map(|m| EditorFile {
            path: folder.join(&m.file),
            start: m.start,
        })
        .collect();
    let wanted = parse_addr(addr).map_err(|_| {
        Failure::Argument(format!(
            "edit {addr}: not an address to listen on (write 127.0.0.1:7481, or a port alone)"
        ))
    })?;
    let access = Access::for_address(wanted, read_only);
    let runtime = super::runtime::runtime(super::runtime::Shape::OneThread)?;
    runtime.block_on(async {
        let editor = tokio::task::spawn_blocking(move || Editor::open(found.label, files))
            .await
            .map_err(|e| Failure::Argument(format!("the editor could not open: {e}")))?;
        editor.set_access(access.clone());
        // Each machine checked in its behaviour as it is edited (labels no expert answers).
        let root = folder.clone();
        editor.set_check(std::sync::Arc::new(
            move |path: &std::path::Path, text: &str| {
                let relative = path.strip_prefix(&root).unwrap_or(path);
                proclaim_behaviour::check_edited(&root, &relative.to_string_lossy(), text)
            },
        ));
        let bound: SocketAddr = editor
            .serve(wanted)
            .await
            .map_err(|e| Failure::Argument(format!("edit {addr}: cannot listen there ({e})")))?;
        println!("editing {}", folder.display());
        match &access {
            Access::Token(token) => println!("  editor: http://{bound}/?token={token}"),
            Access::ReadOnly => println!("  editor: http://{bound}/ (read-only)"),
            Access::Open => println!("  editor: http://{bound}/"),
        }
        println!("  Ctrl-C to stop");
        let _ = tokio::signal::ctrl_c().await;
        Ok(ExitCode::SUCCESS)
    })
}
