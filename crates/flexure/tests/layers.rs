//! The library's layers: every `crate::…` path of every source file checked
//! against the layer table of ARCHITECTURE.md ("Module graph"). Reference:
//! that table, read as written; no tolerance. A module imports only from
//! its own layer and those below, and the top-level modules' imports form
//! no cycle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The table's rows `| N | `a` `b` | … |`: module → layer.
fn table(architecture: &str) -> BTreeMap<String, usize> {
    let start = architecture.find("## Module graph").expect("ARCHITECTURE.md has a Module graph section");
    let section = &architecture[start..];
    let end = section[3..].find("\n## ").map_or(section.len(), |e| e + 3);
    let mut layers = BTreeMap::new();
    for line in section[..end].lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let (Some(layer), Some(modules)) = (cells.get(1).and_then(|c| c.parse::<usize>().ok()), cells.get(2)) else {
            continue;
        };
        for m in modules.split('`').skip(1).step_by(2) {
            assert!(layers.insert(m.to_string(), layer).is_none(), "{m} is listed twice");
        }
    }
    layers
}

/// The library's top-level modules, from lib.rs's `pub mod` lines.
fn modules(lib: &str) -> Vec<String> {
    lib.lines()
        .filter_map(|l| l.strip_prefix("pub mod ").or_else(|| l.strip_prefix("mod ")))
        .map(|m| m.trim_end_matches(';').to_string())
        .collect()
}

/// lib.rs's `pub use m::{a, b};` and `pub use m::a;`: a name at the root → its module.
fn root_names(lib: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    for l in lib.lines() {
        let Some(rest) = l.strip_prefix("pub use ") else { continue };
        let Some((module, items)) = rest.trim_end_matches(';').split_once("::") else { continue };
        for item in items.trim_matches(|c| c == '{' || c == '}').split(',') {
            names.insert(item.trim().to_string(), module.to_string());
        }
    }
    names
}

