//! The architecture as a test (README "Layout"): the library's layers, bottom
//! to top, are
//!
//!   math → scene → loads → model → solve → sim → fmi
//!
//! and a module may only import from its own layer or the layers below it.
//! Inside `model`, the rod and the cable do not know each other, and the
//! shared seam (`model/*.rs`) knows neither; the solvers never name a
//! concrete model. No module depends on itself through others (no cycle).
//!
//! Read from the source: every `crate::…` and `super::…` path in code (not in
//! comments, not in `#[cfg(test)]` items, where a test may compare two
//! implementations; code after such an item is read), resolved to the file of the longest module prefix that
//! exists. `pub use` lines (re-exports for the users) and `mod` declarations
//! are not dependencies.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const LAYERS: [&str; 7] = ["math", "scene", "loads", "model", "solve", "sim", "fmi"];

/// Module path of a source file: src/model/rod/step.rs → [model, rod, step].
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap();
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap();
    if last != "mod.rs" && last != "lib.rs" {
        parts.push(last.trim_end_matches(".rs").to_string());
    }
    parts
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without comments, string literals' contents, the
/// `#[cfg(test)]` module, `pub use` re-exports and `mod` declarations.
fn code_lines(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    // inside a #[cfg(test)] item: its brace depth and whether it has opened
    let mut test_item: Option<(i32, bool)> = None;
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]") {
            test_item = Some((0, false));
            continue;
        }
        if let Some((depth, opened)) = test_item.as_mut() {
            for c in t.chars() {
                match c {
                    '{' => {
                        *depth += 1;
                        *opened = true;
                    }
                    '}' => *depth -= 1,
                    _ => {}
                }
            }
            if (*opened && *depth <= 0) || (!*opened && t.ends_with(';')) {
                test_item = None;
            }
            continue;
        }
        if t.starts_with("//") || t.starts_with("pub use") || t.starts_with("pub mod") || t.starts_with("mod ") {
            continue;
        }
        let code = match t.find("//") {
            Some(i) => &t[..i],
            None => t,
        };
        // drop string literals (messages may mention paths)
        let mut s = String::new();
        let mut in_str = false;
        let mut prev = ' ';
        for c in code.chars() {
            if c == '"' && prev != '\\' {
                in_str = !in_str;
            } else if !in_str {
                s.push(c);
            }
            prev = c;
        }
        out.push(s);
    }
    out
}

/// The module paths a file's code refers to (`crate::a::b`, `super::c`).
fn references(module: &[String], is_mod_rs: bool, code: &[String]) -> BTreeSet<Vec<String>> {
    let mut refs = BTreeSet::new();
    for line in code {
        let bytes: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < bytes.len() {
            let rest: String = bytes[i..].iter().collect();
            let starts_word = i == 0 || !(bytes[i - 1].is_alphanumeric() || bytes[i - 1] == '_' || bytes[i - 1] == ':');
            let (base, skip) = if starts_word && rest.starts_with("crate::") {
                (Vec::new(), "crate::".len())
            } else if starts_word && rest.starts_with("super::") {
                // the parent of this module (of a mod.rs: the module's parent)
                let mut m = module.to_vec();
                if !is_mod_rs || !m.is_empty() {
                    m.pop();
                }
                (m, "super::".len())
            } else {
                i += 1;
                continue;
            };
            let mut path = base;
            let mut j = i + skip;
            loop {
                let seg: String = bytes[j..].iter().take_while(|c| c.is_alphanumeric() || **c == '_').collect();
                if seg.is_empty() {
                    break;
                }
                j += seg.chars().count();
                if seg == "super" {
                    path.pop();
                } else {
                    path.push(seg);
                }
                if bytes[j..].starts_with(&[':', ':']) {
                    j += 2;
                } else {
                    break;
                }
            }
            refs.insert(path);
            i = j.max(i + 1);
        }
    }
    refs
}

/// The longest prefix of `path` that is a module (a file) of the crate.
fn resolve(path: &[String], modules: &BTreeSet<Vec<String>>) -> Vec<String> {
    (0..=path.len()).rev().map(|k| path[..k].to_vec()).find(|p| modules.contains(p)).unwrap_or_default()
}

fn layer(m: &[String]) -> Option<usize> {
    m.first().and_then(|top| LAYERS.iter().position(|l| l == top))
}

fn under(m: &[String], prefix: &[&str]) -> bool {
    m.len() >= prefix.len() && m.iter().zip(prefix).all(|(a, b)| a == b)
}

