//! The library's module graph, read from the syntax tree (issue 40): every file of `src/`
//! (but `src/main.rs` and `src/cli/`, the binary) is parsed with `syn`, and every reference
//! to another module of the crate becomes an edge between two files:
//!
//! - `use` declarations, grouped and nested ones included (`use crate::{a, b::{c, d}}`), with
//!   `crate::`, `super::` (any depth), `self::` and uniform paths (`use child::x`, a name
//!   bound by an earlier `use`);
//! - paths in expressions, types, patterns and trait bounds (`crate::x::f()`,
//!   `super::world::BoxDrive`), and `crate::…` / `super::…` token sequences inside macro
//!   calls (`format!`, `matches!`);
//! - a name reached through a re-export (`crate::prelude::Scene`, `crate::dem::DemWorld`) is
//!   followed to the file that defines it.
//!
//! Code under `#[cfg(test)]` is left out, inside a file or as a whole file of unit tests
//! (`#![cfg(test)]`): unit tests may build what they test from above. So are doc comments (a
//! link is not an import).
//!
//! Two checks: the top-level modules import only down the layers of [`LAYERS`] (the order
//! `src/lib.rs` documents), and no files import each other in a cycle. A re-export (`pub
//! use`), and a path that passes through a module's re-exports (`crate::dem::ReplicaReport`
//! reaches `dem/mod.rs` on its way to the analysis), count for the layers (what a module
//! offers, and the way to it, are dependencies) but not for file cycles: a thin `mod.rs` that
//! re-exports its children's items is their facade, not a user of them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use proc_macro2::{TokenStream, TokenTree};
use syn::visit::Visit;

mod common;
use common::rust_files;

/// The library's layers, highest first: a module may import modules of lower layers only
/// (and never one of its own layer but itself). The same order as `src/lib.rs`'s map.
const LAYERS: &[&[&str]] = &[
    // the common types in one import (re-exports only)
    &["prelude"],
    // reference dynamical systems for tests, benches and examples (the bouncing ball is a
    // scene of the impact model)
    &["systems"],
    // studies of the models: the thesis chapters, the trade-off (and `kind = "auto"`)
    &["study"],
    &["tradeoff"],
    // parameter sweeps and single runs with their analysis
    &["sweep"],
    // figures; the run directory and series files
    &["plot"],
    &["io"],
    // the resolve step: scene → the engine's objects
    &["setup"],
    // which model a scene needs: the ladder of shortcuts, `kind = "auto"`
    &["choice"],
    // the TOML form (it names the engines' defaults)
    &["scene"],
    // the simulators
    &["dem", "impact"],
    // what a run streams (observers); the DEM's parts: contact laws, neighbour search,
    // integration, packing
    &["observe", "contact", "neighbor", "integrate", "packing"],
    // writing files (atomic writes, CSV text)
    &["files"],
    // equations of the primary system and what every run reports
    &["model"],
    // nonlinear time-series analysis: knows nothing of the simulators
    &["analysis"],
    // foundations
    &["simd"],
    &["error", "units"],
];

/// Pairs of top-level modules allowed to import upward for now, each with its reason.
const UPWARD_FOR_NOW: &[(&str, &str, &str)] = &[];

/// File pairs allowed to import each other for now, each with its reason (the edge between
/// them is left out of the cycle search).
const CYCLES_FOR_NOW: &[(&str, &str, &str)] = &[];

/// One file of the library: its module path and its syntax tree.
struct SourceFile {
    module: Vec<String>,
    rel: String,
    ast: syn::File,
}

/// The library's files with their module paths (`src/dem/blocks.rs` → `["dem", "blocks"]`).
fn library() -> Vec<SourceFile> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut paths = Vec::new();
    rust_files(&src, &mut paths);
    paths.sort();
    let mut out = Vec::new();
    for p in paths {
        let rel = p
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if rel == "main.rs" || rel.starts_with("cli/") {
            continue;
        }
        let mut module: Vec<String> = rel
            .trim_end_matches(".rs")
            .split('/')
            .map(String::from)
            .collect();
        if module.last().is_some_and(|m| m == "mod" || m == "lib") {
            module.pop();
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let ast = syn::parse_file(&text).unwrap_or_else(|e| panic!("src/{rel}: {e}"));
        // a file of unit tests (`#![cfg(test)]`, e.g. `foo/tests.rs`) is left out as a
        // `#[cfg(test)] mod tests { … }` inside a file is
        if is_cfg_test(&ast.attrs) {
            continue;
        }
        out.push(SourceFile { module, rel, ast });
    }
    out
}

