//! The documentation's walks through the code name real files and real code: every repository
//! path in `docs/architecture.md` (a backticked path under a top-level folder of the workspace)
//! exists, and every function, type and constant it names in backticks is defined in the
//! workspace's Rust or GLSL sources, called with as many arguments as the definition takes. A
//! move, a rename or a new parameter that leaves the walk behind fails here. Both checks only
//! read files.

use std::collections::HashSet;
use std::path::Path;

/// Top-level folders a repository path in the docs starts with.
const ROOTS: [&str; 8] = [
    "compute/",
    "synth/",
    "renderer/",
    "tools/",
    "tests/",
    "glsl/",
    "docs/",
    "scripts/",
];

/// Every backticked span of `text` that looks like a repository path.
fn repository_paths(text: &str) -> Vec<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| ROOTS.iter().any(|r| span.starts_with(r)))
        .filter(|span| !span.contains(' '))
        .flat_map(expand)
        .collect()
}

/// `a/{b,c}/` names `a/b/` and `a/c/`; `a/b.rs`/`c.rs` stays one path.
fn expand(span: &str) -> Vec<String> {
    match (span.find('{'), span.find('}')) {
        (Some(open), Some(close)) if open < close => span[open + 1..close]
            .split(',')
            .map(|part| format!("{}{}{}", &span[..open], part, &span[close + 1..]))
            .collect(),
        _ => vec![span.to_string()],
    }
}

/// Whether `path` exists below `root`; a `*` in its file name matches any run of characters
/// (`lazy_*.comp` holds when one such file exists).
fn exists(root: &Path, path: &str) -> bool {
    let path = root.join(path.trim_end_matches('/'));
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    let Some((head, tail)) = name.split_once('*') else {
        return path.exists();
    };
    std::fs::read_dir(path.parent().unwrap()).is_ok_and(|entries| {
        entries.flatten().any(|e| {
            let n = e.file_name().to_string_lossy().to_string();
            n.len() >= head.len() + tail.len() && n.starts_with(head) && n.ends_with(tail)
        })
    })
}

#[test]
fn every_path_the_architecture_walks_name_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let text = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let paths = repository_paths(&text);
    assert!(paths.len() >= 30, "only {} paths found", paths.len());
    let missing: Vec<&String> = paths.iter().filter(|p| !exists(&root, p)).collect();
    assert!(
        missing.is_empty(),
        "docs/architecture.md names missing paths: {missing:?}"
    );
}

#[test]
fn the_path_finder_sees_paths_and_expands_braces() {
    let text = "see `compute/src/{gpu,prims}/` and `tools/x.rs`, not `cargo test` or `src/a.rs`";
    assert_eq!(
        repository_paths(text),
        ["compute/src/gpu/", "compute/src/prims/", "tools/x.rs"]
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    assert!(exists(&root, "glsl/synth/solid/lazy_*.comp"));
    assert!(!exists(&root, "glsl/synth/solid/lazy_*.glsl"));
    assert!(!exists(&root, "compute/src/no_such_file.rs"));
}

// ---------------------------------------------------------------------------------------------
// Named functions and types.
//
// A walk that names `Baker::bake` or quotes `store_albedo(slot, pos, normal, gradient)` is only
// useful while that function exists and takes those arguments. The check below indexes every
// definition in the workspace's Rust and GLSL sources (pure text, no compiler) and resolves each
// backticked span of the docs that can only be a code name:
//
// - a call, `name(a, b)`, `Path::name(a)` or `receiver.name(a)`: a function of that name whose
//   parameter count (without `self`) equals the quoted arguments' (`name()` and arguments with
//   `...` name the function without fixing its arity);
// - a path, `Type::member` or `crate::module::Item`: the type's impl, trait, enum or struct
//   has the member (a method, associated item, variant or field); a `lazysolid_*` crate's
//   modules and items are looked up in that crate only; another crate's path is not checked;
// - `fn name`: a function;
// - a CamelCase identifier (no underscore): a Rust type, trait or enum variant, or a GLSL
//   struct or block;
// - a SCREAMING_CASE identifier with an underscore: a Rust constant, a GLSL `const` or
//   `#define`, a kernel (`path_trace.comp` is `PATH_TRACE`), or an environment variable the
//   Rust reads or a script sets.
//
// Everything else (file paths, commands, flags, TOML keys and values, formulas, lower-case
// words that may be fields or variables) is not a name this check can decide, and is left to
// the path check above or to the reader.

/// Crates a path in the docs may start with, and the folder their sources are in.
const CRATES: [(&str, &str); 6] = [
    ("lazysolid_compute", "compute/src/"),
    ("lazysolid_shader_build", "compute/shader-build/"),
    ("lazysolid_synth", "synth/src/"),
    ("lazysolid_renderer", "renderer/src/"),
    ("lazysolid_tools", "tools/src/"),
    ("lazysolid_tests", "tests/"),
];

/// Names the docs may use that are defined outside the workspace: the standard library's traits
/// and types, and GLSL's built-in functions and constructors.
const EXTERNAL: &str = "Drop Clone Copy Default Send Sync Arc Box Vec Option Result String \
    HashMap abs min max clamp mix floor ceil fract sqrt dot cross normalize length vec2 vec3 vec4 \
    uvec4 bitCount";

/// How a span quotes a call: not at all, with any arguments, or with this many.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Args {
    /// A name, not a call.
    None,
    /// `name()` or `name(a, ...)`: the function, whatever it takes.
    Any,
    /// `name(a, b)`: exactly these many.
    Exactly(usize),
}

