//! Hand-written polynomial evaluators for the homotopy tests: sums of terms
//! `c · p_k · Π x_j^{e_j}` evaluated term by term (independent of `crate::system`).
#![allow(dead_code)]

use singdist::C64;
use singdist::random::{complex_normal, seeded};
use singdist::system::Evaluator;

/// One term: coefficient, optional parameter factor, exponents.
#[derive(Clone, Debug)]
pub struct Term {
    pub coefficient: C64,
    pub parameter: Option<usize>,
    pub exponents: Vec<u32>,
}

/// A square (or not) system given by terms.
#[derive(Clone, Debug)]
pub struct TermSystem {
    pub n: usize,
    pub m: usize,
    pub equations: Vec<Vec<Term>>,
}

impl TermSystem {
    pub fn degrees(&self) -> Vec<u32> {
        self.equations
            .iter()
            .map(|eq| {
                eq.iter()
                    .map(|t| t.exponents.iter().sum::<u32>())
                    .max()
                    .unwrap_or(0)
            })
            .collect()
    }

    fn monomial(x: &[C64], e: &[u32]) -> C64 {
        x.iter()
            .zip(e)
            .fold(C64::new(1.0, 0.0), |acc, (v, &k)| acc * v.powu(k))
    }

    fn derivative(x: &[C64], e: &[u32], j: usize) -> C64 {
        if e[j] == 0 {
            return C64::new(0.0, 0.0);
        }
        let mut acc = C64::new(e[j] as f64, 0.0);
        for (i, (v, &k)) in x.iter().zip(e).enumerate() {
            acc *= if i == j { v.powu(k - 1) } else { v.powu(k) };
        }
        acc
    }

    fn coefficient(t: &Term, p: &[C64]) -> C64 {
        match t.parameter {
            Some(k) => t.coefficient * p[k],
            None => t.coefficient,
        }
    }
}

impl Evaluator for TermSystem {
    fn num_variables(&self) -> usize {
        self.n
    }
    fn num_equations(&self) -> usize {
        self.equations.len()
    }
    fn num_parameters(&self) -> usize {
        self.m
    }
    fn workspace_len(&self) -> usize {
        0
    }
    fn evaluate(&self, x: &[C64], p: &[C64], _w: &mut [C64], f: &mut [C64]) {
        for (fi, eq) in f.iter_mut().zip(&self.equations) {
            *fi = eq
                .iter()
                .map(|t| Self::coefficient(t, p) * Self::monomial(x, &t.exponents))
                .sum();
        }
    }
    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        p: &[C64],
        w: &mut [C64],
        f: &mut [C64],
        jac: &mut [C64],
    ) {
        self.evaluate(x, p, w, f);
        let n = self.n;
        for (i, eq) in self.equations.iter().enumerate() {
            for j in 0..n {
                jac[i * n + j] = eq
                    .iter()
                    .map(|t| Self::coefficient(t, p) * Self::derivative(x, &t.exponents, j))
                    .sum();
            }
        }
    }
    fn evaluate_parameter_derivative(
        &self,
        x: &[C64],
        _p: &[C64],
        dp: &[C64],
        _w: &mut [C64],
        out: &mut [C64],
    ) {
        for (o, eq) in out.iter_mut().zip(&self.equations) {
            *o = eq
                .iter()
                .filter_map(|t| {
                    t.parameter
                        .map(|k| t.coefficient * dp[k] * Self::monomial(x, &t.exponents))
                })
                .sum();
        }
    }
}

fn term(c: f64, exps: Vec<u32>) -> Term {
    Term {
        coefficient: C64::new(c, 0.0),
        parameter: None,
        exponents: exps,
    }
}

fn unit(n: usize, i: usize, k: u32) -> Vec<u32> {
    let mut e = vec![0; n];
    e[i] = k;
    e
}

/// katsura-n: n+1 unknowns x_0..x_n, 2^n solutions, all nonsingular.
pub fn katsura(n: usize) -> TermSystem {
    let nv = n + 1;
    let mut equations = Vec::new();
    // Σ_{l=-n}^{n} x_|l| = 1
    let mut lin = vec![term(1.0, unit(nv, 0, 1))];
    for i in 1..nv {
        lin.push(term(2.0, unit(nv, i, 1)));
    }
    lin.push(term(-1.0, vec![0; nv]));
    equations.push(lin);
    // Σ_l x_|l| x_|m−l| = x_m for m = 0..n−1
    for m in 0..n {
        let mut eq = Vec::new();
        for l in -(n as i64)..=(n as i64) {
            let a = l.unsigned_abs() as usize;
            let b = (m as i64 - l).unsigned_abs() as usize;
            if b <= n {
                let mut e = vec![0u32; nv];
                e[a] += 1;
                e[b] += 1;
                eq.push(term(1.0, e));
            }
        }
        eq.push(term(-1.0, unit(nv, m, 1)));
        equations.push(eq);
    }
    TermSystem {
        n: nv,
        m: 0,
        equations,
    }
}

