//! The case-file reference, generated from the case's own schema: the serde structs of
//! [`super`] with their doc comments, defaults, units (`x-unit`), allowed ranges (JSON Schema's
//! `minimum`, `exclusiveMinimum`, `maximum`, `exclusiveMaximum`) and the problems a key applies
//! to (`x-applies`), read through `schemars`. `stiction reference case-keys` prints it,
//! `docs/reference/case-keys.md` holds it, and a test keeps the two equal; `stiction run --help`
//! lists the defaults from the same walk.
//!
//! What it does not know: what a key's value means to the solver (that is the key's doc
//! comment, printed as it is), and the checks between keys (`validate.rs`).

use serde_json::{Map, Value};

/// One key of a table.
#[derive(Debug, Clone)]
pub struct KeyDoc {
    /// The key's name in its table.
    pub name: String,
    /// What a value looks like: "number", "integer", `"a" | "b"`, "array of numbers", ...
    pub kind: String,
    /// The default as written in a case file; None: required, or absent means what the doc says.
    pub default: Option<String>,
    pub required: bool,
    /// The dimension in the case's units ("length", "force", "stress", ...), or a fixed unit.
    pub unit: Option<String>,
    /// The allowed values, e.g. "> 0", "(0, 1)".
    pub range: Option<String>,
    /// Which problems read it ("rigid-flat interfaces", "j2-plasticity", ...); None: all.
    pub applies: Option<String>,
    pub meaning: String,
}

/// One table of the case file: `[solver]`, `[[interfaces]]`, `[interfaces.points]`, ...
#[derive(Debug, Clone)]
pub struct TableDoc {
    /// The table's header as written in a case file ("" for the top level).
    pub header: String,
    /// How `--set` addresses its keys, e.g. "interfaces.N.points." (N the entry's index).
    pub set_prefix: String,
    pub description: String,
    pub keys: Vec<KeyDoc>,
}

/// Every table of the case file, in the order a case file is usually written.
pub fn tables() -> Vec<TableDoc> {
    tables_of(schemars::schema_for!(super::Case))
}

/// Every table of a TOML file whose schema is `schema` (the case file's, the fit file's).
pub fn tables_of(schema: schemars::Schema) -> Vec<TableDoc> {
    let root = schema.as_value().clone();
    let defs = root.get("$defs").and_then(Value::as_object).cloned().unwrap_or_default();
    let mut out = Vec::new();
    let walker = Walker { defs: &defs };
    walker.table(&root, String::new(), String::new(), &mut out);
    out
}

struct Walker<'a> {
    defs: &'a Map<String, Value>,
}

/// A property's schema with `Option`'s null taken out and a `$ref` followed (an absent
/// optional key means what its doc says).
struct Resolved {
    schema: Value,
}

