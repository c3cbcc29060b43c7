//! Electrical contact resistance of an interface from its contact spots (constriction
//! resistance between two bodies, the flat and the body; the same metal unless the counter
//! body's resistivity and mean free path are given).
//!
//! One circular spot of radius a, resistivity rho, electron mean free path lambda
//! (Knudsen number K = lambda / a):
//! - diffusive (Holm / Maxwell) limit, a >> lambda: R_M = rho / (2 a);
//! - ballistic (Sharvin) limit, a << lambda: R_S = 4 rho lambda / (3 pi a^2);
//! - between them Wexler's interpolation (G. Wexler, Proc. Phys. Soc. 89, 927 (1966)):
//!   R = R_S + Gamma(K) R_M, with Gamma(K) = (1 + 0.83 K) / (1 + 1.33 K), the approximation of
//!   Wexler's Gamma by B. Nikolic and P. B. Allen, Phys. Rev. B 60, 3963 (1999); Gamma(0) = 1,
//!   Gamma(inf) = 0.624;
//! - an optional film in series, R_f = sigma_f / (pi a^2), sigma_f the film's specific
//!   resistance (ohm area; e.g. a tunnelling oxide).
//!
//! Two different metals (rho_1, lambda_1 the body, rho_2, lambda_2 the counter body): each
//! half-space carries half of the constriction, so the diffusive part is
//! sum_k Gamma(lambda_k / a) rho_k / (4 a) (Holm's (rho_1 + rho_2) / (4 a) for large spots,
//! R. Holm, Electric Contacts, 1967, section 4) and the ballistic part the mean of the two
//! metals' Sharvin resistances, 2 (rho_1 lambda_1 + rho_2 lambda_2) / (3 pi a^2) (an
//! approximation: a hetero-contact's ballistic resistance depends on both Fermi surfaces). For
//! one metal both reduce to the formulas above.
//!
//! Many spots (J. A. Greenwood, Br. J. Appl. Phys. 17, 1621 (1966)): spot i carries the share
//! w_i of the current, and spots i != j at distance s_ij raise each other's potential as point
//! sources on the two half-spaces do, by rho / (pi s_ij) per unit current ((rho_1 + rho_2) /
//! (2 pi s_ij) for two metals, written rho below). For a current split
//! w the resistance is
//!   R = sum_i w_i^2 R_i + sum_{i != j} w_i w_j rho / (pi s_ij).
//! Greenwood takes w_i proportional to a_i, which with R_i = R_M(a_i) gives his formula
//!   R = rho / (2 sum a_i) + (rho / pi) sum_{i != j} a_i a_j / (s_ij (sum a_i)^2).
//! Here w_i = G_i / sum G_k with G_i = 1 / R_i (the split of isolated spots in parallel), which
//! is Greenwood's choice in the diffusive limit and keeps the first term the parallel resistance
//! 1 / sum G_i at any K. By Thomson's principle any split gives an upper bound of the true
//! resistance; the interaction term assumes s_ij >> a (point sources), so s_ij is taken no
//! smaller than a_i + a_j (touching spots).

/// One contact spot: its centre projected on the flat and its radius (case length units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSpot {
    pub center: [f64; 3],
    pub radius: f64,
}

/// The material data of the constriction, in the case's units: lengths in its length unit L,
/// resistivity in ohm L, film specific resistance in ohm L^2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResistanceModel {
    pub resistivity: f64,
    pub mean_free_path: f64,
    pub film_specific_resistance: f64,
    /// The counter body's (the flat's) resistivity and mean free path; equal to the body's
    /// for one metal.
    pub counter_resistivity: f64,
    pub counter_mean_free_path: f64,
}

/// Wexler's Gamma(K) in the approximation of Nikolic and Allen: (1 + 0.83 K) / (1 + 1.33 K).
pub fn wexler_gamma(knudsen: f64) -> f64 {
    (1.0 + 0.83 * knudsen) / (1.0 + 1.33 * knudsen)
}

impl ResistanceModel {
    /// Both bodies of one metal.
    pub fn same_metal(resistivity: f64, mean_free_path: f64, film_specific_resistance: f64) -> Self {
        Self {
            resistivity,
            mean_free_path,
            film_specific_resistance,
            counter_resistivity: resistivity,
            counter_mean_free_path: mean_free_path,
        }
    }

    /// The two bodies' (resistivity, mean free path).
    fn sides(&self) -> [(f64, f64); 2] {
        [(self.resistivity, self.mean_free_path), (self.counter_resistivity, self.counter_mean_free_path)]
    }

