//! The committed PHCpack demo systems (`tests/demo_systems/`) shared by the homotopy
//! tests, with their verified numbers of distinct nonsingular roots (PHCpack's and
//! singdist's roots refined by Newton's method against the original polynomials;
//! `benches/phc_demo_suite.rs` reproduces them).
#![allow(dead_code)]

/// (file stem, verified number of distinct nonsingular roots) of the systems the
/// total-degree homotopy solves without a failed path.
pub const SYSTEMS: [(&str, usize); 15] = [
    ("cyclic5", 70),
    ("katsura6", 64),
    ("caprasse", 24),
    ("noon4", 73),
    ("camera1s", 20),
    ("lorentz", 11),
    ("sendra", 46),
    ("solotarev", 2),
    // Badly scaled systems whose large finite roots are approached like s^(-1/2) for
    // most of the endgame (they were labelled at infinity), and paths whose step size
    // reached the resolution of t (they failed).
    ("chemequ", 16),
    ("chemequs", 16),
    ("game5two", 44),
    ("kotsireas", 84),
    // Paths to infinity whose norm passes 10⁸ before the endgame zone (they failed).
    ("ku10", 2),
    // A double root whose second path never got a Cauchy loop (its condition number grew,
    // but stayed below the direct finish's bound) and failed.
    ("redcyc5", 14),
    // Roots of norm up to 1.2·10⁵ and condition up to 7·10⁹ (a Hilbert-like quadratic
    // part, nearly solutions at infinity), pairs of them 11 % apart: paths stalled in
    // double-precision residuals and Cauchy loops closed around two roots at once.
    ("discret3s", 128),
];

/// (file stem, singular roots, paths to them) of committed systems whose roots are
/// all singular, or have singular ones besides the nonsingular ones: every path to a
/// singular root ends there, classified, none fails.
pub const SINGULAR_SYSTEMS: [(&str, usize, usize); 2] = [("redcyc5", 2, 4), ("tangents1", 6, 24)];

/// The path of the committed Bertini file of demo system `stem`.
pub fn demo_file(stem: &str) -> String {
    format!(
        "{}/tests/demo_systems/{stem}.input",
        env!("CARGO_MANIFEST_DIR")
    )
}
