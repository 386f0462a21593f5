//! The stages of the main job (SPEC A.9): ab-initio, user homotopy, parameter homotopy, post-processing.
