//! SPEC D.1–D.2: inverse kinematics, A and B against finite differences, singularity tests,
//! LCI and NSIR test vectors.

use singdist::index::prrr::{LciVariant, all_indices, incircle_radius_of_lines, lci, nsir};
use singdist::mechanism::prrr::{Pose, PrrrDesign, PrrrError, Robot, WorkingMode, parse_modes};

const PLUS: WorkingMode = WorkingMode::Plus;
const MINUS: WorkingMode = WorkingMode::Minus;

#[test]
fn spec_d2_test_vector() {
    let design = PrrrDesign::farias2021();
    let pose = Pose::new(0.0, 0.0, 0.0);
    let c = design
        .inverse_kinematics(&pose, &[0.0; 3], &[PLUS; 3])
        .unwrap();
    let idx = all_indices(&design, &c, Robot::ThreePrrr);
    println!("{idx:?}");
    assert!(
        (idx.lci_inv_a_b - 0.785952).abs() < 1e-6,
        "{}",
        idx.lci_inv_a_b
    );
    assert!((idx.r_norm - 0.785952).abs() < 1e-6, "{}", idx.r_norm);
    assert!((idx.xi - 0.559922).abs() < 1e-6, "{}", idx.xi);
    assert!((idx.nsir - 0.440072).abs() < 1e-6, "{}", idx.nsir);
    let c = design
        .inverse_kinematics(&pose, &[0.0; 3], &[PLUS, MINUS, PLUS])
        .unwrap();
    let idx = all_indices(&design, &c, Robot::ThreePrrr);
    println!("{idx:?}");
    assert!(
        (idx.lci_inv_a_b - 0.253256).abs() < 1e-6,
        "{}",
        idx.lci_inv_a_b
    );
    assert!((idx.nsir - 0.305006).abs() < 1e-6, "{}", idx.nsir);
}
