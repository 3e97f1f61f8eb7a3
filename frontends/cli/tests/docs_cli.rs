//! `docs/cli.md` cannot go stale: its reference part is the binary's own
//! `--help` (and `voxtrace stitch --help`) turned into markdown, and this
//! test makes it again and compares. After a flag or its help text changes,
//! refresh the file with
//!
//! ```sh
//! UPDATE_DOCS=1 cargo test -p voxtrace-cli --test docs_cli
//! ```
//!
//! The hand-written part around it may name only flags the binary knows.

mod common;

use std::collections::BTreeSet;
use std::path::PathBuf;

use common::run::voxtrace;

/// The command that rewrites the generated part of `docs/cli.md`.
const REFRESH: &str = "UPDATE_DOCS=1 cargo test -p voxtrace-cli --test docs_cli";
/// The line that opens the generated part; everything up to [`END`] is made here.
const BEGIN: &str = "<!-- BEGIN generated from --help by frontends/cli/tests/docs_cli.rs; \
                     do not edit: UPDATE_DOCS=1 cargo test -p voxtrace-cli --test docs_cli -->";
/// The line that closes the generated part.
const END: &str = "<!-- END generated -->";

fn cli_md() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/cli.md")
}

/// The long help of `voxtrace ARGS --help`, which must succeed.
fn help(args: &[&str]) -> String {
    let mut all = args.to_vec();
    all.push("--help");
    let out = voxtrace(&all);
    assert!(out.status.success(), "voxtrace {all:?} failed");
    String::from_utf8(out.stdout).expect("the help is UTF-8")
}

/// One entry of a help section: its name (`--out <FILE>`, `[PART]...`)
/// and its text, one string per line (empty between paragraphs).
struct Entry {
    name: String,
    lines: Vec<String>,
}

/// clap's help as markdown under a `### title` heading: the about text,
/// the usage, each section's entries as a list, and the closing text.
fn help_markdown(title: &str, help: &str) -> String {
    let mut md = format!("### `{title}`\n\n");
    let mut entries: Vec<Entry> = Vec::new();
    let flush = |md: &mut String, entries: &mut Vec<Entry>| {
        for entry in entries.drain(..) {
            md.push_str(&entry_markdown(&entry));
        }
        if !md.ends_with("\n\n") {
            md.push('\n');
        }
    };
    for line in help.lines() {
        let indent = line.len() - line.trim_start().len();
        let text = line.trim();
        if text.is_empty() {
            // A paragraph break inside an entry, or between sections.
            if let Some(entry) = entries.last_mut() {
                entry.lines.push(String::new());
            }
        } else if indent == 0 {
            flush(&mut md, &mut entries);
            if let Some(usage) = text.strip_prefix("Usage: ") {
                md.push_str(&format!("Usage: `{usage}`\n\n"));
            } else {
                md.push_str(&format!("{text}\n\n"));
            }
        } else if indent < 8 {
            // An entry: its name, then (short help) its text after a gap.
            let (name, rest) = text.split_once("  ").unwrap_or((text, ""));
            let mut lines = Vec::new();
            if !rest.trim().is_empty() {
                lines.push(rest.trim().to_string());
            }
            entries.push(Entry {
                name: name.to_string(),
                lines,
            });
        } else if let Some(entry) = entries.last_mut() {
            entry.lines.push(text.to_string());
        }
    }
    flush(&mut md, &mut entries);
    md
}

/// One entry as a markdown list item: the name in code, the first
/// paragraph after it, then the rest indented under it.
fn entry_markdown(entry: &Entry) -> String {
    let mut paragraphs: Vec<Vec<&str>> = vec![Vec::new()];
    for line in &entry.lines {
        if line.is_empty() {
            paragraphs.push(Vec::new());
        } else {
            paragraphs.last_mut().unwrap().push(line);
        }
    }
    paragraphs.retain(|p| !p.is_empty());
    let mut md = format!("- `{}`", entry.name);
    for (i, paragraph) in paragraphs.iter().enumerate() {
        md.push_str(if i == 0 { ": " } else { "\n\n  " });
        let lines: Vec<String> = paragraph.iter().map(|l| line_markdown(l)).collect();
        md.push_str(&lines.join("\n  "));
    }
    md.push('\n');
    md
}

/// A line of help text: a possible value (`- dense:  Flat array`) as a
/// list item, a lone `[default: X]` as `Default: `X``, other text as is.
fn line_markdown(line: &str) -> String {
    if let Some((value, text)) = line.strip_prefix("- ").and_then(|l| l.split_once(": ")) {
        if !value.contains(char::is_whitespace) {
            return format!("- `{value}`: {}", text.trim());
        }
    }
    if let Some(value) = line
        .strip_prefix("[default: ")
        .and_then(|l| l.strip_suffix(']'))
    {
        return format!("Default: `{value}`");
    }
    line.to_string()
}

/// The generated part: both commands' help as markdown.
fn reference() -> String {
    let commands = [
        help_markdown("voxtrace", &help(&[])),
        help_markdown("voxtrace stitch", &help(&["stitch"])),
    ];
    commands.map(|md| md.trim_end().to_string()).join("\n\n")
}

/// Every `--flag` in `text`, outside HTML comments.
fn flags(text: &str) -> BTreeSet<String> {
    let mut visible = String::new();
    let mut rest = text;
    while let Some((before, after)) = rest.split_once("<!--") {
        visible.push_str(before);
        rest = after.split_once("-->").map_or("", |(_, tail)| tail);
    }
    visible.push_str(rest);
    let bytes = visible.as_bytes();
    let mut found = BTreeSet::new();
    for (i, _) in visible.match_indices("--") {
        let starts_word = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'-');
        let name: String = visible[i + 2..]
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
            .collect();
        if starts_word && name.starts_with(|c: char| c.is_ascii_lowercase()) {
            found.insert(format!("--{}", name.trim_end_matches('-')));
        }
    }
    found
}

#[test]
fn the_reference_in_docs_cli_md_is_the_binarys_help() {
    let path = cli_md();
    let doc = std::fs::read_to_string(&path).expect("docs/cli.md exists");
    let (head, tail) = doc
        .split_once(BEGIN)
        .unwrap_or_else(|| panic!("docs/cli.md lacks the line {BEGIN}"));
    let (generated, foot) = tail
        .split_once(END)
        .unwrap_or_else(|| panic!("docs/cli.md lacks the line {END}"));
    let fresh = format!("\n\n{}\n", reference());
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, format!("{head}{BEGIN}{fresh}{END}{foot}")).unwrap();
        return;
    }
    assert!(
        generated == fresh,
        "docs/cli.md does not match `voxtrace --help` and `voxtrace stitch --help`; \
         refresh it with `{REFRESH}` and commit the result"
    );
}

#[test]
fn docs_cli_md_names_every_flag_of_the_help_and_no_other() {
    let doc = std::fs::read_to_string(cli_md()).expect("docs/cli.md exists");
    let documented = flags(&doc);
    let known: BTreeSet<String> = flags(&help(&[]))
        .union(&flags(&help(&["stitch"])))
        .cloned()
        .collect();
    let missing: Vec<_> = known.difference(&documented).collect();
    let unknown: Vec<_> = documented.difference(&known).collect();
    assert!(
        missing.is_empty(),
        "flags of --help missing from docs/cli.md: {missing:?}; refresh it with `{REFRESH}`"
    );
    assert!(
        unknown.is_empty(),
        "docs/cli.md names flags the binary does not know: {unknown:?}"
    );
}
