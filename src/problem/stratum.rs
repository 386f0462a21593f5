//! The stratum of the design space a sub-problem's system is posed on: generic rigid
//! shapes, or rigid parts whose anchors are collinear.
//!
//! A rigid part's third anchor is `x₃′ = x₁′ + u (x₂′ − x₁′) + v E(x₂′ − x₁′)`
//! (docs/theory.md §4), with the shape constants `(u, v, r²)` as parameters of the
//! Lagrange system. Where the design's anchors of a rigid part are collinear (`v = 0`,
//! a base or platform on a line, as many real designs are), the design lies on a proper
//! subvariety of the parameter space, where some of the generic critical points
//! have gone to infinity: `rigid/rigid` has 88 critical points for a generic design and
//! 84 for a base on a line. From the generic start file the seed stage tracks those
//! paths to infinity at every seed point, and they do not end cleanly (they crawl towards
//! a positive-dimensional set at infinity: in affine coordinates, in the multipliers'
//! projective chart and in a projective chart of all unknowns alike), so every seed
//! point's count stays unconfirmed and costs re-runs and detours.
//!
//! Posed on the stratum — `v = 0` a constant of the system, one parameter fewer — the
//! family is generic again: a start file computed by monodromy at a random complex point
//! *of the stratum* has exactly the stratum's count of finite critical points, every seed
//! path stays finite, and the count the poses expect is the count of that start file
//! (parameter homotopy on the restricted family: Sommese and Wampler, *The Numerical
//! Solution of Systems of Polynomials Arising in Engineering and Science*, 2005, §7).

use super::{ProblemId, SubProblem};
use crate::mechanism::rpr::Design;
use crate::metric::Part;
use serde::{Deserialize, Serialize};

/// Largest `|v|` (anchor 3's offset from the line of anchors 1, 2 over `|e|`) of a rigid
/// part posed on a line: rounding of coordinates given on a line. The system then
/// solves the design with `v = 0`, which moves anchor 3 by at most `10⁻¹²·|e|`, below
/// the reproducibility bound of the distances (`10⁻¹⁰` relative). Parts further off
/// the line (even by `10⁻¹⁰`) stay on the generic stratum.
pub const ON_A_LINE_TOLERANCE: f64 = 1e-12;

/// Which rigid parts of a sub-problem have their anchors on a line (`v = 0` fixed in the
/// system). The default is the generic stratum: every shape constant a parameter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Stratum {
    /// The rigid base's anchors are collinear.
    #[serde(default)]
    pub collinear_base: bool,
    /// The rigid platform's anchors are collinear.
    #[serde(default)]
    pub collinear_platform: bool,
}

impl Stratum {
    /// Every shape constant a parameter.
    pub const GENERIC: Stratum = Stratum {
        collinear_base: false,
        collinear_platform: false,
    };

    /// Whether this is the generic stratum.
    pub fn is_generic(&self) -> bool {
        *self == Self::GENERIC
    }

    /// The stratum of `design` for sub-problem `id`: each rigid part whose anchors are
    /// on a line to rounding (`|v| ≤` [`ON_A_LINE_TOLERANCE`]) fixed at `v = 0`. The
    /// all-collinear sub-problem has no `v` (its rigid parts are on the line by
    /// construction): always generic.
    pub fn of(id: ProblemId, design: &Design) -> Stratum {
        if !Self::has_shape_constants(id) {
            return Self::GENERIC;
        }
        let on_a_line = |v: f64| v.abs() <= ON_A_LINE_TOLERANCE;
        Stratum {
            collinear_base: id.metric.base == Part::Rigid && on_a_line(design.base_shape().v),
            collinear_platform: id.metric.platform == Part::Rigid
                && on_a_line(design.platform_shape().v),
        }
    }

    /// Every stratum of sub-problem `id` other than the generic one: its rigid parts'
    /// subsets on a line.
    pub fn special(id: ProblemId) -> Vec<Stratum> {
        if !Self::has_shape_constants(id) {
            return Vec::new();
        }
        let base = [false, id.metric.base == Part::Rigid];
        let platform = [false, id.metric.platform == Part::Rigid];
        let mut out = Vec::new();
        for collinear_base in base {
            for collinear_platform in platform {
                let stratum = Stratum {
                    collinear_base,
                    collinear_platform,
                };
                if !stratum.is_generic() && !out.contains(&stratum) {
                    out.push(stratum);
                }
            }
        }
        out
    }

