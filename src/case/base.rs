//! `base = "other.toml"`: a case that extends another. The base file's tree is read (itself
//! possibly extending a third, up to [`MAX_DEPTH`] levels) and this file's keys are merged over
//! it: tables merge key by key, any other value (numbers, strings, arrays such as `steps`)
//! replaces the base's. Relative paths in the merged case (the mesh, calibrations) are relative
//! to the extending file's folder, so a base is normally a case in the same folder.
//!
//! `set = ["interfaces.0.parameters.w=3.0", ...]` in the extending file changes single keys of
//! the merged tree, exactly as `--set` does on the command line (and before it): the way to
//! change one entry of an array of tables such as `[[interfaces]]`, which merging replaces.

use crate::error::{Result, StictionError};
use std::path::Path;

/// Bases followed at most (a guard against a cycle of files extending each other).
const MAX_DEPTH: usize = 8;

/// A case file's text, and its merged tree when it names a base (None: use the text as it is,
/// so parse errors keep their line numbers).
pub fn read(path: &Path) -> Result<(String, Option<toml::Value>)> {
    let text = read_text(path)?;
    let value: toml::Value = parse(path, &text)?;
    if value.get("base").is_none() && value.get("set").is_none() {
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
    let sets = value.as_table_mut().and_then(|t| t.remove("set"));
    let Some(base) = value.as_table_mut().and_then(|t| t.remove("base")) else {
        apply_sets(path, &mut value, sets)?;
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
    apply_sets(path, &mut merged, sets)?;
    Ok(merged)
}

/// Applies the file's `set` list (strings `key=value`, as `--set`) to its merged tree.
fn apply_sets(path: &Path, tree: &mut toml::Value, sets: Option<toml::Value>) -> Result<()> {
    let Some(sets) = sets else { return Ok(()) };
    let bad = |key: String, message: String| StictionError::CaseKey { path: path.to_path_buf(), key, message };
    let Some(list) = sets.as_array() else {
        return Err(bad("set".into(), format!("must be a list of \"key=value\" strings, got {sets}")));
    };
    for (i, item) in list.iter().enumerate() {
        let Some(assignment) = item.as_str() else {
            return Err(bad(format!("set[{i}]"), format!("must be a \"key=value\" string, got {item}")));
        };
        super::overrides::apply(tree, assignment)
            .map_err(|m| bad(format!("set[{i}]"), format!("{assignment}: {m}")))?;
    }
    Ok(())
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
    fn set_changes_single_keys_of_the_merged_tree_and_names_a_bad_entry() {
        let dir = folder("set");
        std::fs::write(dir.join("a.toml"), "[[items]]\nw = 1.0\nz = 2.0\n[[items]]\nw = 5.0\n").unwrap();
        std::fs::write(dir.join("b.toml"), "base = \"a.toml\"\nset = [\"items.0.w=3.0\"]\n").unwrap();
        let m = read(&dir.join("b.toml")).unwrap().1.unwrap();
        assert_eq!(m["items"][0]["w"].as_float(), Some(3.0));
        assert_eq!(m["items"][0]["z"].as_float(), Some(2.0), "the rest of the entry is kept");
        assert_eq!(m["items"][1]["w"].as_float(), Some(5.0));
        assert!(m.get("set").is_none());
        std::fs::write(dir.join("c.toml"), "base = \"a.toml\"\nset = [\"items.7.w=3.0\"]\n").unwrap();
        let e = read(&dir.join("c.toml")).unwrap_err().to_string();
        assert!(e.contains("set[0]") && e.contains("items.7.w"), "{e}");
        std::fs::write(dir.join("d.toml"), "set = \"items.0.w=3.0\"\n[[items]]\nw = 1.0\n").unwrap();
        assert!(read(&dir.join("d.toml")).unwrap_err().to_string().contains("list"));
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
