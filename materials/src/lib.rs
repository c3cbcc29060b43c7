//! Stiction materials: isotropic linear elasticity and small-strain J2 (von Mises) plasticity
//! with linear isotropic and linear kinematic hardening (radial return, consistent tangent).

pub mod error;
pub mod j2_plasticity;
pub mod linear_elastic;

pub use error::MaterialsError;
pub use j2_plasticity::J2Plasticity;
pub use linear_elastic::LinearElastic;
