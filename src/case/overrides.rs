//! `--set a.b.c=value` overrides on the parsed TOML tree. Path segments that are numbers index
//! arrays (`steps.0.end_time=2`); the value is parsed as TOML (`1e-3`, `true`, `[0, 1]`,
//! `"text"`), and taken as a string if it does not parse.

/// Applies one `path=value` override to the document `root` (a table).
pub fn apply(root: &mut toml::Value, assignment: &str) -> Result<(), String> {
    let (path, raw) = assignment.split_once('=').ok_or("expected KEY=VALUE")?;
    let path = path.trim();
    if path.is_empty() || path.split('.').any(str::is_empty) {
        return Err(format!("'{path}' is not a valid key path"));
    }
    let value: toml::Value = match toml::from_str::<toml::Table>(&format!("v = {raw}")) {
        Ok(mut t) => t.remove("v").expect("parsed key"),
        Err(_) => toml::Value::String(raw.to_string()),
    };
    let segments: Vec<&str> = path.split('.').collect();
    let (last, parents) = segments.split_last().expect("non-empty path");
    let mut node = root;
    for (i, seg) in parents.iter().enumerate() {
        let here = segments[..=i].join(".");
        node = match node {
            toml::Value::Table(t) => t.entry(seg.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new())),
            toml::Value::Array(a) => {
                let len = a.len();
                let idx: usize = seg.parse().map_err(|_| format!("'{here}': '{seg}' must be an array index"))?;
                a.get_mut(idx).ok_or_else(|| format!("'{here}': index {idx} is past the end (length {len})"))?
            }
            _ => {
                return Err(format!("'{}' is not a table or array", segments[..i].join(".")));
            }
        };
    }
    match node {
        toml::Value::Table(t) => {
            t.insert(last.to_string(), value);
        }
        toml::Value::Array(a) => {
            let len = a.len();
            let idx: usize = last.parse().map_err(|_| format!("'{path}': '{last}' must be an array index"))?;
            if idx == len {
                // one past the end appends, e.g. --set interfaces.1={ ... } adds an interface
                a.push(value);
            } else {
                *a.get_mut(idx)
                    .ok_or_else(|| format!("'{path}': index {idx} is past the end (length {len}; {len} appends)"))? =
                    value;
            }
        }
        _ => return Err(format!("'{}' is not a table or array", parents.join("."))),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn sets_nested_keys_and_array_entries() {
        let mut v: toml::Value = toml::from_str("[a]\nb = 1\n[[s]]\nt = 1.0\n").unwrap();
        apply(&mut v, "a.b=2.5").unwrap();
        apply(&mut v, "s.0.t=3").unwrap();
        apply(&mut v, "c.d=\"x\"").unwrap();
        apply(&mut v, "name=plain text").unwrap();
        assert_eq!(v["a"]["b"].as_float(), Some(2.5));
        assert_eq!(v["s"][0]["t"].as_integer(), Some(3));
        assert_eq!(v["c"]["d"].as_str(), Some("x"));
        assert_eq!(v["name"].as_str(), Some("plain text"));
        apply(&mut v, "s.1={ t = 4.0 }").unwrap();
        assert_eq!(v["s"][1]["t"].as_float(), Some(4.0), "one past the end appends");
        assert!(apply(&mut v, "s.3={ t = 4.0 }").unwrap_err().contains("past the end"));
        assert!(apply(&mut v, "s.4.t=1").unwrap_err().contains("past the end"));
        assert!(apply(&mut v, "nothing").is_err());
    }
}
