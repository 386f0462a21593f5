//! Compilation of a [`System`] to straight-line programs ("tapes").
//!
//! Method: exact symbolic derivatives (∂F/∂x, ∂F/∂p) are formed once with
//! [`Expr::differentiate`]; then F and its derivatives are lowered together into one
//! sequence of two-operand complex instructions (`+ − × neg`) in static single
//! assignment form. Lowering merges common subexpressions twice: nodes shared in the
//! expression DAG are lowered once (memoised by node identity), and structurally equal
//! instructions are emitted once (hash-consing on `(op, operand, operand)`, with the
//! operands of `+` and `×` put in canonical order). Integer powers become
//! square-and-multiply chains whose intermediate powers are shared through the same
//! hash-consing. Because F, ∂F/∂x (and ∂F/∂p) share one tape, the products that appear
//! in several partial derivatives are computed once.
//!
//! Registers live in the caller's workspace: `[x | p | dp | constants | temporaries]`.
//! An evaluation copies the inputs and constants in, runs the instructions, and copies
//! the output registers out: no allocation, no branching on the expression shape.

use super::{Evaluator, System};
use crate::C64;
use crate::system::expr::{Expr, Kind};
use std::collections::HashMap;
use std::sync::Arc;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Op {
    Add,
    Sub,
    Mul,
    Neg,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Operand {
    Input(u32),
    Constant(u32),
    Temporary(u32),
}

/// One instruction `work[destination] ← work[a] op work[b]`, with the destination the
/// next temporary register.
#[derive(Clone, Copy, Debug)]
struct Instruction {
    op: Op,
    a: u32,
    b: u32,
}

/// A finished straight-line program.
#[derive(Clone, Debug)]
struct Tape {
    /// Number of input registers at the start of the workspace.
    num_inputs: usize,
    constants: Vec<C64>,
    instructions: Vec<Instruction>,
    /// Register of each output value.
    outputs: Vec<u32>,
}

impl Tape {
    fn workspace_len(&self) -> usize {
        self.num_inputs + self.constants.len() + self.instructions.len()
    }

    #[inline]
    fn run(&self, work: &mut [C64]) {
        let constants_start = self.num_inputs;
        let temporaries_start = constants_start + self.constants.len();
        assert!(
            work.len() >= self.workspace_len(),
            "workspace shorter than workspace_len()"
        );
        work[constants_start..temporaries_start].copy_from_slice(&self.constants);
        let registers = work.as_mut_ptr();
        for (k, instruction) in self.instructions.iter().enumerate() {
            // SAFETY: `TapeBuilder::finish` only emits operands that are inputs,
            // constants or earlier temporaries, so `a, b < temporaries_start + k`, and
            // the destination `temporaries_start + k < workspace_len() <= work.len()`
            // (asserted above). The pointer comes from a live `&mut [C64]`.
            unsafe {
                let a = *registers.add(instruction.a as usize);
                let b = *registers.add(instruction.b as usize);
                let value = match instruction.op {
                    Op::Add => a + b,
                    Op::Sub => a - b,
                    Op::Mul => a * b,
                    Op::Neg => -a,
                };
                *registers.add(temporaries_start + k) = value;
            }
        }
    }

    #[inline]
    fn write_outputs(&self, work: &[C64], out: &mut [C64]) {
        for (target, &register) in out.iter_mut().zip(&self.outputs) {
            *target = work[register as usize];
        }
    }
}

/// Builds one tape; inputs are addressed by index, symbols resolved through `inputs`.
struct TapeBuilder<'a> {
    inputs: &'a HashMap<&'a str, u32>,
    num_inputs: usize,
    constants: Vec<C64>,
    constant_index: HashMap<(u64, u64), u32>,
    instructions: Vec<(Op, Operand, Operand)>,
    instruction_index: HashMap<(Op, Operand, Operand), Operand>,
    lowered: HashMap<usize, Operand>,
    /// Keeps lowered expressions alive so that node identities stay unique.
    keep_alive: Vec<Expr>,
}

