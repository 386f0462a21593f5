//! Compilation of a [`System`] to straight-line programs ("tapes").
//!
//! Method: exact symbolic derivatives (∂F/∂x, ∂F/∂p) are formed once with
//! [`Expr::differentiate`]; then F and its derivatives are lowered together into one
//! sequence of two-operand complex instructions (`+ − ×`) in static single assignment
//! form. Lowering merges common subexpressions three ways: nodes shared in the
//! expression DAG are lowered once (memoised by node identity); structurally equal
//! instructions are emitted once (hash-consing on `(op, operand, operand)`, with the
//! operands of `+` and `×` put in canonical order); and negations are carried as a
//! sign of the lowered value instead of instructions, so `a − b` and `b − a`, `c·x` and
//! `−c·x` share one instruction (a negated output is negated when copied out). Integer
//! powers become square-and-multiply chains whose intermediate powers are shared
//! through the same hash-consing. Because F, ∂F/∂x (and ∂F/∂p) share one tape, the
//! products that appear in several partial derivatives are computed once.
//!
//! When the tape is finished, every product whose only use is a sum or difference is
//! fused into it (`c + a·b`, `c − a·b`, `a·b − c`), and the instructions are scheduled
//! level by level (independent instructions together) and grouped into blocks of one
//! operation, so the evaluation loop does not branch on the operation per instruction.
//!
//! Registers live in the caller's workspace: `[x | p | dp | constants | temporaries]`.
//! An evaluation copies the inputs and constants in, runs the instructions, and copies
//! the output registers out: no allocation, no branching on the expression shape.

use super::{Evaluator, System};
use crate::C64;
use crate::system::double_double::ComplexDd;
use crate::system::expr::{Expr, Kind};
use crate::system::interval::{ComplexInterval, MidRad};
use crate::system::interval_dd::{MidRadDd, coefficient_enclosure};
use std::collections::HashMap;

mod interval_tapes;
use std::sync::Arc;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Op {
    Add,
    Sub,
    Mul,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Operand {
    Input(u32),
    Constant(u32),
    Temporary(u32),
}

/// An operand with a sign: the value is `−operand` when `negated`.
#[derive(Clone, Copy, Debug)]
struct Signed {
    operand: Operand,
    negated: bool,
}

impl Signed {
    fn positive(operand: Operand) -> Signed {
        Signed {
            operand,
            negated: false,
        }
    }

    fn negative(operand: Operand) -> Signed {
        Signed {
            operand,
            negated: true,
        }
    }

    fn negate(self) -> Signed {
        Signed {
            negated: !self.negated,
            ..self
        }
    }
}

/// One instruction `work[destination] ← work[a] op work[b]`, with the destination the
/// next temporary register.
#[derive(Clone, Copy, Debug)]
struct Instruction {
    op: TapeOp,
    a: u32,
    b: u32,
    /// Third operand of the fused operations (equal to `a` otherwise).
    c: u32,
}

/// Operations of a finished tape: the builder's `+ − ×`, and a product fused with the
/// sum or difference that is its only use (saves a register round trip).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TapeOp {
    Add,
    Sub,
    Mul,
    /// `c + a·b`
    MulAdd,
    /// `c − a·b`
    MulSubtractedFrom,
    /// `a·b − c`
    MulMinus,
    /// `a · Re(b)` for a real constant `b` (two real products instead of four).
    Scale,
}

/// The arithmetic a tape runs in: complex doubles, or complex double-doubles for
/// extended-precision residuals.
trait TapeScalar:
    Copy + std::ops::Add<Output = Self> + std::ops::Sub<Output = Self> + std::ops::Mul<Output = Self>
{
    /// `self · Re(b)` (two real products instead of four).
    fn scale_by_real_part(self, b: Self) -> Self;
}

impl TapeScalar for C64 {
    #[inline]
    fn scale_by_real_part(self, b: Self) -> Self {
        self * b.re
    }
}

impl TapeScalar for ComplexDd {
    #[inline(always)]
    fn scale_by_real_part(self, b: Self) -> Self {
        ComplexDd::scale_by_real_part(self, b)
    }
}

impl TapeScalar for ComplexInterval {
    #[inline]
    fn scale_by_real_part(self, b: Self) -> Self {
        self.scale(b.re)
    }
}

impl TapeScalar for MidRad {
    #[inline(always)]
    fn scale_by_real_part(self, b: Self) -> Self {
        MidRad::scale_by_real_part(self, b)
    }
}

