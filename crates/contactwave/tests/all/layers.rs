//! The library's layering, checked on its source: modules import downwards only
//!
//! ```text
//! error → numeric, material, analytic, human, budget, interrupt → analysis, law → excitation, measured, render → solver
//!       → scenario, model → run → study, inverse → output, reproduce
//! ```
//!
//! (a module may use any module of a lower layer and, without cycles, of its own), and no
//! two sibling modules import each other, directly or through a chain. Names re-exported
//! by a `mod.rs` (or by `lib.rs`) count as the module that defines them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Layer of each top-level module of the library (higher layers use lower ones).
const LAYERS: &[(&str, u32)] = &[
    ("error", 0),
    ("numeric", 1),
    ("material", 1),
    ("analytic", 1),
    ("human", 1),
    ("budget", 1),
    ("interrupt", 1),
    ("analysis", 2),
    ("law", 2),
    ("excitation", 3),
    ("measured", 3),
    ("render", 3),
    ("solver", 4),
    ("scenario", 5),
    ("model", 5),
    ("run", 6),
    ("study", 7),
    ("inverse", 7),
    ("output", 8),
    ("reproduce", 8),
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Module path of a source file: `study/sweep/driver.rs` -> `["study", "sweep", "driver"]`.
fn module_of(file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src()).unwrap_or(file);
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without comments and string literals (approximately: enough for
/// paths in `use` lines and expressions), and without its `#[cfg(test)]` module.
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(k) => &text[..k],
        None => text,
    };
    let mut out = String::new();
    for line in text.lines() {
        let mut in_str = false;
        let mut prev = ' ';
        let mut kept = String::new();
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if !in_str && c == '/' && chars.get(i + 1) == Some(&'/') {
                break;
            }
            if c == '"' && prev != '\\' {
                in_str = !in_str;
            } else if !in_str {
                kept.push(c);
            }
            prev = c;
            i += 1;
        }
        out.push_str(&kept);
        out.push('\n');
    }
    out
}

/// Every path `crate::a::b::...` and `super::...` in the code, as segments (`super`
/// resolved against the file's module).
fn paths(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes: Vec<char> = code.chars().collect();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut i = 0;
    while i < bytes.len() {
        let rest: String = bytes[i..bytes.len().min(i + 7)].iter().collect();
        let starts = |w: &str| rest.starts_with(w) && (i == 0 || !ident(bytes[i - 1]));
        let (mut segs, mut j) = if starts("crate::") {
            (Vec::new(), i + 7)
        } else if starts("super::") {
            // one level up: a mod.rs's `super` is its parent, a file's its folder's module
            // (the module path of a mod.rs already ends at its folder)
            let mut base = module.to_vec();
            base.pop();
            let mut j = i + 7;
            while bytes[j..].iter().take(7).collect::<String>() == "super::" {
                base.pop();
                j += 7;
            }
            (base, j)
        } else {
            i += 1;
            continue;
        };
        loop {
            let s = j;
            while j < bytes.len() && ident(bytes[j]) {
                j += 1;
            }
            if j == s {
                break;
            }
            segs.push(bytes[s..j].iter().collect::<String>());
            if bytes[j..].iter().take(2).collect::<String>() == "::" {
                j += 2;
            } else {
                break;
            }
        }
        // a group `a::{b, c}`: one path per member
        if j < bytes.len() && bytes[j] == '{' {
            let end = bytes[j..]
                .iter()
                .position(|&c| c == '}')
                .map_or(j, |k| j + k);
            let inner: String = bytes[j + 1..end].iter().collect();
            for m in inner.split(',') {
                let first: String = m.trim().chars().take_while(|&c| ident(c)).collect();
                if !first.is_empty() && first != "self" {
                    let mut p = segs.clone();
                    p.push(first);
                    out.push(p);
                }
            }
            if !segs.is_empty() {
                out.push(segs);
            }
        } else if !segs.is_empty() {
            out.push(segs);
        }
        i = j.max(i + 1);
    }
    out
}

struct Tree {
    /// Every module path.
    modules: BTreeSet<Vec<String>>,
    /// Names re-exported by a module, and the child module they come from.
    reexports: BTreeMap<(Vec<String>, String), Vec<String>>,
    /// Code of each module.
    code: BTreeMap<Vec<String>, String>,
}

fn tree() -> Tree {
    let mut fs = Vec::new();
    files(&src(), &mut fs);
    let mut t = Tree {
        modules: BTreeSet::new(),
        reexports: BTreeMap::new(),
        code: BTreeMap::new(),
    };
    for f in &fs {
        let m = module_of(f);
        let text = std::fs::read_to_string(f).unwrap();
        t.modules.insert(m.clone());
        t.code.insert(m, code(&text));
    }
    // `pub use child::...::{A, B}` in a module: A, B come from `child`
    for (m, c) in &t.code {
        for line in c.split(';') {
            let line = line.trim();
            let Some(rest) = line.strip_prefix("pub use ") else {
                continue;
            };
            for p in paths(&format!("crate::{rest}"), m) {
                if p.len() >= 2 {
                    let name = p.last().cloned().unwrap_or_default();
                    let mut child = m.clone();
                    child.push(p[0].clone());
                    let from = if t.modules.contains(&child) {
                        child
                    } else {
                        // `pub use crate::x::y::Name`
                        p[..p.len() - 1].to_vec()
                    };
                    t.reexports.insert((m.clone(), name), from);
                }
            }
        }
    }
    t
}