/// A backticked span that names a function, type or constant.
#[derive(Debug, PartialEq)]
struct CodeName {
    /// The span as written.
    span: String,
    /// `::`-separated segments (a receiver before `.` dropped).
    path: Vec<String>,
    /// How it is called.
    args: Args,
    /// Written as `fn name`.
    is_fn: bool,
}

/// Backticked spans outside fenced code blocks.
fn inline_spans(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut kept = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            kept.push_str(line);
        }
        kept.push('\n');
    }
    kept.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A Rust type's spelling: no underscores (`E_x`, `P_l` are mathematics).
fn is_camel_case(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_uppercase())
        && s.chars().any(|c| c.is_ascii_lowercase())
        && !s.contains('_')
}

/// A constant's spelling: upper case with an underscore and two letters at least (`D_0` is
/// mathematics, `GIF` an acronym).
fn is_screaming_case(s: &str) -> bool {
    s.contains('_')
        && s.chars().filter(|c| c.is_ascii_alphabetic()).count() >= 2
        && s.starts_with(|c: char| c.is_ascii_uppercase())
        && s.chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

/// The code name `span` is, when it can only be one (see the rules at the top of this part).
fn code_name(span: &str) -> Option<CodeName> {
    let (is_fn, rest) = match span.strip_prefix("fn ") {
        Some(rest) => (true, rest.trim()),
        None => (false, span),
    };
    let (head, args) = match rest.split_once('(') {
        Some((head, tail)) => {
            let inner = tail.strip_suffix(')')?;
            // The first parenthesis must close last (`d(e, f) + d(f, g)` is a formula), and
            // the arguments must read as code (`clamp(pos·R, 0, R−1)` and `2^k` are mathematics).
            let mut depth = 0i32;
            for ch in inner.chars() {
                depth += match ch {
                    '(' => 1,
                    ')' => -1,
                    _ => 0,
                };
                if depth < 0 || !ch.is_ascii() || ch == '^' {
                    return None;
                }
            }
            let args = if inner.contains("...") || inner.contains('…') || inner.trim().is_empty()
            {
                Args::Any
            } else {
                Args::Exactly(split_top_level(inner).len())
            };
            (head, args)
        }
        None => (rest, Args::None),
    };
    // `scene.frame_time(f)`: a method called on a value; without a call, a dotted span is a
    // file name or a field.
    let (receiver, path) = match head.rsplit_once('.') {
        Some((receiver, path)) if args != Args::None => (Some(receiver), path),
        Some(_) => return None,
        None => (None, head),
    };
    if receiver.is_some_and(|r| !r.split('.').all(is_identifier)) {
        return None;
    }
    let path: Vec<String> = path.split("::").map(str::to_string).collect();
    if !path.iter().all(|s| is_identifier(s)) {
        return None;
    }
    let last = path.last().unwrap();
    let named = args != Args::None
        || is_fn
        || path.len() > 1
        || is_camel_case(last)
        || is_screaming_case(last);
    named.then(|| CodeName {
        span: span.to_string(),
        path,
        args,
        is_fn,
    })
}

/// Splits `s` at its top-level commas (outside (), [], {} and <>), dropping an empty last part
/// (a trailing comma) and an empty list.
fn split_top_level(s: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    let bytes = s.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        match b {
            b'(' | b'[' | b'{' | b'<' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            b'>' if i == 0 || bytes[i - 1] != b'-' => depth -= 1,
            b',' if depth == 0 => {
                parts.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&s[start..]);
    if parts.last().is_some_and(|p| p.trim().is_empty()) {
        parts.pop();
    }
    parts
}

/// What a definition defines.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    /// A Rust or GLSL function (or a function-like GLSL macro), with its parameter count
    /// without `self`.
    Fn(usize),
    /// A struct, enum, trait, type alias or union; a GLSL struct or interface block.
    Type,
    /// An enum variant.
    Variant,
    /// A named field of a Rust struct, a member of a GLSL struct or block.
    Field,
    /// A Rust `const` or `static`, a GLSL `const` or `#define`.
    Const,
    /// A Rust module (`mod name`).
    Module,
    /// A `macro_rules!` macro.
    Macro,
}

/// One definition found in the sources.
#[derive(Debug)]
struct Definition {
    name: String,
    kind: Kind,
    /// The type whose impl, trait, enum or struct body the definition is directly in.
    owner: Option<String>,
    /// Path relative to the workspace root, `/`-separated.
    file: String,
}

/// Every definition of the workspace's sources, and the other names a SCREAMING_CASE span may
/// be (kernel names, environment variables).
#[derive(Default)]
struct Definitions {
    all: Vec<Definition>,
    /// Upper-cased stems of every `*.comp`: the `KernelDef` constants build.rs makes.
    kernels: HashSet<String>,
    /// SCREAMING_CASE string literals of the Rust sources and words of the shell scripts
    /// (environment and script variables).
    env_names: HashSet<String>,
}

/// This test, which the index leaves out.
const THIS_FILE: &str = "tests/tests/docs.rs";

/// Top-level folders whose `*.rs`, `*.glsl`, `*.comp` and `*.sh` files are indexed.
const SOURCE_ROOTS: [&str; 7] = [
    "compute", "synth", "renderer", "tools", "tests", "glsl", "scripts",
];

impl Definitions {
    fn index(root: &Path) -> Definitions {
        let mut files = Vec::new();
        for dir in SOURCE_ROOTS {
            collect_sources(&root.join(dir), &mut files);
        }
        let mut defs = Definitions::default();
        for file in files {
            let rel = file
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            if rel == THIS_FILE {
                // Its strings and test spans are examples of wrong names, not definitions.
                continue;
            }
            let text = std::fs::read_to_string(&file).unwrap();
            if rel.ends_with(".sh") {
                let words = text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'));
                defs.env_names
                    .extend(words.filter(|w| is_screaming_case(w)).map(str::to_string));
            } else if rel.ends_with(".rs") {
                let (tokens, strings) = tokens(&text, Language::Rust);
                defs.env_names
                    .extend(strings.into_iter().filter(|s| is_screaming_case(s)));
                rust_definitions(&tokens, &rel, &mut defs.all);
            } else {
                if let Some(stem) = rel.strip_suffix(".comp") {
                    let stem = stem.rsplit('/').next().unwrap();
                    defs.kernels.insert(stem.to_ascii_uppercase());
                }
                glsl_definitions(&text, &rel, &mut defs.all);
            }
        }
        defs
    }

    /// Definitions named `name` in files starting with `scope` (any file without one).
    fn named<'a>(
        &'a self,
        name: &'a str,
        scope: Option<&'a str>,
    ) -> impl Iterator<Item = &'a Definition> + 'a {
        self.all
            .iter()
            .filter(move |d| d.name == name && scope.is_none_or(|s| d.file.starts_with(s)))
    }

    /// Why `name` does not resolve, or `None` when it does.
    fn check(&self, name: &CodeName) -> Option<String> {
        let mut path = &name.path[..];
        let mut scope = None;
        if path.len() > 1 {
            if let Some((_, dir)) = CRATES.iter().find(|(c, _)| *c == path[0]) {
                scope = Some(*dir);
                path = &path[1..];
            } else if path[0].starts_with("lazysolid") {
                return Some(format!("`{}` is no workspace crate", path[0]));
            } else if matches!(path[0].as_str(), "crate" | "self" | "super") {
                path = &path[1..];
            } else if !is_camel_case(&path[0])
                && self.named(&path[0], None).all(|d| d.kind != Kind::Module)
            {
                // `std::mem::swap`, `obvhs::...`: another crate's.
                return None;
            }
        }
        // Modules first, then at most a type and its member.
        while path.len() > 1 && !is_camel_case(&path[0]) {
            if self.named(&path[0], scope).all(|d| d.kind != Kind::Module) {
                return Some(format!("no module `{}`", path[0]));
            }
            path = &path[1..];
        }
        let arity_ok = |d: &Definition| match (d.kind, name.args) {
            (Kind::Fn(n), Args::Exactly(m)) => n == m,
            (Kind::Fn(_), _) => true,
            // `ColourSource::Fn(&|voxel| rgba)`: a variant built, not a function called.
            (Kind::Variant, _) => true,
            _ => false,
        };
        let arities = |found: Vec<&Definition>| {
            let described: Vec<String> = found
                .iter()
                .filter_map(|d| match d.kind {
                    Kind::Fn(n) => Some(format!("{n} in {}", d.file)),
                    _ => None,
                })
                .collect();
            described.join(", ")
        };
        if path.len() >= 2 {
            let (owner, member) = (&path[0], &path[1]);
            if self.named(owner, scope).all(|d| d.kind != Kind::Type) {
                return Some(format!("no type `{owner}`"));
            }
            let members: Vec<&Definition> = self
                .named(member, None)
                .filter(|d| d.owner.as_deref() == Some(owner.as_str()))
                .collect();
            if members.is_empty() {
                return Some(format!("`{owner}` has no member `{member}`"));
            }
            if (name.args != Args::None || name.is_fn)
                && path.len() == 2
                && !members.iter().any(|d| arity_ok(d))
            {
                return Some(format!(
                    "`{owner}::{member}` takes other parameters than the docs quote ({})",
                    arities(members)
                ));
            }
            return None;
        }
        let item = &path[0];
        if name.path.len() == 1 && EXTERNAL.split_whitespace().any(|e| e == item) {
            return None;
        }
        let found: Vec<&Definition> = self.named(item, scope).collect();
        if name.args != Args::None || name.is_fn {
            if is_camel_case(item) && name.args != Args::None {
                // `Some(x)`-like construction of a tuple struct or variant.
                let is_value = found
                    .iter()
                    .any(|d| matches!(d.kind, Kind::Type | Kind::Variant));
                return (!is_value).then(|| format!("no type or variant `{item}`"));
            }
            if !found.iter().any(|d| matches!(d.kind, Kind::Fn(_))) {
                return Some(format!("no function `{item}`"));
            }
            if !found.iter().any(|d| arity_ok(d)) {
                return Some(format!(
                    "`{item}` takes other parameters than the docs quote ({})",
                    arities(found)
                ));
            }
            return None;
        }
        if name.path.len() > 1 {
            // `lazysolid_compute::atomic_file`, `crate::module::function`, or a kernel of the
            // generated `kernels` module.
            let known = self.kernels.contains(item.as_str())
                || found
                    .iter()
                    .any(|d| !matches!(d.kind, Kind::Variant | Kind::Field));
            return (!known).then(|| format!("no item `{item}`"));
        }
        if is_camel_case(item) {
            let known = found
                .iter()
                .any(|d| matches!(d.kind, Kind::Type | Kind::Variant));
            return (!known).then(|| format!("no type `{item}`"));
        }
        // SCREAMING_CASE.
        let known = self.kernels.contains(item.as_str())
            || self.env_names.contains(item.as_str())
            || found.iter().any(|d| d.kind == Kind::Const);
        (!known).then(|| format!("no constant, kernel or environment variable `{item}`"))
    }
}

