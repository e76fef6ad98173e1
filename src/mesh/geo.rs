//! What a `.geo` says before gmsh runs it: the parameters it defines with
//! `DefineConstant[ name = {value, ...}, ... ]` (the only names that
//! `-setnumber` overrides), and the commands in it that reach outside the
//! mesh: `SystemCall`, `NonBlockingSystemCall` and `OnelabRun` run
//! programs through the shell; `Save`, `Print`, `CreateDir`, `SendToServer`
//! and `Printf(...) > "file"` write files where the script says. The text
//! is read as gmsh's lexer reads it (`//` and `/* */` comments and
//! `"strings"` are not code), and files pulled in with `Include "..."`
//! (relative to the including file) are read the same way.

use std::path::{Path, PathBuf};

/// Commands that run programs or write files.
const COMMANDS: [&str; 7] =
    ["SystemCall", "NonBlockingSystemCall", "OnelabRun", "Save", "Print", "CreateDir", "SendToServer"];

/// A token of a `.geo`: a name, a string, or one character of punctuation.
#[derive(Clone, Debug, PartialEq)]
enum Token {
    Name(String),
    Str(String),
    Punct(char),
}

/// The tokens of `text`, with the line each starts on.
fn tokens(text: &str) -> Vec<(Token, usize)> {
    let b = text.as_bytes();
    let (mut i, mut line, mut out) = (0, 1, Vec::new());
    while i < b.len() {
        let c = b[i];
        if c == b'\n' {
            line += 1;
            i += 1;
        } else if c.is_ascii_whitespace() {
            i += 1;
        } else if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            i += 2;
            while i < b.len() && !b[i..].starts_with(b"*/") {
                line += usize::from(b[i] == b'\n');
                i += 1;
            }
            i += 2;
        } else if c == b'"' {
            let (start, at) = (i + 1, line);
            i += 1;
            while i < b.len() && b[i] != b'"' {
                line += usize::from(b[i] == b'\n');
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            out.push((Token::Str(String::from_utf8_lossy(&b[start..i.min(b.len())]).into_owned()), at));
            i += 1;
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'.') {
                i += 1;
            }
            out.push((Token::Name(String::from_utf8_lossy(&b[start..i]).into_owned()), line));
        } else {
            out.push((Token::Punct(c as char), line));
            i += 1;
        }
    }
    out
}

/// What a `.geo` (with its includes) defines and runs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GeoText {
    /// Names defined by `DefineConstant`, in order of appearance.
    pub constants: Vec<String>,
    /// Commands that reach outside the mesh: (file, line, command).
    pub commands: Vec<(PathBuf, usize, String)>,
}

/// Reads `geo` and the files it includes (a file that cannot be read is
/// left to gmsh to report).
pub fn scan(geo: &Path, text: &str) -> GeoText {
    let mut found = GeoText::default();
    scan_into(geo, text, &mut found, 0);
    found
}

fn scan_into(file: &Path, text: &str, found: &mut GeoText, depth: usize) {
    let t = tokens(text);
    for (k, (tok, line)) in t.iter().enumerate() {
        let Token::Name(name) = tok else { continue };
        let next = |d: usize| t.get(k + d).map(|(t, _)| t);
        match name.as_str() {
            "DefineConstant" if next(1) == Some(&Token::Punct('[')) => constants(&t[k + 2..], &mut found.constants),
            "Include" => {
                if let (Some(Token::Str(inc)), true) = (next(1), depth < 16) {
                    let path = file.parent().unwrap_or(Path::new(".")).join(inc);
                    if let Ok(text) = std::fs::read_to_string(&path) {
                        scan_into(&path, &text, found, depth + 1);
                    }
                }
            }
            "Printf" if redirects(&t[k + 1..]) => {
                found.commands.push((file.to_path_buf(), *line, "Printf > file".into()))
            }
            c if COMMANDS.contains(&c) => found.commands.push((file.to_path_buf(), *line, c.to_string())),
            _ => {}
        }
    }
}

/// The names of `name = ...` at the top level of `DefineConstant[ ... ]`
/// (the tokens after its `[`).
fn constants(t: &[(Token, usize)], names: &mut Vec<String>) {
    let mut depth = 0usize;
    for (k, (tok, _)) in t.iter().enumerate() {
        match tok {
            Token::Punct('[' | '{' | '(') => depth += 1,
            Token::Punct(']' | '}' | ')') if depth == 0 => return,
            Token::Punct(']' | '}' | ')') => depth -= 1,
            Token::Name(n)
                if depth == 0 && t.get(k + 1).is_some_and(|(t, _)| *t == Token::Punct('=')) && !names.contains(n) =>
            {
                names.push(n.clone());
            }
            _ => {}
        }
    }
}

/// Whether `Printf( ... )` (the tokens after `Printf`) is followed by `>`.
fn redirects(t: &[(Token, usize)]) -> bool {
    let mut depth = 0usize;
    for (k, (tok, _)) in t.iter().enumerate() {
        match tok {
            Token::Punct('(') => depth += 1,
            Token::Punct(')') if depth <= 1 => return t.get(k + 1).is_some_and(|(n, _)| *n == Token::Punct('>')),
            Token::Punct(')') => depth -= 1,
            _ if depth == 0 => return false,
            _ => {}
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_and_commands_are_found_outside_comments_and_strings() {
        let text = r#"
// SystemCall "not this";
/* Save "nor this"; DefineConstant[ x = 1 ]; */
DefineConstant[ lc = {0.2, Name "Mesh size (SystemCall)"}, n = 3,
                h = {1, Min 0, Max 2, Choices {0, 1}} ];
Printf("lc = %g", lc);
Printf("to a file") > "/tmp/out.txt";
SystemCall "touch x";
Point(1) = {0, 0, 0, lc};
Save "copy.msh";
"#;
        let g = scan(Path::new("a.geo"), text);
        assert_eq!(g.constants, ["lc", "n", "h"]);
        let cmds: Vec<(usize, &str)> = g.commands.iter().map(|(_, l, c)| (*l, c.as_str())).collect();
        assert_eq!(cmds, [(7, "Printf > file"), (8, "SystemCall"), (10, "Save")]);
    }
}