    /// The special strata that contain this one, itself first (a design with both rigid
    /// parts on lines is on the strata of either part on a line too): the start files
    /// the seed stage tries, in order, before the generic one.
    pub fn containing(&self) -> Vec<Stratum> {
        let mut out = Vec::new();
        if !self.is_generic() {
            out.push(*self);
        }
        if self.collinear_base && self.collinear_platform {
            out.push(Stratum {
                collinear_platform: false,
                ..*self
            });
            out.push(Stratum {
                collinear_base: false,
                ..*self
            });
        }
        out
    }

    /// Whether sub-problem `id`'s rigid parts carry the shape constants `(u, v, r²)`.
    fn has_shape_constants(id: ProblemId) -> bool {
        id.subproblem != SubProblem::AllCollinear
    }

    /// Whether the rigid part `role` (`"base"` or `"platform"`) has `v = 0` fixed.
    pub fn fixes(&self, role: &str) -> bool {
        match role {
            "base" => self.collinear_base,
            "platform" => self.collinear_platform,
            _ => false,
        }
    }

    /// Its name in file names and messages (`None` for the generic stratum).
    pub fn name(&self) -> Option<&'static str> {
        match (self.collinear_base, self.collinear_platform) {
            (false, false) => None,
            (true, false) => Some("collinear-base-anchors"),
            (false, true) => Some("collinear-platform-anchors"),
            (true, true) => Some("collinear-anchors"),
        }
    }

    /// The start file's name (without `.json`) of sub-problem `id` on this stratum:
    /// `PLATFORM-BASE-SUBPROBLEM` for the generic one, with `.STRATUM` appended
    /// otherwise (`rigid-rigid-singularity.collinear-base-anchors`).
    pub fn file_stem(&self, id: ProblemId) -> String {
        match self.name() {
            None => id.file_stem(),
            Some(name) => format!("{}.{name}", id.file_stem()),
        }
    }

    /// The stratum named `name` (as [`Stratum::name`]; `generic` too).
    pub fn from_name(name: &str) -> Option<Stratum> {
        let (collinear_base, collinear_platform) = match name {
            "generic" => (false, false),
            "collinear-base-anchors" => (true, false),
            "collinear-platform-anchors" => (false, true),
            "collinear-anchors" => (true, true),
            _ => return None,
        };
        Some(Stratum {
            collinear_base,
            collinear_platform,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::Metric;

    fn id(name: &str) -> ProblemId {
        name.parse().unwrap()
    }

    #[test]
    fn only_rigid_parts_with_shape_constants_have_special_strata() {
        assert!(Stratum::special(id("plate/bars:singularity")).is_empty());
        assert!(Stratum::special(id("rigid/rigid:all-collinear")).is_empty());
        assert_eq!(Stratum::special(id("bars/rigid:singularity")).len(), 1);
        assert_eq!(Stratum::special(id("rigid/rigid:singularity")).len(), 3);
        for stratum in Stratum::special(id("rigid/rigid:singularity")) {
            let name = stratum.name().unwrap();
            assert_eq!(Stratum::from_name(name), Some(stratum));
        }
        assert_eq!(Stratum::from_name("generic"), Some(Stratum::GENERIC));
        let both = Stratum::from_name("collinear-anchors").unwrap();
        let names: Vec<_> = both
            .containing()
            .iter()
            .map(|s| s.name().unwrap())
            .collect();
        assert_eq!(
            names,
            [
                "collinear-anchors",
                "collinear-base-anchors",
                "collinear-platform-anchors"
            ]
        );
        assert!(Stratum::GENERIC.containing().is_empty());
    }

    #[test]
    fn a_design_with_a_base_on_a_line_is_on_the_collinear_base_stratum() {
        let design = Design::new(
            [[-1.0, -0.5], [0.25, 0.125], [1.0, 0.5]],
            [[0.07, 0.45], [-0.42, 0.05], [-0.02, -0.33]],
        )
        .unwrap();
        let rigid_rigid = id("rigid/rigid:singularity");
        let stratum = Stratum::of(rigid_rigid, &design);
        assert!(stratum.collinear_base && !stratum.collinear_platform);
        assert_eq!(
            stratum.file_stem(rigid_rigid),
            "rigid-rigid-singularity.collinear-base-anchors"
        );
        // A plate base is not a rigid part: no fixed shape constant.
        let plate_base: ProblemId = ProblemId {
            metric: Metric {
                platform: Part::Rigid,
                base: Part::Plate,
            },
            subproblem: SubProblem::Singularity,
        };
        assert!(Stratum::of(plate_base, &design).is_generic());
        // Anchor 3 off the line by 10⁻³ of the base: generic.
        let off = Design::new(
            [[-1.0, -0.5], [0.25, 0.126], [1.0, 0.5]],
            [[0.07, 0.45], [-0.42, 0.05], [-0.02, -0.33]],
        )
        .unwrap();
        assert!(Stratum::of(rigid_rigid, &off).is_generic());
    }
}
