//! Bisection of a sign change of a real function of the motion parameter τ (the
//! singularity polynomial `S(K(τ))` of the 3-RPR, the parallel determinant of the
//! 3-RRR): where it vanishes, so does the signed singularity distance (docs/theory.md §7).

/// Halvings at most (far more than the 1e-14 relative width needs from any bracket of
/// finite doubles).
const MAX_HALVINGS: usize = 200;

/// The zero of `value` in the bracket `[lo, hi]` on which it changes sign (`s_lo`, its
/// value at `lo`, nonzero): the bracket is halved, keeping the half whose ends have
/// opposite signs, until `|hi − lo| ≤ 1e-14·(1 + |τ|)`, an exact zero is met, or `value`
/// is undefined at a midpoint (`None`); returns the midpoint of the last bracket.
pub fn bisect_sign_change(
    (mut lo, mut hi): (f64, f64),
    mut s_lo: f64,
    value: impl Fn(f64) -> Option<f64>,
) -> f64 {
    for _ in 0..MAX_HALVINGS {
        let mid = 0.5 * (lo + hi);
        if (hi - lo).abs() <= 1e-14 * (1.0 + mid.abs()) {
            break;
        }
        let Some(s_mid) = value(mid) else { break };
        if s_mid == 0.0 {
            return mid;
        }
        if (s_mid < 0.0) == (s_lo < 0.0) {
            lo = mid;
            s_lo = s_mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `τ² − 2` on [1, 2]: the bracket shrinks to √2 within the stopping width.
    #[test]
    fn finds_the_square_root_of_two() {
        let root = bisect_sign_change((1.0, 2.0), -1.0, |t| Some(t * t - 2.0));
        assert!((root - 2f64.sqrt()).abs() <= 3e-14, "{root}");
    }

    /// An exact zero at a midpoint is returned as it is; an undefined value stops the
    /// halving at the current bracket (here: [0, 1] → [0.5, 1], then τ = 0.75 is
    /// undefined, so the midpoint of [0.5, 1]).
    #[test]
    fn stops_at_an_exact_zero_or_an_undefined_value() {
        assert_eq!(bisect_sign_change((0.0, 1.0), -1.0, |t| Some(t - 0.5)), 0.5);
        let undefined = |t: f64| if t < 0.75 { Some(t - 0.6) } else { None };
        assert_eq!(bisect_sign_change((0.0, 1.0), -0.6, undefined), 0.75);
    }
}