    /// The resistivity seen by the spots' interaction: (rho_1 + rho_2) / 2.
    fn mean_resistivity(&self) -> f64 {
        0.5 * (self.resistivity + self.counter_resistivity)
    }

    /// Holm / Maxwell resistance of a spot of radius `a`: (rho_1 + rho_2) / (4 a).
    pub fn maxwell(&self, a: f64) -> f64 {
        self.mean_resistivity() / (2.0 * a)
    }

    /// Sharvin resistance of a spot of radius `a`: 2 (rho_1 lambda_1 + rho_2 lambda_2) /
    /// (3 pi a^2).
    pub fn sharvin(&self, a: f64) -> f64 {
        self.sides().iter().map(|(rho, lambda)| 2.0 * rho * lambda / (3.0 * std::f64::consts::PI * a * a)).sum()
    }

    /// One spot of radius `a`: R_S + sum_k Gamma(lambda_k / a) rho_k / (4 a) + sigma_f / (pi a^2).
    pub fn spot(&self, a: f64) -> f64 {
        let film = self.film_specific_resistance / (std::f64::consts::PI * a * a);
        let diffusive: f64 = self.sides().iter().map(|(rho, lambda)| wexler_gamma(lambda / a) * rho / (4.0 * a)).sum();
        self.sharvin(a) + diffusive + film
    }

