//! Fuzz target: any bytes through both parsers, the checker and the renderer must not panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    for language in [proclaim_syntax::Language::Dl, proclaim_syntax::Language::Dfl] {
        let checked = proclaim_cdl::check(proclaim_syntax::parse(&text, language), &text);
        let _ = proclaim_syntax::render(&checked.diagnostics, "fuzz.dl", &text, false);
        if let Some(theory) = checked.theory {
            let mut session = proclaim_cdl::Session::new(proclaim_cdl::Engine::new(theory));
            let _ = session.count_conclusions(proclaim_cdl::Algorithm::Beta);
        }
    }
    let _ = proclaim_syntax::parse_query(&text);
});