impl Walker<'_> {
    fn deref(&self, s: &Value) -> Value {
        match s.get("$ref").and_then(Value::as_str) {
            Some(r) => {
                let name = r.trim_start_matches("#/$defs/");
                let mut target = self.defs.get(name).cloned().unwrap_or(Value::Null);
                // the property's own description, default and extensions win over the type's
                if let (Some(t), Some(own)) = (target.as_object_mut(), s.as_object()) {
                    for (k, v) in own {
                        if k != "$ref" {
                            t.insert(k.clone(), v.clone());
                        }
                    }
                }
                target
            }
            None => s.clone(),
        }
    }

    fn resolve(&self, s: &Value) -> Resolved {
        let mut s = s.clone();
        if let Some(any) = s.get("anyOf").and_then(Value::as_array).cloned() {
            let kept: Vec<Value> = any.into_iter().filter(|v| v.get("type") != Some(&Value::from("null"))).collect();
            if kept.len() == 1 {
                let mut inner = self.deref(&kept[0]);
                if let (Some(t), Some(own)) = (inner.as_object_mut(), s.as_object()) {
                    for (k, v) in own {
                        if k != "anyOf" {
                            t.insert(k.clone(), v.clone());
                        }
                    }
                }
                s = inner;
            }
        }
        let mut s = self.deref(&s);
        if let Some(types) = s.get("type").and_then(Value::as_array).cloned() {
            let kept: Vec<Value> = types.into_iter().filter(|t| t != "null").collect();
            if kept.len() == 1 {
                s["type"] = kept[0].clone();
            }
        }
        Resolved { schema: s }
    }

    /// A table's keys, then its sub-tables.
    fn table(&self, s: &Value, header: String, set_prefix: String, out: &mut Vec<TableDoc>) {
        let required: Vec<&str> = s
            .get("required")
            .and_then(Value::as_array)
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        let mut doc =
            TableDoc { header: header.clone(), set_prefix: set_prefix.clone(), description: text(s), keys: vec![] };
        let mut subtables = Vec::new();
        let Some(props) = s.get("properties").and_then(Value::as_object) else { return };
        for (name, p) in props {
            let r = self.resolve(p);
            let dotted = if header.is_empty() { name.clone() } else { format!("{}.{name}", bare(&header)) };
            if is_table(&r.schema) {
                subtables.push((format!("[{dotted}]"), format!("{set_prefix}{name}."), r.schema));
                continue;
            }
            if let Some(item) = r.schema.get("items").map(|i| self.resolve(i)).filter(|i| is_table(&i.schema)) {
                subtables.push((format!("[[{dotted}]]"), format!("{set_prefix}{name}.N."), item.schema));
                continue;
            }
            if let Some(item) =
                r.schema.get("additionalProperties").map(|i| self.resolve(i)).filter(|i| is_table(&i.schema))
            {
                subtables.push((format!("[{dotted}.<name>]"), format!("{set_prefix}{name}.<name>."), item.schema));
                continue;
            }
            doc.keys.push(self.key(name, p, &r, required.contains(&name.as_str())));
        }
        if !doc.keys.is_empty() || !doc.description.is_empty() {
            out.push(doc);
        }
        for (h, prefix, sub) in subtables {
            self.table(&sub, h, prefix, out);
        }
    }

    fn key(&self, name: &str, raw: &Value, r: &Resolved, required: bool) -> KeyDoc {
        let s = &r.schema;
        let get = |k: &str| raw.get(k).or_else(|| s.get(k));
        KeyDoc {
            name: name.to_string(),
            kind: self.kind(s),
            default: get("default").map(toml_text),
            required,
            unit: get("x-unit").and_then(Value::as_str).map(str::to_string),
            range: range(raw).or_else(|| range(s)),
            applies: get("x-applies").and_then(Value::as_str).map(str::to_string),
            meaning: text(raw),
        }
    }

    fn kind(&self, s: &Value) -> String {
        if let Some(values) = s.get("enum").and_then(Value::as_array) {
            return values
                .iter()
                .map(|v| format!("\"{}\"", v.as_str().unwrap_or_default()))
                .collect::<Vec<_>>()
                .join(" \\| ");
        }
        if let Some(any) = s.get("anyOf").and_then(Value::as_array) {
            return any.iter().map(|a| self.kind(&self.resolve(a).schema)).collect::<Vec<_>>().join(" or ");
        }
        match s.get("type").and_then(Value::as_str) {
            Some("array") => {
                let item = s.get("items").map(|i| self.kind(&self.resolve(i).schema)).unwrap_or_else(|| "value".into());
                match s.get("minItems").and_then(Value::as_u64) {
                    Some(n) if s.get("maxItems").and_then(Value::as_u64) == Some(n) => format!("[{item}; {n}]"),
                    _ => format!("array of {item}"),
                }
            }
            Some("object") => {
                let item = s
                    .get("additionalProperties")
                    .map(|i| self.kind(&self.resolve(i).schema))
                    .unwrap_or_else(|| "value".into());
                format!("table of {item}")
            }
            Some(t) => t.to_string(),
            None => "any value".to_string(),
        }
    }
}

fn is_table(s: &Value) -> bool {
    s.get("properties").is_some()
}

/// "[[interfaces]]" -> "interfaces", "[materials.<name>]" -> "materials.<name>".
fn bare(header: &str) -> &str {
    header.trim_start_matches('[').trim_end_matches(']')
}

/// A doc comment as one paragraph.
fn text(s: &Value) -> String {
    let d = s.get("description").and_then(Value::as_str).unwrap_or_default();
    d.split('\n').map(str::trim).collect::<Vec<_>>().join(" ")
}

/// A number as a person writes it: 25, 0.25, 1e-8.
pub fn number(x: f64) -> String {
    if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e6) { format!("{x:e}") } else { format!("{x}") }
}

fn toml_text(v: &Value) -> String {
    match v {
        Value::String(s) => format!("\"{s}\""),
        Value::Number(n) => n.as_f64().map(number).unwrap_or_else(|| n.to_string()),
        Value::Array(a) => format!("[{}]", a.iter().map(toml_text).collect::<Vec<_>>().join(", ")),
        Value::Object(o) if o.is_empty() => "{}".to_string(),
        other => other.to_string(),
    }
}

/// The allowed range from JSON Schema's bounds.
fn range(s: &Value) -> Option<String> {
    let num = |k: &str| s.get(k).and_then(Value::as_f64);
    let low = num("exclusiveMinimum").map(|v| (v, false)).or_else(|| num("minimum").map(|v| (v, true)));
    let high = num("exclusiveMaximum").map(|v| (v, false)).or_else(|| num("maximum").map(|v| (v, true)));
    match (low, high) {
        (Some((a, ai)), Some((b, bi))) => {
            Some(format!("{}{}, {}{}", if ai { "[" } else { "(" }, number(a), number(b), if bi { "]" } else { ")" }))
        }
        (Some((a, true)), None) => Some(format!(">= {}", number(a))),
        (Some((a, false)), None) => Some(format!("> {}", number(a))),
        (None, Some((b, true))) => Some(format!("<= {}", number(b))),
        (None, Some((b, false))) => Some(format!("< {}", number(b))),
        (None, None) => None,
    }
}

