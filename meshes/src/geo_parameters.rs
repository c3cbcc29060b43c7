//! The parameters a `.geo` file declares, read from its `DefineConstant[...]` blocks, so a case
//! can be checked before gmsh runs: gmsh silently ignores `-setnumber` for an undeclared name,
//! and does not enforce the ONELAB `Min`/`Max` attributes on the command line.
//!
//! Understood forms: `DefineConstant[ a = 1.0, b = {2.0, Min 0.5, Max 10, Name "..."} ];`.
//! Comments (`//` and `/* */`) are skipped.

/// One declared parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct GeoParameter {
    pub name: String,
    /// 1-based line of the declaration in the `.geo`.
    pub line: usize,
    /// Bounds given by `Min`/`Max` (inclusive), when they are plain numbers.
    pub min: Option<f64>,
    pub max: Option<f64>,
}

impl GeoParameter {
    /// Whether `value` is finite and inside the declared bounds.
    pub fn admits(&self, value: f64) -> bool {
        value.is_finite() && self.min.is_none_or(|m| value >= m) && self.max.is_none_or(|m| value <= m)
    }

    /// The declared range as text, e.g. "[0.5, 10]" or "[0.5, inf)".
    pub fn range_text(&self) -> String {
        let lo = self.min.map_or("(-inf".to_string(), |m| format!("[{m}"));
        let hi = self.max.map_or("inf)".to_string(), |m| format!("{m}]"));
        format!("{lo}, {hi}")
    }
}

/// The text with comments replaced by spaces (newlines kept, so line numbers stay right).
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut in_string = false;
    while let Some(c) = chars.next() {
        if in_string {
            in_string = c != '"';
            out.push(c);
        } else if c == '"' {
            in_string = true;
            out.push(c);
        } else if c == '/' && chars.peek() == Some(&'/') {
            while chars.peek().is_some_and(|&n| n != '\n') {
                chars.next();
            }
        } else if c == '/' && chars.peek() == Some(&'*') {
            chars.next();
            let mut previous = ' ';
            for n in chars.by_ref() {
                if n == '\n' {
                    out.push('\n');
                }
                if previous == '*' && n == '/' {
                    break;
                }
                previous = n;
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// Splits `text` at commas outside brackets, braces, parentheses and strings; each piece
/// with its byte offset in `text`.
fn split_top_level(text: &str) -> Vec<(usize, &str)> {
    let (mut depth, mut in_string, mut start) = (0i32, false, 0);
    let mut pieces = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '[' | '{' | '(' if !in_string => depth += 1,
            ']' | '}' | ')' if !in_string => depth -= 1,
            ',' if !in_string && depth == 0 => {
                pieces.push((start, &text[start..i]));
                start = i + 1;
            }
            _ => {}
        }
    }
    pieces.push((start, &text[start..]));
    pieces
}

/// The byte index of the bracket closing the one just before `from`, or None.
fn closing_bracket(text: &str, from: usize) -> Option<usize> {
    let mut depth = 1;
    for (i, c) in text[from..].char_indices() {
        match c {
            '[' => depth += 1,
            ']' => {
                depth -= 1;
                if depth == 0 {
                    return Some(from + i);
                }
            }
            _ => {}
        }
    }
    None
}

/// `Min`/`Max` of an ONELAB attribute list `{value, Min a, Max b, ...}` (inner text).
fn bounds(attributes: &str) -> (Option<f64>, Option<f64>) {
    let (mut min, mut max) = (None, None);
    for (_, piece) in split_top_level(attributes).into_iter().skip(1) {
        let mut words = piece.split_whitespace();
        match (words.next(), words.next().and_then(|v| v.parse::<f64>().ok())) {
            (Some("Min"), Some(v)) => min = Some(v),
            (Some("Max"), Some(v)) => max = Some(v),
            _ => {}
        }
    }
    (min, max)
}

/// Every parameter the `.geo` text declares with `DefineConstant`, in order.
pub fn declared_parameters(text: &str) -> Vec<GeoParameter> {
    let text = without_comments(text);
    let mut found = Vec::new();
    let mut search = 0;
    while let Some(at) = text[search..].find("DefineConstant") {
        let keyword_end = search + at + "DefineConstant".len();
        search = keyword_end;
        let Some(open) =
            text[keyword_end..].find('[').filter(|&o| text[keyword_end..keyword_end + o].trim().is_empty())
        else {
            continue;
        };
        let body_start = keyword_end + open + 1;
        let Some(body_end) = closing_bracket(&text, body_start) else { break };
        for (offset, entry) in split_top_level(&text[body_start..body_end]) {
            let Some((name, value)) = entry.split_once('=') else { continue };
            let name = name.trim();
            if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let value = value.trim();
            let (min, max) = match value.strip_prefix('{').and_then(|v| v.strip_suffix('}')) {
                Some(attributes) => bounds(attributes),
                None => (None, None),
            };
            let name_at = body_start + offset + entry.find(name).unwrap_or(0);
            let line = 1 + text[..name_at].matches('\n').count();
            found.push(GeoParameter { name: name.to_string(), line, min, max });
        }
        search = body_end;
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_plain_and_bounded_declarations_with_their_lines() {
        let text = "// R = 5 in a comment\nDefineConstant[ R = 1000.0, /* h = 2 */\n  h = {12.0, Min 0.5, Max 1e3, Name \"a, b\"},\n  n = {3, Min 1} ];\nx = R;\n";
        let p = declared_parameters(text);
        let names: Vec<&str> = p.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["R", "h", "n"]);
        assert_eq!(p.iter().map(|p| p.line).collect::<Vec<_>>(), [2, 3, 4]);
        assert_eq!((p[0].min, p[0].max), (None, None));
        assert_eq!((p[1].min, p[1].max), (Some(0.5), Some(1e3)));
        assert_eq!((p[2].min, p[2].max), (Some(1.0), None));
        assert!(p[1].admits(0.5) && p[1].admits(1e3) && !p[1].admits(0.0) && !p[1].admits(f64::NAN));
        assert!(!p[0].admits(f64::INFINITY) && p[0].admits(-3.0));
        assert_eq!(p[1].range_text(), "[0.5, 1000]");
        assert_eq!(p[2].range_text(), "[1, inf)");
    }

    #[test]
    fn a_file_without_declarations_declares_nothing() {
        assert!(declared_parameters("Point(1) = {0, 0, 0};").is_empty());
        assert!(declared_parameters("").is_empty());
        assert!(declared_parameters("DefineConstant[ a = 1").is_empty());
    }
}