fn is_cfg_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg") && {
            let t = a.meta.to_token_stream_string();
            t.contains("test") && !t.contains("not")
        }
    })
}

trait MetaText {
    fn to_token_stream_string(&self) -> String;
}
impl MetaText for syn::Meta {
    fn to_token_stream_string(&self) -> String {
        quote::ToTokens::to_token_stream(self).to_string()
    }
}

/// A `use` binding: in module `scope`, the name `name` stands for the path `target` (as
/// written, not yet resolved); `glob` for `use target::*`.
#[derive(Debug, Clone)]
struct Binding {
    scope: Vec<String>,
    name: String,
    target: Vec<String>,
    glob: bool,
    public: bool,
}

/// What one file says: its `use` bindings, the paths it mentions (with the module they are
/// written in), the items it defines (by module) and its inline modules.
#[derive(Default)]
struct Collected {
    bindings: Vec<Binding>,
    paths: Vec<(Vec<String>, Vec<String>)>,
    defined: BTreeSet<(Vec<String>, String)>,
    inline_modules: BTreeSet<Vec<String>>,
}

struct Collector<'a> {
    scope: Vec<String>,
    out: &'a mut Collected,
}

fn flatten_use(
    tree: &syn::UseTree,
    prefix: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, String, bool)>,
) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            flatten_use(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let name = n.ident.to_string();
            if name == "self" {
                let last = prefix.last().cloned().unwrap_or_default();
                out.push((prefix.clone(), last, false));
            } else {
                let mut t = prefix.clone();
                t.push(name.clone());
                out.push((t, name, false));
            }
        }
        syn::UseTree::Rename(r) => {
            let mut t = prefix.clone();
            if r.ident != "self" {
                t.push(r.ident.to_string());
            }
            out.push((t, r.rename.to_string(), false));
        }
        syn::UseTree::Glob(_) => out.push((prefix.clone(), "*".into(), true)),
        syn::UseTree::Group(g) => {
            for t in &g.items {
                flatten_use(t, prefix, out);
            }
        }
    }
}