fn collect_sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().to_string();
        if name.starts_with('.') || name == "target" {
            continue;
        }
        if path.is_dir() {
            collect_sources(&path, out);
        } else if [".rs", ".glsl", ".comp", ".sh"]
            .iter()
            .any(|e| name.ends_with(e))
        {
            out.push(path);
        }
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Language {
    Rust,
    Glsl,
}

/// The identifiers and punctuation of `text` (`::`, `->` and `=>` as one token), without
/// comments, numbers, character literals, lifetimes and string literals (whose contents are
/// returned apart). A GLSL preprocessor line becomes `#`, its directive, its name, a
/// function-like macro's parameters as one token, and a `\n` token.
fn tokens(text: &str, language: Language) -> (Vec<String>, Vec<String>) {
    let c: Vec<char> = text.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let (mut out, mut strings) = (Vec::new(), Vec::new());
    let mut i = 0;
    let mut line_start = true;
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line_start = true;
            i += 1;
            continue;
        }
        if ch.is_whitespace() {
            i += 1;
            continue;
        }
        let was_line_start = std::mem::replace(&mut line_start, false);
        if ch == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 || language == Language::Glsl {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if ch == '#' && language == Language::Glsl && was_line_start {
            // A preprocessor line, with its continuations.
            out.push("#".to_string());
            i += 1;
            let mut words = String::new();
            while i < c.len() && !(c[i] == '\n' && at(i.wrapping_sub(1)) != '\\') {
                words.push(c[i]);
                i += 1;
            }
            let word_end = |s: &str| {
                s.find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_'))
                    .unwrap_or(s.len())
            };
            let directive = words.trim_start();
            let (directive, rest) = directive.split_at(word_end(directive));
            out.push(directive.to_string());
            let rest = rest.trim_start();
            let (name, rest) = rest.split_at(word_end(rest));
            if !name.is_empty() {
                out.push(name.to_string());
            }
            if rest.starts_with('(') {
                // A function-like macro's parameters, kept as one token.
                out.push(rest[..rest.find(')').map_or(rest.len(), |e| e + 1)].to_string());
            }
            out.push("\n".to_string());
        } else if ch == '"' || (language == Language::Rust && raw_string_start(&c, i).is_some()) {
            let (start, hashes) = if ch == '"' {
                (i + 1, None)
            } else {
                raw_string_start(&c, i).unwrap()
            };
            let mut j = start;
            let mut s = String::new();
            loop {
                if j >= c.len() {
                    break;
                }
                if hashes.is_none() && c[j] == '\\' {
                    j += 2;
                    continue;
                }
                if c[j] == '"' && (0..hashes.unwrap_or(0)).all(|k| at(j + 1 + k) == '#') {
                    j += 1 + hashes.unwrap_or(0);
                    break;
                }
                s.push(c[j]);
                j += 1;
            }
            strings.push(s);
            i = j;
        } else if ch == '\'' && language == Language::Rust {
            if at(i + 1) == '\\' {
                // '\n', '\u{..}': to the closing quote.
                i += 2;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                // A lifetime.
                i += 1;
                while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                    i += 1;
                }
            }
        } else if ch.is_alphabetic() || ch == '_' {
            let start = if ch == 'r' && at(i + 1) == '#' {
                i + 2
            } else {
                i
            };
            let mut j = start;
            while j < c.len() && (c[j].is_alphanumeric() || c[j] == '_') {
                j += 1;
            }
            out.push(c[start..j].iter().collect());
            i = j;
        } else if ch.is_ascii_digit() {
            while i < c.len()
                && (c[i].is_alphanumeric()
                    || c[i] == '_'
                    || (c[i] == '.' && at(i + 1).is_ascii_digit()))
            {
                i += 1;
            }
        } else {
            let pair: String = [ch, at(i + 1)].iter().collect();
            if matches!(pair.as_str(), "::" | "->" | "=>") {
                out.push(pair);
                i += 2;
            } else {
                out.push(ch.to_string());
                i += 1;
            }
        }
    }
    (out, strings)
}

