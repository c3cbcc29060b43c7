//! `table-spring` (the law; `plugin/` exports it as a shared library): a compressive spring
//! per discrete point, F = T(s) with the closure s = -gap, T a table (s_i, F_i) interpolated
//! linearly and held constant past its last sample (as CalculiX's `*SPRING, NONLINEAR`
//! extrapolates), F = 0 for s <= 0. Value (positive pushes apart) = T(-gap); tangent
//! d value / d gap = -T'(-gap). The configuration text is the table as CSV with a header line
//! (e.g. `s_nm,force_nN`) and at least two rows with s increasing from 0.

use stiction_law_sdk::{Law, LawKind, Parameter, Response};

#[derive(Debug, Clone)]
pub struct TableSpring {
    closure: Vec<f64>,
    force: Vec<f64>,
}

impl TableSpring {
    /// Reads the CSV table; errors name the line.
    pub fn from_csv(text: &str) -> Result<Self, String> {
        let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
        lines.next().ok_or("the table is empty: expected a header line and rows 's,force'")?;
        let (mut closure, mut force) = (Vec::new(), Vec::new());
        for (i, line) in lines {
            let v: Vec<f64> = line
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("table line {}: expected two numbers 's,force', found '{line}'", i + 1))?;
            if v.len() != 2 || !v.iter().all(|x| x.is_finite()) {
                return Err(format!("table line {}: expected two finite numbers 's,force', found '{line}'", i + 1));
            }
            if closure.last().is_some_and(|&s| v[0] <= s) {
                return Err(format!(
                    "table line {}: closures must increase, {} follows {}",
                    i + 1,
                    v[0],
                    closure.last().unwrap()
                ));
            }
            closure.push(v[0]);
            force.push(v[1]);
        }
        if closure.len() < 2 || closure[0] != 0.0 {
            return Err("the table needs at least two rows, the first at closure 0".into());
        }
        Ok(Self { closure, force })
    }

    /// T(s) and T'(s) (the slope of the segment s lies in; 0 past the table).
    pub fn table(&self, s: f64) -> (f64, f64) {
        let n = self.closure.len();
        if s <= 0.0 {
            return (0.0, 0.0);
        }
        if s >= self.closure[n - 1] {
            return (self.force[n - 1], 0.0);
        }
        let k = self.closure.partition_point(|&c| c <= s) - 1;
        let slope = (self.force[k + 1] - self.force[k]) / (self.closure[k + 1] - self.closure[k]);
        (self.force[k] + slope * (s - self.closure[k]), slope)
    }
}

impl Law for TableSpring {
    const NAME: &'static std::ffi::CStr = c"table-spring";
    const VERSION: &'static std::ffi::CStr = c"0.1.0";
    const KIND: LawKind = LawKind::ForcePerPoint;
    const N_STATE: usize = 0;

    fn parameters() -> Vec<Parameter> {
        Vec::new()
    }

    fn config_description() -> Option<&'static std::ffi::CStr> {
        Some(c"force table (CSV: header, then rows 'closure,force' from closure 0)")
    }

    fn create(_p: &[f64], config: &str) -> Result<Self, String> {
        Self::from_csv(config)
    }

    fn evaluate(&self, gap: f64, _old: &[f64], _new: &mut [f64]) -> Result<Response, String> {
        let (force, slope) = self.table(-gap);
        Ok(Response { value: force, tangent: -slope, in_contact: gap < 0.0, area: 0.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn power_law_table() -> TableSpring {
        let mut text = String::from("s_nm,force_nN\n");
        for j in 0..=120 {
            let s = 0.025 * j as f64;
            text.push_str(&format!("{s},{}\n", 200.0 * s.powf(1.5)));
        }
        TableSpring::from_csv(&text).unwrap()
    }

    #[test]
    fn interpolates_the_table_and_holds_it_past_the_end() {
        let law = power_law_table();
        // at samples: the closed form 200 s^1.5; between: the chord
        for s in [0.025, 0.5, 1.0, 2.975] {
            let v = law.evaluate(-s, &[], &mut []).unwrap().value;
            assert!((v - 200.0 * f64::powf(s, 1.5)).abs() < 1e-9 * v, "s = {s}: {v}");
        }
        let mid = law.evaluate(-0.0375, &[], &mut []).unwrap().value;
        let chord = 0.5 * 200.0 * (f64::powf(0.025, 1.5) + f64::powf(0.05, 1.5));
        assert!((mid - chord).abs() < 1e-12);
        let past = law.evaluate(-4.0, &[], &mut []).unwrap();
        assert_eq!((past.value, past.tangent), (200.0 * 3f64.powf(1.5), 0.0));
        let open = law.evaluate(0.1, &[], &mut []).unwrap();
        assert_eq!((open.value, open.tangent, open.in_contact), (0.0, 0.0, false));
    }

    #[test]
    fn tangent_matches_finite_differences_inside_segments() {
        let law = power_law_table();
        for g in [-0.0301, -0.61, -1.777, -2.91] {
            let h = 1e-7;
            let f = |x: f64| law.evaluate(x, &[], &mut []).unwrap().value;
            let fd = (f(g + h) - f(g - h)) / (2.0 * h);
            let t = law.evaluate(g, &[], &mut []).unwrap().tangent;
            assert!((fd - t).abs() < 1e-6 * t.abs(), "gap {g}: {fd} vs {t}");
        }
    }

    #[test]
    fn bad_tables_name_the_line() {
        assert!(TableSpring::from_csv("s,f\n0,0\n0.1,x\n").unwrap_err().contains("line 3"));
        assert!(TableSpring::from_csv("s,f\n0,0\n0.2,1\n0.1,2\n").unwrap_err().contains("increase"));
        assert!(TableSpring::from_csv("s,f\n0.1,0\n0.2,1\n").unwrap_err().contains("closure 0"));
    }
}