/// `crate :: a :: b` and `super :: …` sequences in a macro's tokens.
fn token_paths(ts: TokenStream, out: &mut Vec<Vec<String>>) {
    let tokens: Vec<TokenTree> = ts.into_iter().collect();
    let mut i = 0;
    while i < tokens.len() {
        match &tokens[i] {
            TokenTree::Group(g) => token_paths(g.stream(), out),
            TokenTree::Ident(id) if *id == "crate" || *id == "super" => {
                let mut path = vec![id.to_string()];
                let mut j = i + 1;
                while let (
                    Some(TokenTree::Punct(a)),
                    Some(TokenTree::Punct(b)),
                    Some(TokenTree::Ident(next)),
                ) = (tokens.get(j), tokens.get(j + 1), tokens.get(j + 2))
                {
                    if a.as_char() != ':' || b.as_char() != ':' {
                        break;
                    }
                    path.push(next.to_string());
                    j += 3;
                }
                if path.len() > 1 {
                    out.push(path);
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
}

impl<'ast> Visit<'ast> for Collector<'_> {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let attrs: &[syn::Attribute] = match item {
            syn::Item::Const(i) => &i.attrs,
            syn::Item::Enum(i) => &i.attrs,
            syn::Item::Fn(i) => &i.attrs,
            syn::Item::Impl(i) => &i.attrs,
            syn::Item::Mod(i) => &i.attrs,
            syn::Item::Static(i) => &i.attrs,
            syn::Item::Struct(i) => &i.attrs,
            syn::Item::Trait(i) => &i.attrs,
            syn::Item::Type(i) => &i.attrs,
            syn::Item::Use(i) => &i.attrs,
            syn::Item::Macro(i) => &i.attrs,
            _ => &[],
        };
        if is_cfg_test(attrs) {
            return;
        }
        let name = match item {
            syn::Item::Const(i) => Some(i.ident.to_string()),
            syn::Item::Enum(i) => Some(i.ident.to_string()),
            syn::Item::Fn(i) => Some(i.sig.ident.to_string()),
            syn::Item::Static(i) => Some(i.ident.to_string()),
            syn::Item::Struct(i) => Some(i.ident.to_string()),
            syn::Item::Trait(i) => Some(i.ident.to_string()),
            syn::Item::Type(i) => Some(i.ident.to_string()),
            syn::Item::Union(i) => Some(i.ident.to_string()),
            syn::Item::Mod(i) => Some(i.ident.to_string()),
            syn::Item::Macro(i) => i.ident.as_ref().map(|i| i.to_string()),
            _ => None,
        };
        if let Some(n) = name {
            self.out.defined.insert((self.scope.clone(), n));
        }
        syn::visit::visit_item(self, item);
    }

    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if let Some((_, items)) = &m.content {
            self.scope.push(m.ident.to_string());
            self.out.inline_modules.insert(self.scope.clone());
            for i in items {
                self.visit_item(i);
            }
            self.scope.pop();
        }
    }

    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        let mut flat = Vec::new();
        flatten_use(&u.tree, &mut Vec::new(), &mut flat);
        let public = !matches!(u.vis, syn::Visibility::Inherited);
        for (target, name, glob) in flat {
            self.out.bindings.push(Binding {
                scope: self.scope.clone(),
                name,
                target,
                glob,
                public,
            });
        }
    }

    fn visit_path(&mut self, p: &'ast syn::Path) {
        let segs: Vec<String> = p.segments.iter().map(|s| s.ident.to_string()).collect();
        if segs.len() > 1 {
            self.out.paths.push((self.scope.clone(), segs));
        }
        syn::visit::visit_path(self, p);
    }

    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        let mut found = Vec::new();
        token_paths(m.tokens.clone(), &mut found);
        for f in found {
            self.out.paths.push((self.scope.clone(), f));
        }
        syn::visit::visit_macro(self, m);
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        if !is_cfg_test(&f.attrs) {
            syn::visit::visit_impl_item_fn(self, f);
        }
    }
}

/// The crate's modules and what they bind, to resolve paths to files.
struct Crate {
    /// Module path → file (relative to `src/`), for file modules and inline ones.
    file_of: BTreeMap<Vec<String>, String>,
    bindings: BTreeMap<Vec<String>, Vec<Binding>>,
    defined: BTreeSet<(Vec<String>, String)>,
}

impl Crate {
    /// `path` (as written in module `scope`) made absolute (without `crate`), or `None` for
    /// an external or local name.
    fn absolute(&self, scope: &[String], path: &[String]) -> Option<Vec<String>> {
        let first = path.first()?;
        let mut base: Vec<String>;
        let mut rest = path;
        match first.as_str() {
            "crate" => {
                base = Vec::new();
                rest = &path[1..];
            }
            "super" | "self" => {
                base = scope.to_vec();
                while let Some(s) = rest.first() {
                    match s.as_str() {
                        "super" => {
                            base.pop()?;
                        }
                        "self" => {}
                        _ => break,
                    }
                    rest = &rest[1..];
                }
            }
            _ => {
                // a name bound by a `use` of this module, or a child module
                if let Some(b) = self
                    .bindings
                    .get(scope)
                    .and_then(|bs| bs.iter().find(|b| !b.glob && &b.name == first))
                {
                    if b.target.as_slice() == path {
                        // `use child::x` binds `x` to itself: a uniform path
                    } else {
                        let mut t = self.absolute(scope, &b.target)?;
                        t.extend_from_slice(&path[1..]);
                        return Some(t);
                    }
                }
                let mut child = scope.to_vec();
                child.push(first.clone());
                if self.file_of.contains_key(&child) {
                    base = scope.to_vec();
                } else {
                    return None;
                }
            }
        }
        base.extend(rest.iter().cloned());
        Some(base)
    }