/// Where the contents of a raw or byte string starting at `i` begin, and its `#` count
/// (`None`: escapes apply, as in `b"..."`).
fn raw_string_start(c: &[char], i: usize) -> Option<(usize, Option<usize>)> {
    let at = |k: usize| c.get(k).copied().unwrap_or('\0');
    if i > 0 && (c[i - 1].is_alphanumeric() || c[i - 1] == '_') {
        return None;
    }
    let mut j = i;
    if at(j) == 'b' {
        j += 1;
        if at(j) == '"' {
            return Some((j + 1, None));
        }
    }
    if at(j) != 'r' {
        return None;
    }
    j += 1;
    let mut hashes = 0;
    while at(j) == '#' {
        hashes += 1;
        j += 1;
    }
    (at(j) == '"').then_some((j + 1, Some(hashes)))
}

/// The index of the token closing the bracket opened at `open`.
fn closing(tokens: &[String], open: usize) -> usize {
    let mut depth = 0i32;
    for (k, t) in tokens.iter().enumerate().skip(open) {
        match t.as_str() {
            "(" | "[" | "{" => depth += 1,
            ")" | "]" | "}" => {
                depth -= 1;
                if depth == 0 {
                    return k;
                }
            }
            _ => {}
        }
    }
    tokens.len()
}

