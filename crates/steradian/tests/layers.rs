//! Purpose: the module map in the core's and the loader's `lib.rs` is the code's. Every module imports only
//! modules of lower layers (as the numbered list under "## Layers" in `lib.rs` orders them),
//! and the files inside each module import each other without cycles.
//!
//! Imports are read from the source text: every `crate::a::…` path and every `super::…` path,
//! in code outside `#[cfg(test)]` items (tests may build fixtures from any layer). Comments and
//! string literals are skipped.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// A module's path inside its crate (`["render", "driver"]`); `[]` is the crate root.
type ModPath = Vec<String>;

/// Every `.rs` file under `src` with its module path.
fn modules(src: &Path) -> BTreeMap<ModPath, PathBuf> {
    fn walk(dir: &Path, prefix: &[String], out: &mut BTreeMap<ModPath, PathBuf>) {
        for entry in fs::read_dir(dir).expect("readable source folder") {
            let path = entry.expect("readable entry").path();
            let name = path.file_stem().and_then(|s| s.to_str()).expect("utf-8 name").to_string();
            let mut m = prefix.to_vec();
            if path.is_dir() {
                m.push(name);
                walk(&path, &m, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                if name != "mod" && name != "lib" {
                    m.push(name);
                }
                out.insert(m, path);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(src, &[], &mut out);
    out
}

/// The source without comments, string and char literals, and `#[cfg(test)]` items.
fn code_of(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        if text[i..].starts_with("//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if text[i..].starts_with("/*") {
            let end = text[i + 2..].find("*/").map_or(b.len(), |e| i + 2 + e + 2);
            i = end;
        } else if text[i..].starts_with("r#\"") {
            let end = text[i + 3..].find("\"#").map_or(b.len(), |e| i + 3 + e + 2);
            out.push_str("\"\"");
            i = end;
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            out.push_str("\"\"");
            i += 1;
        } else if b[i] == b'\'' && i + 2 < b.len() && (b[i + 2] == b'\'' || b[i + 1] == b'\\') {
            // a char literal ('a', '\n', '\''); lifetimes ('a) have no closing quote
            let end = text[i + 2..].find('\'').map_or(b.len(), |e| i + 2 + e + 1);
            i = end;
        } else if text[i..].starts_with("#[cfg(test)]") {
            // skip the attribute's item: up to its `;` or its brace-matched body
            let mut depth = 0;
            i += "#[cfg(test)]".len();
            while i < b.len() {
                match b[i] {
                    b'{' => depth += 1,
                    b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            i += 1;
                            break;
                        }
                    }
                    b';' if depth == 0 => {
                        i += 1;
                        break;
                    }
                    _ => {}
                }
                i += 1;
            }
        } else {
            let c = text[i..].chars().next().expect("in bounds");
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// The modules that the code of module `m` refers to by `crate::` and `super::` paths, each
/// resolved to the longest existing module path.
fn imports(m: &ModPath, code: &str, all: &BTreeSet<ModPath>) -> BTreeSet<ModPath> {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut heads: Vec<ModPath> = Vec::new();
    for kw in ["crate::", "super::"] {
        for (start, _) in code.match_indices(kw) {
            // `$crate::`, `a::super::` and the second `super::` of `super::super::` are parts
            // of a longer path
            let before = code[..start].trim_end();
            if code[..start].ends_with(|c: char| is_ident(c) || c == '$') || before.ends_with("::")
            {
                continue;
            }
            let base = if kw == "crate::" { Vec::new() } else { m[..m.len() - 1].to_vec() };
            path_heads(&code[start + kw.len()..], base, &mut heads);
        }
    }
    let mut out = BTreeSet::new();
    for h in heads {
        let resolved = (0..=h.len()).rev().map(|k| h[..k].to_vec()).find(|p| all.contains(p));
        if let Some(r) = resolved.filter(|r| r != m) {
            out.insert(r);
        }
    }
    out
}

/// Follows the path segments at the start of `rest` from module `path`; at a `{…}` group,
/// each item's path (recursively); pushes each path reached.
fn path_heads(rest: &str, mut path: ModPath, out: &mut Vec<ModPath>) {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut rest = rest.trim_start();
    loop {
        if let Some(group) = rest.strip_prefix('{') {
            // split the group's items at depth-0 commas
            let (mut depth, mut item_start) = (0, 0);
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        path_heads(&group[item_start..i], path.clone(), out);
                        return;
                    }
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        path_heads(&group[item_start..i], path.clone(), out);
                        item_start = i + 1;
                    }
                    _ => {}
                }
            }
            return;
        }
        let len = rest.find(|c: char| !is_ident(c)).unwrap_or(rest.len());
        let seg = &rest[..len];
        match seg {
            "" | "self" | "Self" => break,
            "super" => {
                path.pop();
            }
            _ => path.push(seg.to_string()),
        }
        match rest[len..].trim_start().strip_prefix("::") {
            Some(r) => rest = r.trim_start(),
            None => break,
        }
    }
    out.push(path);
}

/// The numbered layers listed under "## Layers" in `lib.rs`: each line `//! N. `a`, `b`: …`
/// gives the modules of layer N (the backquoted names before the first colon).
fn layers(lib: &str) -> BTreeMap<String, usize> {
    let mut out = BTreeMap::new();
    let section = lib.split("## Layers").nth(1).expect("lib.rs has a '## Layers' section");
    for line in section.lines().map(|l| l.trim_start_matches("//!").trim()) {
        let Some((num, rest)) = line.split_once(". ") else { continue };
        let Ok(n) = num.parse::<usize>() else { continue };
        let names = rest.split(':').next().unwrap_or("");
        for name in names.split('`').skip(1).step_by(2) {
            assert!(out.insert(name.to_string(), n).is_none(), "{name} listed twice");
        }
    }
    assert!(!out.is_empty(), "no layers listed");
    out
}