/// cyclic-n: Σ_i Π_{j<k} x_{i+j} = 0 (k = 1..n−1), Π x_i − 1 = 0.
pub fn cyclic(n: usize) -> TermSystem {
    let mut equations = Vec::new();
    for k in 1..n {
        let mut eq = Vec::new();
        for i in 0..n {
            let mut e = vec![0u32; n];
            for j in 0..k {
                e[(i + j) % n] += 1;
            }
            eq.push(term(1.0, e));
        }
        equations.push(eq);
    }
    equations.push(vec![term(1.0, vec![1; n]), term(-1.0, vec![0; n])]);
    TermSystem { n, m: 0, equations }
}

fn monomials(n: usize, degree: u32) -> Vec<Vec<u32>> {
    if n == 0 {
        return vec![vec![]];
    }
    let mut out = Vec::new();
    for k in 0..=degree {
        for mut rest in monomials(n - 1, degree - k) {
            rest.insert(0, k);
            out.push(rest);
        }
    }
    out
}

/// Dense random system with the given degrees (all monomials, complex normal
/// coefficients): generic, so its number of solutions equals the Bézout number.
pub fn random_dense(degrees: &[u32], seed: u64) -> TermSystem {
    let n = degrees.len();
    let mut rng = seeded(seed);
    let equations = degrees
        .iter()
        .map(|&d| {
            monomials(n, d)
                .into_iter()
                .map(|e| Term {
                    coefficient: complex_normal(&mut rng),
                    parameter: None,
                    exponents: e,
                })
                .collect()
        })
        .collect();
    TermSystem { n, m: 0, equations }
}

/// Dense system whose every coefficient is a parameter (value = coefficient · p_k);
/// returns the system and a random complex parameter point.
pub fn parametric_dense(degrees: &[u32], seed: u64) -> (TermSystem, Vec<C64>) {
    let n = degrees.len();
    let mut rng = seeded(seed);
    let mut k = 0;
    let mut equations = Vec::new();
    for &d in degrees {
        let mut eq = Vec::new();
        for e in monomials(n, d) {
            eq.push(Term {
                coefficient: C64::new(1.0, 0.0),
                parameter: Some(k),
                exponents: e,
            });
            k += 1;
        }
        equations.push(eq);
    }
    let p = (0..k).map(|_| complex_normal(&mut rng)).collect();
    (TermSystem { n, m: k, equations }, p)
}

/// Makes every coefficient of `system` a parameter; returns the parameter point that
/// reproduces the original system.
pub fn coefficients_as_parameters(system: &TermSystem) -> (TermSystem, Vec<C64>) {
    let mut p = Vec::new();
    let equations = system
        .equations
        .iter()
        .map(|eq| {
            eq.iter()
                .map(|t| {
                    p.push(t.coefficient);
                    Term {
                        coefficient: C64::new(1.0, 0.0),
                        parameter: Some(p.len() - 1),
                        exponents: t.exponents.clone(),
                    }
                })
                .collect()
        })
        .collect();
    (
        TermSystem {
            n: system.n,
            m: p.len(),
            equations,
        },
        p,
    )
}

pub fn residual(system: &TermSystem, x: &[C64], p: &[C64]) -> f64 {
    let mut f = vec![C64::new(0.0, 0.0); system.equations.len()];
    system.evaluate(x, p, &mut [], &mut f);
    f.iter().fold(0.0, |m, v| m.max(v.norm()))
}

/// Greedy matching of two point sets: max over `a` of the distance to the nearest `b`.
pub fn set_distance(a: &[Vec<C64>], b: &[Vec<C64>]) -> f64 {
    a.iter()
        .map(|u| {
            b.iter()
                .map(|v| {
                    u.iter()
                        .zip(v)
                        .fold(0.0f64, |m, (s, t)| m.max((s - t).norm()))
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// katsura-n built with the symbolic builder (`crate::system`), compiled.
pub fn katsura_compiled(n: usize) -> (singdist::system::CompiledSystem, Vec<u32>) {
    use singdist::system::{Expr, System};
    let names: Vec<String> = (0..=n).map(|i| format!("x{i}")).collect();
    let x: Vec<Expr> = names.iter().map(Expr::variable).collect();
    let at = |l: i64| -> Option<&Expr> { x.get(l.unsigned_abs() as usize) };
    let mut equations = Vec::new();
    let mut linear = Expr::from(-1.0);
    for l in -(n as i64)..=(n as i64) {
        linear += at(l).unwrap();
    }
    equations.push(linear);
    for m in 0..n as i64 {
        let mut eq = -&x[m as usize];
        for l in -(n as i64)..=(n as i64) {
            if let (Some(a), Some(b)) = (at(l), at(m - l)) {
                eq += a * b;
            }
        }
        equations.push(eq);
    }
    let system = System::new(&names, Vec::<String>::new(), equations).unwrap();
    let degrees = system.degrees().iter().map(|&d| d as u32).collect();
    (system.compile(), degrees)
}
