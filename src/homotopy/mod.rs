//! Homotopy continuation: homotopies, predictor–corrector path tracking, endgame and path classification, start systems, monodromy with trace test, and the parallel `solve`.
