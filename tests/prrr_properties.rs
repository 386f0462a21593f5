//! Property tests: indices are finite and in [0, 1] for any input, reachable or not, and
//! the inverse kinematics never returns NaN.

use proptest::prelude::*;
use singdist::index::prrr::{LciVariant, all_indices, lci, nsir};
use singdist::mechanism::prrr::{Pose, PrrrDesign, Robot, WorkingMode};

fn mode(b: bool) -> WorkingMode {
    if b {
        WorkingMode::Plus
    } else {
        WorkingMode::Minus
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn indices_are_bounded_and_finite(
        x in -0.5f64..0.5, y in -0.5f64..0.5, alpha in -3.2f64..3.2,
        d0 in -0.3f64..0.3, d1 in -0.3f64..0.3, d2 in -0.3f64..0.3,
        m0: bool, m1: bool, m2: bool, fontes: bool,
    ) {
        let design = if fontes { PrrrDesign::fontes2017() } else { PrrrDesign::farias2021() };
        match design.inverse_kinematics(&Pose::new(x, y, alpha), &[d0, d1, d2], &[mode(m0), mode(m1), mode(m2)]) {
            Ok(c) => {
                for v in c.theta.iter().chain(&c.beta) {
                    prop_assert!(v.is_finite());
                }
                for robot in [Robot::ThreePrrr, Robot::ThreeRrr] {
                    let i = all_indices(&design, &c, robot);
                    for v in [i.lci_inv_a_b, i.lci_a, i.xi, i.nsir] {
                        prop_assert!(v.is_finite() && (0.0..=1.0 + 1e-12).contains(&v), "{:?}", i);
                    }
                    prop_assert!(i.r_norm.is_finite() && i.r_norm >= 0.0);
                    prop_assert_eq!(i.nsir, nsir(&design, &c, robot).nsir);
                    prop_assert_eq!(i.lci_a, lci(&design, &c, robot, LciVariant::DirectA));
                }
            }
            Err(e) => prop_assert!(e.to_string().contains("cannot reach")),
        }
    }
}