/// A cycle in `graph`, if any (depth-first search).
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        v: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(v.to_string(), 1);
        stack.push(v.to_string());
        for w in graph.get(v).into_iter().flatten() {
            match state.get(w.as_str()).copied().unwrap_or(0) {
                1 => {
                    let at = stack.iter().position(|s| s == w).expect("on the stack");
                    return Some(stack[at..].to_vec());
                }
                0 => {
                    if let Some(c) = visit(w, graph, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(v.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for v in graph.keys() {
        if state.get(v.as_str()).copied().unwrap_or(0) == 0 {
            if let Some(c) = visit(v, graph, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

/// Whether module `m` is declared only for tests (`#[cfg(test)] mod name;` in its parent's
/// file): such files are test code, exempt like `#[cfg(test)]` items.
fn test_only(m: &ModPath, mods: &BTreeMap<ModPath, PathBuf>) -> bool {
    let Some((name, parent)) = m.split_last() else { return false };
    let Some(text) = mods.get(parent).and_then(|f| fs::read_to_string(f).ok()) else {
        return false;
    };
    text.match_indices("#[cfg(test)]").any(|(i, attr)| {
        let rest = text[i + attr.len()..].trim_start();
        let rest =
            rest.strip_prefix("pub(crate)").or_else(|| rest.strip_prefix("pub")).unwrap_or(rest);
        rest.trim_start().strip_prefix("mod").is_some_and(|r| {
            r.trim_start()
                .strip_prefix(name.as_str())
                .is_some_and(|r| r.trim_start().starts_with(';'))
        })
    })
}

fn check_crate(src: &Path) {
    let mut mods = modules(src);
    let tests: Vec<ModPath> = mods.keys().filter(|m| test_only(m, &mods)).cloned().collect();
    // a test-only module's own children are test code too
    mods.retain(|m, _| !tests.iter().any(|t| m.starts_with(t)));
    let all: BTreeSet<ModPath> = mods.keys().cloned().collect();
    let lib = fs::read_to_string(src.join("lib.rs")).expect("lib.rs");
    let layer = layers(&lib);
    let top: BTreeSet<&String> = all.iter().filter(|m| m.len() == 1).map(|m| &m[0]).collect();
    for t in &top {
        assert!(layer.contains_key(t.as_str()), "{}: module `{t}` is in no layer", src.display());
    }
    for name in layer.keys() {
        assert!(top.contains(name), "{}: layer lists `{name}`, no such module", src.display());
    }
    let mut problems = Vec::new();
    // sibling graphs: for each parent, edges between its children
    let mut siblings: BTreeMap<ModPath, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for (m, file) in &mods {
        let text = fs::read_to_string(file).expect("readable source");
        for target in imports(m, &code_of(&text), &all) {
            // the first level where the two paths part
            let k = m.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if k == m.len() || k == target.len() {
                continue; // a module and its own parent or child
            }
            let (a, b) = (&m[k], &target[k]);
            if k == 0 {
                let (la, lb) = (layer[a.as_str()], layer[b.as_str()]);
                if la <= lb {
                    problems.push(format!(
                        "{} (layer {la}) imports {} (layer {lb})",
                        m.join("::"),
                        target.join("::")
                    ));
                }
            } else {
                siblings
                    .entry(m[..k].to_vec())
                    .or_default()
                    .entry(a.clone())
                    .or_default()
                    .insert(b.clone());
            }
        }
    }
    for (parent, graph) in &siblings {
        if let Some(cycle) = find_cycle(graph) {
            problems.push(format!("files of {} import in a circle: {cycle:?}", parent.join("::")));
        }
    }
    assert!(problems.is_empty(), "{}:\n{}", src.display(), problems.join("\n"));
}

#[test]
fn core_modules_import_only_lower_layers() {
    check_crate(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
}

#[test]
fn loader_modules_import_only_lower_layers() {
    check_crate(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../steradian-mitsuba/src"));
}

#[test]
fn the_checker_sees_a_cycle_and_a_layer_violation() {
    let all: BTreeSet<ModPath> =
        [vec![], vec!["a".into()], vec!["b".into()], vec!["b".into(), "x".into()]]
            .into_iter()
            .collect();
    let code = code_of(
        "use crate::b::x::Thing; // crate::a in a comment\nfn f() { \"crate::a\"; }\n\
         #[cfg(test)]\nmod tests { use crate::a; }",
    );
    let found = imports(&vec!["a".into()], &code, &all);
    assert_eq!(found, [vec!["b".to_string(), "x".to_string()]].into_iter().collect());
    let grouped = imports(&vec!["b".into(), "x".into()], "use super::super::{a, b};", &all);
    assert_eq!(grouped, [vec!["a".to_string()], vec!["b".to_string()]].into_iter().collect());
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("p".into()).or_default().insert("q".into());
    assert!(find_cycle(&g).is_none());
    g.entry("q".into()).or_default().insert("p".into());
    assert!(find_cycle(&g).is_some());
    let l = layers("//! ## Layers\n//! 1. `a`, `c`: things\n//! 2. `b`: more `d`");
    assert_eq!((l["a"], l["c"], l["b"]), (1, 1, 2));
    assert!(!l.contains_key("d"));
}