impl<'a> TapeBuilder<'a> {
    fn new(inputs: &'a HashMap<&'a str, u32>, num_inputs: usize) -> Self {
        TapeBuilder {
            inputs,
            num_inputs,
            constants: Vec::new(),
            constant_index: HashMap::new(),
            instructions: Vec::new(),
            instruction_index: HashMap::new(),
            lowered: HashMap::new(),
            keep_alive: Vec::new(),
        }
    }

    fn constant(&mut self, value: C64) -> Operand {
        let key = (value.re.to_bits(), value.im.to_bits());
        if let Some(&index) = self.constant_index.get(&key) {
            return Operand::Constant(index);
        }
        let index = self.constants.len() as u32;
        self.constants.push(value);
        self.constant_index.insert(key, index);
        Operand::Constant(index)
    }

    fn emit(&mut self, op: Op, a: Operand, b: Operand) -> Operand {
        let (a, b) = match op {
            Op::Add | Op::Mul if b < a => (b, a),
            Op::Neg => (a, a),
            _ => (a, b),
        };
        let key = (op, a, b);
        if let Some(&existing) = self.instruction_index.get(&key) {
            return existing;
        }
        let result = Operand::Temporary(self.instructions.len() as u32);
        self.instructions.push(key);
        self.instruction_index.insert(key, result);
        result
    }

    fn power(&mut self, base: Operand, exponent: u32) -> Operand {
        match exponent {
            0 => self.constant(C64::new(1.0, 0.0)),
            1 => base,
            e if e % 2 == 0 => {
                let half = self.power(base, e / 2);
                self.emit(Op::Mul, half, half)
            }
            e => {
                let rest = self.power(base, e - 1);
                self.emit(Op::Mul, rest, base)
            }
        }
    }

    /// Lowers `e` (symbols must all be inputs; checked when the system was built).
    fn lower(&mut self, e: &Expr) -> Operand {
        if let Some(&done) = self.lowered.get(&e.node_id()) {
            return done;
        }
        let result = match e.kind() {
            Kind::Constant(c) => self.constant(*c),
            Kind::Symbol(name) => match self.inputs.get(&**name) {
                Some(&index) => Operand::Input(index),
                // Unreachable for a validated system; lowering a NaN keeps it total.
                None => self.constant(C64::new(f64::NAN, f64::NAN)),
            },
            Kind::Add(a, b) => {
                let (a, b) = (self.lower(a), self.lower(b));
                self.emit(Op::Add, a, b)
            }
            Kind::Sub(a, b) => {
                let (a, b) = (self.lower(a), self.lower(b));
                self.emit(Op::Sub, a, b)
            }
            Kind::Mul(a, b) => {
                let (a, b) = (self.lower(a), self.lower(b));
                self.emit(Op::Mul, a, b)
            }
            Kind::Neg(a) => {
                let a = self.lower(a);
                self.emit(Op::Neg, a, a)
            }
            Kind::Pow(a, n) => {
                let a = self.lower(a);
                self.power(a, *n)
            }
        };
        self.lowered.insert(e.node_id(), result);
        self.keep_alive.push(e.clone());
        result
    }

    fn finish(self, outputs: &[Operand]) -> Tape {
        let constants_start = self.num_inputs as u32;
        let temporaries_start = constants_start + self.constants.len() as u32;
        let register = |operand: Operand| match operand {
            Operand::Input(i) => i,
            Operand::Constant(i) => constants_start + i,
            Operand::Temporary(i) => temporaries_start + i,
        };
        let instructions: Vec<Instruction> = self
            .instructions
            .iter()
            .map(|&(op, a, b)| Instruction {
                op,
                a: register(a),
                b: register(b),
            })
            .collect();
        // The invariant `Tape::run` relies on: every operand is already computed.
        for (k, instruction) in instructions.iter().enumerate() {
            let limit = temporaries_start as usize + k;
            assert!((instruction.a as usize) < limit && (instruction.b as usize) < limit);
        }
        Tape {
            num_inputs: self.num_inputs,
            instructions,
            outputs: outputs.iter().map(|&o| register(o)).collect(),
            constants: self.constants,
        }
    }
}

