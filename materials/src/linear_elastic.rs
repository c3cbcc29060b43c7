//! Isotropic linear elasticity: sigma = C epsilon, C = lambda 1 x 1 + 2 mu I.

use crate::error::MaterialsError;
use stiction_core::material::{Material, MaterialError};
use stiction_core::voigt::{Strain, Stress, Tangent, isotropic_elasticity};

#[derive(Debug, Clone)]
pub struct LinearElastic {
    name: String,
    youngs_modulus: f64,
    c: Tangent,
}

/// Checks E > 0 and -1 < nu < 0.5.
pub(crate) fn check_elastic(name: &str, e: f64, nu: f64) -> Result<(), MaterialsError> {
    if !(e > 0.0 && e.is_finite()) {
        return Err(MaterialsError::Parameter {
            material: name.into(),
            key: "youngs_modulus",
            value: e,
            expected: "a positive number",
        });
    }
    if !(nu > -1.0 && nu < 0.5) {
        return Err(MaterialsError::Parameter {
            material: name.into(),
            key: "poissons_ratio",
            value: nu,
            expected: "a number in (-1, 0.5)",
        });
    }
    Ok(())
}

impl LinearElastic {
    pub fn new(name: impl Into<String>, youngs_modulus: f64, poissons_ratio: f64) -> Result<Self, MaterialsError> {
        let name = name.into();
        check_elastic(&name, youngs_modulus, poissons_ratio)?;
        Ok(Self { name, youngs_modulus, c: isotropic_elasticity(youngs_modulus, poissons_ratio) })
    }
}

impl Material for LinearElastic {
    fn name(&self) -> &str {
        &self.name
    }
    fn update(
        &self,
        strain: &Strain,
        _committed: &[f64],
        _trial: &mut [f64],
        stress: &mut Stress,
        tangent: &mut Tangent,
    ) -> Result<(), MaterialError> {
        for i in 0..6 {
            stress[i] = (0..6).map(|j| self.c[i][j] * strain[j]).sum();
        }
        *tangent = self.c;
        Ok(())
    }
    fn stiffness_scale(&self) -> f64 {
        self.youngs_modulus
    }
}
