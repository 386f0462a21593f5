//! Option values given as lists on the command line: comma-separated numbers (a pose
//! `x,y,phi`, prismatic inputs, a range `lo,hi`), metric names, and parameter values
//! `NAME=VALUE`. Errors name the option and the item at fault.

use anyhow::{Context, Result, bail};
use singdist::C64;
use singdist::mechanism::rpr::{Pose, check_input_number};
use singdist::metric::Metric;
use singdist::system::bertini;

/// Parses `N` comma-separated numbers called `names` (e.g. `x`, `y`, `phi`), the value
/// of `option`; each must be finite and within ±1e12
/// ([`singdist::mechanism::MAX_INPUT_MAGNITUDE`]). Errors name the option and the
/// component (`--pose: x: 1e308 is outside ±1e12`).
pub fn parse_numbers<const N: usize>(
    text: &str,
    option: &str,
    names: [&str; N],
) -> Result<[f64; N]> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != N {
        bail!(
            "{option}: expected {} ({N} comma-separated numbers), got `{text}`",
            names.join(",")
        );
    }
    let mut values = [0.0; N];
    for (value, (part, name)) in values.iter_mut().zip(parts.iter().zip(names)) {
        let number: f64 = part
            .parse()
            .ok()
            .with_context(|| format!("{option}: {name}: `{part}` is not a number"))?;
        check_input_number(|| name.to_string(), number).with_context(|| option.to_string())?;
        *value = number;
    }
    Ok(values)
}

/// Parses the `--pose` value `x,y,phi` of a 3-RPR or 3-RRR (position in the design's
/// length unit, φ in radians), as [`parse_numbers`].
pub fn parse_pose(text: &str) -> Result<Pose> {
    let [x, y, phi] = parse_numbers(text, "--pose", ["x", "y", "phi"])?;
    Ok(Pose::new(x, y, phi))
}

/// Parses `--metric` values (each `all` or a comma-separated list of names), each
/// metric kept once in the order given.
pub fn parse_metrics(values: &[String]) -> Result<Vec<Metric>> {
    let mut metrics: Vec<Metric> = Vec::new();
    for value in values {
        for metric in Metric::parse_list(value).context("--metric")? {
            if !metrics.contains(&metric) {
                metrics.push(metric);
            }
        }
    }
    if metrics.is_empty() {
        bail!("--metric: no metric given");
    }
    Ok(metrics)
}

/// Parses a `--set NAME=VALUE` parameter value (VALUE a Bertini constant like `1.5` or
/// `0.5+2*I`).
pub fn parse_assignment(text: &str) -> Result<(String, C64)> {
    let (name, value) = text
        .split_once('=')
        .with_context(|| format!("--set `{text}`: expected NAME=VALUE"))?;
    let value = bertini::read_constant(value.trim())
        .with_context(|| format!("--set `{text}`: cannot read the value"))?;
    Ok((name.trim().to_string(), value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_counted_parsed_and_range_checked_naming_option_and_component() {
        assert_eq!(
            parse_numbers("1, -2.5,3e2", "--delta", ["d1", "d2", "d3"]).unwrap(),
            [1.0, -2.5, 300.0]
        );
        let message = |text: &str| format!("{:#}", parse_pose(text).unwrap_err());
        assert!(message("1,2").contains("--pose: expected x,y,phi"));
        assert!(message("1,a,2").contains("--pose: y: `a` is not a number"));
        assert!(message("1e308,0,0").contains("--pose: x: 1e308 is outside ±1e12"));
        assert!(message("0,0,inf").contains("--pose"));
        assert!(message("0,0,NaN").contains("phi"));
    }
}
