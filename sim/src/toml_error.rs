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
///
/// An error the parser places on a whole table (a table read through an
/// intermediate value, as `[object]` is) but whose message names one of
/// its keys (`` `width`: … ``, ``unknown field `widht` ``) is placed on
/// that key's assignment within the table.
pub fn position(text: &str, e: &toml::de::Error) -> (usize, usize) {
    match e.span() {
        Some(span) => {
            let start = char_floor(text, span.start);
            let end = table_end(text, start, char_floor(text, span.end).max(start));
            let at = named_key(e.message())
                .and_then(|key| assignment_of(&text[start..end], key))
                .map_or(start, |offset| start + offset);
            let before = &text[..at];
            let line = before.matches('\n').count() + 1;
            let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            (line, column)
        }
        None => (1, 1),
    }
}

/// The largest char boundary of `text` at or below `i`.
fn char_floor(text: &str, i: usize) -> usize {
    let mut i = i.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Where the table whose span is `start..end` ends: for a `[header]` span,
/// the next header's line (or the text's end), for an inline table `end`.
fn table_end(text: &str, start: usize, end: usize) -> usize {
    if !text[start..].starts_with('[') {
        return end;
    }
    let mut at = end;
    for line in text[end..].split_inclusive('\n') {
        if at > end && line.trim_start().starts_with('[') {
            break;
        }
        at += line.len();
    }
    at
}

/// The key a deserialiser's message names: `` `key`: … `` or
/// ``unknown field `key`, … ``.
fn named_key(message: &str) -> Option<&str> {
    let rest = message
        .strip_prefix("unknown field `")
        .or_else(|| message.strip_prefix('`'))?;
    let (key, _) = rest.split_once('`')?;
    (!key.is_empty()).then_some(key)
}

/// Byte offset in `table` of the first assignment to the bare `key`
/// (`key = …`, at a line's start or after `{` or `,` of an inline table).
fn assignment_of(table: &str, key: &str) -> Option<usize> {
    table.match_indices(key).map(|(i, _)| i).find(|&i| {
        let before = table[..i].trim_end_matches([' ', '\t']);
        let opens = before.is_empty() || before.ends_with(['\n', '{', ',']);
        opens
            && table[i + key.len()..]
                .trim_start_matches([' ', '\t'])
                .starts_with('=')
    })
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
/// characters, after the key assigned on the error's line when there is
/// one and the parser's message does not already name it.
pub fn message(text: &str, e: &toml::de::Error) -> String {
    let parser = e.message().split_whitespace().collect::<Vec<_>>().join(" ");
    let one_line = match key_at(text, e) {
        Some(key) if named_key(&parser) != Some(key.as_str()) => format!("`{key}`: {parser}"),
        _ => parser,
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
    fn an_error_in_a_table_read_whole_is_placed_on_its_key() {
        // `[object]` is read through a table (object/table.rs), so the
        // parser's span is the whole table.
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct File {
            name: String,
            object: crate::ObjectShape,
        }
        let head = "name = \"x\"\n\n[object]\nkind = \"half-potato\"\nlength = 0.09\n";
        let cases = [
            (
                format!("{head}widht = 0.06\n"),
                "6:1: unknown field `widht`, expected",
            ),
            (
                format!("{head}  width = \"w\"\n"),
                "6:3: `width`: invalid type: string",
            ),
            (
                "name = \"x\"\nobject = { kind = \"half-potato\", width = true }\n".to_string(),
                "2:34: `object`: `width`: invalid type: boolean",
            ),
            // `length` as a key's value is not its assignment.
            (
                "name = \"length\"\n[object]\nkind = \"cuboid\"\nlength = \"l\"\n".to_string(),
                "4:1: `length`: invalid type",
            ),
            // A missing key stays on the table.
            (
                format!("{head}width = 0.06\n"),
                "3:1: missing field `height`",
            ),
        ];
        for (text, expected) in cases {
            let e = toml::from_str::<File>(&text).unwrap_err();
            let line = one_line(&text, &e);
            assert!(line.starts_with(expected), "{text:?}: {line}");
        }
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
