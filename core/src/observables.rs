//! What an interface reports at its committed state, as typed data: the driver's summary,
//! events and separation test read these fields, and `history.csv` gets them as columns.

/// The name of the point field that holds a point law's own gap where it differs from the gap
/// at the mesh (a footprint correction puts the footprint's compliance and indentation between
/// them): the asperity's own deformation is read from it.
pub const LAW_GAP_FIELD: &str = "footprint_law_gap";

/// Interface quantities at the committed state (forces positive compressive).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InterfaceObservables {
    /// Approach of a rigid flat toward the body (None for interfaces without a flat).
    pub approach: Option<f64>,
    /// Resultant normal force on the interface.
    pub force: f64,
    /// Real contact area.
    pub contact_area: f64,
    /// Points in contact.
    pub n_contact: usize,
    /// Energy dissipated so far by a viscous regularisation (None where there is none).
    pub viscous_dissipation: Option<f64>,
    /// Electrical contact resistance in ohm (None where it is not modelled; infinite with no
    /// contact).
    pub contact_resistance: Option<f64>,
}

/// One `history.csv` value: integers are written as integers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    Real(f64),
    Count(usize),
}

impl InterfaceObservables {
    /// Column names and values for `history.csv`, in a fixed order, present fields only.
    pub fn columns(&self) -> Vec<(&'static str, Value)> {
        let mut out = Vec::with_capacity(6);
        if let Some(a) = self.approach {
            out.push(("approach", Value::Real(a)));
        }
        out.push(("force", Value::Real(self.force)));
        out.push(("contact_area", Value::Real(self.contact_area)));
        out.push(("n_contact", Value::Count(self.n_contact)));
        if let Some(v) = self.viscous_dissipation {
            out.push(("viscous_dissipation", Value::Real(v)));
        }
        if let Some(r) = self.contact_resistance {
            out.push(("contact_resistance", Value::Real(r)));
        }
        out
    }
}
