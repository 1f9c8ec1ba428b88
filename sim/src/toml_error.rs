//! A TOML parse error as one line that never quotes the file.
//!
//! The `toml` crate's own message shows the offending line of the source;
//! for a file that is not TOML at all (a path mistyped into
//! `surrogate = "…"`) that would print a line of an unrelated file. The line
//! here is `LINE:COLUMN: message`, with the parser's message cut to
//! [`MAX_MESSAGE_CHARS`] characters.

/// Longest parser message kept, in characters.
pub const MAX_MESSAGE_CHARS: usize = 160;

/// 1-based line and column of the error in `text` ((1, 1) if unknown).
pub fn position(text: &str, e: &toml::de::Error) -> (usize, usize) {
    match e.span() {
        Some(span) => {
            let mut start = span.start.min(text.len());
            while !text.is_char_boundary(start) {
                start -= 1;
            }
            let before = &text[..start];
            let line = before.matches('\n').count() + 1;
            let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            (line, column)
        }
        None => (1, 1),
    }
}

/// The bare key assigned on the error's line (`key = …`), if that line
/// is an assignment to a bare key of at most 64 characters: the one part of
/// the text an error may repeat, since it names what to fix.
fn key_at(text: &str, e: &toml::de::Error) -> Option<String> {
    // A missing field's span is the table that lacks it, whose first line
    // assigns some other key.
    if e.message().starts_with("missing field") {
        return None;
    }
    let (line, _) = position(text, e);
    let source = text.lines().nth(line - 1)?;
    let (key, _) = source.split_once('=')?;
    let key = key.trim();
    let bare = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.');
    (!key.is_empty() && key.len() <= 64 && key.chars().all(bare)).then(|| key.to_string())
}

/// The parser's message on one line, at most [`MAX_MESSAGE_CHARS`]
/// characters, after the key assigned on the error's line when there is one.
pub fn message(text: &str, e: &toml::de::Error) -> String {
    let parser = e.message().split_whitespace().collect::<Vec<_>>().join(" ");
    let one_line = match key_at(text, e) {
        Some(key) => format!("`{key}`: {parser}"),
        None => parser,
    };
    if one_line.chars().count() > MAX_MESSAGE_CHARS {
        let cut: String = one_line.chars().take(MAX_MESSAGE_CHARS).collect();
        format!("{cut}…")
    } else {
        one_line
    }
}

/// `LINE:COLUMN: message`.
pub fn one_line(text: &str, e: &toml::de::Error) -> String {
    let (line, column) = position(text, e);
    format!("{line}:{column}: {}", message(text, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_table_is_not_blamed_on_the_first_key() {
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct File {
            name: String,
            knife: toml::Table,
        }
        let text = "name = \"x\"\n";
        let e = toml::from_str::<File>(text).unwrap_err();
        let m = message(text, &e);
        assert!(m.starts_with("missing field `knife`"), "{m}");
    }

    #[test]
    fn a_non_toml_file_is_described_not_quoted() {
        let text = "root:x:0:0:root:/root:/bin/bash\n";
        let e = toml::from_str::<toml::Table>(text).unwrap_err();
        let line = one_line(text, &e);
        assert!(line.starts_with("1:"), "{line}");
        assert!(
            !line.contains("/bin/bash") && !line.contains('\n'),
            "{line}"
        );
    }
}
