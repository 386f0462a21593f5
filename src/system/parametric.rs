//! A square parametric polynomial system `F(x; p) = 0` kept with its compiled
//! evaluator: what every mechanism's sub-problem (the 3-RPR Lagrange problems, the
//! 3-RRR ones) hands to the solvers, with the names of its unknowns and parameters.

use super::{CompiledSystem, System};

/// A symbolic system and its compiled evaluator ([`System::compile`]).
#[derive(Clone)]
pub struct ParametricSystem {
    system: System,
    compiled: CompiledSystem,
}

impl ParametricSystem {
    /// Compiles `system` and keeps both.
    pub fn new(system: System) -> Self {
        ParametricSystem {
            compiled: system.compile(),
            system,
        }
    }

    /// The symbolic system.
    pub fn system(&self) -> &System {
        &self.system
    }

    /// The compiled system, for the tracker.
    pub fn evaluator(&self) -> &CompiledSystem {
        &self.compiled
    }

    /// Names of the unknowns, in order.
    pub fn variable_names(&self) -> &[String] {
        self.system.variables()
    }

    /// Names of the parameters, in order.
    pub fn parameter_names(&self) -> &[String] {
        self.system.parameters()
    }
}
