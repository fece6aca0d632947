//! Strings a user wrote, shown back to them: cut to a readable length, so that a 50 MB key in a scene file makes a
//! one-line error message and a 50 MB title a figure caption that renders at once.

/// Longest echo of a user's string in an error message, in characters.
pub const MESSAGE_CHARS: usize = 100;

/// Longest title a figure shows, in characters.
pub const TITLE_CHARS: usize = 120;

/// `text` itself if it has at most `max_chars` characters; otherwise its first `max_chars` characters, an ellipsis
/// and the full length, e.g. `aaaa… (50000000 characters)`, so the reader knows that it was cut and by how much.
pub fn cut(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_string(),
        Some((end, _)) => format!("{}… ({} characters)", &text[..end], text.chars().count()),
    }
}

/// `message` with every span between backticks (the way messages quote a user's key or value) cut to
/// [`MESSAGE_CHARS`]: for messages composed by a library that echoes what it was given.
pub fn cut_quoted(message: &str) -> String {
    message
        .split('`')
        .enumerate()
        .map(|(i, part)| if i % 2 == 1 { cut(part, MESSAGE_CHARS) } else { part.to_string() })
        .collect::<Vec<_>>()
        .join("`")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_text_is_kept_whole() {
        assert_eq!(cut("contact.law", 11), "contact.law");
        assert_eq!(cut("", 3), "");
    }

    #[test]
    fn long_text_is_cut_at_a_character_boundary_with_its_length() {
        // Three two-byte characters, cut after two: a cut by bytes would split the second.
        assert_eq!(cut("ééé", 2), "éé… (3 characters)");
        assert_eq!(cut(&"a".repeat(1000), 4), "aaaa… (1000 characters)");
    }

    #[test]
    fn only_quoted_spans_are_cut() {
        let key = "k".repeat(MESSAGE_CHARS + 1);
        let message = format!("unknown field `{key}`, expected `title` or `bodies`");
        let expected = format!(
            "unknown field `{}… ({} characters)`, expected `title` or `bodies`",
            "k".repeat(MESSAGE_CHARS),
            MESSAGE_CHARS + 1
        );
        assert_eq!(cut_quoted(&message), expected);
    }
}
