//! An SCXML document as a tree of elements with their attributes and lines: what the mapping
//! to the native format walks (the documents are small; a tree keeps the mapping plain).

use quick_xml::events::{BytesStart, Event};
use quick_xml::{Reader, XmlVersion};

/// One element: its local name (the SCXML namespace is the only one read), attributes in
/// order, child elements and the line it starts on.
#[derive(Debug, Default)]
pub struct Element {
    pub name: String,
    pub attributes: Vec<(String, String)>,
    pub children: Vec<Element>,
    /// What text it holds directly (a `<script>`'s), trimmed.
    pub text: String,
    /// Written with a namespace prefix (`qt:editorinfo`): an editor's or a tool's own
    /// element, which SCXML processors ignore.
    pub foreign: bool,
    pub line: usize,
}

impl Element {
    pub fn attribute(&self, name: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }
}

/// How deep elements may nest: far past any chart, short of what walking a tree that deep would
/// take of a thread's stack.
const MAX_DEPTH: usize = 256;

/// The document's root element, or the line and reason it does not read as XML.
pub fn read(text: &str) -> Result<Element, (usize, String)> {
    // Every element asks its line: looked up, not counted from the start each time.
    let lines = crate::native::LineIndex::new(text);
    let line_of = |offset: u64| lines.line((offset as usize).min(text.len()));
    let mut reader = Reader::from_str(text);
    let mut open: Vec<Element> = vec![Element::default()];
    loop {
        let position = reader.buffer_position();
        let event = reader.read_event().map_err(|e| {
            (
                line_of(reader.error_position()),
                format!("malformed XML: {e}"),
            )
        })?;
        match event {
            Event::Start(_) if open.len() > MAX_DEPTH => {
                let message = format!("elements nest deeper than {MAX_DEPTH}");
                return Err((line_of(position), message));
            }
            Event::Start(e) => open.push(element(&e, line_of(position))),
            Event::Empty(e) => {
                let done = element(&e, line_of(position));
                if let Some(parent) = open.last_mut() {
                    parent.children.push(done);
                }
            }
            Event::End(_) => {
                let done = open.pop().filter(|_| !open.is_empty());
                match (done, open.last_mut()) {
                    (Some(done), Some(parent)) => parent.children.push(done),
                    _ => return Err((line_of(position), "a closing tag closes nothing".into())),
                }
            }
            Event::Text(t) => {
                if let Some(top) = open.last_mut() {
                    top.text.push_str(t.xml10_content().trim());
                }
            }
            Event::CData(t) => {
                if let Some(top) = open.last_mut() {
                    top.text.push_str(t.into_inner().trim());
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if open.len() > 1 {
        return Err((
            line_of(text.len() as u64),
            "the file ends inside an element".into(),
        ));
    }
    let mut document = open.pop().unwrap_or_default();
    match document.children.len() {
        1 => Ok(document.children.remove(0)),
        _ => Err((1, "an XML document has one root element".into())),
    }
}

fn element(e: &BytesStart<'_>, line: usize) -> Element {
    let name = e.local_name().as_ref().to_string();
    let foreign = e.name().prefix().is_some();
    let attributes = e
        .attributes()
        .flatten()
        .map(|a| {
            let key = a.key.local_name().as_ref().to_string();
            let value = a
                .normalized_value(XmlVersion::Implicit1_0)
                .map(|v| v.into_owned())
                .unwrap_or_else(|_| a.value.to_string());
            (key, value)
        })
        .collect();
    Element {
        name,
        attributes,
        line,
        foreign,
        ..Element::default()
    }
}
