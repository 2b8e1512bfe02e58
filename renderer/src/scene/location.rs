//! Where a problem is: byte spans of the TOML text turned into 1-based lines, and toml's
//! deserialization errors (which carry a span but no usable key path) turned into the field
//! path that the loader's own checks also use (`material "glass".ior`, `camera.position[2]`).

use super::SceneError;
use std::ops::Range;
use std::path::Path;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// The scene file being loaded: its name for messages and its text for line numbers.
#[derive(Clone, Copy)]
pub(super) struct Doc<'a> {
    /// The scene file as given by the caller.
    pub file: &'a Path,
    /// Its content.
    pub text: &'a str,
}

impl Doc<'_> {
    /// 1-based line of a byte offset (clamped to the text).
    pub fn line(&self, offset: usize) -> usize {
        let end = offset.min(self.text.len());
        1 + self.text.as_bytes()[..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    }

    /// A content error at a span.
    pub fn invalid(
        &self,
        span: Range<usize>,
        field: impl Into<String>,
        problem: impl Into<String>,
    ) -> SceneError {
        SceneError::Invalid {
            file: self.file.to_path_buf(),
            line: self.line(span.start),
            field: field.into(),
            problem: problem.into(),
        }
    }

    /// Parses the text into `T`, turning TOML syntax and serde errors into [`SceneError`]s
    /// with line and field path.
    pub fn deserialize<T: serde::de::DeserializeOwned>(&self) -> Result<T, SceneError> {
        let table = DeTable::parse(self.text).map_err(|e| {
            let span = e.span().unwrap_or(0..0);
            let mut problem = e.message().trim_end().to_string();
            // Quote what the parser stopped at ("duplicate key `camera`") when it is short.
            let at = self.text.get(span.clone()).unwrap_or("").trim();
            if !at.is_empty() && at.len() <= 40 && !at.contains('\n') {
                problem = format!("{problem} (at `{at}`)");
            }
            SceneError::Syntax {
                file: self.file.to_path_buf(),
                line: self.line(span.start),
                problem,
            }
        })?;
        toml::from_str(self.text).map_err(|e| {
            // The document itself has an empty span: its errors (a missing table) are about
            // the whole scene.
            let span = e.span().filter(|s| !s.is_empty()).unwrap_or(0..0);
            let field = if span.is_empty() {
                None
            } else {
                field_at(table.get_ref(), span.start, "")
            };
            let field = field.unwrap_or_else(|| "scene".into());
            self.invalid(span, field, e.message().trim_end())
        })
    }
}

/// Label of the `index`-th (0-based) `[[section]]` table: by its name where it has one
/// (`material "glass"`), by its 1-based position otherwise (`instance #2`).
pub(super) fn element_label(section: &str, index: usize, name: Option<&str>) -> String {
    match name {
        Some(name) => format!("{section} {name:?}"),
        None => format!("{section} #{}", index + 1),
    }
}

/// `prefix.key`, or `key` at the top level.
pub(super) fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

fn contains(span: &Range<usize>, offset: usize) -> bool {
    span.contains(&offset) || (span.is_empty() && span.start == offset)
}

/// The deepest field of `table` whose key or value covers `offset`.
fn field_at(table: &DeTable<'_>, offset: usize, prefix: &str) -> Option<String> {
    table.iter().find_map(|(key, value)| {
        let path = join(prefix, key.get_ref());
        let deeper = match value.get_ref() {
            DeValue::Table(t) => field_at(t, offset, &path),
            DeValue::Array(a) => a
                .iter()
                .enumerate()
                .find_map(|(i, elem)| element_at(key.get_ref(), prefix, &path, i, elem, offset)),
            _ => None,
        };
        deeper.or_else(|| {
            (contains(&key.span(), offset) || contains(&value.span(), offset)).then_some(path)
        })
    })
}

/// The deepest field inside the `i`-th element of the array `path`.
fn element_at(
    key: &str,
    prefix: &str,
    path: &str,
    i: usize,
    elem: &Spanned<DeValue<'_>>,
    offset: usize,
) -> Option<String> {
    let label = match elem.get_ref() {
        DeValue::Table(t) => {
            let name = t.get("name").and_then(|n| n.get_ref().as_str());
            join(prefix, &element_label(key, i, name))
        }
        _ => format!("{path}[{i}]"),
    };
    let deeper = match elem.get_ref() {
        DeValue::Table(t) => field_at(t, offset, &label),
        DeValue::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(j, e)| element_at(key, prefix, &label, j, e, offset)),
        _ => None,
    };
    deeper.or_else(|| contains(&elem.span(), offset).then_some(label))
}