/// The index after the `<...>` starting at `open` (`->` is one token, so it does not close).
fn after_angles(tokens: &[String], open: usize) -> usize {
    let mut depth = 0i32;
    for (k, t) in tokens.iter().enumerate().skip(open) {
        match t.as_str() {
            "<" => depth += 1,
            ">" => {
                depth -= 1;
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
    }
    tokens.len()
}

/// The top-level comma-separated groups of the tokens between `open` and its closing bracket,
/// an empty last group (a trailing comma) dropped.
fn groups(tokens: &[String], open: usize) -> Vec<&[String]> {
    let close = closing(tokens, open);
    let inner = &tokens[open + 1..close.min(tokens.len())];
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (k, t) in inner.iter().enumerate() {
        match t.as_str() {
            "(" | "[" | "{" | "<" => depth += 1,
            ")" | "]" | "}" | ">" => depth -= 1,
            "," if depth == 0 => {
                out.push(&inner[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    out.push(&inner[start..]);
    if out.last().is_some_and(|g| g.is_empty()) {
        out.pop();
    }
    out
}

/// The type an `impl` header starting at `i` implements for (the last path segment, generics
/// dropped: `impl<'a> MatterStore for SceneStore<'a>` is `SceneStore`).
fn impl_self_type(tokens: &[String], i: usize) -> Option<String> {
    let mut j = i + 1;
    if tokens.get(j).is_some_and(|t| t == "<") {
        j = after_angles(tokens, j);
    }
    let mut depth = 0i32;
    let mut name = None;
    while let Some(t) = tokens.get(j) {
        match t.as_str() {
            "{" | "where" if depth == 0 => break,
            ";" if depth == 0 => return None,
            "<" | "(" | "[" => depth += 1,
            ">" | ")" | "]" => depth -= 1,
            "for" if depth == 0 && tokens.get(j + 1).is_none_or(|t| t != "<") => name = None,
            "dyn" | "mut" | "const" | "unsafe" => {}
            w if depth == 0 && is_identifier(w) => name = Some(w.to_string()),
            _ => {}
        }
        j += 1;
    }
    name
}

/// Whether the token before `i` leaves `i` at the start of an item.
fn item_position(tokens: &[String], i: usize) -> bool {
    i == 0
        || matches!(
            tokens[i - 1].as_str(),
            "}" | ";" | "{" | "]" | "unsafe" | "default"
        )
}

/// Every definition of a Rust file's tokens.
fn rust_definitions(tokens: &[String], file: &str, out: &mut Vec<Definition>) {
    /// What the innermost open brace belongs to.
    enum Scope {
        /// An impl or trait body: its items are the type's members.
        Owner(String),
        /// Anything else.
        Plain,
    }
    let mut scopes: Vec<Scope> = Vec::new();
    let mut pending: Option<Scope> = None;
    let mut push = |name: &str, kind: Kind, owner: Option<String>| {
        out.push(Definition {
            name: name.to_string(),
            kind,
            owner,
            file: file.to_string(),
        })
    };
    for (i, token) in tokens.iter().enumerate() {
        let owner = match scopes.last() {
            Some(Scope::Owner(o)) => Some(o.clone()),
            _ => None,
        };
        let next = tokens.get(i + 1).map(String::as_str).unwrap_or("");
        let named = is_identifier(next) && next != "_";
        match token.as_str() {
            "{" => scopes.push(pending.take().unwrap_or(Scope::Plain)),
            "}" => {
                scopes.pop();
            }
            ";" => pending = None,
            "impl" if item_position(tokens, i) => {
                pending = impl_self_type(tokens, i).map(Scope::Owner);
            }
            "trait" if named => {
                push(next, Kind::Type, None);
                pending = Some(Scope::Owner(next.to_string()));
            }
            "enum" if named => {
                push(next, Kind::Type, None);
                let Some(open) = tokens[i..].iter().position(|t| t == "{") else {
                    continue;
                };
                for variant in enum_variants(tokens, i + open) {
                    push(variant, Kind::Variant, Some(next.to_string()));
                }
                pending = Some(Scope::Plain);
            }
            "struct" | "union" if named => {
                push(next, Kind::Type, None);
                let body = tokens[i..]
                    .iter()
                    .position(|t| matches!(t.as_str(), "{" | "(" | ";"))
                    .map(|k| i + k);
                if let Some(open) = body.filter(|&k| tokens[k] == "{") {
                    for field in rust_fields(tokens, open) {
                        push(field, Kind::Field, Some(next.to_string()));
                    }
                }
            }
            "type" if named => push(next, Kind::Type, owner),
            // Not `const fn`, nor a `*const T` pointer.
            "const" | "static"
                if named && next != "fn" && next != "mut" && (i == 0 || tokens[i - 1] != "*") =>
            {
                push(next, Kind::Const, owner)
            }
            "static" if next == "mut" => {
                if let Some(name) = tokens.get(i + 2).filter(|t| is_identifier(t)) {
                    push(name, Kind::Const, owner);
                }
            }
            "mod" if named => push(next, Kind::Module, None),
            "macro_rules" if next == "!" => {
                if let Some(name) = tokens.get(i + 2).filter(|t| is_identifier(t)) {
                    push(name, Kind::Macro, None);
                }
            }
            "fn" if named => {
                let mut open = i + 2;
                if tokens.get(open).is_some_and(|t| t == "<") {
                    open = after_angles(tokens, open);
                }
                if tokens.get(open).is_some_and(|t| t == "(") {
                    let params = groups(tokens, open)
                        .into_iter()
                        .filter(|g| !is_self_parameter(g))
                        .count();
                    push(next, Kind::Fn(params), owner);
                }
                pending = Some(Scope::Plain);
            }
            _ => {}
        }
    }
}

/// `self`, `&self`, `&'a mut self`, `mut self`, `self: Box<Self>`.
fn is_self_parameter(group: &[String]) -> bool {
    group
        .iter()
        .find(|t| !matches!(t.as_str(), "&" | "mut"))
        .is_some_and(|t| t == "self")
}

/// The variants of the enum whose body opens at `open`.
fn enum_variants(tokens: &[String], open: usize) -> Vec<&str> {
    body_members(tokens, open, false)
}

/// The named fields of the struct whose body opens at `open`.
fn rust_fields(tokens: &[String], open: usize) -> Vec<&str> {
    body_members(tokens, open, true)
}

/// The first identifier of each comma-separated member of the body opening at `open`
/// (attributes and bracketed groups skipped); with `fields`, only one followed by `:` after
/// its visibility.
fn body_members(tokens: &[String], open: usize, fields: bool) -> Vec<&str> {
    let close = closing(tokens, open);
    let mut variants = Vec::new();
    let mut expecting = true;
    let mut k = open + 1;
    while k < close {
        let t = tokens[k].as_str();
        match t {
            "#" => {
                // An attribute: skip its brackets.
                k = closing(tokens, k + 1) + 1;
                continue;
            }
            "(" | "[" | "{" => {
                k = closing(tokens, k) + 1;
                continue;
            }
            "," => expecting = true,
            "pub" if fields => {}
            w if expecting && is_identifier(w) => {
                if !fields || tokens.get(k + 1).is_some_and(|t| t == ":") {
                    variants.push(w);
                }
                expecting = false;
            }
            _ => {}
        }
        k += 1;
    }
    variants
}

/// Every definition of a GLSL file: functions (with their parameter counts), structs and
/// interface blocks, `const`s and `#define`s.
fn glsl_definitions(text: &str, file: &str, out: &mut Vec<Definition>) {
    let (tokens, _) = tokens(text, Language::Glsl);
    let mut push = |name: &str, kind: Kind, owner: Option<&str>| {
        out.push(Definition {
            name: name.to_string(),
            kind,
            owner: owner.map(str::to_string),
            file: file.to_string(),
        })
    };
    let mut depth = 0i32;
    let mut i = 0;
    while i < tokens.len() {
        let t = tokens[i].as_str();
        let next = tokens.get(i + 1).map(String::as_str).unwrap_or("");
        match t {
            "#" => {
                if next == "define" {
                    if let Some(name) = tokens.get(i + 2).filter(|t| is_identifier(t)) {
                        let kind = match tokens.get(i + 3) {
                            Some(p) if p.starts_with('(') => {
                                let inner = p.trim_start_matches('(').trim_end_matches(')');
                                Kind::Fn(split_top_level(inner).len())
                            }
                            _ => Kind::Const,
                        };
                        push(name, kind, None);
                    }
                }
                while i < tokens.len() && tokens[i] != "\n" {
                    i += 1;
                }
            }
            "{" => depth += 1,
            "}" => depth -= 1,
            "struct" | "buffer" | "uniform" if depth == 0 && is_identifier(next) => {
                push(next, Kind::Type, None);
                if tokens.get(i + 2).is_some_and(|t| t == "{") {
                    let close = closing(&tokens, i + 2);
                    for (k, member) in tokens.iter().enumerate().take(close).skip(i + 3) {
                        let after = tokens.get(k + 1).map(String::as_str);
                        if is_identifier(member) && matches!(after, Some(";" | "[" | ",")) {
                            push(member, Kind::Field, Some(next));
                        }
                    }
                }
            }
            "const" if depth == 0 && is_identifier(next) => {
                if let Some(name) = tokens.get(i + 2).filter(|t| is_identifier(t)) {
                    push(name, Kind::Const, None);
                }
            }
            // `type name(...) {`: a definition (a prototype ends with `;`).
            w if depth == 0
                && is_identifier(w)
                && is_identifier(next)
                && tokens.get(i + 2).is_some_and(|t| t == "(") =>
            {
                let close = closing(&tokens, i + 2);
                if tokens.get(close + 1).is_some_and(|t| t == "{") {
                    let params = groups(&tokens, i + 2);
                    let void = params.len() == 1 && params[0].len() == 1 && params[0][0] == "void";
                    push(next, Kind::Fn(if void { 0 } else { params.len() }), None);
                }
            }
            _ => {}
        }
        i += 1;
    }
}

/// Every code name in `docs/architecture.md` resolves to a definition with the quoted
/// parameters: a rename, a move between types or a new parameter that leaves the walk behind
/// fails here.
#[test]
fn every_function_and_type_the_architecture_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let root = root.canonicalize().unwrap();
    let text = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let names: Vec<CodeName> = inline_spans(&text)
        .iter()
        .filter_map(|s| code_name(s))
        .collect();
    assert!(names.len() >= 40, "only {} code names found", names.len());
    let defs = Definitions::index(&root);
    let wrong: Vec<String> = names
        .iter()
        .filter_map(|n| defs.check(n).map(|why| format!("`{}`: {why}", n.span)))
        .collect();
    assert!(
        wrong.is_empty(),
        "docs/architecture.md names code that is not there:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_name_finder_picks_code_names_only() {
    let text = "`Baker::bake`, `store_albedo(slot, pos, normal, gradient)`, `GpuLazySolid`, \
                `fn foo`, `scene.frame_time(f)`, `params()`, `f(a, ...)`, `NO_STORE`, \
                `lazysolid_compute::atomic_file`\n\
                not `renderer/src/bake/mod.rs`, `cargo test`, `--frames`, `[[fracture]]`, \
                `kind = \"synthesized\"`, `store`, `NAME_NNNN.png`, `GIF`, `a.b`, \
                `crate::kernels::<folder>::<NAME>`, `d(e, f) + d(f, g)`, `clamp(pos·R, 0, R−1)`, \
                `E_x`, `D_0`\n```toml\n`Fenced`\n```\n";
    let names: Vec<(Vec<String>, Args)> = inline_spans(text)
        .iter()
        .filter_map(|s| code_name(s))
        .map(|n| (n.path, n.args))
        .collect();
    let p = |s: &str| s.split("::").map(str::to_string).collect::<Vec<_>>();
    assert_eq!(
        names,
        [
            (p("Baker::bake"), Args::None),
            (p("store_albedo"), Args::Exactly(4)),
            (p("GpuLazySolid"), Args::None),
            (p("foo"), Args::None),
            (p("frame_time"), Args::Exactly(1)),
            (p("params"), Args::Any),
            (p("f"), Args::Any),
            (p("NO_STORE"), Args::None),
            (p("lazysolid_compute::atomic_file"), Args::None),
        ]
    );
}

/// The check fails on what it is for: unknown names, members of the wrong type and calls with
/// the wrong number of arguments; and it passes the forms the docs use.
#[test]
fn the_name_check_rejects_wrong_names_and_arities() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap();
    let defs = Definitions::index(&root);
    let check = |span: &str| defs.check(&code_name(span).unwrap());
    for good in [
        "Baker::bake",
        "SparseStore::params",
        "ColourSource::Buffer",
        "store_albedo(slot, pos, normal, gradient)",
        "fn store_albedo",
        "lazysolid_compute::atomic_file",
        "lazysolid_synth::solid::lazy::GpuLazySolid",
        "StoreRecords",
        "GpuInstance::uv_offset",
        "TraceHit::instance",
        "NO_STORE",
        "PATH_TRACE",
        "LAZYSOLID_VALIDATION",
        "Drop",
    ] {
        assert_eq!(check(good), None, "{good}");
    }
    for bad in [
        "NoSuchType",
        "Baker::no_such_method",
        "SceneBvh::bake",
        "GpuInstance::uv_offsets",
        "store_albedo(slot, pos, normal)",
        "SceneBvh::set_transforms(a, b)",
        "fn no_such_function",
        "lazysolid_compute::no_such_module::Gpu",
        "lazysolid_computer::Gpu",
        "NO_SUCH_CONSTANT",
    ] {
        assert!(check(bad).is_some(), "{bad} passed");
    }
}
