//! The book (`docs/book`) cannot drift from what proclaim does: the tutorial's files are written
//! and its commands run as a reader would, in an empty folder with `proclaim` on the PATH, and
//! every link of the book and of README.md leads to a file (and heading) that exists.
//!
//! The tutorial marks what the test reads with HTML comments, which a reader does not see:
//! `<!-- file: PATH -->` before a code block writes it to PATH (`PATH (appended)` adds it to the
//! end); every line of a `sh` block is a command, which must exit 0, or N where it ends in
//! `# exit N`, and one ending in `# until Ctrl-C` must print the page's address, serve it, and
//! stop at SIGINT; `<!-- output -->` before a block says lines the block of commands above must
//! print (each line, trimmed, somewhere in its output). The tutorial's pytest runs here where
//! `python3` has the package, and always in the Python suite (`python/tests/test_tutorial.py`).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What the tutorial asks of the test, in order.
#[derive(Debug, PartialEq)]
enum Step {
    File {
        path: String,
        text: String,
        append: bool,
    },
    Commands(Vec<String>),
    Output(Vec<String>),
}

/// The steps of a page: its marked code blocks and its `sh` blocks.
fn steps(page: &str) -> Vec<Step> {
    let mut steps = Vec::new();
    let mut marker: Option<String> = None;
    let mut lines = page.lines();
    while let Some(line) = lines.next() {
        let trimmed = line.trim();
        if let Some(inner) = trimmed
            .strip_prefix("<!--")
            .and_then(|r| r.strip_suffix("-->"))
        {
            marker = Some(inner.trim().to_string());
            continue;
        }
        let Some(info) = trimmed.strip_prefix("```") else {
            continue;
        };
        let mut body = Vec::new();
        for inside in lines.by_ref() {
            if inside.trim_start().starts_with("```") {
                break;
            }
            body.push(inside.to_string());
        }
        match marker.take() {
            Some(m) if m.starts_with("file:") => {
                let path = m["file:".len()..].trim();
                let (path, append) = match path.strip_suffix("(appended)") {
                    Some(p) => (p.trim(), true),
                    None => (path, false),
                };
                steps.push(Step::File {
                    path: path.to_string(),
                    text: body.join("\n") + "\n",
                    append,
                });
            }
            Some(m) if m == "output" => steps.push(Step::Output(
                body.iter()
                    .map(|l| l.trim().to_string())
                    .filter(|l| !l.is_empty())
                    .collect(),
            )),
            _ if info == "sh" => steps.push(Step::Commands(
                body.into_iter().filter(|l| !l.trim().is_empty()).collect(),
            )),
            _ => {}
        }
    }
    steps
}

/// The exit status a command line says it ends with (`# exit N`), 0 when it says none.
fn expected_exit(line: &str) -> i32 {
    line.rsplit_once("# exit ")
        .and_then(|(_, n)| n.trim().parse().ok())
        .unwrap_or(0)
}

fn shell(line: &str, dir: &Path) -> Command {
    let bin = Path::new(env!("CARGO_BIN_EXE_proclaim")).parent().unwrap();
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut paths = vec![bin.to_path_buf()];
    paths.extend(std::env::split_paths(&path));
    let mut command = Command::new("sh");
    command
        .arg("-c")
        .arg(line)
        .current_dir(dir)
        .env("PATH", std::env::join_paths(paths).unwrap())
        .env("NO_COLOR", "1")
        // A Cargo project the tutorial builds shares one target folder across test runs.
        .env(
            "CARGO_TARGET_DIR",
            Path::new(env!("CARGO_TARGET_TMPDIR")).join("tutorial-rust"),
        )
        .env("CARGO_PROFILE_DEV_DEBUG", "0");
    command
}

/// Runs a command that serves a page until Ctrl-C: its address is printed, the page answers,
/// and SIGINT ends it.
fn serve_until_interrupted(line: &str, dir: &Path) -> String {
    let mut child = shell(&format!("exec {line}"), dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sh runs");
    let (tell, heard) = std::sync::mpsc::channel();
    for stream in [
        Box::new(child.stdout.take().unwrap()) as Box<dyn std::io::Read + Send>,
        Box::new(child.stderr.take().unwrap()),
    ] {
        let tell = tell.clone();
        std::thread::spawn(move || {
            use std::io::BufRead;
            for l in std::io::BufReader::new(stream)
                .lines()
                .map_while(Result::ok)
            {
                let _ = tell.send(l);
            }
        });
    }
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut said = Vec::new();
    let address = loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let line = heard
            .recv_timeout(left)
            .unwrap_or_else(|_| panic!("`{line}` printed no address: {said:?}"));
        said.push(line.clone());
        if let Some(at) = line.find("http://") {
            break line[at..].split_whitespace().next().unwrap().to_string();
        }
    };
    let (status, _) = crate::monitor::http(address.trim_end_matches('/'), "GET", "/", None);
    assert_eq!(status, 200, "{address} answers");
    let _ = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    let ended = Instant::now() + Duration::from_secs(20);
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.code().is_some(), "`{line}` ended by SIGINT cleanly");
            break;
        }
        assert!(Instant::now() < ended, "`{line}` did not stop at Ctrl-C");
        std::thread::sleep(Duration::from_millis(50));
    }
    said.join("\n")
}