/// The source without comments and without `#[cfg(doc)]` imports (a doc
/// link is not a dependency).
fn code(text: &str) -> String {
    let mut out = String::new();
    let mut doc_only = false;
    for line in text.lines() {
        let line = line.split("//").next().unwrap_or("");
        let t = line.trim();
        if t == "#[cfg(doc)]" {
            doc_only = true;
            continue;
        }
        if doc_only {
            doc_only = !t.ends_with(';');
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The first path segment of every `crate::…` path, including each item
/// of a `crate::{a::x, b}` group.
fn crate_paths(code: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let bytes = code.as_bytes();
    let mut at = 0;
    while let Some(i) = code[at..].find("crate::") {
        let start = at + i + "crate::".len();
        // Not `$crate::` or `my_crate::`.
        let before = (at + i).checked_sub(1).map(|b| bytes[b]);
        at = start;
        if before.is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'$') {
            continue;
        }
        if bytes.get(start) == Some(&b'{') {
            // The group's items, split at its own commas.
            let mut depth = 0;
            let mut item_start = start + 1;
            for (k, &c) in bytes.iter().enumerate().skip(start) {
                match c {
                    b'{' => depth += 1,
                    b'}' if depth == 1 => {
                        found.insert(ident(&code[item_start..k]));
                        break;
                    }
                    b'}' => depth -= 1,
                    b',' if depth == 1 => {
                        found.insert(ident(&code[item_start..k]));
                        item_start = k + 1;
                    }
                    _ => {}
                }
            }
        } else {
            found.insert(ident(&code[start..]));
        }
    }
    found.remove("");
    found
}

/// The identifier `text` starts with (after white space).
fn ident(text: &str) -> String {
    text.trim_start().chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect()
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Every top-level module's imports of other top-level modules of the
/// crate at `src`, with the file that makes each.
fn graph_of(src: &Path) -> BTreeMap<String, BTreeMap<String, String>> {
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    let modules = modules(&lib);
    let root_names = root_names(&lib);
    let mut files = Vec::new();
    sources(src, &mut files);
    let mut graph: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for file in files {
        let rel = file.strip_prefix(src).unwrap().to_string_lossy().replace('\\', "/");
        if rel == "lib.rs" {
            continue;
        }
        let top = rel.split('/').next().unwrap().trim_end_matches(".rs").to_string();
        let text = std::fs::read_to_string(&file).unwrap();
        for name in crate_paths(&code(&text)) {
            let target = if modules.contains(&name) { Some(name.clone()) } else { root_names.get(&name).cloned() };
            if let Some(t) = target.filter(|t| *t != top) {
                graph.entry(top.clone()).or_default().entry(t).or_insert_with(|| rel.clone());
            }
        }
    }
    graph
}

/// The library's module graph.
fn graph() -> BTreeMap<String, BTreeMap<String, String>> {
    graph_of(&root().join("src"))
}

#[test]
fn the_parser_reads_groups_and_paths() {
    let found = crate_paths("use crate::{a::{X, Y}, b, c::d::E};\nlet v = crate::e::f(); // crate::g\n");
    assert_eq!(found, ["a", "b", "c", "e", "g"].map(String::from).into());
    let code = code("use crate::a; // crate::b\n#[cfg(doc)]\nuse crate::c::{\n    D,\n};\n");
    assert_eq!(crate_paths(&code), ["a"].map(String::from).into());
}

#[test]
fn every_module_is_in_the_layer_table() {
    let architecture = std::fs::read_to_string(root().join("../../ARCHITECTURE.md")).unwrap();
    let layers = table(&architecture);
    let lib = std::fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let modules: BTreeSet<String> = modules(&lib).into_iter().collect();
    let listed: BTreeSet<String> = layers.keys().cloned().collect();
    assert_eq!(listed, modules, "ARCHITECTURE.md's layer table against lib.rs's modules");
}

#[test]
fn no_module_imports_from_a_layer_above_its_own() {
    let architecture = std::fs::read_to_string(root().join("../../ARCHITECTURE.md")).unwrap();
    let layers = table(&architecture);
    let mut above = Vec::new();
    for (from, targets) in graph() {
        for (to, file) in targets {
            let (a, b) = (layers[&from], layers[&to]);
            if b > a {
                above.push(format!("{file}: {from} (layer {a}) imports {to} (layer {b})"));
            }
        }
    }
    assert!(above.is_empty(), "imports from a layer above:\n{}", above.join("\n"));
}

/// The imports of `graph` that lead back to where they start.
fn cycles(graph: &BTreeMap<String, BTreeMap<String, String>>) -> Vec<String> {
    // A cycle passes through an edge a → b with a path b →* a.
    let reaches = |from: &str, to: &str| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.to_string()];
        while let Some(m) = stack.pop() {
            if m == to {
                return true;
            }
            if seen.insert(m.clone()) {
                stack.extend(graph.get(&m).into_iter().flat_map(|t| t.keys().cloned()));
            }
        }
        false
    };
    let mut cycles = Vec::new();
    for (from, targets) in graph {
        for (to, file) in targets {
            if reaches(to, from) {
                cycles.push(format!("{file}: {from} imports {to}, which leads back to {from}"));
            }
        }
    }
    cycles
}

#[test]
fn no_two_modules_import_each_other() {
    let cycles = cycles(&graph());
    assert!(cycles.is_empty(), "cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_command_line_and_python_modules_form_no_cycle() {
    for krate in ["flexure-cli", "flexure-py"] {
        let graph = graph_of(&root().join("..").join(krate).join("src"));
        assert!(graph.len() > 5, "{krate}: the graph was read ({} modules import others)", graph.len());
        let cycles = cycles(&graph);
        assert!(cycles.is_empty(), "{krate}: cycles:\n{}", cycles.join("\n"));
    }
}

#[test]
fn a_cycle_is_found() {
    let edge = |a: &str, b: &str| (a.to_string(), BTreeMap::from([(b.to_string(), format!("{a}.rs"))]));
    let graph = BTreeMap::from([edge("a", "b"), edge("b", "c"), edge("c", "a"), edge("d", "a")]);
    assert_eq!(cycles(&graph).len(), 3);
}

/// Reference: the tree. Every file or folder ARCHITECTURE.md names in
/// backticks (`….rs`, `…/`, `….md`, `….mjs`) exists, under the repository,
/// the library's `src/` or tests, or a front end's `src/`; and the page
/// stays short enough to read first (at most 250 lines).
#[test]
fn architecture_names_only_what_exists() {
    let repo = root().join("../..");
    let architecture = std::fs::read_to_string(repo.join("ARCHITECTURE.md")).unwrap();
    assert!(architecture.lines().count() <= 250, "ARCHITECTURE.md has {} lines", architecture.lines().count());
    let bases = ["", "crates/flexure/src", "crates/flexure", "crates/flexure-cli/src", "crates/flexure-py/src"];
    let mut missing = Vec::new();
    let mut named = 0;
    for quoted in architecture.split('`').skip(1).step_by(2) {
        let path = quoted.trim_start_matches("../");
        let is_path = [".rs", "/", ".md", ".mjs"].iter().any(|e| path.ends_with(e))
            && path.chars().all(|c| c.is_ascii_alphanumeric() || "_-./".contains(c));
        if !is_path || path.contains("NAME") {
            continue;
        }
        named += 1;
        if !bases.iter().any(|b| repo.join(b).join(path).exists()) {
            missing.push(path.to_string());
        }
    }
    assert!(named > 40, "only {named} paths read");
    assert!(missing.is_empty(), "ARCHITECTURE.md names paths that do not exist: {missing:?}");
}

/// Every `pub struct|enum|trait|type|union NAME` in `text`, each with
/// whether a `#[pyclass` attribute stands right above it.
fn public_types(text: &str) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    let mut pyclass = false;
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("#[") {
            pyclass |= t.starts_with("#[pyclass");
            continue;
        }
        let kinds = ["pub struct ", "pub enum ", "pub trait ", "pub type ", "pub union "];
        if let Some(rest) = kinds.iter().find_map(|k| t.strip_prefix(k)) {
            out.push((ident(rest), pyclass));
        }
        if !t.starts_with("///") {
            pyclass = false;
        }
    }
    out
}