    /// The resistance of all `spots` together (see the module documentation); infinite with no
    /// spot.
    pub fn total(&self, spots: &[ContactSpot]) -> f64 {
        let conductances: Vec<f64> = spots.iter().map(|s| 1.0 / self.spot(s.radius)).collect();
        let total_conductance: f64 = conductances.iter().sum();
        if spots.is_empty() || total_conductance <= 0.0 {
            return f64::INFINITY;
        }
        let share: Vec<f64> = conductances.iter().map(|g| g / total_conductance).collect();
        let mut interaction = 0.0;
        for (i, a) in spots.iter().enumerate() {
            for (j, b) in spots.iter().enumerate().skip(i + 1) {
                let d = [a.center[0] - b.center[0], a.center[1] - b.center[1], a.center[2] - b.center[2]];
                let s = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(a.radius + b.radius);
                // both orders (i, j) and (j, i)
                interaction += 2.0 * share[i] * share[j] * self.mean_resistivity() / (std::f64::consts::PI * s);
            }
        }
        1.0 / total_conductance + interaction
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const RU: ResistanceModel = ResistanceModel {
        resistivity: 71.0,
        mean_free_path: 6.59,
        film_specific_resistance: 0.0,
        counter_resistivity: 71.0,
        counter_mean_free_path: 6.59,
    };

    fn spot(x: f64, radius: f64) -> ContactSpot {
        ContactSpot { center: [x, 0.0, 0.0], radius }
    }

    #[test]
    fn a_single_spot_tends_to_holm_when_large_and_to_sharvin_when_small() {
        // a >> lambda: Holm rho / (2a), within the Sharvin correction 4 lambda / (3 pi a) + Gamma
        let a = 1e5;
        let r = RU.spot(a);
        assert!((r / (RU.resistivity / (2.0 * a)) - 1.0).abs() < 1e-4, "{r}");
        // a << lambda: Sharvin 4 rho lambda / (3 pi a^2), within Gamma(inf) R_M / R_S
        let a = 1e-4;
        let r = RU.spot(a);
        let sharvin = 4.0 * RU.resistivity * RU.mean_free_path / (3.0 * PI * a * a);
        assert!((r / sharvin - 1.0).abs() < 1e-4, "{r}");
        // Gamma's limits
        assert_eq!(wexler_gamma(0.0), 1.0);
        assert!((wexler_gamma(1e9) - 0.83 / 1.33).abs() < 1e-8);
        // a film adds sigma_f / (pi a^2) in series
        let film = ResistanceModel { film_specific_resistance: 3.0, ..RU };
        assert!((film.spot(2.0) - RU.spot(2.0) - 3.0 / (PI * 4.0)).abs() < 1e-12);
    }

    #[test]
    fn spots_far_apart_are_in_parallel() {
        let spots = [spot(0.0, 2.0), spot(1e9, 3.0)];
        let parallel = 1.0 / (1.0 / RU.spot(2.0) + 1.0 / RU.spot(3.0));
        assert!((RU.total(&spots) / parallel - 1.0).abs() < 1e-8);
        assert_eq!(RU.total(&[]), f64::INFINITY);
    }

    #[test]
    fn two_equal_diffusive_spots_follow_greenwood() {
        // diffusive limit (lambda -> 0): two spots of radius a at distance s have
        // R = rho / (4 a) + rho / (2 pi s) (Greenwood 1966, n = 2)
        let diffusive = ResistanceModel { mean_free_path: 0.0, counter_mean_free_path: 0.0, ..RU };
        let (a, s) = (2.0, 11.0);
        let greenwood = RU.resistivity / (4.0 * a) + RU.resistivity / (2.0 * PI * s);
        let r = diffusive.total(&[spot(0.0, a), spot(s, a)]);
        assert!((r / greenwood - 1.0).abs() < 1e-12, "{r} vs {greenwood}");
        // unequal diffusive spots: Greenwood's general formula
        let (a1, a2, a3) = (1.0, 2.0, 3.0);
        let spots = [spot(0.0, a1), spot(20.0, a2), spot(45.0, a3)];
        let sum = a1 + a2 + a3;
        let pairs = a1 * a2 / 20.0 + a1 * a3 / 45.0 + a2 * a3 / 25.0;
        let greenwood = RU.resistivity / (2.0 * sum) + RU.resistivity / PI * 2.0 * pairs / (sum * sum);
        assert!((diffusive.total(&spots) / greenwood - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_uniform_cluster_follows_greenwoods_cluster_estimate() {
        // Greenwood: n spots spread uniformly over a disc of radius alpha, each carrying the
        // same current: R = rho / (2 sum a) + (rho / pi) <1/s>, with <1/s> = 16 / (3 pi alpha)
        // for two points uniform in the disc, less what the sum over distinct spots leaves out:
        // each spot's own cell (a disc of radius r_c = alpha / sqrt(n), where the mean of 1/r
        // about the centre is 2 / r_c), i.e. 2 / (n r_c). Never below Holm's rho / (2 alpha).
        let diffusive = ResistanceModel { mean_free_path: 0.0, counter_mean_free_path: 0.0, ..RU };
        let alpha = 100.0;
        let step = alpha * (PI / 400.0f64).sqrt();
        let mut spots = Vec::new();
        for i in -30..=30 {
            for j in -30..=30 {
                let c = [i as f64 * step, j as f64 * step, 0.0];
                if c[0].hypot(c[1]) < alpha {
                    spots.push(ContactSpot { center: c, radius: 0.5 });
                }
            }
        }
        let n = spots.len() as f64;
        let mean_inverse_distance = 16.0 / (3.0 * PI * alpha) - 2.0 / (n * alpha / n.sqrt());
        let estimate = RU.resistivity / (2.0 * 0.5 * n) + RU.resistivity / PI * mean_inverse_distance;
        let r = diffusive.total(&spots);
        println!("{n} spots: R = {r:.5}, Greenwood's cluster estimate {estimate:.5}");
        assert!((r / estimate - 1.0).abs() < 0.015, "{r} vs {estimate}");
        assert!(r > RU.resistivity / (2.0 * alpha));
    }

    #[test]
    fn two_metals_share_the_constriction_half_and_half() {
        // Ru against Au (rho 22.1 nOhm m, lambda 37.9 nm, Gall 2016), in the units of RU
        let au = (22.1, 37.9);
        let m = ResistanceModel { counter_resistivity: au.0, counter_mean_free_path: au.1, ..RU };
        // a >> both lambdas: Holm's (rho_1 + rho_2) / (4 a)
        let a = 1e6;
        let holm = (RU.resistivity + au.0) / (4.0 * a);
        assert!((m.spot(a) / holm - 1.0).abs() < 1e-4, "{} vs {holm}", m.spot(a));
        // a << both: the mean of the two Sharvin resistances
        let a = 1e-4;
        let sharvin = 2.0 * (RU.resistivity * RU.mean_free_path + au.0 * au.1) / (3.0 * PI * a * a);
        assert!((m.spot(a) / sharvin - 1.0).abs() < 1e-4);
        // the same metal on both sides is the one-metal model
        let same = ResistanceModel::same_metal(71.0, 6.59, 0.0);
        assert_eq!(same, RU);
        // two diffusive spots far from each other interact through (rho_1 + rho_2) / (2 pi s)
        let diffusive = ResistanceModel { mean_free_path: 0.0, counter_mean_free_path: 0.0, ..m };
        let (a, s) = (2.0, 11.0);
        let greenwood = (RU.resistivity + au.0) / 2.0 * (1.0 / (4.0 * a) + 1.0 / (2.0 * PI * s));
        let r = diffusive.total(&[spot(0.0, a), spot(s, a)]);
        assert!((r / greenwood - 1.0).abs() < 1e-12, "{r} vs {greenwood}");
    }
}
