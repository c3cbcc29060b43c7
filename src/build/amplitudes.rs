//! The case's named amplitudes; "ramp" (0 -> 1 over t in [0, 1]) always exists.

use crate::case::LoadedCase;
use crate::error::Result;
use std::collections::BTreeMap;
use std::sync::Arc;
use stiction_core::amplitude::Amplitude;

pub struct Amplitudes(BTreeMap<String, Arc<Amplitude>>);

impl Amplitudes {
    pub fn new(case: &LoadedCase) -> Result<Self> {
        let mut map: BTreeMap<String, Arc<Amplitude>> = BTreeMap::new();
        map.insert("ramp".into(), Arc::new(Amplitude::ramp()));
        for (name, a) in &case.case.amplitudes {
            let amp = Amplitude::new(a.time.clone(), a.value.clone())
                .map_err(|e| case.error(format!("amplitudes.{name}"), e.to_string()))?;
            map.insert(name.clone(), Arc::new(amp));
        }
        Ok(Self(map))
    }

    /// The ramp (for constraints that hold a value of zero).
    pub fn ramp(&self) -> Arc<Amplitude> {
        self.0["ramp"].clone()
    }

    /// The amplitude `name` (default "ramp") that case key `key` refers to.
    pub fn get(&self, case: &LoadedCase, key: String, name: &Option<String>) -> Result<Arc<Amplitude>> {
        let n = name.as_deref().unwrap_or("ramp");
        self.0.get(n).cloned().ok_or_else(|| {
            case.error(
                key,
                format!("no amplitude '{n}' (defined: {})", self.0.keys().cloned().collect::<Vec<_>>().join(", ")),
            )
        })
    }
}
