//! `stiction run --resume`: which checkpoint a case goes on from, and whether the case still
//! describes the checkpointed problem.
//!
//! A run checkpoints to [`CHECKPOINT_FILE`] in its output folder (`output.checkpoint_minutes`).
//! The checkpoint carries the case's fingerprint: the case as read (merged over its base, with
//! the `--set` overrides) without what may change between the parts of a run, the solver
//! settings (`[solver]`), the increment sizes and output spacing of the steps, and where and how
//! often output is written (`output.directory`, `output.checkpoint_minutes`). Everything else
//! (mesh, materials, interfaces, boundary conditions, amplitudes, the steps' times) must be the
//! same, or the run is refused with the first key that differs. The files a case names (a mesh,
//! a layout of points) are not read into the fingerprint: the model's sizes are checked against
//! the checkpoint when it is taken up, not their every number.

use crate::case::LoadedCase;
use crate::error::{Result, StictionError};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The checkpoint file of a run, in its output folder.
pub const CHECKPOINT_FILE: &str = "restart.bin";

/// Keys of a step that may change when a run is resumed.
const STEP_SOLVER_KEYS: [&str; 4] = ["initial_increment", "min_increment", "max_increment", "output_every"];

/// The fingerprint of `case`'s problem (see the module documentation), as JSON text.
pub fn fingerprint(case: &LoadedCase) -> String {
    let mut value = serde_json::to_value(&case.value).expect("a TOML value converts to JSON");
    if let Some(table) = value.as_object_mut() {
        table.remove("solver");
        if let Some(output) = table.get_mut("output").and_then(Value::as_object_mut) {
            output.remove("directory");
            output.remove("checkpoint_minutes");
        }
        for step in table.get_mut("steps").and_then(Value::as_array_mut).into_iter().flatten() {
            if let Some(step) = step.as_object_mut() {
                STEP_SOLVER_KEYS.iter().for_each(|k| drop(step.remove(*k)));
            }
        }
    }
    value.to_string()
}

/// The checkpoint a resumed run of `case` goes on from, in its output folder `out`; Err when
/// there is none to go on from, with what to do instead.
pub fn checkpoint_path(case: &LoadedCase, out: &Path) -> Result<PathBuf> {
    let path = out.join(CHECKPOINT_FILE);
    if path.exists() {
        return Ok(path);
    }
    let summary =
        std::fs::read_to_string(out.join("summary.json")).ok().and_then(|t| serde_json::from_str::<Value>(&t).ok());
    let status = summary.as_ref().and_then(|s| s["status"].as_str().map(str::to_string));
    let increments = summary.as_ref().and_then(|s| s["increments"].as_u64()).unwrap_or(0);
    let why = match status.as_deref() {
        Some("completed") => {
            "the run there completed (a completed run removes its checkpoint): there is nothing to resume".to_string()
        }
        Some("running") => "the run there was stopped before its first checkpoint (its summary.json still says \
             \"running\": it was killed); start it afresh with --overwrite, and set output.checkpoint_minutes \
             lower to checkpoint sooner"
            .to_string(),
        Some(other) if increments == 0 => format!(
            "the run there ended \"{other}\" before its first increment was committed; start it afresh with --overwrite"
        ),
        Some(other) => format!(
            "the run there ended \"{other}\" after {increments} increments but its checkpoint is gone (a \
             failed run keeps it: was it removed?); start it afresh with --overwrite"
        ),
        None => "no run of this case has written there; give the folder of the run to resume with --out".to_string(),
    };
    Err(StictionError::Output {
        path: out.to_path_buf(),
        message: format!("has no checkpoint ({CHECKPOINT_FILE}) to resume case '{}' from: {why}", case.name),
    })
}

/// Ok when `now` (the fingerprint of the case given) is that of the checkpointed run
/// (`saved`); Err names the first key where they differ and both values.
pub fn check_same_problem(case: &LoadedCase, checkpoint: &Path, saved: &str, now: &str) -> Result<()> {
    let parse = |text: &str| serde_json::from_str::<Value>(text).unwrap_or(Value::Null);
    let Some((key, was, is)) = first_difference(&parse(saved), &parse(now), String::new()) else {
        return Ok(());
    };
    Err(case.error(
        if key.is_empty() { "(the case)".to_string() } else { key },
        format!(
            "differs from the checkpointed run's ({was} there, {is} now) in '{}': a run resumes only the \
             problem it checkpointed (its [solver] settings, step increments and output spacing may change)",
            checkpoint.display()
        ),
    ))
}

/// The first key (dotted, array entries by index) where `a` and `b` differ, with both values
/// ("absent" where a key is missing).
fn first_difference(a: &Value, b: &Value, key: String) -> Option<(String, String, String)> {
    let join = |k: &str| if key.is_empty() { k.to_string() } else { format!("{key}.{k}") };
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort();
            keys.dedup();
            keys.into_iter().find_map(|k| match (x.get(k), y.get(k)) {
                (Some(p), Some(q)) => first_difference(p, q, join(k)),
                (p, q) => Some((join(k), shown(p), shown(q))),
            })
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            x.iter().zip(y).enumerate().find_map(|(i, (p, q))| first_difference(p, q, join(&i.to_string())))
        }
        _ if a == b => None,
        _ => Some((key, a.to_string(), b.to_string())),
    }
}

fn shown(value: Option<&Value>) -> String {
    value.map_or_else(|| "absent".to_string(), Value::to_string)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_difference_is_named_by_its_dotted_key() {
        let a: Value = serde_json::json!({"materials": {"ru": {"E": 400.0, "nu": 0.3}}, "steps": [{"end_time": 1.0}]});
        let b: Value = serde_json::json!({"steps": [{"end_time": 1.0}], "materials": {"ru": {"nu": 0.3, "E": 410.0}}});
        assert_eq!(first_difference(&a, &a, String::new()), None);
        assert_eq!(
            first_difference(&a, &b, String::new()),
            Some(("materials.ru.E".into(), "400.0".into(), "410.0".into()))
        );
        let c: Value = serde_json::json!({"materials": {"ru": {"E": 400.0, "nu": 0.3}}, "steps": [{"end_time": 2.0}]});
        assert_eq!(
            first_difference(&a, &c, String::new()),
            Some(("steps.0.end_time".into(), "1.0".into(), "2.0".into()))
        );
        let d: Value = serde_json::json!({"materials": {"ru": {"E": 400.0}}, "steps": [{"end_time": 1.0}]});
        assert_eq!(
            first_difference(&a, &d, String::new()),
            Some(("materials.ru.nu".into(), "0.3".into(), "absent".into()))
        );
    }
}
