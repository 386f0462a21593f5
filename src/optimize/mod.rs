//! Seeded genetic algorithm and local constrained refinement, for redundancy resolution and design optimisation (SPEC D.3, D.5).
