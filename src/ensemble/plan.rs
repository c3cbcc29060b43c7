//! The members of an ensemble: for member i, the `--set` assignments of its varied keys.

use crate::case::ensemble_spec::{EnsembleSpec, Variation};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal, Uniform};
use serde::{Deserialize, Serialize};

/// One realization of the case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Member {
    /// 0-based index.
    pub index: usize,
    /// Folder name under the ensemble's output folder, `member-NNN` (at least three digits, so
    /// a larger ensemble keeps the folders of a smaller one).
    pub folder: String,
    /// The varied keys as `key=value` assignments (applied after the command's own --set).
    pub sets: Vec<String>,
}

/// The members of `spec`. Member i gets, per varied key: `start + i`, `values[i]`, or the i-th
/// draw of a ChaCha8 stream seeded with `spec.seed` (stream number = the key's position in
/// `vary`), so the first members of a larger ensemble are those of a smaller one.
pub fn members(spec: &EnsembleSpec) -> Vec<Member> {
    let columns: Vec<Vec<String>> = spec
        .vary
        .iter()
        .enumerate()
        .map(|(k, v)| values(&v.variation().expect("validated"), spec.members, spec.seed, k as u64))
        .collect();
    (0..spec.members)
        .map(|i| Member {
            index: i,
            folder: format!("member-{i:03}"),
            sets: spec.vary.iter().zip(&columns).map(|(v, col)| format!("{}={}", v.key, col[i])).collect(),
        })
        .collect()
}

/// The values of one varied key for `n` members, as TOML literals.
fn values(variation: &Variation, n: usize, seed: u64, stream: u64) -> Vec<String> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    match variation {
        Variation::Sequence(start) => (0..n).map(|i| (start + i as i64).to_string()).collect(),
        Variation::Values(values) => values.iter().take(n).map(ToString::to_string).collect(),
        Variation::Uniform(a, b) => {
            let d = Uniform::new_inclusive(*a, *b).expect("validated bounds");
            (0..n).map(|_| literal(d.sample(&mut rng))).collect()
        }
        Variation::Normal(m, s) => {
            let d = Normal::new(*m, *s).expect("validated std");
            (0..n).map(|_| literal(d.sample(&mut rng))).collect()
        }
    }
}

/// A float as a TOML literal that reads back to the same number (Rust's shortest round trip,
/// always with a decimal point or exponent so TOML reads a float).
fn literal(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains(['.', 'e', 'E']) { s } else { format!("{s}.0") }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(text: &str) -> EnsembleSpec {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn sequences_values_and_draws_per_member() {
        let s = spec(
            "members = 3\n[[vary]]\nkey = \"a.seed\"\nstart = 5\n[[vary]]\nkey = \"b\"\nvalues = [\"x.toml\", \"y.toml\", \"z.toml\"]\n\
             [[vary]]\nkey = \"c\"\nuniform = [1.0, 2.0]\n",
        );
        let m = members(&s);
        assert_eq!(m[2].folder, "member-002");
        assert_eq!(m[0].sets[0], "a.seed=5");
        assert_eq!(m[2].sets[0], "a.seed=7");
        assert_eq!(m[1].sets[1], "b=\"y.toml\"");
        for member in &m {
            let v: f64 = member.sets[2].split_once('=').unwrap().1.parse().unwrap();
            assert!((1.0..=2.0).contains(&v), "uniform draw {v} outside [1, 2]");
        }
    }

    #[test]
    fn a_larger_ensemble_extends_a_smaller_one() {
        let small = members(&spec("members = 4\nseed = 9\n[[vary]]\nkey = \"h\"\nnormal = [0.0, 1.0]\n"));
        let large = members(&spec("members = 10\nseed = 9\n[[vary]]\nkey = \"h\"\nnormal = [0.0, 1.0]\n"));
        assert_eq!(small[..], large[..4]);
        assert_ne!(large[4].sets, large[5].sets);
    }

    #[test]
    fn float_literals_read_back_exactly() {
        for x in [1.0, 0.1, 1e-300, 2.5e17, -3.0] {
            let t: toml::Table = toml::from_str(&format!("v = {}", literal(x))).unwrap();
            assert_eq!(t["v"].as_float(), Some(x));
        }
    }
}
