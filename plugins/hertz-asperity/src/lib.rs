//! `hertz-asperity` (the law; `plugin/` exports it as a shared library): an elastic sphere of
//! radius R pressed by a rigid flat, the asperity of the Greenwood-Williamson model. With the
//! overlap d = -gap (gap: the distance from the asperity's tip to the flat, positive when
//! open), Hertz's solution gives
//!
//!   F = 4/3 E* R^(1/2) d^(3/2),   a^2 = R d (contact radius), area = pi R d,
//!
//! for d > 0 and nothing for d <= 0. E* is the contact modulus, 1/E* = (1 - nu1^2)/E1 +
//! (1 - nu2^2)/E2. Value (positive pushes apart) = F; tangent d value / d gap =
//! -2 E* R^(1/2) d^(1/2), continuous at first touch.
//!
//! Each point has its own radius: the law keeps R as its one state variable, `radius`, set at
//! the start from the parameter `radius` and carried unchanged. A layout that knows each
//! point's radius (the summits of a height map, `points.surface`) writes it there; a law that
//! declares a state named `radius` is how the host knows it takes one.

use stiction_law_sdk::{Law, LawKind, Parameter, Response};

#[derive(Debug, Clone)]
pub struct HertzAsperity {
    modulus: f64,
    radius: f64,
}

impl HertzAsperity {
    /// Force, d force / d overlap and contact area at overlap `d` for radius `r`.
    pub fn hertz(&self, r: f64, d: f64) -> (f64, f64, f64) {
        if d <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let root = (r * d).sqrt();
        (4.0 / 3.0 * self.modulus * root * d, 2.0 * self.modulus * root, std::f64::consts::PI * r * d)
    }
}

impl Law for HertzAsperity {
    const NAME: &'static std::ffi::CStr = c"hertz-asperity";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::ForcePerPoint;
    const N_STATE: usize = 1;

    fn parameters() -> Vec<Parameter> {
        vec![
            Parameter::required(c"modulus", c"stress", c"contact modulus E* of asperity and flat", 0.0, f64::INFINITY),
            Parameter::required(
                c"radius",
                c"length",
                c"asperity radius (points whose layout gives one keep their own)",
                0.0,
                f64::INFINITY,
            ),
        ]
    }

    fn create(p: &[f64], _config: &str) -> Result<Self, String> {
        if p[0] <= 0.0 || p[1] <= 0.0 {
            return Err(format!("modulus and radius must be positive, got {} and {}", p[0], p[1]));
        }
        Ok(Self { modulus: p[0], radius: p[1] })
    }

    fn initialize_state(&self, state: &mut [f64]) {
        state[0] = self.radius;
    }

    fn evaluate(&self, gap: f64, old: &[f64], new: &mut [f64]) -> Result<Response, String> {
        let r = old[0];
        if !(r > 0.0 && r.is_finite()) {
            return Err(format!("the point's radius is {r}: expected a positive number"));
        }
        new[0] = r;
        let (force, stiffness, area) = self.hertz(r, -gap);
        Ok(Response { value: force, tangent: -stiffness, in_contact: gap < 0.0, area })
    }

    fn state_names() -> Vec<&'static std::ffi::CStr> {
        vec![c"radius"]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> HertzAsperity {
        HertzAsperity::create(&[100.0, 50.0], "").unwrap()
    }

    /// Hertz in closed form at a few overlaps, each with the point's own radius.
    #[test]
    fn force_and_area_are_hertz_with_the_points_own_radius() {
        let law = law();
        let mut state = [0.0];
        law.initialize_state(&mut state);
        assert_eq!(state, [50.0]);
        for (r, d) in [(50.0, 0.1), (50.0, 1.5), (12.5, 0.4), (200.0, 2.0)] {
            let mut trial = [0.0];
            let out = law.evaluate(-d, &[r], &mut trial).unwrap();
            let exact = 4.0 / 3.0 * 100.0 * f64::sqrt(r) * f64::powf(d, 1.5);
            assert!((out.value - exact).abs() < 1e-12 * exact, "R {r}, d {d}: {} vs {exact}", out.value);
            assert!((out.area - std::f64::consts::PI * r * d).abs() < 1e-12 * out.area);
            assert!(out.in_contact);
            assert_eq!(trial, [r], "the radius is carried");
        }
        let open = law.evaluate(0.3, &[50.0], &mut [0.0]).unwrap();
        assert_eq!((open.value, open.tangent, open.area, open.in_contact), (0.0, 0.0, 0.0, false));
    }

    #[test]
    fn the_tangent_matches_finite_differences() {
        let law = law();
        for g in [-0.01, -0.3, -1.7] {
            let h = 1e-7;
            let f = |x: f64| law.evaluate(x, &[30.0], &mut [0.0]).unwrap().value;
            let fd = (f(g + h) - f(g - h)) / (2.0 * h);
            let t = law.evaluate(g, &[30.0], &mut [0.0]).unwrap().tangent;
            assert!((fd - t).abs() < 1e-6 * t.abs(), "gap {g}: {fd} vs {t}");
        }
    }

    #[test]
    fn a_point_without_a_valid_radius_is_an_error() {
        let e = law().evaluate(-0.1, &[0.0], &mut [0.0]).unwrap_err();
        assert!(e.contains("radius is 0"), "{e}");
        assert!(HertzAsperity::create(&[0.0, 1.0], "").is_err());
    }
}
