//! The house rules a program can check on the source itself (issue 21):
//! no import circle between files. Data flows one way, mesh -> fem ->
//! substructure -> contact -> recover -> output, and within a module too no
//! two files should need each other: a circle means neither can be read,
//! changed or tested alone.
//!
//! Every `use crate::..`, `use super::..`, `use self::..` (and a child
//! module named without `self::`) of every file under src/ is an edge to
//! the file that defines the module it names; tests (`#[cfg(test)]`
//! modules, `tests.rs`, files under a `tests/` folder) are left out. A
//! module and its own `mod.rs` (or `foo.rs` of `foo/`) are not counted: the
//! parent declares the child. The test fails naming every circle left.
//!
//! And no child imports its parent (issue 33): a parent module's file
//! (`mod.rs`, or `foo.rs` of `foo/`) is the folder's entry point and its
//! re-exports; what its children share lives in leaf files named for what
//! it is (`contact/system/relation.rs`), so no import runs back up inside a
//! folder. An item an ancestor's file defines (not re-exports), named by a
//! child in a `use` or by a path in code, fails the second test, unless
//! `CALLS_BACK` says why the child calls back into its parent.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The module path of every source file (`["contact", "system", "dense"]`).
fn modules(root: &Path) -> BTreeMap<Vec<String>, PathBuf> {
    let mut out = BTreeMap::new();
    let mut dirs = vec![root.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("a source folder").flatten() {
            let path = entry.path();
            if path.is_dir() {
                if path.file_name().is_some_and(|n| n != "tests") {
                    dirs.push(path);
                }
                continue;
            }
            let rel = path.strip_prefix(root).expect("under src");
            let Some(stem) = rel.to_str().and_then(|s| s.strip_suffix(".rs")) else { continue };
            let mut m: Vec<String> = stem.split('/').map(str::to_string).collect();
            if m.last().is_some_and(|l| l == "tests") {
                continue;
            }
            if m.last().is_some_and(|l| l == "mod") || m == ["lib"] || m == ["main"] {
                m.pop();
            }
            out.insert(m, path);
        }
    }
    out
}

/// The source without comments and without `#[cfg(test)]` modules.
fn code(text: &str) -> String {
    let mut s: String = text.lines().map(|l| l.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n");
    while let Some(at) = s.find("#[cfg(test)]") {
        let Some(open) = s[at..].find('{').map(|i| at + i) else { break };
        let (mut depth, mut end) = (0, open);
        for (i, c) in s[open..].char_indices() {
            depth += match c {
                '{' => 1,
                '}' => -1,
                _ => 0,
            };
            if depth == 0 {
                end = open + i + 1;
                break;
            }
        }
        s.replace_range(at..end, "");
    }
    s
}

/// The paths a `use` tree names: `a::{b, c::{d, e}}` is a::b, a::c::d, a::c::e.
fn expand(tree: &str) -> Vec<String> {
    let tree: String = tree.split_whitespace().collect();
    let Some(open) = tree.find('{') else { return vec![tree.split(" as ").next().unwrap_or("").to_string()] };
    let prefix = tree[..open].trim_end_matches("::");
    let inner = &tree[open + 1..tree.len() - 1];
    let (mut parts, mut depth, mut start) = (Vec::new(), 0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty())
        .flat_map(expand)
        .map(|p| if p == "self" { prefix.to_string() } else { format!("{prefix}::{p}") })
        .collect()
}

/// The tree of the `use` statement that ends a `;`-separated chunk of code
/// (after attributes and a visibility), if it is one.
fn use_tree(chunk: &str) -> Option<&str> {
    chunk.lines().find_map(|line| {
        let t = line.trim_start();
        let t = ["pub(crate) ", "pub(super) ", "pub "].iter().find_map(|v| t.strip_prefix(v)).unwrap_or(t);
        // from `use ` to the end of the chunk: a tree may span lines
        t.strip_prefix("use ").map(|tree| &chunk[tree.as_ptr() as usize - chunk.as_ptr() as usize..])
    })
}

/// The full module path a `use` path names from the file `here`; None for
/// paths outside the crate (std, other crates).
fn resolve(files: &BTreeMap<Vec<String>, PathBuf>, here: &[String], p: &str) -> Option<Vec<String>> {
    let segs: Vec<&str> = p.split("::").filter(|s| !s.is_empty()).collect();
    let (mut base, mut rest) = (here.to_vec(), &segs[..]);
    match rest.first() {
        Some(&"crate") => {
            base.clear();
            rest = &rest[1..];
        }
        Some(&"super") | Some(&"self") => {
            while let Some(&s) = rest.first().filter(|s| **s == "super" || **s == "self") {
                if s == "super" {
                    base.pop();
                }
                rest = &rest[1..];
            }
        }
        Some(first) if files.contains_key(&[here.to_vec(), vec![first.to_string()]].concat()) => {}
        _ => return None,
    }
    Some(base.into_iter().chain(rest.iter().map(|s| s.to_string())).collect())
}

/// The file modules each file imports from (parents and children left out).
fn edges(files: &BTreeMap<Vec<String>, PathBuf>) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let mut out: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    for (here, path) in files {
        let text = code(&std::fs::read_to_string(path).expect("a source file"));
        for stmt in text.split(';').filter_map(use_tree) {
            for p in expand(stmt) {
                let Some(full) = resolve(files, here, &p) else { continue };
                // the longest prefix that is a file of its own
                let Some(target) = (0..=full.len()).rev().map(|k| full[..k].to_vec()).find(|m| files.contains_key(m))
                else {
                    continue;
                };
                let family = target.len() + 1 == here.len() && here.starts_with(&target)
                    || here.len() + 1 == target.len() && target.starts_with(here);
                if &target != here && !family {
                    out.entry(here.clone()).or_default().insert(target);
                }
            }
        }
    }
    out
}

