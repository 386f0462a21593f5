//! # singdist
//!
//! How far is a planar parallel manipulator from its nearest singularity, and which
//! singular configuration is that, at every pose of a motion?
//!
//! The theory behind every computation, with the paper equation each formula comes from,
//! is in `docs/theory.md` of the repository. The crate reads as the data flows:
//!
//! 1. [`system`]: polynomial systems with variables and parameters, symbolic
//!    differentiation, compiled straight-line evaluation, Bertini/PHCpack formats.
//! 2. [`homotopy`]: homotopies, the predictor–corrector path tracker, endgame,
//!    start systems, monodromy with trace test, parallel `solve`.
//! 3. [`mechanism`]: 3-RPR, 3-RRR and 3-PRRR designs, poses, motions, configurations.
//! 4. [`metric`]: extrinsic distances between configurations (the nine metrics).
//! 5. [`problem`]: the Lagrangian sub-problems of every metric, built with [`system`].
//! 6. [`pipeline`]: ab-initio, user homotopy, parameter homotopy, post-processing.
//! 7. [`index`]: classic kinematic performance indices (for comparison).
//! 8. [`optimize`]: genetic algorithm and local constrained refinement.
//! 9. [`analysis`]: mechanism studies combining indices and optimisers (3-PRRR redundancy
//!    resolution, 3-RRR actuation-scheme design optimisation).
//! 10. [`io`]: serde types of input and output files, CSV/JSON/SVG writers.
//! 11. [`reference`](mod@reference): an independent yardstick for the pipeline: many-start local
//!     minimisation of the singularity distances, and a matrix of test designs.
//! 12. [`certify`]: Krawczyk certificates in interval arithmetic that critical points
//!     are exact, distinct and real, and that a sub-problem's set of them is complete.
//!
//! Arrows point one way: `pipeline → problem → {metric, mechanism, system}`,
//! `pipeline → homotopy → system`, `analysis → {index, optimize}`. Nothing numerical
//! depends on [`io`].
//!
//! # References
//!
//! Doc comments cite the papers below by the short form in bold (e.g. "Kapilavai and
//! Nawratil, Eq. 6") and the sections of `docs/theory.md` as "docs/theory.md §5.3".
//!
//! ## The methods singdist implements
//!
//! - **Kapilavai and Nawratil**: A. Kapilavai, G. Nawratil, "Singularity distance
//!   computations for 3-RPR manipulators using extrinsic metrics" (the extrinsic metrics,
//!   sub-problems, root counts and pipeline of the 3-RPR and 3-RRR distances).
//!   Supplementary materials: A. Kapilavai, Mendeley Data (2023), V3,
//!   doi:10.17632/vwgxrjkhhm.3.
//! - **Farias Filho et al. (2021)**: F. M. Farias Filho, M. M. da Silva, J. V. de C. Fontes,
//!   "Comparison between two singularity avoidance indices for planar parallel kinematically
//!   redundant manipulators", paper COB-2021-0059, 2021 (3-PRRR geometry, LCI, NSIR,
//!   redundancy resolution; preset `farias2021`).
//! - **Fontes et al.**: J. V. C. Fontes, H. L. Vieira, M. M. da Silva, "The impact of
//!   kinematic redundancies on the conditioning of a planar parallel manipulator"
//!   (conditioning maps of the 3RRR and the 3-PRRR; preset `fontes2017`).
//! - **Ramana Babu et al.**: S. Ramana Babu, V. Ramachandra Raju, K. Ramji, "Singularity loci
//!   of actuation schemes for 3RRR planar parallel manipulator", Vol. 9, No. 12, 2015
//!   (actuation schemes, singularity loci, GCI; `singdist schemes`).
//!
//! ## Kinematic indices and designs compared with
//!
//! - **Yoshikawa**: T. Yoshikawa, "Manipulability of robotic mechanisms", The International
//!   Journal of Robotics Research 4 (2) (1985) 3–9.
//! - **Ebrahimi et al.**: I. Ebrahimi, J. A. Carretero, R. Boudreau, "Actuation scheme for a
//!   6-dof kinematically redundant planar parallel manipulator", Proceedings of the IFToMM
//!   World Congress, 2007 (incircle radius).
//! - **Takeda and Funabashi**: Y. Takeda, H. Funabashi, "Motion transmissibility of
//!   in-parallel actuated manipulators", Transactions of the Japan Society of Mechanical
//!   Engineers, Ser. C, 38 (4) (1995) 749–755 (transmission index).
//! - **Gómez et al.**: O. A. Gómez, P. Wenger, A. Pámanes, "Performance indices for
//!   kinematically redundant parallel planar manipulators", Problems of Mechanics 22 (1)
//!   (2006) 22–40 (distance to singularity DS).
//! - **Nawratil**: G. Nawratil, "New performance indices for 6-dof UPS and 3-dof RPR parallel
//!   manipulators", Mechanism and Machine Theory 44 (1) (2009) 208–221 (control number).
//! - **Mao et al.**: J. Mao, Y. Guo, J. Ren, W. Guo, "A new Euclidian distance based approach
//!   to measure closeness to singularity for parallel manipulators", Intelligent Robotics and
//!   Applications (ICIRA 2013), Springer, 2013, pp. 41–53 (orientation singularity distance).
//! - **Nag et al.**: A. Nag, S. Bandyopadhyay, "Singularity-free spheres in the position and
//!   orientation workspaces of Stewart platform manipulators", Mechanism and Machine Theory
//!   155 (2021) 104041 (position singularity distance).
//! - **Li, Gosselin and Richard 2006**: H. Li, C. M. Gosselin, M. J. Richard, "Determination of
//!   maximal singularity-free zones in the workspace of planar three-degree-of-freedom
//!   parallel mechanisms", Mechanism and Machine Theory 41 (10) (2006) 1157–1167
//!   (singularity-free cylinder).
//! - **Nasa and Bandyopadhyay 2011**: C. Nasa, S. Bandyopadhyay, "Trajectory-tracking control
//!   of a planar 3-RRR parallel manipulator with singularity avoidance", World Congress in
//!   Mechanism and Machine Science, 2011, pp. 19–25 (the 3-RRR example of Kapilavai and
//!   Nawratil).
//! - **Gosselin and Angeles**: C. M. Gosselin, J. Angeles, "Singularity analysis of
//!   closed-loop kinematic chains", IEEE Transactions on Robotics and Automation 6 (3) (1990)
//!   281–290.
//! - **Hunt**: K. H. Hunt, "Kinematic geometry of mechanisms", 1978.
//!
//! ## Homotopy continuation
//!
//! - **Morgan and Sommese 1989**: A. P. Morgan, A. J. Sommese, "Coefficient-parameter
//!   polynomial continuation", Applied Mathematics and Computation 29 (1989) (parameter
//!   homotopies; no parameter has more isolated solutions than the generic count).
//! - **Morgan, Sommese and Wampler 1991**: A. P. Morgan, A. J. Sommese, C. W. Wampler,
//!   "Computing singular solutions to nonlinear analytic systems", Numerische Mathematik 58
//!   (1991) 669–684 (the Cauchy endgame).
//! - **Wampler 1994**: C. W. Wampler, "An efficient start system for multi-homogeneous
//!   polynomial continuation", Numerische Mathematik 66 (1994) 517–523 (searching variable
//!   groupings for the least multi-homogeneous Bézout number).
//! - **Griewank and Osborne 1983**: A. Griewank, M. R. Osborne, "Analysis of Newton's method
//!   at irregular singularities", SIAM Journal on Numerical Analysis 20 (4) (1983) 747–773 (the
//!   linear convergence that tells a point at infinity of the Fritz John chart).
//! - **Hairer, Nørsett and Wanner**: E. Hairer, S. P. Nørsett, G. Wanner, "Solving ordinary
//!   differential equations I: nonstiff problems", 2nd ed., Springer, 1993 (the step-size
//!   controller of the path tracker).
//! - **Sommese and Wampler**: A. J. Sommese, C. W. Wampler, "The numerical solution of systems
//!   of polynomials arising in engineering and science", World Scientific, 2005.
//! - **Duff et al. 2019**: T. Duff, C. Hill, A. Jensen, K. Lee, A. Leykin, J. Sommars, "Solving
//!   polynomial systems via homotopy continuation and monodromy", IMA Journal of Numerical
//!   Analysis 39 (2019) (monodromy solving).
//! - **Sommese, Verschelde and Wampler 2002**: A. J. Sommese, J. Verschelde, C. W. Wampler,
//!   "Symmetric functions applied to decomposing solution sets of polynomial systems", SIAM
//!   Journal on Numerical Analysis 40 (6) (2002) (the trace test).
//! - **Leykin, Rodriguez and Sottile 2018**: A. Leykin, J. I. Rodriguez, F. Sottile, "Trace
//!   test", Arnold Mathematical Journal 4 (2018) 113–125.
//! - **Huber and Verschelde**: B. Huber, J. Verschelde, "Polyhedral end games for polynomial
//!   continuation", Numerical Algorithms 18 (1998) 91–108 (the power-series test for paths
//!   to infinity).
//! - **Verschelde, Verlinden and Cools 1994**: J. Verschelde, P. Verlinden, R. Cools,
//!   "Homotopies exploiting Newton polytopes for solving sparse polynomial systems", SIAM
//!   Journal on Numerical Analysis 31 (3) (1994) 915–930 (the relation table and pruning of
//!   the mixed-cell search).
//! - **Li 2003**: T. Y. Li, "Numerical solution of polynomial systems by homotopy
//!   continuation methods", Handbook of Numerical Analysis XI, North-Holland, 2003 (polyhedral
//!   homotopies, binomial start systems, the mixed-cell search).
//! - **Telen, Van Barel and Verschelde 2020**: S. Telen, M. Van Barel, J. Verschelde, "A
//!   robust numerical path tracking algorithm for polynomial homotopy continuation", SIAM
//!   Journal on Scientific Computing 42 (6) (2020) A3610–A3637 (pole estimates along a path).
//! - **Bates, Hauenstein, Sommese and Wampler**: D. J. Bates, J. D. Hauenstein, A. J. Sommese,
//!   C. W. Wampler, "Adaptive multiprecision path tracking", SIAM Journal on Numerical
//!   Analysis 46 (2) (2008) 722–746.
//! - **Bertini**: D. J. Bates, J. D. Hauenstein, A. J. Sommese, C. W. Wampler, "Bertini:
//!   Software for numerical algebraic geometry", bertini.nd.edu, doi:10.7274/R0H41PB5 (2013);
//!   D. J. Bates, A. J. Sommese, J. D. Hauenstein, C. W. Wampler, "Numerically solving
//!   polynomial systems with Bertini", SIAM, 2013 (the input format `singdist system` reads
//!   and writes).
//! - **PHCpack**: J. Verschelde, "Algorithm 795: PHCpack: a general-purpose solver for
//!   polynomial systems by homotopy continuation", ACM Transactions on Mathematical Software
//!   25 (2) (1999) 251–276 (the export format of `singdist system export --to phc`).
//! - **Blum, Cucker, Shub and Smale**: L. Blum, F. Cucker, M. Shub, S. Smale, "Complexity and
//!   real computation", Springer, 1998 (α-theory).
//!
//! ## Certification and floating-point arithmetic
//!
//! - **Krawczyk 1969**: R. Krawczyk, "Newton-Algorithmen zur Bestimmung von Nullstellen mit
//!   Fehlerschranken", Computing 4 (1969) 187–201.
//! - **Moore 1977**: R. E. Moore, "A test for existence of solutions to nonlinear systems",
//!   SIAM Journal on Numerical Analysis 14 (1977).
//! - **Rump 2010**: S. M. Rump, "Verification methods: Rigorous results using floating-point
//!   arithmetic", Acta Numerica 19 (2010).
//! - **Rump 1999**: S. M. Rump, "Fast and parallel interval arithmetic", BIT Numerical
//!   Mathematics 39 (1999).
//! - **Rump 2012**: S. M. Rump, "Fast interval matrix multiplication", Numerical
//!   Algorithms 61 (2012) 1–34.
//! - **Breiding, Rose and Timme 2023**: P. Breiding, K. Rose, S. Timme, "Certifying zeros of
//!   polynomial systems using interval arithmetic", ACM Transactions on Mathematical Software
//!   (2023).
//! - **Moore, Kearfott and Cloud**: R. E. Moore, R. B. Kearfott, M. J. Cloud, "Introduction to
//!   interval analysis", SIAM, 2009.
//! - **Dekker 1971**: T. J. Dekker, "A floating-point technique for extending the available
//!   precision", Numerische Mathematik 18 (1971) 224–242.
//! - **Hida, Li and Bailey**: Y. Hida, X. S. Li, D. H. Bailey, "Algorithms for quad-double
//!   precision floating point arithmetic", 2001.
//! - **Higham**: N. J. Higham, "Accuracy and stability of numerical algorithms", 2nd ed.,
//!   SIAM, 2002.
//! - **Golub and Van Loan**: G. H. Golub, C. F. Van Loan, "Matrix computations", Johns Hopkins
//!   University Press.
//!
//! ## Other numerical methods cited in the code
//!
//! - **Nocedal and Wright**: J. Nocedal, S. J. Wright, "Numerical optimization", 2nd ed.,
//!   Springer, 2006 (the reference local minimisation).
//! - **Griewank and Walther**: A. Griewank, A. Walther, "Evaluating derivatives", SIAM, 2008.
//! - **Squire and Trapp**: W. Squire, G. Trapp, "Using complex variables to estimate
//!   derivatives of real functions", SIAM Review 40 (1998).
//! - **Wong**: B. Wong, "Points of view: Color blindness", Nature Methods 2011 (the plot
//!   colours).

pub mod algebra;
#[macro_use]
pub mod choice;
pub mod analysis;
pub mod certify;
pub mod homotopy;
pub mod index;
pub mod io;
pub mod mechanism;
pub mod metric;
pub mod optimize;
pub mod pipeline;
pub mod problem;
pub mod random;
pub mod reference;
pub mod system;

/// Complex double, the scalar of every numerical routine.
pub type C64 = num_complex::Complex64;

/// `|z| = √(re² + im²)` without the overflow guard of [`num_complex::Complex::norm`]
/// (`hypot`, several times slower; it was 10 % of a curve run's profile). Exact to
/// rounding for `|z| < 1e150`, which covers every finite point the tracker keeps.
#[inline(always)]
pub fn modulus(z: C64) -> f64 {
    z.norm_sqr().sqrt()
}