/// Symbolic partial derivatives `∂f_i/∂s` for every equation and every symbol in
/// `symbols`, row-major (equation, symbol).
fn symbolic_jacobian(equations: &[Expr], symbols: &[String]) -> Vec<Expr> {
    let mut columns: Vec<Vec<Expr>> = Vec::with_capacity(symbols.len());
    for symbol in symbols {
        let mut memo = HashMap::new();
        columns.push(
            equations
                .iter()
                .map(|f| f.differentiate_memo(symbol, &mut memo))
                .collect(),
        );
    }
    let mut jacobian = Vec::with_capacity(equations.len() * symbols.len());
    for i in 0..equations.len() {
        for column in &columns {
            jacobian.push(column[i].clone());
        }
    }
    jacobian
}

#[derive(Debug)]
struct CompiledParts {
    variables: Vec<String>,
    parameters: Vec<String>,
    num_equations: usize,
    values: Tape,
    values_and_jacobian: Tape,
    parameter_jacobian: Tape,
    parameter_derivative: Tape,
    workspace_len: usize,
}

/// A [`System`] compiled to straight-line programs; implements [`Evaluator`].
///
/// Cheap to clone (shared tapes), `Send + Sync`; each thread brings its own workspace
/// from [`CompiledSystem::new_workspace`].
#[derive(Clone, Debug)]
pub struct CompiledSystem {
    parts: Arc<CompiledParts>,
}

impl CompiledSystem {
    /// Compiles `system` (see the module documentation for the method).
    pub fn new(system: &System) -> CompiledSystem {
        let variables = system.variables().to_vec();
        let parameters = system.parameters().to_vec();
        let equations = system.equations();
        let (n, m) = (variables.len(), parameters.len());
        let mut inputs: HashMap<&str, u32> = HashMap::new();
        for (i, name) in variables.iter().chain(parameters.iter()).enumerate() {
            inputs.insert(name.as_str(), i as u32);
        }
        let num_inputs = n + 2 * m;

        let jacobian_x = symbolic_jacobian(equations, &variables);
        let jacobian_p = symbolic_jacobian(equations, &parameters);

        let mut builder = TapeBuilder::new(&inputs, num_inputs);
        let outputs: Vec<Operand> = equations.iter().map(|f| builder.lower(f)).collect();
        let values = builder.finish(&outputs);

        let mut builder = TapeBuilder::new(&inputs, num_inputs);
        let outputs: Vec<Operand> = equations
            .iter()
            .chain(jacobian_x.iter())
            .map(|f| builder.lower(f))
            .collect();
        let values_and_jacobian = builder.finish(&outputs);

        let mut builder = TapeBuilder::new(&inputs, num_inputs);
        let outputs: Vec<Operand> = jacobian_p.iter().map(|f| builder.lower(f)).collect();
        let parameter_jacobian = builder.finish(&outputs);

        // Σ_k ∂f_i/∂p_k · dp_k with dp_k in input registers n + m + k.
        let mut builder = TapeBuilder::new(&inputs, num_inputs);
        let mut outputs = Vec::with_capacity(equations.len());
        for i in 0..equations.len() {
            let mut sum: Option<Operand> = None;
            for k in 0..m {
                let entry = &jacobian_p[i * m + k];
                if entry.is_zero() {
                    continue;
                }
                let derivative = builder.lower(entry);
                let term = builder.emit(Op::Mul, derivative, Operand::Input((n + m + k) as u32));
                sum = Some(match sum {
                    None => term,
                    Some(previous) => builder.emit(Op::Add, previous, term),
                });
            }
            let zero = builder.constant(C64::new(0.0, 0.0));
            outputs.push(sum.unwrap_or(zero));
        }
        let parameter_derivative = builder.finish(&outputs);

        let workspace_len = [
            &values,
            &values_and_jacobian,
            &parameter_jacobian,
            &parameter_derivative,
        ]
        .iter()
        .map(|t| t.workspace_len())
        .max()
        .unwrap_or(num_inputs);

        CompiledSystem {
            parts: Arc::new(CompiledParts {
                variables,
                parameters,
                num_equations: equations.len(),
                values,
                values_and_jacobian,
                parameter_jacobian,
                parameter_derivative,
                workspace_len,
            }),
        }
    }