impl Tree {
    /// The module a path refers to: its longest module prefix, following re-exports of
    /// the next segment.
    fn resolve(&self, path: &[String]) -> Vec<String> {
        let mut m: Vec<String> = Vec::new();
        for seg in path {
            let mut next = m.clone();
            next.push(seg.clone());
            if self.modules.contains(&next) {
                m = next;
            } else if let Some(from) = self.reexports.get(&(m.clone(), seg.clone())) {
                if from != &m {
                    return self.resolve(from);
                }
                break;
            } else {
                break;
            }
        }
        m
    }

    fn edges(&self) -> BTreeSet<(Vec<String>, Vec<String>)> {
        let mut e = BTreeSet::new();
        for (m, c) in &self.code {
            for p in paths(c, m) {
                let target = self.resolve(&p);
                if !target.is_empty() && &target != m {
                    e.insert((m.clone(), target));
                }
            }
        }
        e
    }
}

fn layer(top: &str) -> Option<u32> {
    LAYERS.iter().find(|(n, _)| *n == top).map(|(_, l)| *l)
}

#[test]
fn every_top_level_module_has_a_layer() {
    let t = tree();
    for m in &t.modules {
        if let Some(top) = m.first() {
            assert!(
                layer(top).is_some(),
                "module `{top}` has no layer in tests/all/layers.rs"
            );
        }
    }
}

#[test]
fn imports_go_downwards_only() {
    let t = tree();
    let mut bad = Vec::new();
    for (from, to) in t.edges() {
        let (Some(a), Some(b)) = (from.first(), to.first()) else {
            continue;
        };
        if let (Some(la), Some(lb)) = (layer(a), layer(b))
            && lb > la
        {
            bad.push(format!("{} -> {}", from.join("::"), to.join("::")));
        }
    }
    assert!(
        bad.is_empty(),
        "imports from a lower to a higher layer:\n{}",
        bad.join("\n")
    );
}

/// Cycles between siblings: for each module, its children (and for the crate, the
/// top-level modules) form a graph where `a -> b` when anything inside `a` uses anything
/// inside `b`.
#[test]
fn no_import_cycles_between_sibling_modules() {
    let t = tree();
    let edges = t.edges();
    let mut parents: BTreeSet<Vec<String>> = BTreeSet::new();
    for m in &t.modules {
        if !m.is_empty() {
            parents.insert(m[..m.len() - 1].to_vec());
        }
    }
    let mut cycles = Vec::new();
    for parent in parents {
        let d = parent.len();
        let child_of = |m: &Vec<String>| -> Option<String> {
            (m.len() > d && m[..d] == parent[..]).then(|| m[d].clone())
        };
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in &edges {
            if let (Some(x), Some(y)) = (child_of(a), child_of(b))
                && x != y
            {
                g.entry(x).or_default().insert(y);
            }
        }
        // depth-first search for a back edge
        fn visit(
            n: &str,
            g: &BTreeMap<String, BTreeSet<String>>,
            state: &mut BTreeMap<String, u8>,
            stack: &mut Vec<String>,
            found: &mut Vec<String>,
        ) {
            state.insert(n.to_string(), 1);
            stack.push(n.to_string());
            for m in g.get(n).into_iter().flatten() {
                match state.get(m.as_str()).copied().unwrap_or(0) {
                    0 => visit(m, g, state, stack, found),
                    1 => {
                        let k = stack.iter().position(|s| s == m).unwrap_or(0);
                        let mut c = stack[k..].to_vec();
                        c.push(m.clone());
                        found.push(c.join(" -> "));
                    }
                    _ => {}
                }
            }
            stack.pop();
            state.insert(n.to_string(), 2);
        }
        let mut state = BTreeMap::new();
        let mut found = Vec::new();
        for n in g.keys() {
            if state.get(n.as_str()).copied().unwrap_or(0) == 0 {
                visit(n, &g, &mut state, &mut Vec::new(), &mut found);
            }
        }
        for c in found {
            cycles.push(format!("in `{}`: {c}", parent.join("::")));
        }
    }
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_scanner_sees_a_known_edge() {
    // the check above must be able to fail: the model layer does use the solvers
    let t = tree();
    let e = t.edges();
    assert!(e
        .iter()
        .any(|(a, b)| a.first().is_some_and(|x| x == "model")
            && b.first().is_some_and(|x| x == "solver")));
}
