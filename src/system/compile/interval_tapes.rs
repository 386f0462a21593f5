//! The compiled tapes run in interval arithmetic: `F` and `∂F/∂x` over boxes in
//! midpoint–radius form with double midpoints ([`MidRad`]), and `F` at a point with
//! double-double midpoints ([`MidRadDd`]), for certification
//! ([`crate::certify::krawczyk`]).

use super::{CompiledSystem, Tape};
use crate::C64;
use crate::system::interval::{ComplexInterval, MidRad};
use crate::system::interval_dd::{MidRadDd, coefficient};

impl CompiledSystem {
    /// `F` and `∂F/∂x` over the complex box `x` at the parameter box `p`, in interval
    /// arithmetic with outward rounding ([`crate::system::interval`]): `f[i]` contains
    /// `F_i(ξ; π)` and `jac[i·n + j]` contains `∂F_i/∂x_j(ξ; π)` for every `ξ ∈ x`,
    /// `π ∈ p`. The same tape as [`crate::system::Evaluator::evaluate_with_jacobian`], run on
    /// intervals (each register then encloses the exact value of its subexpression).
    pub fn evaluate_interval_with_jacobian(
        &self,
        x: &[ComplexInterval],
        p: &[ComplexInterval],
        f: &mut [ComplexInterval],
        jac: &mut [ComplexInterval],
    ) {
        let parts = &self.parts;
        let (n, m, k) = (
            parts.variables.len(),
            parts.parameters.len(),
            parts.num_equations,
        );
        assert_eq!(x.len(), n, "interval evaluation: variable count");
        assert_eq!(p.len(), m, "interval evaluation: parameter count");
        assert_eq!(f.len(), k, "interval evaluation: equation count");
        assert_eq!(jac.len(), k * n, "interval evaluation: Jacobian size");
        let outputs = f.iter_mut().chain(jac.iter_mut());
        run_interval(&parts.values_and_jacobian, (x, p), outputs);
    }

    /// `F` over the complex box `x` at the parameter box `p` (as
    /// [`CompiledSystem::evaluate_interval_with_jacobian`], without the Jacobian: the
    /// tape of [`crate::system::Evaluator::evaluate`] run on intervals).
    pub fn evaluate_interval(
        &self,
        x: &[ComplexInterval],
        p: &[ComplexInterval],
        f: &mut [ComplexInterval],
    ) {
        let parts = &self.parts;
        assert_eq!(
            x.len(),
            parts.variables.len(),
            "interval evaluation: variable count"
        );
        assert_eq!(
            p.len(),
            parts.parameters.len(),
            "interval evaluation: parameter count"
        );
        assert_eq!(
            f.len(),
            parts.num_equations,
            "interval evaluation: equation count"
        );
        run_interval(&parts.values, (x, p), f.iter_mut());
    }

    /// `F` at `x` over the parameters `p`, both with double-double midpoints
    /// ([`crate::system::interval_dd`]): every register encloses the exact value of its
    /// subexpression, with each constant taken as the exact coefficient it is the
    /// rounding of ([`coefficient`]). `false` (and `f` untouched) where a constant is
    /// not recognised. Allocates its registers: it serves the rare points that double
    /// precision cannot certify.
    pub fn evaluate_interval_dd(&self, x: &[MidRadDd], p: &[MidRadDd], f: &mut [MidRadDd]) -> bool {
        let tape = &self.parts.values;
        let (n, m) = (x.len(), p.len());
        assert_eq!(
            n,
            self.parts.variables.len(),
            "interval evaluation: variable count"
        );
        assert_eq!(
            m,
            self.parts.parameters.len(),
            "interval evaluation: parameter count"
        );
        assert_eq!(
            f.len(),
            self.parts.num_equations,
            "interval evaluation: equation count"
        );
        let mut registers = vec![MidRadDd::default(); tape.workspace_len()];
        registers[..n].copy_from_slice(x);
        registers[n..n + m].copy_from_slice(p);
        for (r, c) in registers[tape.num_inputs..].iter_mut().zip(&tape.constants) {
            match coefficient(*c) {
                Some(v) => *r = v,
                None => return false,
            }
        }
        tape.execute_dispatched(&mut registers);
        for (target, &(register, sign)) in f.iter_mut().zip(&tape.outputs) {
            let value = registers[register as usize];
            *target = if sign < 0.0 { -value } else { value };
        }
        true
    }
}

/// Runs `tape` in interval arithmetic on the variables `x` and parameters `p` and
/// writes its outputs, in order, to `outputs`. The registers hold midpoint–radius
/// rectangles ([`MidRad`]: the boxes are converted exactly, the outputs rounded
/// outwards), and the tape runs in the copy compiled for AVX2 and FMA where the CPU has
/// them (the operations and their rounding are the same: no fused multiply–add is
/// formed from separate `*` and `+`).
fn run_interval<'a>(
    tape: &Tape,
    (x, p): (&[ComplexInterval], &[ComplexInterval]),
    outputs: impl Iterator<Item = &'a mut ComplexInterval>,
) {
    let (n, m) = (x.len(), p.len());
    // The registers are reused per thread (no allocation per evaluation); every one
    // read is written first: inputs (those of other tapes zeroed) and constants here,
    // temporaries by the tape.
    thread_local! {
        static REGISTERS: std::cell::RefCell<Vec<MidRad>> =
            const { std::cell::RefCell::new(Vec::new()) };
    }
    let zero = MidRad::point(C64::new(0.0, 0.0));
    REGISTERS.with(|cell| {
        let mut registers = cell.borrow_mut();
        let len = tape.workspace_len();
        if registers.len() < len {
            registers.resize(len, zero);
        }
        let registers = &mut registers[..len];
        for (r, v) in registers.iter_mut().zip(x.iter().chain(p)) {
            *r = MidRad::from_interval(v);
        }
        let constants_start = tape.num_inputs;
        registers[n + m..constants_start].fill(zero);
        registers[constants_start..constants_start + tape.interval_constants.len()]
            .copy_from_slice(&tape.interval_constants);
        tape.execute_dispatched(registers);
        for (target, &(register, sign)) in outputs.zip(&tape.outputs) {
            let value = registers[register as usize];
            *target = if sign < 0.0 { -value } else { value }.to_interval();
        }
    });
}