/// The reference as Markdown (`docs/reference/case-keys.md`).
pub fn case_keys_markdown() -> String {
    let mut md = String::from(
        "# Case-file reference\n\n\
         <!-- generated by `stiction reference case-keys`; do not edit by hand -->\n\n\
         Every key a case file (TOML) takes, generated from the program's own schema. Unknown keys \
         are refused with their path. Units: a case's numbers are in the user's units, one \
         consistent set (the Ru cases: nm, nN, GPa = nN/nm^2, J/m^2 = nN/nm); \"length\", \
         \"force\", \"stress\" (force per area), \"energy per area\" (force per length) name \
         the dimension; \"pseudo-time\" is the load parameter t of the steps and amplitudes. \
         `--set KEY=VALUE` changes one key from the command line; in arrays of tables the entry's \
         index takes the place of N (`--set interfaces.0.parameters.w=3`).\n\n\
         Two keys are read before the rest: `base = \"other.toml\"` (this case extends another: its \
         keys are merged over the base's, tables key by key, other values replaced) and \
         `set = [\"key=value\", ...]` (single keys changed after the merge, as `--set` does).\n\n",
    );
    md.push_str(&tables_markdown(&tables(), true));
    md
}

/// The tables as Markdown: an index, then a section per table with its keys (and how `--set`
/// addresses them, where `with_set`).
pub fn tables_markdown(tables: &[TableDoc], with_set: bool) -> String {
    let mut md = String::from("Tables: ");
    let names: Vec<String> = tables
        .iter()
        .map(|t| {
            let h = if t.header.is_empty() { "top level".to_string() } else { t.header.clone() };
            format!("[`{h}`](#{})", anchor(&h))
        })
        .collect();
    md.push_str(&names.join(", "));
    md.push_str("\n\n");
    for t in tables {
        let h = if t.header.is_empty() { "top level".to_string() } else { t.header.clone() };
        md.push_str(&format!("## `{h}`\n\n"));
        if !t.description.is_empty() {
            md.push_str(&format!("{}\n\n", t.description));
        }
        if with_set && !t.set_prefix.is_empty() {
            md.push_str(&format!("`--set {}KEY=VALUE`\n\n", t.set_prefix));
        }
        md.push_str(
            "| key | value | default | unit | allowed | applies to | meaning |\n|---|---|---|---|---|---|---|\n",
        );
        for k in &t.keys {
            let default = match (&k.default, k.required) {
                (Some(d), _) => format!("`{d}`"),
                (None, true) => "required".to_string(),
                (None, false) => "none".to_string(),
            };
            md.push_str(&format!(
                "| `{}` | {} | {} | {} | {} | {} | {} |\n",
                k.name,
                k.kind,
                default,
                k.unit.as_deref().unwrap_or("-"),
                k.range.as_deref().unwrap_or("-"),
                k.applies.as_deref().unwrap_or("all"),
                k.meaning.replace('|', "\\|"),
            ));
        }
        md.push('\n');
    }
    md
}

/// GitHub's heading anchor of a header such as "[[interfaces]]".
fn anchor(h: &str) -> String {
    h.chars()
        .filter_map(|c| match c {
            'a'..='z' | '0'..='9' | '_' | '-' => Some(c),
            'A'..='Z' => Some(c.to_ascii_lowercase()),
            ' ' => Some('-'),
            _ => None,
        })
        .collect()
}

