//! `base = "other.toml"`: a case that extends another. The base file's tree is read (itself
//! possibly extending a third, up to [`MAX_DEPTH`] levels) and this file's keys are merged over
//! it: tables merge key by key, any other value (numbers, strings, arrays such as `steps`)
//! replaces the base's. Relative paths in the merged case (the mesh, calibrations) are relative
//! to the extending file's folder, so a base is normally a case in the same folder.

use crate::error::{Result, StictionError};
use std::path::Path;

/// Bases followed at most (a guard against a cycle of files extending each other).
const MAX_DEPTH: usize = 8;

/// A case file's text, and its merged tree when it names a base (None: use the text as it is,
/// so parse errors keep their line numbers).
pub fn read(path: &Path) -> Result<(String, Option<toml::Value>)> {
    let text = read_text(path)?;
    let value: toml::Value = parse(path, &text)?;
    if value.get("base").is_none() {
        return Ok((text, None));
    }
    let merged = resolve(path, value, 0)?;
    Ok((text, Some(merged)))
}

fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path)
        .map_err(|e| StictionError::Case { path: path.to_path_buf(), message: format!("cannot read it: {e}") })
}

fn parse(path: &Path, text: &str) -> Result<toml::Value> {
    toml::from_str(text).map_err(|e| StictionError::Case { path: path.to_path_buf(), message: e.to_string() })
}

/// The tree of `path` (already parsed as `value`) with its base chain merged underneath.
fn resolve(path: &Path, mut value: toml::Value, depth: usize) -> Result<toml::Value> {
    let bad = |message: String| StictionError::CaseKey { path: path.to_path_buf(), key: "base".into(), message };
    let Some(base) = value.as_table_mut().and_then(|t| t.remove("base")) else {
        return Ok(value);
    };
    let Some(file) = base.as_str() else {
        return Err(bad(format!("must be the path of a case file (a string), got {base}")));
    };
    if depth >= MAX_DEPTH {
        return Err(bad(format!("more than {MAX_DEPTH} levels of base files (do they extend each other?)")));
    }
    let base_path = path.parent().unwrap_or(Path::new(".")).join(file);
    if !base_path.is_file() {
        return Err(bad(format!("'{}' is not a file", base_path.display())));
    }
    let base_value = parse(&base_path, &read_text(&base_path)?)?;
    let mut merged = resolve(&base_path, base_value, depth + 1)?;
    // the case is named by the extending file (its `name`, else its file stem), not the base
    let own_name = value.get("name").is_some();
    merge(&mut merged, value);
    if !own_name && let Some(t) = merged.as_table_mut() {
        t.remove("name");
    }
    Ok(merged)
}

/// Merges `over` into `under`: tables key by key, anything else replaced.
fn merge(under: &mut toml::Value, over: toml::Value) {
    match (under, over) {
        (toml::Value::Table(u), toml::Value::Table(o)) => {
            for (k, v) in o {
                match u.get_mut(&k) {
                    Some(existing) => merge(existing, v),
                    None => {
                        u.insert(k, v);
                    }
                }
            }
        }
        (u, o) => *u = o,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("stiction-base-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn tables_merge_values_replace_and_the_name_is_the_extending_files() {
        let dir = folder("merge");
        std::fs::write(dir.join("a.toml"), "name = \"a\"\nx = 1\n[t]\np = 1\nq = [1, 2]\n").unwrap();
        std::fs::write(dir.join("b.toml"), "base = \"a.toml\"\n[t]\nq = [3]\nr = 2\n").unwrap();
        let (_, merged) = read(&dir.join("b.toml")).unwrap();
        let m = merged.unwrap();
        assert_eq!(m["x"].as_integer(), Some(1));
        assert_eq!(m["t"]["p"].as_integer(), Some(1));
        assert_eq!(m["t"]["q"].as_array().unwrap().len(), 1, "arrays replace");
        assert_eq!(m["t"]["r"].as_integer(), Some(2));
        assert!(m.get("name").is_none() && m.get("base").is_none());
        let (_, none) = read(&dir.join("a.toml")).unwrap();
        assert!(none.is_none(), "no base: the text is parsed as it is");
    }

    #[test]
    fn a_cycle_or_a_missing_base_is_an_error_naming_the_key() {
        let dir = folder("cycle");
        std::fs::write(dir.join("a.toml"), "base = \"b.toml\"\n").unwrap();
        std::fs::write(dir.join("b.toml"), "base = \"a.toml\"\n").unwrap();
        let e = read(&dir.join("a.toml")).unwrap_err().to_string();
        assert!(e.contains("'base'") && e.contains("levels"), "{e}");
        std::fs::write(dir.join("c.toml"), "base = \"nowhere.toml\"\n").unwrap();
        let e = read(&dir.join("c.toml")).unwrap_err().to_string();
        assert!(e.contains("nowhere.toml") && e.contains("not a file"), "{e}");
        std::fs::write(dir.join("d.toml"), "base = 3\n").unwrap();
        assert!(read(&dir.join("d.toml")).unwrap_err().to_string().contains("must be the path"));
    }
}
