//! Kinematic performance indices of a 3-RPR (SPEC Part B).

use nalgebra::Vector3;
use singdist::index::rpr::{
    CnVariant, DsAggregate, IndexOptions, Legs, SingularConic, SingularOrientations,
    compute_indices, control_number, incircle_radius, orientation_singularity_distance,
    position_singularity_distance, pressure_cosines, singular_orientations,
    singularity_free_cylinder_radius,
};
use singdist::mechanism::rpr::{Configuration, Design, Pose};
use singdist::random::{seeded, uniform};

fn design() -> Design {
    Design::new(
        [[0.0, 0.0], [10.0, 0.0], [4.0, 8.0]],
        [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
    )
    .unwrap()
}

fn pose() -> Pose {
    Pose::new(4.0, 3.0, 0.3)
}

fn close(value: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (value - expected).abs() <= tol,
        "{what}: {value} vs expected {expected}"
    );
}

#[test]
fn spec_test_vector() {
    let r = compute_indices(&design(), pose(), &IndexOptions::default());
    close(r.s, 125.29749, 1e-5, "S");
    close(r.m.unwrap(), 1.781467, 1e-6, "M");
    let cos = r.pressure_cosines.unwrap();
    for (c, e) in cos.iter().zip([0.787796, 0.883815, 0.918092]) {
        close(*c, e, 1e-6, "cos alpha");
    }
    close(r.ti.unwrap(), 0.787796, 1e-6, "TI");
    let cos_star = r.pressure_cosines_exchanged.unwrap();
    for (c, e) in cos_star.iter().zip([0.406690, 0.319097, 0.445024]) {
        close(*c, e, 1e-6, "cos alpha*");
    }
    close(r.mti.unwrap(), 0.319097, 1e-6, "MTI");
    close(r.ds.unwrap(), 0.787796 * 0.883815 * 0.918092, 1e-6, "DS");
    close(r.mds.unwrap(), 0.406690 * 0.319097 * 0.445024, 1e-6, "MDS");
    close(r.ir.unwrap(), 0.744749, 1e-6, "IR");
    close(r.lambda_min.unwrap(), 0.0399153, 1e-6, "lambda_min");
    close(r.lambda_max.unwrap(), 3.574523, 1e-6, "lambda_max");
    close(r.cn.unwrap(), 0.0111666, 1e-6, "CN");
    close(r.mcn.unwrap(), 0.528921, 1e-6, "MCN");
    let conic = SingularConic::at_orientation(&design(), 0.3);
    let expected = [-7.092485, 4.412386, -7.821077, 56.605541, 9.932048, 0.0];
    let got = [conic.cxx, conic.cxy, conic.cyy, conic.cx, conic.cy, conic.c0];
    for (g, e) in got.iter().zip(expected) {
        close(*g, e, 1e-6, "conic");
    }
    close(r.position_distance.unwrap(), 2.589166, 1e-6, "position distance");
    let foot = r.position_foot.unwrap();
    close(foot[0], 2.43476, 1e-5, "foot x");
    close(foot[1], 5.06248, 1e-5, "foot y");
    match singular_orientations(&design(), 4.0, 3.0) {
        SingularOrientations::Finite(roots) => {
            assert_eq!(roots.len(), 2, "{roots:?}");
            close(roots[0], 3.111238, 1e-6, "orientation root 1");
            close(roots[1], 6.194301, 1e-6, "orientation root 2");
        }
        other => panic!("{other:?}"),
    }
    close(r.orientation_distance.unwrap(), 0.388884, 1e-6, "orientation distance");
    close(r.orientation_distance_signed.unwrap(), 0.388884, 1e-6, "signed (S > 0)");
    let cyl = singularity_free_cylinder_radius(&design(), 4.0, 3.0, [0.2, 0.4])
        .unwrap()
        .unwrap();
    close(cyl.radius, 2.54565, 1e-5, "cylinder radius");
    close(cyl.at_phi, 0.4, 1e-6, "cylinder phi");
}