impl TapeScalar for MidRadDd {
    #[inline(always)]
    fn scale_by_real_part(self, b: Self) -> Self {
        MidRadDd::scale_by_real_part(self, b)
    }
}

/// A finished straight-line program.
#[derive(Clone, Debug)]
struct Tape {
    /// Number of input registers at the start of the workspace.
    num_inputs: usize,
    constants: Vec<C64>,
    /// The constants as intervals for [`run_interval`]: each encloses the exact
    /// coefficient its double is the rounding of ([`coefficient_enclosure`]: `1/3`,
    /// `1/√2`, …),
    /// so that a certificate is about the system itself, not about its rounded
    /// coefficients (a constant not recognised stands for itself).
    interval_constants: Vec<MidRad>,
    instructions: Vec<Instruction>,
    /// Runs `start..end` of consecutive instructions with the same operation, so the
    /// inner loops do not branch on the operation.
    blocks: Vec<Block>,
    /// Register of each output value, and the sign (±1) it is multiplied by (a
    /// multiplication rather than a data-dependent branch, which mispredicts).
    outputs: Vec<(u32, f64)>,
}

/// A run of instructions with the same operation.
#[derive(Clone, Copy, Debug)]
struct Block {
    op: TapeOp,
    start: u32,
    end: u32,
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
        self.execute_dispatched(work);
    }

    /// [`Tape::execute`] in double-double (see [`Tape::execute_dispatched`]).
    fn execute_double_double(&self, registers: &mut [ComplexDd]) {
        self.execute_dispatched(registers);
    }

    /// [`Tape::execute`], compiled a second time with the `avx2` and `fma` target
    /// features and chosen at run time where the CPU has them. In double precision the
    /// operations are the same (no explicit `mul_add`), so the rounding is too; in
    /// double-double the exact products become one FMA instruction each.
    #[inline(always)]
    fn execute_dispatched<T: TapeScalar>(&self, registers: &mut [T]) {
        #[cfg(target_arch = "x86_64")]
        if crate::system::double_double::has_avx2_fma() {
            // SAFETY: the CPU supports AVX2 and FMA (checked at run time just above).
            unsafe { self.execute_with_avx2_fma(registers) };
            return;
        }
        self.execute(registers);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn execute_with_avx2_fma<T: TapeScalar>(&self, registers: &mut [T]) {
        self.execute(registers);
    }

    /// Runs the instructions on `registers` (inputs and constants already loaded),
    /// block by block so the inner loops do not branch on the operation. (Always
    /// inlined, so [`Tape::execute_with_avx2_fma`] compiles it with those features.)
    #[inline(always)]
    fn execute<T: TapeScalar>(&self, registers: &mut [T]) {
        let temporaries_start = self.num_inputs + self.constants.len();
        assert!(
            registers.len() >= self.workspace_len(),
            "workspace shorter than workspace_len()"
        );
        let registers = registers.as_mut_ptr();
        let instructions = self.instructions.as_slice();
        // SAFETY (all blocks): `TapeBuilder::finish` checks that every operand of
        // instruction k is an input, a constant or a temporary computed before k, so
        // `a, b < temporaries_start + k`, that the blocks cover `0..instructions.len()`,
        // and the destination `temporaries_start + k < workspace_len() <= len`
        // (asserted above). The pointer comes from a live `&mut [T]`.
        macro_rules! run_block {
            ($block:expr, |$a:ident, $b:ident, $c:ident| $value:expr) => {
                for k in $block.start as usize..$block.end as usize {
                    let instruction = &instructions[k];
                    unsafe {
                        let $a = *registers.add(instruction.a as usize);
                        let $b = *registers.add(instruction.b as usize);
                        let $c = *registers.add(instruction.c as usize);
                        *registers.add(temporaries_start + k) = $value;
                    }
                }
            };
        }
        for block in &self.blocks {
            match block.op {
                TapeOp::Add => run_block!(block, |a, b, _c| a + b),
                TapeOp::Sub => run_block!(block, |a, b, _c| a - b),
                TapeOp::Mul => run_block!(block, |a, b, _c| a * b),
                TapeOp::MulAdd => run_block!(block, |a, b, c| c + a * b),
                TapeOp::MulSubtractedFrom => run_block!(block, |a, b, c| c - a * b),
                TapeOp::MulMinus => run_block!(block, |a, b, c| a * b - c),
                TapeOp::Scale => run_block!(block, |a, b, _c| a.scale_by_real_part(b)),
            }
        }
    }

    /// Runs the tape in double-double arithmetic on `inputs` (the first `num_inputs`
    /// registers) and writes the first `out.len()` outputs, rounded to double. The
    /// registers live in a per-thread buffer that grows once.
    fn run_extended(&self, inputs: &[C64], out: &mut [C64]) {
        self.run_extended_split(inputs, out, &mut [], &mut []);
    }

    /// [`Tape::run_extended`] with the outputs split: the first `first.len()` into
    /// `first`, the next `rest.len()` into `rest` (rounded) and their trailing parts
    /// (value − rounded) into `rest_low` (if not empty).
    fn run_extended_split(
        &self,
        inputs: &[C64],
        first: &mut [C64],
        rest: &mut [C64],
        rest_low: &mut [C64],
    ) {
        thread_local! {
            static REGISTERS: std::cell::RefCell<Vec<ComplexDd>> =
                const { std::cell::RefCell::new(Vec::new()) };
        }
        REGISTERS.with(|cell| {
            let mut registers = cell.borrow_mut();
            let len = self.workspace_len();
            if registers.len() < len {
                registers.resize(len, ComplexDd::default());
            }
            let loaded = inputs[..self.num_inputs].iter().chain(&self.constants);
            for (r, v) in registers.iter_mut().zip(loaded) {
                *r = ComplexDd::from_c64(*v);
            }
            self.execute_double_double(&mut registers);
            let (head, tail) = self.outputs.split_at(first.len().min(self.outputs.len()));
            for (target, &(register, sign)) in first.iter_mut().zip(head) {
                *target = registers[register as usize].to_c64() * sign;
            }
            for (k, (target, &(register, sign))) in rest.iter_mut().zip(tail).enumerate() {
                let value = registers[register as usize];
                *target = value.to_c64() * sign;
                if let Some(low) = rest_low.get_mut(k) {
                    *low = C64::new(value.re.lo, value.im.lo) * sign;
                }
            }
        });
    }

    /// Copies outputs `first..first + out.len()` into `out`.
    #[inline]
    fn write_outputs(&self, work: &[C64], first: usize, out: &mut [C64]) {
        debug_assert!(
            first + out.len() <= self.outputs.len(),
            "output buffer length"
        );
        for (target, &(register, sign)) in out.iter_mut().zip(&self.outputs[first..]) {
            *target = work[register as usize] * sign;
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
    lowered: HashMap<usize, Signed>,
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

    /// A constant as a signed operand: `c` and `−c` share one register.
    fn signed_constant(&mut self, value: C64) -> Signed {
        let negative = value.re < 0.0 || (value.re == 0.0 && value.im < 0.0);
        if negative {
            Signed::negative(self.constant(-value))
        } else {
            // Also maps −0 to +0.
            Signed::positive(self.constant(value + C64::new(0.0, 0.0)))
        }
    }

    /// `u − v` with the operands in canonical order (`v − u = −(u − v)`).
    fn difference(&mut self, u: Operand, v: Operand) -> Signed {
        match u.cmp(&v) {
            std::cmp::Ordering::Equal => Signed::positive(self.constant(C64::new(0.0, 0.0))),
            std::cmp::Ordering::Less => Signed::positive(self.emit(Op::Sub, u, v)),
            std::cmp::Ordering::Greater => Signed::negative(self.emit(Op::Sub, v, u)),
        }
    }

    /// `x + y` for signed operands.
    fn sum(&mut self, x: Signed, y: Signed) -> Signed {
        match (x.negated, y.negated) {
            (false, false) => Signed::positive(self.emit(Op::Add, x.operand, y.operand)),
            (true, true) => Signed::negative(self.emit(Op::Add, x.operand, y.operand)),
            (false, true) => self.difference(x.operand, y.operand),
            (true, false) => self.difference(y.operand, x.operand),
        }
    }

    /// `x · y` for signed operands.
    fn product(&mut self, x: Signed, y: Signed) -> Signed {
        Signed {
            operand: self.emit(Op::Mul, x.operand, y.operand),
            negated: x.negated != y.negated,
        }
    }

    /// Lowers `e` (symbols must all be inputs; checked when the system was built).
    /// Negations are not instructions: they travel as the sign of the result, so that
    /// `a − b` and `b − a`, `c·x` and `−c·x` share their instruction.
    fn lower(&mut self, e: &Expr) -> Signed {
        if let Some(&done) = self.lowered.get(&e.node_id()) {
            return done;
        }
        let result = match e.kind() {
            Kind::Constant(c) => self.signed_constant(*c),
            Kind::Symbol(name) => match self.inputs.get(&**name) {
                Some(&index) => Signed::positive(Operand::Input(index)),
                // Unreachable for a validated system; lowering a NaN keeps it total.
                None => Signed::positive(self.constant(C64::new(f64::NAN, f64::NAN))),
            },
            Kind::Add(a, b) => {
                let (a, b) = (self.lower(a), self.lower(b));
                self.sum(a, b)
            }
            Kind::Sub(a, b) => {
                let (a, b) = (self.lower(a), self.lower(b));
                self.sum(a, b.negate())
            }
            Kind::Mul(a, b) => {
                let (a, b) = (self.lower(a), self.lower(b));
                self.product(a, b)
            }
            Kind::Neg(a) => self.lower(a).negate(),
            Kind::Pow(a, n) => {
                let a = self.lower(a);
                Signed {
                    operand: self.power(a.operand, *n),
                    negated: a.negated && n % 2 == 1,
                }
            }
        };
        self.lowered.insert(e.node_id(), result);
        self.keep_alive.push(e.clone());
        result
    }

    /// Schedules the instructions level by level (an instruction's level is one more
    /// than its operands'), grouping equal operations within a level into blocks, and
    /// assigns registers `[inputs | constants | temporaries]`.
    fn finish(self, outputs: &[Signed]) -> Tape {
        let count = self.instructions.len();
        // Fuse each product whose only use is a sum or difference into it.
        let mut uses = vec![0u32; count];
        let mut count_use = |operand: Operand| {
            if let Operand::Temporary(t) = operand {
                uses[t as usize] += 1;
            }
        };
        for &(_, a, b) in &self.instructions {
            count_use(a);
            count_use(b);
        }
        for output in outputs {
            count_use(output.operand);
        }
        let single_product = |operand: Operand| match operand {
            Operand::Temporary(t)
                if self.instructions[t as usize].0 == Op::Mul && uses[t as usize] == 1 =>
            {
                Some(t as usize)
            }
            _ => None,
        };
        let real_constant = |operand: Operand| match operand {
            Operand::Constant(i) => self.constants[i as usize].im == 0.0,
            _ => false,
        };
        let mut fused: Vec<(TapeOp, Operand, Operand, Operand)> = Vec::with_capacity(count);
        let mut deleted = vec![false; count];
        for &(op, a, b) in &self.instructions {
            let mut fuse = |product: usize, op: TapeOp, other: Operand| {
                deleted[product] = true;
                let (_, x, y) = self.instructions[product];
                (op, x, y, other)
            };
            let instruction = match op {
                Op::Mul => match (real_constant(a), real_constant(b)) {
                    (_, true) => (TapeOp::Scale, a, b, a),
                    (true, false) => (TapeOp::Scale, b, a, b),
                    (false, false) => (TapeOp::Mul, a, b, a),
                },
                Op::Add => match (single_product(b), single_product(a)) {
                    (Some(t), _) => fuse(t, TapeOp::MulAdd, a),
                    (None, Some(t)) => fuse(t, TapeOp::MulAdd, b),
                    (None, None) => (TapeOp::Add, a, b, a),
                },
                Op::Sub => match (single_product(b), single_product(a)) {
                    (Some(t), _) => fuse(t, TapeOp::MulSubtractedFrom, a),
                    (None, Some(t)) => fuse(t, TapeOp::MulMinus, b),
                    (None, None) => (TapeOp::Sub, a, b, a),
                },
            };
            fused.push(instruction);
        }

        let mut level = vec![0u32; count];
        for (k, &(_, a, b, c)) in fused.iter().enumerate() {
            let of = |operand: Operand| match operand {
                Operand::Temporary(i) => level[i as usize] + 1,
                _ => 0,
            };
            level[k] = of(a).max(of(b)).max(of(c));
        }
        let rank = |op: TapeOp| op as u8;
        let mut order: Vec<usize> = (0..count).filter(|&k| !deleted[k]).collect();
        order.sort_by_key(|&k| (level[k], rank(fused[k].0)));
        let mut position = vec![u32::MAX; count];
        for (new, &old) in order.iter().enumerate() {
            position[old] = new as u32;
        }

        let constants_start = self.num_inputs as u32;
        let temporaries_start = constants_start + self.constants.len() as u32;
        let register = |operand: Operand| match operand {
            Operand::Input(i) => i,
            Operand::Constant(i) => constants_start + i,
            Operand::Temporary(i) => temporaries_start.saturating_add(position[i as usize]),
        };
        let instructions: Vec<Instruction> = order
            .iter()
            .map(|&old| {
                let (op, a, b, c) = fused[old];
                Instruction {
                    op,
                    a: register(a),
                    b: register(b),
                    c: register(c),
                }
            })
            .collect();
        let mut blocks: Vec<Block> = Vec::new();
        for (k, instruction) in instructions.iter().enumerate() {
            match blocks.last_mut() {
                Some(block) if block.op == instruction.op => block.end = k as u32 + 1,
                _ => blocks.push(Block {
                    op: instruction.op,
                    start: k as u32,
                    end: k as u32 + 1,
                }),
            }
        }
        // The invariants `Tape::run` relies on: every operand is already computed and
        // the blocks cover the instructions in order.
        for (k, instruction) in instructions.iter().enumerate() {
            let limit = temporaries_start as usize + k;
            assert!(
                (instruction.a as usize) < limit
                    && (instruction.b as usize) < limit
                    && (instruction.c as usize) < limit
            );
        }
        assert!(
            blocks.first().is_none_or(|b| b.start == 0)
                && blocks.windows(2).all(|w| w[0].end == w[1].start)
                && blocks.last().map_or(0, |b| b.end as usize) == instructions.len()
        );
        let outputs = outputs
            .iter()
            .map(|o| {
                let target = register(o.operand);
                assert!((target as usize) < temporaries_start as usize + instructions.len());
                (target, if o.negated { -1.0 } else { 1.0 })
            })
            .collect();
        Tape {
            num_inputs: self.num_inputs,
            instructions,
            blocks,
            outputs,
            interval_constants: self
                .constants
                .iter()
                .map(|&c| coefficient_enclosure(c))
                .collect(),
            constants: self.constants,
        }
    }
}

/// Symbolic partial derivatives `∂f_i/∂s` for every equation and every symbol in
/// `symbols`, row-major (equation, symbol). An equation is differentiated only by the
/// symbols it contains (the others give 0): a sparse system's equations each hold few
/// of them, and the polyhedral term family has one parameter per term, each in one
/// equation.
fn symbolic_jacobian(equations: &[Expr], symbols: &[String]) -> Vec<Expr> {
    let contained: Vec<std::collections::HashSet<String>> = equations
        .iter()
        .map(|f| f.symbols().into_iter().collect())
        .collect();
    let mut columns: Vec<Vec<Expr>> = Vec::with_capacity(symbols.len());
    for symbol in symbols {
        let mut memo = HashMap::new();
        columns.push(
            equations
                .iter()
                .zip(&contained)
                .map(|(f, symbols)| {
                    if symbols.contains(symbol) {
                        f.differentiate_memo(symbol, &mut memo)
                    } else {
                        Expr::zero()
                    }
                })
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

/// The tape of `∂F/∂p` (row-major entries `jacobian_p`).
fn compile_parameter_jacobian(
    inputs: &HashMap<&str, u32>,
    num_inputs: usize,
    jacobian_p: &[Expr],
) -> Tape {
    let mut builder = TapeBuilder::new(inputs, num_inputs);
    let outputs: Vec<Signed> = jacobian_p.iter().map(|f| builder.lower(f)).collect();
    builder.finish(&outputs)
}

/// The tape of `(∂F/∂p)·dp`: `Σ_k ∂f_i/∂p_k · dp_k` with `dp_k` in input register
/// `n + m + k`, for `equations` equations in `n` unknowns and `m` parameters.
fn compile_parameter_derivative(
    inputs: &HashMap<&str, u32>,
    (n, m): (usize, usize),
    equations: usize,
    jacobian_p: &[Expr],
) -> Tape {
    let mut builder = TapeBuilder::new(inputs, n + 2 * m);
    let mut outputs = Vec::with_capacity(equations);
    for i in 0..equations {
        let mut sum: Option<Signed> = None;
        for k in 0..m {
            let entry = &jacobian_p[i * m + k];
            if entry.is_zero() {
                continue;
            }
            let derivative = builder.lower(entry);
            let direction = Signed::positive(Operand::Input((n + m + k) as u32));
            let term = builder.product(derivative, direction);
            sum = Some(match sum {
                None => term,
                Some(previous) => builder.sum(previous, term),
            });
        }
        let zero = Signed::positive(builder.constant(C64::new(0.0, 0.0)));
        outputs.push(sum.unwrap_or(zero));
    }
    builder.finish(&outputs)
}

#[derive(Debug)]
struct CompiledParts {
    variables: Vec<String>,
    homogenizing: Option<usize>,
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
        CompiledSystem::build(system, true)
    }

    /// [`CompiledSystem::new`] without the tapes of `∂F/∂p` and `(∂F/∂p)·dp`, for a
    /// system whose parameters only ever take values (the polyhedral term family, one
    /// parameter per term: those tapes were most of its compile time). Its
    /// parameter derivatives evaluate to NaN, which no tracker accepts.
    pub fn without_parameter_derivatives(system: &System) -> CompiledSystem {
        CompiledSystem::build(system, false)
    }

    fn build(system: &System, parameter_derivatives: bool) -> CompiledSystem {
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
        let jacobian_p = if parameter_derivatives {
            symbolic_jacobian(equations, &parameters)
        } else {
            Vec::new()
        };

        let mut builder = TapeBuilder::new(&inputs, num_inputs);
        let outputs: Vec<Signed> = equations.iter().map(|f| builder.lower(f)).collect();
        let values = builder.finish(&outputs);

        let mut builder = TapeBuilder::new(&inputs, num_inputs);
        let outputs: Vec<Signed> = equations
            .iter()
            .chain(jacobian_x.iter())
            .map(|f| builder.lower(f))
            .collect();
        let values_and_jacobian = builder.finish(&outputs);

        let (parameter_jacobian, parameter_derivative) = if parameter_derivatives {
            let parameter_jacobian = compile_parameter_jacobian(&inputs, num_inputs, &jacobian_p);
            let parameter_derivative =
                compile_parameter_derivative(&inputs, (n, m), equations.len(), &jacobian_p);
            (parameter_jacobian, parameter_derivative)
        } else {
            let not_available = |outputs: usize| {
                let mut builder = TapeBuilder::new(&inputs, num_inputs);
                let nan = Signed::positive(builder.constant(C64::new(f64::NAN, f64::NAN)));
                builder.finish(&vec![nan; outputs])
            };
            (
                not_available(equations.len() * m),
                not_available(equations.len()),
            )
        };

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
                homogenizing: system.homogenizing(),
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

    /// Human-readable listing of the F + ∂F/∂x tape (`r12 = r3 * r7`, outputs last),
    /// for inspecting what the compiler produced.
    pub fn jacobian_tape_listing(&self) -> String {
        let tape = &self.parts.values_and_jacobian;
        let start = tape.num_inputs + tape.constants.len();
        let mut out = String::new();
        for (i, c) in tape.constants.iter().enumerate() {
            out.push_str(&format!("r{} = {c}\n", tape.num_inputs + i));
        }
        for (k, instruction) in tape.instructions.iter().enumerate() {
            let (a, b, c) = (instruction.a, instruction.b, instruction.c);
            let text = match instruction.op {
                TapeOp::Add => format!("r{a} + r{b}"),
                TapeOp::Sub => format!("r{a} - r{b}"),
                TapeOp::Mul => format!("r{a} * r{b}"),
                TapeOp::MulAdd => format!("r{c} + r{a} * r{b}"),
                TapeOp::MulSubtractedFrom => format!("r{c} - r{a} * r{b}"),
                TapeOp::MulMinus => format!("r{a} * r{b} - r{c}"),
                TapeOp::Scale => format!("r{a} * re(r{b})"),
            };
            out.push_str(&format!("r{} = {text}\n", start + k));
        }
        let outputs: Vec<String> = tape
            .outputs
            .iter()
            .map(|&(r, sign)| format!("{}r{r}", if sign < 0.0 { "-" } else { "" }))
            .collect();
        out.push_str(&format!("outputs: {}\n", outputs.join(" ")));
        out
    }

    /// Sizes of the tapes: instructions of (F, F + ∂F/∂x, ∂F/∂p, (∂F/∂p)·dp) and
    /// the number of multiplications of the F + ∂F/∂x tape.
    pub fn tape_statistics(&self) -> ([usize; 4], usize) {
        let parts = &self.parts;
        let multiplications = parts
            .values_and_jacobian
            .instructions
            .iter()
            .filter(|i| {
                matches!(
                    i.op,
                    TapeOp::Mul
                        | TapeOp::MulAdd
                        | TapeOp::MulSubtractedFrom
                        | TapeOp::MulMinus
                        | TapeOp::Scale
                )
            })
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

    /// Whether every coefficient of the system is real (the tapes' constants): then
    /// for real parameters the solution set is closed under complex conjugation.
    pub fn has_real_coefficients(&self) -> bool {
        self.parts
            .values_and_jacobian
            .constants
            .iter()
            .all(|c| c.im == 0.0)
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

    /// [`CompiledSystem::load`] and the parameter direction `dp` after `p` (the input
    /// registers of the parameter-derivative tape).
    fn load_with_direction(&self, x: &[C64], p: &[C64], dp: &[C64], work: &mut [C64]) {
        self.load(x, p, work);
        let n = self.parts.variables.len();
        let m = self.parts.parameters.len();
        debug_assert_eq!(dp.len(), m);
        work[n + m..n + 2 * m].copy_from_slice(dp);
    }
}

impl Evaluator for CompiledSystem {
    fn num_variables(&self) -> usize {
        self.parts.variables.len()
    }

    fn homogenizing_variable(&self) -> Option<usize> {
        self.parts.homogenizing
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
        tape.write_outputs(work, 0, f);
    }

    fn evaluate_extended(&self, x: &[C64], p: &[C64], work: &mut [C64], f: &mut [C64]) {
        self.load(x, p, work);
        // The tape's input registers are the workspace's first ones (x, p, then inputs
        // only other tapes read).
        self.parts.values.run_extended(work, f);
    }

    fn evaluate_with_jacobian_extended(
        &self,
        x: &[C64],
        p: &[C64],
        work: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
        jac_low: &mut [C64],
    ) {
        self.load(x, p, work);
        self.parts
            .values_and_jacobian
            .run_extended_split(work, f, jac, jac_low);
    }

    fn evaluate_parameter_derivative_extended(
        &self,
        x: &[C64],
        p: &[C64],
        dp: &[C64],
        work: &mut [C64],
        out: &mut [C64],
    ) {
        self.load_with_direction(x, p, dp, work);
        self.parts.parameter_derivative.run_extended(work, out);
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
        let k = self.parts.num_equations;
        debug_assert_eq!(f.len(), k);
        debug_assert_eq!(jac.len(), k * x.len());
        let tape = &self.parts.values_and_jacobian;
        tape.run(work);
        tape.write_outputs(work, 0, f);
        tape.write_outputs(work, k, jac);
    }

    fn evaluate_parameter_derivative(
        &self,
        x: &[C64],
        p: &[C64],
        dp: &[C64],
        work: &mut [C64],
        out: &mut [C64],
    ) {
        self.load_with_direction(x, p, dp, work);
        let tape = &self.parts.parameter_derivative;
        tape.run(work);
        tape.write_outputs(work, 0, out);
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
        tape.write_outputs(work, 0, jac_p);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AVX2 copy of the double-precision tape run (chosen at run time) rounds
    /// exactly as the baseline: bit-identical registers on a 3-RPR Lagrange system.
    #[test]
    fn dispatched_tape_matches_the_baseline_bit_for_bit() {
        let id = crate::problem::ProblemId::all()[0];
        let problem = crate::problem::LagrangeProblem::new(id).unwrap();
        let tape = &problem.evaluator().parts.values_and_jacobian;
        let mut rng = crate::random::seeded(3);
        let mut dispatched = vec![C64::new(0.0, 0.0); tape.workspace_len()];
        for v in dispatched[..tape.num_inputs].iter_mut() {
            *v = crate::random::complex_normal(&mut rng);
        }
        let mut baseline = dispatched.clone();
        tape.run(&mut dispatched);
        let constants_start = tape.num_inputs;
        baseline[constants_start..constants_start + tape.constants.len()]
            .copy_from_slice(&tape.constants);
        tape.execute(&mut baseline);
        assert_eq!(dispatched, baseline);
    }

    /// The midpoint–radius interval run ([`run_interval`]) of a 3-RPR Lagrange system's
    /// values-and-Jacobian tape on a box around a random point contains the inf–sup
    /// interval run of the same tape at sampled points of the box (each an enclosure of
    /// the exact value there), and is not much wider than the inf–sup run on the box.
    #[test]
    fn midpoint_radius_tape_encloses_the_inf_sup_tape_at_sampled_points() {
        let inf_sup = |tape: &Tape, inputs: &[ComplexInterval]| -> Vec<ComplexInterval> {
            let mut registers = vec![ComplexInterval::default(); tape.workspace_len()];
            registers[..inputs.len()].copy_from_slice(inputs);
            for (r, c) in registers[tape.num_inputs..].iter_mut().zip(&tape.constants) {
                *r = ComplexInterval::point(*c);
            }
            tape.execute(&mut registers);
            let out = tape.outputs.iter();
            out.map(|&(r, sign)| registers[r as usize].scale(Interval::point(sign)))
                .collect()
        };
        use crate::system::interval::Interval;
        for id in crate::problem::ProblemId::all().into_iter().take(4) {
            let problem = crate::problem::LagrangeProblem::new(id).unwrap();
            let system = problem.evaluator();
            let tape = &system.parts.values_and_jacobian;
            let (n, m) = (system.num_variables(), system.num_parameters());
            let mut rng = crate::random::seeded(5);
            let x0: Vec<C64> = (0..n)
                .map(|_| crate::random::complex_normal(&mut rng))
                .collect();
            let p0: Vec<C64> = (0..m)
                .map(|_| C64::new(crate::random::complex_normal(&mut rng).re, 0.0))
                .collect();
            let x = ComplexInterval::boxes(&x0, 1e-6);
            let p = ComplexInterval::boxes(&p0, 1e-12);
            let k = system.num_equations();
            let mut f = vec![ComplexInterval::default(); k];
            let mut jac = vec![ComplexInterval::default(); k * n];
            system.evaluate_interval_with_jacobian(&x, &p, &mut f, &mut jac);
            let got: Vec<ComplexInterval> = f.iter().chain(&jac).copied().collect();
            let mut inputs = vec![ComplexInterval::default(); tape.num_inputs];
            inputs[..n].copy_from_slice(&x);
            inputs[n..n + m].copy_from_slice(&p);
            let whole = inf_sup(tape, &inputs);
            for (g, w) in got.iter().zip(&whole) {
                let close = |g: Interval, w: Interval| g.width() <= 3.0 * w.width() + 1e-300;
                assert!(close(g.re, w.re) && close(g.im, w.im), "{g:?} vs {w:?}");
            }
            for sample in 0..6 {
                let t = [-1.0, 1.0, 0.5, -0.25, 0.9, 0.0][sample];
                for (i, input) in inputs.iter_mut().enumerate().take(n + m) {
                    let (c, r) = if i < n {
                        (x0[i], 1e-6)
                    } else {
                        (p0[i - n], 1e-12)
                    };
                    let s = if i % 2 == 0 { t } else { -t };
                    *input = ComplexInterval::point(c + C64::new(s, t) * r * 0.999);
                }
                for (g, e) in got.iter().zip(inf_sup(tape, &inputs)) {
                    assert!(
                        g.re.lo <= e.re.lo
                            && e.re.hi <= g.re.hi
                            && g.im.lo <= e.im.lo
                            && e.im.hi <= g.im.hi,
                        "{}: {e:?} not in {g:?}",
                        id.name()
                    );
                }
            }
        }
    }

    #[test]
    fn every_tape_operation_is_used_and_evaluates_like_the_expressions() {
        let (x, y, z) = (
            Expr::variable("x"),
            Expr::variable("y"),
            Expr::variable("z"),
        );
        let i = C64::new(0.0, 1.0);
        // Each product below has a single use in F, so it is fused where possible.
        let equations = vec![
            &z + &x * &y,                         // MulAdd
            &y - &x * &z,                         // MulSubtractedFrom
            &y * &z - (&x + 1.0),                 // MulMinus
            3.0 * (&x + &y) * (&y - &z),          // Scale, Add, Sub, Mul
            (&y - &x) * (&x - &y) * i + x.pow(5), // shared sign-flipped difference
            -(y.pow(2) * &z),                     // negated output
        ];
        let system = System::new(["x", "y", "z"], [""; 0], equations).unwrap();
        let compiled = system.compile();
        let ops: std::collections::HashSet<String> = compiled
            .parts
            .values
            .instructions
            .iter()
            .map(|instruction| format!("{:?}", instruction.op))
            .collect();
        for op in [
            "Add",
            "Sub",
            "Mul",
            "MulAdd",
            "MulSubtractedFrom",
            "MulMinus",
            "Scale",
        ] {
            assert!(ops.contains(op), "{op} missing from {ops:?}");
        }
        let point = [C64::new(0.3, -1.1), C64::new(-0.7, 0.4), C64::new(1.3, 0.2)];
        let mut work = compiled.new_workspace();
        let mut f = [C64::new(0.0, 0.0); 6];
        let mut jac = [C64::new(0.0, 0.0); 18];
        compiled.evaluate_with_jacobian(&point, &[], &mut work, &mut f, &mut jac);
        let expected_f = system.evaluate_naive(&point, &[]);
        let expected_jac = system.jacobian_naive(&point, &[]);
        for (got, want) in f
            .iter()
            .zip(&expected_f)
            .chain(jac.iter().zip(&expected_jac))
        {
            assert!(
                (got - want).norm() <= 1e-14 * want.norm().max(1.0),
                "{got} vs {want}"
            );
        }
    }
}
