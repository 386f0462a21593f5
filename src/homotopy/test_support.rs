//! Helpers shared by the homotopy tests: small systems in Bertini syntax and path
//! results made by hand.

use super::{PathResult, PathStatus};
use crate::C64;
use crate::system::CompiledSystem;

/// Equations `f`, `g` in `x`, `y` (Bertini syntax), compiled.
pub(crate) fn read_xy(equations: &str) -> CompiledSystem {
    let text = format!("INPUT\nvariable_group x, y;\nfunction f, g;\n{equations}\nEND;\n");
    crate::system::bertini::read(&text).unwrap().compile()
}

/// A path `index` of ten steps that ended with `status` at `solution` (residual 0,
/// condition 1, winding number and multiplicity 1, at `t = 1`).
pub(crate) fn path_result(index: usize, status: PathStatus, solution: Vec<C64>) -> PathResult {
    PathResult {
        path_index: index,
        solution,
        status,
        residual: 0.0,
        condition: 1.0,
        winding_number: 1,
        multiplicity: 1,
        steps: 10,
        rejected_steps: 0,
        used_extended_precision: false,
        last_t: C64::new(1.0, 0.0),
        stalled_at_infinity: false,
    }
}
