//! The study's files import one way (issue 11, step 3): orchestrator (`reproduce.rs`) →
//! figure families → `kit.rs` → `pipeline.rs`, with no cycle among the files of `src/study`
//! (`reproduce.rs`, `dem_figures.rs` and `readme.rs` used to form one). Doc comments are
//! ignored (links are not imports).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The study files a study file refers to (`super::x`, `super::{x, y}`, `crate::study::x`).
fn references(text: &str, files: &BTreeSet<String>) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let code = line.trim_start();
        if code.starts_with("//") {
            continue;
        }
        for prefix in ["super::", "crate::study::"] {
            for (i, _) in code.match_indices(prefix) {
                let rest = &code[i + prefix.len()..];
                let names: Vec<&str> = match rest.strip_prefix('{') {
                    Some(group) => group
                        .split('}')
                        .next()
                        .unwrap_or("")
                        .split(',')
                        .map(|s| s.trim().split("::").next().unwrap_or(""))
                        .collect(),
                    None => vec![rest
                        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                        .next()
                        .unwrap_or("")],
                };
                out.extend(
                    names
                        .into_iter()
                        .filter(|n| files.contains(*n))
                        .map(String::from),
                );
            }
        }
    }
    out
}

#[test]
fn study_files_form_no_cycle() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/study");
    let mut texts = BTreeMap::new();
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "rs") {
            let name = p.file_stem().unwrap().to_string_lossy().to_string();
            if name != "mod" {
                texts.insert(name, std::fs::read_to_string(&p).unwrap());
            }
        }
    }
    let files: BTreeSet<String> = texts.keys().cloned().collect();
    let graph: BTreeMap<String, BTreeSet<String>> = texts
        .iter()
        .map(|(n, t)| {
            let mut r = references(t, &files);
            r.remove(n);
            (n.clone(), r)
        })
        .collect();
    assert!(graph["reproduce"].contains("impact_frf"), "{graph:?}");
    // depth-first search for a back edge
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        match state.get(n) {
            Some(2) => return None,
            Some(1) => {
                let start = path.iter().position(|p| p == n).unwrap();
                let mut cycle = path[start..].to_vec();
                cycle.push(n.to_string());
                return Some(cycle);
            }
            _ => {}
        }
        state.insert(n.to_string(), 1);
        path.push(n.to_string());
        for m in &graph[n] {
            if let Some(c) = visit(m, graph, state, path) {
                return Some(c);
            }
        }
        path.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if let Some(cycle) = visit(n, &graph, &mut state, &mut Vec::new()) {
            panic!(
                "study files import each other in a cycle: {}",
                cycle.join(" → ")
            );
        }
    }
}