/// A circle through `start`, if the edges have one: the files in order.
fn circle(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>, start: &Vec<String>) -> Option<Vec<Vec<String>>> {
    let mut stack = vec![(start.clone(), vec![start.clone()])];
    let mut seen = BTreeSet::new();
    while let Some((at, path)) = stack.pop() {
        for next in edges.get(&at).into_iter().flatten() {
            if next == start {
                return Some(path);
            }
            if seen.insert(next.clone()) {
                stack.push((next.clone(), [path.clone(), vec![next.clone()]].concat()));
            }
        }
    }
    None
}

#[test]
fn no_two_files_import_each_other_around_a_circle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = modules(&root);
    let edges = edges(&files);
    let n: usize = edges.values().map(|e| e.len()).sum();
    assert!(files.len() > 50 && n > 200, "the source was read: {} files, {n} imports", files.len());
    let name =
        |m: &Vec<String>| files[m].strip_prefix(&root).map_or_else(|_| String::new(), |p| p.display().to_string());
    let mut circles: BTreeSet<Vec<String>> = BTreeSet::new();
    for m in files.keys() {
        if let Some(c) = circle(&edges, m) {
            let mut names: Vec<String> = c.iter().map(name).collect();
            // one circle, whichever file it was found from
            let first = names.iter().enumerate().min_by_key(|(_, n)| n.as_str()).map_or(0, |(i, _)| i);
            names.rotate_left(first);
            circles.insert(names);
        }
    }
    let listed: Vec<String> = circles.iter().map(|c| format!("{} -> {}", c.join(" -> "), c[0])).collect();
    assert!(circles.is_empty(), "import circles between files:\n{}", listed.join("\n"));
}

