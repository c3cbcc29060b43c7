//! Parameter errors of the materials crate; each names the parameter key.

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MaterialsError {
    #[error("material '{material}': parameter '{key}' = {value} is invalid: {expected}")]
    Parameter { material: String, key: &'static str, value: f64, expected: &'static str },
}