#[test]
fn imports_only_go_down_the_layers_and_form_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.retain(|f| !f.starts_with(src.join("bin")));
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_of(&src, f)).collect();
    // every top-level module has a layer
    for m in &modules {
        if let Some(top) = m.first() {
            assert!(LAYERS.contains(&top.as_str()), "module {} is in no layer: add it to LAYERS", m.join("::"));
        }
    }
    let mut graph: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    let mut violations = Vec::new();
    for f in &files {
        let m = module_of(&src, f);
        let is_mod_rs = f.file_name().is_some_and(|n| n == "mod.rs" || n == "lib.rs");
        let code = code_lines(&std::fs::read_to_string(f).unwrap());
        for r in references(&m, is_mod_rs, &code) {
            let target = resolve(&r, &modules);
            if target == m || target.is_empty() {
                continue;
            }
            graph.entry(m.clone()).or_default().insert(target.clone());
            let (from, to) = (layer(&m), layer(&target));
            let name = |x: &[String]| x.join("::");
            if let (Some(a), Some(b)) = (from, to)
                && b > a
            {
                violations.push(format!("{} imports {} (a higher layer)", name(&m), name(&target)));
            }
            let rod = under(&target, &["model", "rod"]);
            let cable = under(&target, &["model", "cable"]);
            if under(&m, &["model", "rod"]) && cable || under(&m, &["model", "cable"]) && rod {
                violations.push(format!("{} imports {} (the models do not know each other)", name(&m), name(&target)));
            }
            let seam = under(&m, &["model"]) && !under(&m, &["model", "rod"]) && !under(&m, &["model", "cable"]);
            if seam && (rod || cable) {
                violations.push(format!("{} imports {} (the seam knows no model)", name(&m), name(&target)));
            }
            if under(&m, &["solve"]) && (rod || cable) {
                violations.push(format!("{} imports {} (the solvers name no model)", name(&m), name(&target)));
            }
        }
    }
    assert!(violations.is_empty(), "layering violations:\n  {}", violations.join("\n  "));
    // no cycle: depth-first search with colours
    fn visit(
        n: &Vec<String>,
        g: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        colour: &mut BTreeMap<Vec<String>, u8>,
        stack: &mut Vec<Vec<String>>,
    ) -> Option<Vec<Vec<String>>> {
        colour.insert(n.clone(), 1);
        stack.push(n.clone());
        for t in g.get(n).into_iter().flatten() {
            match colour.get(t).copied().unwrap_or(0) {
                1 => {
                    let i = stack.iter().position(|x| x == t).unwrap();
                    let mut cycle = stack[i..].to_vec();
                    cycle.push(t.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(t, g, colour, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        colour.insert(n.clone(), 2);
        None
    }
    let mut colour = BTreeMap::new();
    for n in graph.keys() {
        if colour.get(n).copied().unwrap_or(0) == 0
            && let Some(c) = visit(n, &graph, &mut colour, &mut Vec::new())
        {
            let names: Vec<String> = c.iter().map(|x| x.join("::")).collect();
            panic!("import cycle: {}", names.join(" → "));
        }
    }
    // the check sees the code: the crate has its layers and the seam
    assert!(graph.len() >= 30, "only {} modules with imports found", graph.len());
    assert!(graph.values().flatten().any(|t| t == &vec!["model".to_string(), "rod".to_string(), "gauss".to_string()]));
}

/// The checker itself catches what it is meant to: an upward import, a
/// `super::` path, a cycle's edge, and ignores comments and re-exports.
#[test]
fn the_checker_reads_paths_as_the_compiler_does() {
    let module = vec!["model".to_string(), "rod".to_string(), "step".to_string()];
    let code = code_lines(
        "use super::RodModel;\nuse crate::solve::Integrator; // crate::sim\n/// crate::fmi\npub use crate::sim::X;\n\
         let x = crate::math::band::new(\"crate::fmi\");\n#[cfg(test)]\nmod tests {\n    use crate::sim;\n}\n\
         use crate::scene::Scene;",
    );
    let refs = references(&module, false, &code);
    let want: BTreeSet<Vec<String>> = [
        vec!["model", "rod", "RodModel"],
        vec!["solve", "Integrator"],
        vec!["math", "band", "new"],
        vec!["scene", "Scene"],
    ]
    .iter()
    .map(|v| v.iter().map(|s| s.to_string()).collect())
    .collect();
    assert_eq!(refs, want);
    let modules: BTreeSet<Vec<String>> = [vec!["model"], vec!["model", "rod"], vec!["solve"]]
        .iter()
        .map(|v| v.iter().map(|s| s.to_string()).collect())
        .collect();
    assert_eq!(resolve(&["model".into(), "rod".into(), "RodModel".into()], &modules), vec!["model", "rod"]);
    assert_eq!(layer(&["solve".into()]), Some(4));
    assert!(layer(&["solve".into()]) > layer(&module));
}