/// Every `.rs` file under `root`, test files included.
fn rust_files(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut dirs = vec![root.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("a source folder").flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The source with comments, strings and character literals blanked out
/// (newlines kept), so that the braces left are the code's own. Knows
/// nested block comments, escapes, raw strings (`r#"..."#`, `br"..."`) and
/// tells a character literal (`'{'`, `'\''`) from a lifetime (`'a`).
fn blanked(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    // blanks c[from..to] into `out`, keeping its newlines
    let blank = |out: &mut String, from: usize, to: usize| {
        out.extend(c[from..to.min(c.len())].iter().map(|&x| if x == '\n' { '\n' } else { ' ' }))
    };
    let mut i = 0;
    while i < c.len() {
        let at = |k: usize| c.get(i + k).copied().unwrap_or('\0');
        let end = if at(0) == '/' && at(1) == '/' {
            (i..c.len()).find(|&k| c[k] == '\n').unwrap_or(c.len())
        } else if at(0) == '/' && at(1) == '*' {
            let (mut k, mut depth) = (i + 2, 1);
            while k < c.len() && depth > 0 {
                match (c[k], c.get(k + 1).copied().unwrap_or('\0')) {
                    ('/', '*') => (depth, k) = (depth + 1, k + 1),
                    ('*', '/') => (depth, k) = (depth - 1, k + 1),
                    _ => {}
                }
                k += 1;
            }
            k
        } else if let Some(k) = raw_string_end(&c, i) {
            k
        } else if at(0) == '"' {
            let mut k = i + 1;
            while k < c.len() && c[k] != '"' {
                k += if c[k] == '\\' { 2 } else { 1 };
            }
            k + 1
        } else if at(0) == '\'' && (at(1) == '\\' || (at(2) == '\'' && at(1) != '\'')) {
            let mut k = i + 1;
            while k < c.len() && c[k] != '\'' {
                k += if c[k] == '\\' { 2 } else { 1 };
            }
            k + 1
        } else {
            out.push(c[i]);
            i += 1;
            continue;
        };
        blank(&mut out, i, end);
        i = end;
    }
    out
}

/// The end of a raw string starting at `i` (`r"`, `r#"`, `br"`, ... not
/// inside an identifier), if one starts there.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    if i > 0 && (c[i - 1].is_alphanumeric() || c[i - 1] == '_') {
        return None;
    }
    let mut k = i + usize::from(c.get(i) == Some(&'b'));
    if c.get(k) != Some(&'r') {
        return None;
    }
    k += 1;
    let hashes = c[k..].iter().take_while(|&&x| x == '#').count();
    k += hashes;
    if c.get(k) != Some(&'"') {
        return None;
    }
    let close: Vec<char> = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
    (k + 1..c.len()).find(|&e| c[e..].starts_with(&close)).map(|e| e + close.len())
}

/// Every function with a body in `code` (blanked): its name, the line of
/// its `fn` (from 1) and its length in lines, from the `fn` line to the
/// line of its closing brace.
fn functions(code: &str) -> Vec<(String, usize, usize)> {
    let bytes = code.as_bytes();
    let line_at = |p: usize| code[..p].matches('\n').count() + 1;
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(found) = code[from..].find("fn ") {
        let at = from + found;
        from = at + 3;
        if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_') {
            continue;
        }
        let rest = code[from..].trim_start();
        let name: String = rest.chars().take_while(|x| x.is_alphanumeric() || *x == '_').collect();
        if name.is_empty() {
            continue;
        }
        // the body: the first `{` outside brackets, unless a `;` (a
        // declaration's end, not one of `[f64; 3]`) comes first
        let mut nest = 0i32;
        let Some(open) = (from..bytes.len()).find(|&k| {
            match bytes[k] {
                b'(' | b'[' => nest += 1,
                b')' | b']' => nest -= 1,
                _ => {}
            }
            nest == 0 && matches!(bytes[k], b'{' | b';')
        }) else {
            break;
        };
        if bytes[open] == b';' {
            continue;
        }
        let mut depth = 0usize;
        let Some(close) = (open..bytes.len()).find(|&k| {
            match bytes[k] {
                b'{' => depth += 1,
                b'}' => depth -= 1,
                _ => {}
            }
            depth == 0
        }) else {
            break;
        };
        out.push((name, line_at(at), line_at(close) - line_at(at) + 1));
    }
    out
}

/// The longest a function may be, in lines (issue 33).
const MOST_LINES: usize = 80;

#[test]
fn the_counter_sees_braces_only_in_code() {
    let src = "fn a() {\n    let s = \"}}\"; // }\n    let c = '}';\n    let r = r#\"{\"#;\n    /* { /* } */ */\n    \
               let t: &'static str = \"\\\"}\";\n    fn inner(x: [u8; 2]) -> u8 {\n        x[0]\n    }\n}\nfn b();\nfn c() {}\n";
    let found = functions(&blanked(src));
    let names: Vec<(&str, usize, usize)> = found.iter().map(|(n, l, k)| (n.as_str(), *l, *k)).collect();
    assert_eq!(names, [("a", 1, 10), ("inner", 7, 3), ("c", 12, 1)], "{src}");
}