/// The defaults of every key that has one, a line each, for `stiction run --help`.
pub fn defaults_list() -> String {
    let mut lines = vec!["Defaults of the case keys (docs/reference/case-keys.md has every key):".to_string()];
    for t in tables() {
        for k in &t.keys {
            if let Some(d) = &k.default {
                lines.push(format!("  {}{} = {d}", t.set_prefix, k.name));
            }
        }
    }
    lines.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::{Path, PathBuf};

    fn root() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
    }

    #[test]
    fn the_checked_in_reference_is_the_generated_one() {
        let path = root().join("docs/reference/case-keys.md");
        let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            checked_in == case_keys_markdown(),
            "{} is not what the program generates: run `cargo run --release -- reference case-keys > \
             docs/reference/case-keys.md`",
            path.display()
        );
    }

    #[test]
    fn every_table_and_key_is_documented() {
        let mut missing = Vec::new();
        for t in tables() {
            for k in &t.keys {
                if k.meaning.is_empty() {
                    missing.push(format!("{}{}", t.set_prefix, k.name));
                }
            }
            if t.description.is_empty() {
                missing.push(format!("table {}", t.header));
            }
        }
        assert!(missing.is_empty(), "keys and tables without a doc comment: {missing:?}");
    }

    /// An MD file (`stiction md`: a `[lattice]` table), run by tests/md.rs, not a case.
    fn is_md_file(path: &Path) -> bool {
        let text = std::fs::read_to_string(path).unwrap();
        toml::from_str::<toml::Table>(&text).is_ok_and(|t| t.contains_key("lattice"))
    }

    /// Every shipped case file, merged over its base.
    fn shipped_cases() -> Vec<(PathBuf, toml::Value)> {
        fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
            for e in std::fs::read_dir(dir).unwrap().flatten() {
                let p = e.path();
                if p.is_dir() && p.file_name().is_some_and(|n| n == "fit") {
                    // fit files (`stiction fit`), checked by crate::fit::spec's tests
                    continue;
                } else if p.is_dir() {
                    walk(&p, out);
                } else if p.extension().is_some_and(|x| x == "toml")
                    && !p.to_string_lossy().contains("calibrations")
                    && !is_md_file(&p)
                {
                    out.push(p);
                }
            }
        }
        let mut files = Vec::new();
        walk(&root().join("cases"), &mut files);
        files.sort();
        files
            .into_iter()
            .map(|p| (p.clone(), super::super::load(&p, &[]).expect("a shipped case loads").value))
            .collect()
    }

    /// The `--set` path of a key in `case` (N -> 0, <name> -> the table's first entry), if the
    /// case has the key's table.
    fn set_path(case: &toml::Value, prefix: &str) -> Option<String> {
        let mut at = case;
        let mut path = Vec::new();
        for part in prefix.trim_end_matches('.').split('.').filter(|p| !p.is_empty()) {
            let (next, name) = match part {
                "N" => (at.as_array()?.first()?, "0".to_string()),
                "<name>" => {
                    let (k, v) = at.as_table()?.iter().next()?;
                    (v, k.clone())
                }
                key => (at.get(key)?, key.to_string()),
            };
            at = next;
            path.push(name);
        }
        Some(path.iter().map(|p| format!("{p}.")).collect())
    }

    /// A value just below a key's declared range.
    fn below(kind: &str, range: &str) -> String {
        let bound = |s: &str| s.trim().trim_matches(|c| "[]()".contains(c)).parse::<f64>().unwrap();
        let below = if let Some(v) = range.strip_prefix(">= ") {
            bound(v) - 1.0
        } else if let Some(v) = range.strip_prefix("> ") {
            bound(v)
        } else {
            let (low, _) = range.split_once(',').unwrap();
            if low.starts_with('[') { bound(low) - 1.0 } else { bound(low) }
        };
        if kind == "integer" { format!("{}", below as i64) } else { format!("{below:?}") }
    }

    fn high_of(range: &str) -> Option<f64> {
        let (_, high) = range.split_once(',')?;
        high.trim().trim_end_matches([']', ')']).parse().ok()
    }

    #[test]
    fn every_declared_range_is_refused_outside_it_with_the_key_named() {
        let cases = shipped_cases();
        let mut problems = Vec::new();
        let mut checked = 0;
        for t in tables() {
            for k in t.keys.iter().filter(|k| k.range.is_some()) {
                let range = k.range.as_deref().unwrap();
                // the integer types' own minimum (>= 0) cannot be crossed by a case file
                if range == ">= 0" && k.kind == "integer" {
                    continue;
                }
                let Some((file, prefix)) = cases.iter().find_map(|(f, v)| set_path(v, &t.set_prefix).map(|p| (f, p)))
                else {
                    problems.push(format!("{}{}: no shipped case has its table", t.set_prefix, k.name));
                    continue;
                };
                let mut values = vec![below(&k.kind, range)];
                if let Some(high) = high_of(range) {
                    let closed = range.ends_with(']');
                    values.push(if closed { format!("{:?}", high + 1.0) } else { format!("{high:?}") });
                }
                for value in values {
                    checked += 1;
                    let set = format!("{prefix}{}={value}", k.name);
                    let result = super::super::load(file, std::slice::from_ref(&set))
                        .and_then(|c| crate::build::sections::materials(&c).map(|_| ()));
                    match result {
                        Ok(()) => problems.push(format!("{} --set {set}: accepted (declared {range})", file.display())),
                        Err(e) if !e.to_string().contains(&k.name) => problems
                            .push(format!("{} --set {set}: the error does not name the key: {e}", file.display())),
                        Err(_) => {}
                    }
                }
            }
        }
        assert!(problems.is_empty(), "{}", problems.join("\n"));
        assert!(checked > 30, "only {checked} values checked");
    }
}
