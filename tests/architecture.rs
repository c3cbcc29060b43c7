//! The module structure: no module of a crate uses a module that uses it back (an import circle,
//! direct or through others). A module's uses are the `crate::` and `super::` paths of its code
//! (comments and its `#[cfg(test)] mod tests` left out), resolved to the longest module they
//! name; a module and its own parent or children do not count (`mod.rs` declares them).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const CRATES: [&str; 5] = ["core/src", "interfaces/src", "elements/src", "materials/src", "src"];

/// Module path ("path::driver") -> file, for every `.rs` file under `root`.
fn modules(root: &Path) -> BTreeMap<String, PathBuf> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()) {
            if entry.is_dir() {
                stack.push(entry);
            } else if entry.extension().is_some_and(|e| e == "rs") {
                let relative = entry.strip_prefix(root).unwrap().with_extension("");
                let mut parts: Vec<String> = relative.iter().map(|p| p.to_string_lossy().into_owned()).collect();
                if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
                    parts.pop();
                }
                out.insert(parts.join("::"), entry);
            }
        }
    }
    out
}

/// The modules `module` (in `file`) uses, among `all`.
fn uses(module: &str, file: &Path, all: &BTreeMap<String, PathBuf>) -> BTreeSet<String> {
    let text = std::fs::read_to_string(file).unwrap();
    // the test module left out, up to its closing brace (code after it still counts)
    let code = match text.split_once("#[cfg(test)]\nmod tests {") {
        Some((before, after)) => format!("{before}{}", after.split_once("\n}\n").map_or("", |(_, rest)| rest)),
        None => text.clone(),
    };
    let mut out = BTreeSet::new();
    let parent: Vec<&str> = module.split("::").filter(|p| !p.is_empty()).collect();
    // `super::` of "path::driver" (path/driver.rs or path/driver/mod.rs) is "path"
    let above = parent[..parent.len().saturating_sub(1)].to_vec();
    for line in code.lines().map(str::trim).filter(|l| !l.starts_with("//")) {
        for (prefix, base) in [("crate::", Vec::new()), ("super::", above.clone())] {
            for (at, _) in line.match_indices(prefix) {
                if line[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                    continue;
                }
                let rest = &line[at + prefix.len()..];
                let path: Vec<&str> = rest
                    .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                    .next()
                    .unwrap_or("")
                    .split("::")
                    .take_while(|p| !p.is_empty() && p.chars().next().is_some_and(|c| c.is_lowercase()))
                    .collect();
                let mut candidate: Vec<&str> = base.iter().copied().chain(path).collect();
                while !candidate.is_empty() {
                    let name = candidate.join("::");
                    let related = name == module
                        || module.starts_with(&format!("{name}::"))
                        || name.starts_with(&format!("{module}::"));
                    if all.contains_key(&name) && !related {
                        out.insert(name);
                        break;
                    }
                    candidate.pop();
                }
            }
        }
    }
    out
}

/// The strongly connected components of more than one module (Tarjan).
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct Search<'a> {
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, (usize, usize)>,
        stack: Vec<&'a str>,
        found: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut Search<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, (n, n));
        s.stack.push(v);
        for w in &s.graph[v] {
            if !s.index.contains_key(w.as_str()) {
                visit(s, w);
                let low = s.index[v].1.min(s.index[w.as_str()].1);
                s.index.get_mut(v).unwrap().1 = low;
            } else if s.stack.contains(&w.as_str()) {
                let low = s.index[v].1.min(s.index[w.as_str()].0);
                s.index.get_mut(v).unwrap().1 = low;
            }
        }
        if s.index[v].0 == s.index[v].1 {
            let at = s.stack.iter().rposition(|&x| x == v).unwrap();
            let component: Vec<String> = s.stack.drain(at..).map(String::from).collect();
            if component.len() > 1 {
                s.found.push(component);
            }
        }
    }
    let mut search = Search { graph, index: BTreeMap::new(), stack: Vec::new(), found: Vec::new() };
    for v in graph.keys() {
        if !search.index.contains_key(v.as_str()) {
            visit(&mut search, v);
        }
    }
    search.found
}

#[test]
fn no_module_uses_a_module_that_uses_it_back() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = Vec::new();
    for krate in CRATES {
        let all = modules(&root.join(krate));
        let graph: BTreeMap<String, BTreeSet<String>> =
            all.iter().map(|(m, file)| (m.clone(), uses(m, file, &all))).collect();
        found.extend(circles(&graph).into_iter().map(|c| format!("{krate}: {}", c.join(" <-> "))));
    }
    assert!(found.is_empty(), "import circles:\n{}", found.join("\n"));
}

/// The check finds a circle where there is one.
#[test]
fn a_circle_of_two_modules_is_found() {
    let graph: BTreeMap<String, BTreeSet<String>> = [
        ("a".to_string(), BTreeSet::from(["b".to_string()])),
        ("b".to_string(), BTreeSet::from(["a".to_string(), "c".to_string()])),
        ("c".to_string(), BTreeSet::new()),
    ]
    .into();
    assert_eq!(circles(&graph).len(), 1);
    let mut without = graph.clone();
    without.get_mut("b").unwrap().remove("a");
    assert!(circles(&without).is_empty());
}