    /// The file that defines what the absolute path `abs` names, following re-exports; the
    /// files whose re-exports were followed go to `passed`.
    fn file(&self, abs: &[String], depth: usize, passed: &mut Vec<String>) -> Option<String> {
        // the longest prefix that is a module
        let mut k = abs.len();
        while k > 0 && !self.file_of.contains_key(&abs[..k]) {
            k -= 1;
        }
        let module = abs[..k].to_vec();
        let file = self.file_of.get(&module)?.clone();
        let Some(name) = abs.get(k) else {
            return Some(file);
        };
        if depth > 16 || self.defined.contains(&(module.clone(), name.clone())) {
            return Some(file);
        }
        if let Some(bs) = self.bindings.get(&module) {
            if let Some(b) = bs.iter().find(|b| !b.glob && &b.name == name) {
                if let Some(mut t) = self.absolute(&module, &b.target) {
                    t.extend_from_slice(&abs[k + 1..]);
                    passed.push(file.clone());
                    return self.file(&t, depth + 1, passed).or(Some(file));
                }
                return Some(file);
            }
            for b in bs.iter().filter(|b| b.glob) {
                if let Some(mut t) = self.absolute(&module, &b.target) {
                    t.extend_from_slice(&abs[k..]);
                    let mut through = Vec::new();
                    if let Some(f) = self.file(&t, depth + 1, &mut through) {
                        if f != file {
                            passed.push(file.clone());
                            passed.extend(through);
                            return Some(f);
                        }
                    }
                }
            }
        }
        Some(file)
    }
}

/// How one file refers to another: only through a `pub use` (a re-export), and only by
/// passing through its re-exports on the way to a third file (a facade).
#[derive(Debug, Clone, Copy)]
struct Kind {
    reexport: bool,
    facade: bool,
}

/// The references between files: (from, to) → how.
type Edges = BTreeMap<(String, String), Kind>;

fn graph() -> (Vec<SourceFile>, Edges) {
    let files = library();
    let mut collected: Vec<Collected> = Vec::new();
    let mut krate = Crate {
        file_of: BTreeMap::new(),
        bindings: BTreeMap::new(),
        defined: BTreeSet::new(),
    };
    for f in &files {
        krate.file_of.insert(f.module.clone(), f.rel.clone());
    }
    for f in &files {
        let mut c = Collected::default();
        let mut v = Collector {
            scope: f.module.clone(),
            out: &mut c,
        };
        for item in &f.ast.items {
            v.visit_item(item);
        }
        for m in &c.inline_modules {
            krate.file_of.insert(m.clone(), f.rel.clone());
        }
        for b in &c.bindings {
            krate
                .bindings
                .entry(b.scope.clone())
                .or_default()
                .push(b.clone());
        }
        krate.defined.extend(c.defined.iter().cloned());
        collected.push(c);
    }
    let mut edges = Edges::new();
    for (f, c) in files.iter().zip(&collected) {
        let mut add = |to: &str, reexport: bool, facade: bool| {
            if to != f.rel {
                let e = edges
                    .entry((f.rel.clone(), to.to_string()))
                    .or_insert(Kind {
                        reexport: true,
                        facade: true,
                    });
                e.reexport &= reexport;
                e.facade &= facade;
            }
        };
        let mut resolve = |scope: &[String], path: &[String], reexport: bool| {
            if let Some(abs) = krate.absolute(scope, path) {
                let mut passed = Vec::new();
                if let Some(to) = krate.file(&abs, 0, &mut passed) {
                    add(&to, reexport, false);
                }
                for p in passed {
                    add(&p, reexport, true);
                }
            }
        };
        for b in &c.bindings {
            resolve(&b.scope, &b.target, b.public);
        }
        for (scope, p) in &c.paths {
            resolve(scope, p, false);
        }
    }
    (files, edges)
}