/// Reference: the sources of the library, the CLI and the Python crate
/// (issue 34, item 7: one word for one thing). No two public types share
/// a name, so a name found in a message, a doc or a search is one type. A
/// Python class (`#[pyclass]`) is the library's type in the other
/// language and takes its name on purpose.
#[test]
fn no_two_public_types_share_a_name() {
    let mut places: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for krate in ["flexure", "flexure-cli", "flexure-py"] {
        let mut files = Vec::new();
        sources(&root().join("..").join(krate).join("src"), &mut files);
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            for (name, pyclass) in public_types(&text) {
                if !pyclass {
                    places.entry(name).or_default().push(file.display().to_string());
                }
            }
        }
    }
    assert!(places.len() > 200, "only {} public types read", places.len());
    let shared: Vec<_> = places.iter().filter(|(_, at)| at.len() > 1).collect();
    assert!(shared.is_empty(), "public types that share a name: {shared:#?}");
}

#[test]
fn a_shared_name_is_found_and_a_python_class_is_told_apart() {
    let text = "/// A.\n#[pyclass(frozen)]\n/// More.\npub struct Flexure {}\n#[derive(Debug)]\npub enum Stop { A }\npub(crate) struct Hidden;";
    assert_eq!(public_types(text), [("Flexure".to_string(), true), ("Stop".to_string(), false)]);
}

/// The front ends' source files (CLI and Python) whose code, comments
/// left out, contains any of `needles`, as paths under `crates/`.
fn front_end_files_naming(needles: &[&str]) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    for krate in ["flexure-cli", "flexure-py"] {
        let mut files = Vec::new();
        sources(&root().join("..").join(krate).join("src"), &mut files);
        for file in files {
            let text = code(&std::fs::read_to_string(&file).unwrap());
            if needles.iter().any(|n| text.contains(n)) {
                let at = file.strip_prefix(root().join("..")).unwrap().display().to_string();
                found.insert(at);
            }
        }
    }
    found
}

/// Reference: the front ends' sources (issue 34, item 4: one door for the
/// front ends). They match on no flexure's dimension: the door to one
/// flexure's variants are named nowhere, and `--spatial` is read only
/// where the options become the door's keys (and a batch of planar rows
/// is refused it). A mechanism's variants are named nowhere either: what
/// a front end does with the mechanism itself (draw's picture) it hands
/// to `Model::visit`, which matches for it (issue 34: one mechanism for
/// both dimensions).
#[test]
fn the_front_ends_match_on_the_dimension_only_in_the_door() {
    assert_eq!(front_end_files_naming(&["OneFlexure::Planar", "OneFlexure::Spatial"]), BTreeSet::new());
    let flag = front_end_files_naming(&["spatial.spatial", "self.spatial.then"]);
    assert_eq!(flag, BTreeSet::from(["flexure-cli/src/joint_options.rs".to_string()]));
    let mechanism = front_end_files_naming(&["Model::Planar", "Model::Spatial", "Dimension::"]);
    assert_eq!(mechanism, BTreeSet::new(), "front-end files that match on a mechanism's dimension");
    // The files deleted with the twins stay deleted.
    assert!(!root().join("../flexure-cli/src/spatial.rs").exists());
}

/// The library does no I/O and prints nothing: no `print!`, `println!`,
/// `eprint!`, `eprintln!` or `dbg!` in its code (doc comments and line
/// comments aside). The front ends print what it returns.
#[test]
fn the_library_prints_nothing() {
    let mut files = Vec::new();
    sources(&root().join("src"), &mut files);
    assert!(files.len() > 100, "only {} library files read", files.len());
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for (i, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            if ["print!(", "println!(", "eprint!(", "eprintln!(", "dbg!("].iter().any(|m| code.contains(m)) {
                found.push(format!("{}:{}", file.display(), i + 1));
            }
        }
    }
    assert!(found.is_empty(), "the library prints at {found:#?}");
}