#[test]
fn no_function_in_src_is_over_80_lines() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = rust_files(&root);
    let mut long = Vec::new();
    let mut seen = 0;
    for path in &files {
        let text = std::fs::read_to_string(path).expect("a source file");
        for (name, line, lines) in functions(&blanked(&text)) {
            seen += 1;
            if lines > MOST_LINES {
                let rel = path.strip_prefix(&root).unwrap_or(path);
                long.push(format!("src/{}:{line} fn {name}: {lines} lines", rel.display()));
            }
        }
    }
    assert!(files.len() > 50 && seen > 1000, "the source was read: {} files, {seen} functions", files.len());
    assert!(long.is_empty(), "functions over {MOST_LINES} lines (split each into named steps):\n{}", long.join("\n"));
}

/// Where `code` opens and closes braces: the depth before each line
/// (string and character literals skipped, so `"{{"` does not count).
fn line_depths(code: &str) -> Vec<(i32, &str)> {
    let mut out = Vec::new();
    let (mut depth, mut in_str, mut raw_hashes): (i32, bool, Option<usize>) = (0, false, None);
    for line in code.lines() {
        out.push((if in_str { -1 } else { depth }, line));
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if in_str {
                match (c, raw_hashes) {
                    ('\\', None) => i += 1,
                    ('"', None) => in_str = false,
                    ('"', Some(h)) if chars[i + 1..].iter().take(h).filter(|&&x| x == '#').count() == h => {
                        in_str = false;
                        i += h;
                    }
                    _ => {}
                }
            } else if c == '"' {
                let hashes = chars[..i].iter().rev().take_while(|&&x| x == '#').count();
                let raw = i > hashes && chars[i - hashes - 1] == 'r';
                (in_str, raw_hashes) = (true, raw.then_some(hashes));
            } else if c == '\'' && chars.get(i + 1) == Some(&'\\') {
                i += chars[i + 2..].iter().position(|&x| x == '\'').map_or(chars.len(), |p| p + 2);
            } else if c == '\'' && chars.get(i + 2) == Some(&'\'') {
                i += 2;
            } else if c == '{' {
                depth += 1;
            } else if c == '}' {
                depth -= 1;
            }
            i += 1;
        }
    }
    out
}

/// The items a module's own file defines at its top level: structs, enums,
/// functions, constants, traits, types (not `pub use`, not child modules).
fn defined(code: &str) -> BTreeSet<String> {
    const MODIFIERS: &[&str] = &["pub", "crate", "super", "self", "in", "unsafe", "async", "extern", "C", "mut"];
    const KINDS: &[&str] = &["struct", "enum", "fn", "const", "static", "trait", "type", "union"];
    let mut out = BTreeSet::new();
    for (_, line) in line_depths(code).into_iter().filter(|(d, _)| *d == 0) {
        let words: Vec<&str> =
            line.split(|c: char| !c.is_alphanumeric() && c != '_').filter(|w| !w.is_empty()).collect();
        let mut rest = words.into_iter().skip_while(|w| MODIFIERS.contains(w)).peekable();
        if rest.peek().is_some_and(|w| KINDS.contains(w)) {
            // `const fn f`, `static mut X`: the name follows the last keyword
            out.extend(rest.find(|w| !KINDS.contains(w) && *w != "mut").map(str::to_string));
        }
    }
    out
}

/// The paths written out in code (`super::num(v)`, `crate::driver::say`),
/// outside `use` trees as well as in them.
fn inline_paths(code: &str) -> Vec<String> {
    let word = |c: char| c.is_alphanumeric() || c == '_' || c == ':';
    let mut out = Vec::new();
    for start in ["super::", "crate::"] {
        for (at, _) in code.match_indices(start) {
            if code[..at].chars().next_back().is_some_and(word) {
                continue;
            }
            let path: String = code[at..].chars().take_while(|&c| word(c)).collect();
            out.push(path.trim_end_matches(':').to_string());
        }
    }
    out
}

