//! The layout ARCHITECTURE.md describes, checked from the source text: no
//! module of the core imports another through a loop, none imports through
//! the crate root's re-exports, later pipeline stages never reach back into
//! earlier ones' dependents, every folder says what it holds, and files stay
//! small.
//!
//! Imports are read as text (`crate::a::b` paths outside comments) and
//! resolved to the file of the longest module prefix, which is exact for
//! this crate's style: it imports by full path and never globs a module.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Files under `src/`, keyed by module path (`storage::octree::trace`).
fn modules() -> BTreeMap<String, PathBuf> {
    fn walk(dir: &Path, prefix: &[String], out: &mut BTreeMap<String, PathBuf>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_stem().unwrap().to_str().unwrap().to_owned();
            if path.is_dir() {
                let mut inner = prefix.to_vec();
                inner.push(name);
                walk(&path, &inner, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let mut segments = prefix.to_vec();
                if name != "mod" && name != "lib" {
                    segments.push(name);
                }
                out.insert(segments.join("::"), path);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(Path::new("src"), &[], &mut out);
    out
}

/// The source text without comments (line and doc comments), so that links
/// in docs are not taken for imports.
fn code(path: &Path) -> String {
    code_of(&fs::read_to_string(path).unwrap())
}

/// Every `crate::...` path in `text`, expanded over one level of braces
/// (`crate::a::{b, c::D}` gives `a::b` and `a::c::D`).
fn crate_paths(text: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("crate::") {
        let preceded_by_ident = rest[..i]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_');
        rest = &rest[i + "crate::".len()..];
        if preceded_by_ident {
            continue;
        }
        let end = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
            .unwrap_or(rest.len());
        let head: Vec<String> = rest[..end]
            .split("::")
            .filter(|s| !s.is_empty())
            .map(str::to_owned)
            .collect();
        if rest[end..].starts_with('{') {
            let close = rest[end..].find('}').unwrap() + end;
            for item in rest[end + 1..close].split(',') {
                let mut path = head.clone();
                path.extend(
                    item.split("::")
                        .map(str::trim)
                        .filter(|s| !s.is_empty())
                        .map(str::to_owned),
                );
                paths.push(path);
            }
        } else {
            paths.push(head);
        }
    }
    paths
}

/// The module a path points into: its longest prefix that is a file.
fn resolve(path: &[String], modules: &BTreeMap<String, PathBuf>) -> Option<String> {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].join("::"))
        .find(|m| modules.contains_key(m))
}

/// Imports between modules: module -> the modules it uses (not itself, and
/// not the crate root, which only declares and re-exports).
fn imports() -> BTreeMap<String, BTreeSet<String>> {
    let (graph, through_root) = read_imports();
    assert!(through_root.is_empty(), "{}", through_root.join("\n"));
    graph
}

/// The import graph, and every path that goes through the crate root's
/// re-exports instead of the module that defines it.
fn read_imports() -> (BTreeMap<String, BTreeSet<String>>, Vec<String>) {
    let modules = modules();
    let (mut graph, mut through_root) = (BTreeMap::new(), Vec::new());
    for (module, path) in &modules {
        if module.is_empty() {
            continue;
        }
        let mut uses = BTreeSet::new();
        for p in crate_paths(&code(path)) {
            match resolve(&p, &modules) {
                Some(target) if &target != module => {
                    uses.insert(target);
                }
                Some(_) => {}
                None => through_root.push(format!(
                    "{}: `crate::{}` goes through the crate root's re-exports; \
                     import it from the module that defines it",
                    path.display(),
                    p.join("::")
                )),
            }
        }
        graph.insert(module.clone(), uses);
    }
    (graph, through_root)
}

#[test]
fn no_module_imports_through_the_crate_root() {
    let (graph, through_root) = read_imports();
    assert_eq!(through_root, Vec::<String>::new());
    // The reader found the imports it must: a few edges every layout of
    // this crate has, so that an empty or half-read graph fails here.
    let edge = |from: &str, to: &str| graph.get(from).is_some_and(|uses| uses.contains(to));
    for (from, to) in [
        ("render::frame", "render::tiles"),
        ("render::tiles", "render::shader"),
        ("storage::octree::trace", "storage::walk"),
        ("storage::dense::walk", "storage::walk"),
        ("source::terrain", "source::noise"),
    ] {
        assert!(
            edge(from, to),
            "{from} does not import {to}: the reader missed it"
        );
    }
}

#[test]
fn no_import_loops() {
    let graph = imports();
    // Depth-first search with colors: a grey node met again closes a loop.
    fn visit<'a>(
        node: &'a str,
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<&'a str, bool>,
        stack: &mut Vec<&'a str>,
    ) {
        match state.get(node) {
            Some(true) => return,
            Some(false) => {
                let start = stack.iter().position(|n| *n == node).unwrap();
                panic!("import loop: {} -> {node}", stack[start..].join(" -> "));
            }
            None => {}
        }
        state.insert(node, false);
        stack.push(node);
        for next in graph.get(node).into_iter().flatten() {
            visit(next, graph, state, stack);
        }
        stack.pop();
        state.insert(node, true);
    }
    let mut state = BTreeMap::new();
    for node in graph.keys() {
        visit(node, &graph, &mut state, &mut Vec::new());
    }
}

/// The stage of a module: the shared vocabulary at the root, then the
/// pipeline's folders in the order data flows through them; inside
/// `storage`, the walk both storages share before either storage, and
/// what compares their sizes after both.
fn stage(module: &str) -> (usize, usize) {
    let mut parts = module.split("::");
    match (parts.next().unwrap(), parts.next()) {
        ("source", _) => (1, 0),
        ("storage", Some("dense" | "octree")) => (2, 1),
        ("storage", Some("estimate")) => (2, 2),
        ("storage", _) => (2, 0),
        ("render", _) => (3, 0),
        ("io", _) => (4, 0),
        _ => (0, 0),
    }
}

#[test]
fn stages_import_only_earlier_stages() {
    for (module, uses) in imports() {
        for target in uses {
            assert!(
                stage(&target) <= stage(&module),
                "{module} (stage {:?}) imports {target} (stage {:?}): a stage \
                 may import only itself and earlier ones",
                stage(&module),
                stage(&target)
            );
        }
    }
}

#[test]
fn every_folder_says_what_it_holds() {
    for (module, path) in modules() {
        if path.file_name().is_some_and(|n| n == "mod.rs") {
            let text = fs::read_to_string(&path).unwrap();
            assert!(
                text.starts_with("//!"),
                "{} (module {module}) has no module doc comment",
                path.display()
            );
        }
    }
}

#[test]
fn files_stay_small() {
    // "About 400 lines": one idea a file. Split a file that outgrows this.
    const LIMIT: usize = 420;
    for path in modules().values() {
        let lines = fs::read_to_string(path).unwrap().lines().count();
        assert!(
            lines <= LIMIT,
            "{} has {lines} lines (limit {LIMIT})",
            path.display()
        );
    }
}

#[test]
fn the_path_reader_sees_what_it_must() {
    // The checks above are only as good as the reader: braces, nested
    // paths, comments and identifiers ending in `crate` handled as meant.
    let text = "use crate::a::{b, c::D};\n// crate::e::f\nlet x = crate::g::h(1); my_crate::i::j";
    let paths = crate_paths(&code_of(text));
    let joined: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(joined, ["a::b", "a::c::D", "g::h"]);
}

/// `text` with every comment cut off its line.
fn code_of(text: &str) -> String {
    text.lines()
        .map(|line| match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}