/// Whether this machine's Python has the `proclaim` package and pytest. The Python suite runs
/// the tutorial's Python test where it does not (`python/tests/test_tutorial.py`), as CI does.
fn python_package() -> bool {
    Command::new("python3")
        .args(["-c", "import proclaim, pytest"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Runs one command line of the tutorial; its output.
fn run_line(line: &str, dir: &Path) -> String {
    if line.contains("python3 -m pytest") && !python_package() {
        eprintln!("not run here (no proclaim package for python3; python/tests/test_tutorial.py runs it): {line}");
        return String::new();
    }
    if line.contains("# until Ctrl-C") {
        return serve_until_interrupted(line.split('#').next().unwrap().trim(), dir);
    }
    let o = shell(line, dir).output().expect("sh runs");
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        o.status.code(),
        Some(expected_exit(line)),
        "`{line}` in {}:\n{out}",
        dir.display()
    );
    out
}

fn book_page(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/book/src")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn the_tutorial_runs_as_written() {
    let dir = crate::compiled::scratch("tutorial");
    let mut last = String::new();
    let mut commands = 0;
    for step in steps(&book_page("tutorial.md")) {
        match step {
            Step::File { path, text, append } => {
                let file = dir.join(&path);
                std::fs::create_dir_all(file.parent().unwrap()).unwrap();
                let mut all = if append {
                    std::fs::read_to_string(&file).unwrap()
                } else {
                    String::new()
                };
                all.push_str(&text);
                std::fs::write(&file, all).unwrap();
            }
            Step::Commands(lines) => {
                last = lines.iter().map(|l| run_line(l, &dir)).collect();
                commands += lines.len();
            }
            Step::Output(wanted) => {
                for w in wanted {
                    assert!(
                        last.contains(&w),
                        "the tutorial shows `{w}`; the commands printed:\n{last}"
                    );
                }
            }
        }
    }
    assert!(
        commands >= 15,
        "the tutorial's commands were found ({commands})"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn the_tutorials_marks_are_read_as_the_test_means() {
    let page = "Text.\n<!-- file: g/a.dl -->\n```text\nname{a}.\n```\n```sh\nproclaim check g   # exit 1\n\nproclaim run g\n```\n<!-- output -->\n```text\n  ok \n\n```\n```toml\nnot run\n```\n<!-- file: g/a.dl (appended) -->\n```text\nx.\n```\n";
    assert_eq!(
        steps(page),
        vec![
            Step::File {
                path: "g/a.dl".into(),
                text: "name{a}.\n".into(),
                append: false
            },
            Step::Commands(vec![
                "proclaim check g   # exit 1".into(),
                "proclaim run g".into()
            ]),
            Step::Output(vec!["ok".into()]),
            Step::File {
                path: "g/a.dl".into(),
                text: "x.\n".into(),
                append: true
            },
        ]
    );
    assert_eq!(expected_exit("proclaim check g   # exit 1"), 1);
    assert_eq!(expected_exit("proclaim run g"), 0);
}

/// Markdown links of a text (`[text](target)`), images included, outside code.
fn links(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut fence = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fence = !fence;
            continue;
        }
        if fence {
            continue;
        }
        // Inline code is not a link.
        let plain: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        let mut rest = plain.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            found.push(after[..end].to_string());
            rest = &after[end..];
        }
    }
    found
}

/// GitHub's and mdBook's anchor of a heading.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn headings(text: &str) -> Vec<String> {
    let mut fence = false;
    let mut found = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fence = !fence;
        } else if !fence && line.starts_with('#') {
            found.push(slug(line.trim_start_matches('#')));
        }
    }
    found
}

fn pages() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md")];
    let mut book: Vec<PathBuf> = std::fs::read_dir(root.join("docs/book/src"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    book.sort();
    pages.extend(book);
    pages
}

#[test]
fn every_link_of_the_book_and_readme_leads_somewhere() {
    let mut broken = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        for link in links(&text) {
            if link.starts_with("http://") || link.starts_with("https://") {
                continue;
            }
            let (file, anchor) = link.split_once('#').unwrap_or((&link, ""));
            let target = if file.is_empty() {
                page.clone()
            } else {
                page.parent().unwrap().join(file)
            };
            if !target.exists() {
                broken.push(format!("{}: {link} (no such file)", page.display()));
                continue;
            }
            if !anchor.is_empty() && target.extension().is_some_and(|e| e == "md") {
                let text = std::fs::read_to_string(&target).unwrap();
                if !headings(&text).contains(&anchor.to_string()) {
                    broken.push(format!("{}: {link} (no such heading)", page.display()));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn every_page_of_the_book_is_in_its_summary() {
    let summary = book_page("SUMMARY.md");
    let listed = links(&summary);
    for page in pages().iter().skip(1) {
        let name = page.file_name().unwrap().to_string_lossy().into_owned();
        if name != "SUMMARY.md" {
            assert!(listed.contains(&name), "{name} is not in SUMMARY.md");
        }
    }
}

#[test]
fn links_and_headings_are_read_as_a_reader_follows_them() {
    let text = "# The `.dl` language\nSee [a](b.md#the-dl-language) and `[not](a link)`.\n```\n[no](code)\n```\n![pic](images/x.png)\n";
    assert_eq!(links(text), ["b.md#the-dl-language", "images/x.png"]);
    assert_eq!(headings(text), ["the-dl-language"]);
}
