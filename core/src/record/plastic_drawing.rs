//! Plastic drawing at the end of an unloading: an interface that still holds while the flat
//! retracts, because the continuum under its attached points yields in tension and follows the
//! flat (a cold weld), rather than because the flat has not yet gone far enough.
//!
//! Over the trailing retraction in which the flat kept pulling, the flat's work is
//!   W = sum_i 1/2 (|F_i| + |F_i+1|) |a_i+1 - a_i|,
//! and it goes into the continuum's plastic dissipation dD, the elastic energy, and the
//! interface's own energy. When the attached points hold at a constant force and distance,
//! the last two do not change and dD = W; a body merely stretched elastically towards a
//! pull-off has dD = 0. dD > W / 2 is reported as drawing.

use super::cycles::InterfaceSample;

/// The trailing retraction of an interface still pulling at the end of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drawing {
    /// How far the flat retracted over it (positive).
    pub retraction: f64,
    /// The flat's work over it, W (positive when it pulled).
    pub work: f64,
    /// The plastic dissipation over it, dD (the whole model's: the mesh's continuum and the
    /// footprint sliders).
    pub plastic_dissipation: f64,
    /// The part of dD in the footprint sliders (the rest is the mesh's continuum).
    pub footprint_dissipation: f64,
    /// The snaps' dissipation over it.
    pub snap_dissipation: f64,
}

impl Drawing {
    /// dD / W.
    pub fn plastic_share(&self) -> f64 {
        self.plastic_dissipation / self.work
    }

    /// More than half the flat's work went into plastic flow.
    pub fn is_drawing(&self) -> bool {
        self.work > 0.0 && self.plastic_dissipation > 0.5 * self.work
    }
}

/// The trailing span of `samples` over which the flat retracted (approach not increasing)
/// while pulling with a force within a factor 2 of the final tensile one (the hold, not the
/// pull-off of the rest of the contact before it); None when the last state is not tensile or
/// the span did not retract.
pub fn trailing_drawing(samples: &[InterfaceSample]) -> Option<Drawing> {
    let last = samples.last()?;
    if !(last.force < 0.0) {
        return None;
    }
    let mut first = samples.len() - 1;
    while first > 0 {
        let (before, after) = (&samples[first - 1], &samples[first]);
        let (held, tail) = (before.force.abs(), last.force.abs());
        if !(before.force < 0.0 && held >= 0.5 * tail && held <= 2.0 * tail && before.approach >= after.approach) {
            break;
        }
        first -= 1;
    }
    let span = &samples[first..];
    let work: f64 = span
        .windows(2)
        .map(|w| 0.5 * (w[0].force.abs() + w[1].force.abs()) * (w[1].approach - w[0].approach).abs())
        .sum();
    let retraction = span[0].approach - last.approach;
    (retraction > 0.0).then(|| Drawing {
        retraction,
        work,
        plastic_dissipation: last.plastic_dissipation - span[0].plastic_dissipation,
        footprint_dissipation: last.footprint_dissipation - span[0].footprint_dissipation,
        snap_dissipation: last.snap_dissipation - span[0].snap_dissipation,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(approach: f64, force: f64, plastic_dissipation: f64) -> InterfaceSample {
        InterfaceSample {
            approach,
            force,
            contact_area: 0.0,
            n_contact: 1,
            resistance: None,
            plastic_dissipation,
            footprint_dissipation: 0.0,
            snap_dissipation: 0.0,
        }
    }

    /// A pull-off followed by a hold at -10 over 2 units of retraction, all of it dissipated
    /// plastically: the span starts where the force came within a factor 2 of the final one
    /// (-8), after the pull-off (-25) and before it (-2).
    #[test]
    fn a_hold_whose_work_is_dissipated_plastically_is_drawing() {
        let samples = [
            at(1.0, 5.0, 0.0),
            at(0.0, -2.0, 0.0),
            at(-0.5, -25.0, 0.0),
            at(-1.0, -8.0, 0.0),
            at(-2.0, -10.0, 9.0),
            at(-3.0, -10.0, 19.0),
            at(-4.0, -10.0, 29.0),
        ];
        let d = trailing_drawing(&samples).unwrap();
        assert_eq!(d.retraction, 3.0);
        assert_eq!(d.work, 9.0 + 10.0 + 10.0);
        assert_eq!(d.plastic_dissipation, 29.0);
        assert!(d.is_drawing() && (d.plastic_share() - 1.0).abs() < 1e-15);
    }

    /// An elastic approach to a pull-off (no plastic dissipation) is not drawing; a state that
    /// pushes, or a last step that closes the contact again, has no trailing retraction.
    #[test]
    fn elastic_stretching_and_pushing_states_are_not_drawing() {
        let elastic = [at(0.0, -2.0, 5.0), at(-1.0, -4.0, 5.0), at(-2.0, -5.0, 5.0)];
        let d = trailing_drawing(&elastic).unwrap();
        assert_eq!((d.retraction, d.work, d.plastic_dissipation), (1.0, 4.5, 0.0));
        assert!(!d.is_drawing());
        assert_eq!(trailing_drawing(&[at(0.0, -2.0, 0.0), at(1.0, 3.0, 0.0)]), None);
        assert_eq!(trailing_drawing(&[at(-1.0, -2.0, 0.0), at(0.0, -2.0, 1.0)]), None);
    }
}