/// Files allowed to import an item their parent module's file defines, and
/// why: the parent's entry point or main type, which the child calls back
/// into.
const CALLS_BACK: &[(&str, &str, &str)] = &[
    ("contact/cutting.rs", "iterate", "each piece of a cut load step is solved by the module's entry point"),
    ("contact/ramp.rs", "iterate", "each piece of the stage's strength ramp is solved by the module's entry point"),
    (
        "contact/system/iterative/stiffness.rs",
        "Iterative",
        "the friction's scale is measured through the interface's own parts and preconditioner blocks",
    ),
    ("contact/system/junction/tie_cache.rs", "Junction", "the cache memoises the junction's own null space"),
    ("fem/shape/inverse.rs", "eval", "the inverse map's Newton steps evaluate the shape functions themselves"),
    ("output/files/stage.rs", "Staged", "the folder's entry point; in a leaf, staged.rs and stage.rs would circle"),
];

#[test]
fn no_child_file_imports_what_its_parent_module_file_defines() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = modules(&root);
    let defs: BTreeMap<&Vec<String>, BTreeSet<String>> =
        files.iter().map(|(m, p)| (m, defined(&code(&std::fs::read_to_string(p).expect("a source file"))))).collect();
    let name =
        |m: &Vec<String>| files[m].strip_prefix(&root).map_or_else(|_| String::new(), |p| p.display().to_string());
    let (mut found, mut checked) = (BTreeSet::new(), 0);
    for (here, path) in &files {
        let text = code(&std::fs::read_to_string(path).expect("a source file"));
        let trees = text.split(';').filter_map(use_tree).flat_map(expand);
        for p in trees.chain(inline_paths(&text)) {
            let Some(full) = resolve(&files, here, &p) else { continue };
            let Some(target) = (0..full.len()).rev().map(|k| full[..k].to_vec()).find(|m| files.contains_key(m)) else {
                continue;
            };
            if target.len() >= here.len() || !here.starts_with(&target) {
                continue;
            }
            checked += 1;
            let item = &full[target.len()];
            let allowed = CALLS_BACK.iter().any(|(f, i, _)| *f == name(here) && i == item);
            if defs[&target].contains(item) && !allowed {
                found.insert(format!("{} imports `{item}` from {}", name(here), name(&target)));
            }
        }
    }
    assert!(checked > 50, "the source was read: {checked} paths into a parent module");
    let listed: Vec<String> = found.into_iter().collect();
    assert!(
        listed.is_empty(),
        "{} imports of an item a parent module's file defines; move it to a leaf file named for what it is \
         and import it from there (or, for the parent's entry point, say why in CALLS_BACK):\n{}",
        listed.len(),
        listed.join("\n")
    );
}

/// Writers take data, not the scene: no file under src/output names the
/// scene module or reads a run's scene (`run.scene`); they read
/// `run.about`, which the driver makes once. The unit tests (`tests.rs`)
/// may load a scene to run the driver on it.
#[test]
fn no_writer_reads_the_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/output");
    let files = rust_files(&root);
    let mut found = Vec::new();
    for path in files.iter().filter(|p| !p.ends_with("tests.rs")) {
        let code = blanked(&std::fs::read_to_string(path).expect("a source file"));
        for (i, line) in code.lines().enumerate() {
            let reads = line
                .match_indices(".scene")
                .any(|(at, w)| line[at + w.len()..].chars().next().is_none_or(|c| !(c.is_alphanumeric() || c == '_')));
            if reads || line.contains("crate::scene") || line.contains("super::scene") {
                found.push(format!(
                    "src/output/{}:{}: {}",
                    path.strip_prefix(&root).unwrap_or(path).display(),
                    i + 1,
                    line.trim()
                ));
            }
        }
    }
    assert!(files.len() > 20, "the writers were read: {} files", files.len());
    assert!(
        found.is_empty(),
        "writers that read the scene (give them the data in results::About):\n{}",
        found.join("\n")
    );
}