fn top(rel: &str) -> String {
    rel.trim_end_matches(".rs")
        .split('/')
        .next()
        .unwrap()
        .to_string()
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

#[test]
fn the_parser_sees_grouped_imports_reexports_and_paths() {
    let (_, edges) = graph();
    let has = |a: &str, b: &str| edges.contains_key(&(a.to_string(), b.to_string()));
    // `use crate::{…}` groups, `super::` and re-exports followed to the defining file
    assert!(
        has("setup/dem.rs", "dem/stability.rs"),
        "setup/dem.rs → dem/stability.rs"
    );
    assert!(
        has("prelude.rs", "scene/mod.rs"),
        "prelude.rs → scene/mod.rs"
    );
    assert!(
        has("sweep/run.rs", "setup/mod.rs"),
        "sweep/run.rs → setup/mod.rs"
    );
}

#[test]
fn every_top_level_module_has_a_layer() {
    let lib =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod "))
        .map(|l| l.trim_end_matches(';'))
        .collect();
    assert!(declared.len() > 10, "{declared:?}");
    for m in declared {
        assert!(
            layer_of(m).is_some(),
            "src/lib.rs's module {m} has no layer in LAYERS"
        );
    }
}

#[test]
fn modules_import_only_down_the_layers() {
    let (_, edges) = graph();
    let mut bad = Vec::new();
    for (from, to) in edges.keys() {
        let (a, b) = (top(from), top(to));
        if a == b || a == "lib" || b == "lib" {
            continue;
        }
        let (la, lb) = (layer_of(&a), layer_of(&b));
        let allowed = matches!((la, lb), (Some(x), Some(y)) if x < y)
            || UPWARD_FOR_NOW.iter().any(|(x, y, _)| *x == a && *y == b);
        if !allowed {
            bad.push(format!("src/{from} → src/{to} ({a} → {b})"));
        }
    }
    assert!(
        bad.is_empty(),
        "imports against the layers of src/lib.rs:\n{}",
        bad.join("\n")
    );
}

#[test]
fn no_files_import_each_other_in_a_cycle() {
    let (files, edges) = graph();
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for ((a, b), kind) in &edges {
        let excused = CYCLES_FOR_NOW
            .iter()
            .any(|(x, y, _)| (x == a && y == b) || (x == b && y == a));
        if !kind.reexport && !kind.facade && !excused {
            next.entry(a).or_default().push(b);
        }
    }
    // Tarjan's strongly connected components
    struct Tarjan<'a> {
        next: &'a BTreeMap<&'a str, Vec<&'a str>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<Vec<&'a str>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            self.on.insert(v);
            for &w in self.next.get(v).map(|x| x.as_slice()).unwrap_or(&[]) {
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let l = self.low[v].min(self.low[w]);
                    self.low.insert(v, l);
                } else if self.on.contains(w) {
                    let l = self.low[v].min(self.index[w]);
                    self.low.insert(v, l);
                }
            }
            if self.low[v] == self.index[v] {
                let mut c = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on.remove(w);
                    c.push(w);
                    if w == v {
                        break;
                    }
                }
                if c.len() > 1 {
                    c.sort();
                    self.out.push(c);
                }
            }
        }
    }
    let mut t = Tarjan {
        next: &next,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for f in &files {
        if !t.index.contains_key(f.rel.as_str()) {
            t.visit(f.rel.as_str());
        }
    }
    let shown: Vec<String> = t
        .out
        .iter()
        .map(|c| {
            let inner: Vec<String> = c
                .iter()
                .flat_map(|a| {
                    c.iter()
                        .filter(|b| next.get(a).is_some_and(|n| n.contains(b)))
                        .map(move |b| format!("{a} → {b}"))
                })
                .collect();
            format!("{{{}}}: {}", c.join(", "), inner.join("; "))
        })
        .collect();
    assert!(
        shown.is_empty(),
        "files that import each other (src/…):\n{}",
        shown.join("\n")
    );
}

/// `PDAMP_PRINT_GRAPH=1 cargo test --test design_module_graph -- --nocapture print` lists the
/// edges between top-level modules.
#[test]
fn print_the_graph_when_asked() {
    if std::env::var_os("PDAMP_PRINT_GRAPH").is_none() {
        return;
    }
    let (_, edges) = graph();
    let mut tops: BTreeMap<(String, String), Vec<String>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        if top(a) != top(b) {
            tops.entry((top(a), top(b)))
                .or_default()
                .push(format!("{a} → {b}"));
        }
    }
    for ((a, b), v) in tops {
        println!("{a} → {b}: {}", v.join(", "));
    }
}