    /// Names of the unknowns, in the order of `x`.
    pub fn variable_names(&self) -> &[String] {
        &self.parts.variables
    }

    /// Names of the parameters, in the order of `p`.
    pub fn parameter_names(&self) -> &[String] {
        &self.parts.parameters
    }

    /// A zeroed workspace of length [`Evaluator::workspace_len`].
    pub fn new_workspace(&self) -> Vec<C64> {
        vec![C64::new(0.0, 0.0); self.parts.workspace_len]
    }

    /// Number of instructions of the F + ∂F/∂x tape (a size measure for reports).
    pub fn jacobian_instruction_count(&self) -> usize {
        self.parts.values_and_jacobian.instructions.len()
    }

    /// Sizes of the tapes: instructions of (F, F + ∂F/∂x, ∂F/∂p, (∂F/∂p)·dp) and
    /// the number of multiplications of the F + ∂F/∂x tape.
    pub fn tape_statistics(&self) -> ([usize; 4], usize) {
        let parts = &self.parts;
        let multiplications = parts
            .values_and_jacobian
            .instructions
            .iter()
            .filter(|i| i.op == Op::Mul)
            .count();
        (
            [
                parts.values.instructions.len(),
                parts.values_and_jacobian.instructions.len(),
                parts.parameter_jacobian.instructions.len(),
                parts.parameter_derivative.instructions.len(),
            ],
            multiplications,
        )
    }

    #[inline]
    fn load(&self, x: &[C64], p: &[C64], work: &mut [C64]) {
        let n = self.parts.variables.len();
        let m = self.parts.parameters.len();
        debug_assert_eq!(x.len(), n);
        debug_assert_eq!(p.len(), m);
        debug_assert!(work.len() >= self.parts.workspace_len);
        work[..n].copy_from_slice(x);
        work[n..n + m].copy_from_slice(p);
    }
}

impl Evaluator for CompiledSystem {
    fn num_variables(&self) -> usize {
        self.parts.variables.len()
    }

    fn num_equations(&self) -> usize {
        self.parts.num_equations
    }

    fn num_parameters(&self) -> usize {
        self.parts.parameters.len()
    }

    fn workspace_len(&self) -> usize {
        self.parts.workspace_len
    }

    fn evaluate(&self, x: &[C64], p: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.load(x, p, work);
        let tape = &self.parts.values;
        tape.run(work);
        tape.write_outputs(work, f);
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) {
        self.load(x, p, work);
        let tape = &self.parts.values_and_jacobian;
        tape.run(work);
        let k = self.parts.num_equations;
        for (target, &register) in f.iter_mut().zip(&tape.outputs[..k]) {
            *target = work[register as usize];
        }
        for (target, &register) in jac.iter_mut().zip(&tape.outputs[k..]) {
            *target = work[register as usize];
        }
    }

    fn evaluate_parameter_derivative(
        &self,
        x: &[C64],
        p: &[C64],
        dp: &[C64],
        work: &mut [C64],
        out: &mut [C64],
    ) {
        self.load(x, p, work);
        let n = self.parts.variables.len();
        let m = self.parts.parameters.len();
        debug_assert_eq!(dp.len(), m);
        work[n + m..n + 2 * m].copy_from_slice(dp);
        let tape = &self.parts.parameter_derivative;
        tape.run(work);
        tape.write_outputs(work, out);
    }

    fn evaluate_parameter_jacobian(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        jac_p: &mut [C64],
    ) {
        self.load(x, p, work);
        let tape = &self.parts.parameter_jacobian;
        tape.run(work);
        tape.write_outputs(work, jac_p);
    }
}
