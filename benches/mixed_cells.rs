//! Mixed-cell search of the polyhedral start system on PHCpack's demo systems: per
//! system the mixed volume, the number of mixed cells, the LP feasibility tests and the
//! time of the search (the lifting of `PolyhedralStartSystem`, seed 1 unless given).
//!
//! Usage (after `cargo build --release`):
//!
//! ```text
//! cargo bench --bench mixed_cells -- [--dir DIR] [--seed SEED] [NAME …]
//! ```
//!
//! `DIR` defaults to `/usr/share/doc/phcpack/examples` (files possibly gzipped).

mod bench_support;
use singdist::homotopy::polyhedral::{
    CellError, Supports, mixed_cells, random_lifting, start::LIFTING_RANGE,
};
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

/// The liftings' random streams of `PolyhedralStartSystem` (`start.rs`).
const LIFTING_STREAM: u64 = 0x9020;

fn read(dir: &std::path::Path, name: &str) -> Option<String> {
    let plain = dir.join(name);
    if plain.exists() {
        return std::fs::read_to_string(plain).ok();
    }
    let gz = dir.join(format!("{name}.gz"));
    let out = Command::new("gzip").arg("-dc").arg(gz).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// FNV-1a hash of the cells' pairs, normals and volumes in order (the same cells in
/// the same order give the same hash).
fn hash(cells: &[singdist::homotopy::polyhedral::MixedCell]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |v: u64| {
        for b in v.to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for c in cells {
        for &(p, q) in &c.pairs {
            eat(p as u64);
            eat(q as u64);
        }
        for &v in &c.normal {
            eat(v as u64);
        }
        eat(c.volume);
    }
    h
}

fn main() {
    let mut dir = PathBuf::from("/usr/share/doc/phcpack/examples");
    let mut seed = 1u64;
    let mut names = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--dir" => dir = PathBuf::from(args.next().expect("--dir DIR")),
            "--seed" => seed = args.next().expect("--seed SEED").parse().expect("seed"),
            "--bench" => {}
            _ => names.push(a),
        }
    }
    if names.is_empty() {
        names = [
            "cyclic5",
            "cyclic6",
            "cyclic7",
            "katsura6",
            "katsura7",
            "katsura8",
            "eco7",
            "eco8",
            "noon4",
            "noon5",
            "cpdm5",
            "chandra6",
            "game5two",
            "kotsireas",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
    }
    println!(
        "{:<12} {:>3} {:>8} {:>7} {:>10} {:>9} {:>16}",
        "system", "n", "MV", "cells", "LP tests", "seconds", "cells' hash"
    );
    for name in names {
        let Some(text) = read(&dir, &name) else {
            println!("{name:<12} (not found)");
            continue;
        };
        let Some(system) = bench_support::parse_phc(&name, &text) else {
            continue;
        };
        let supports = match Supports::from_system(&system) {
            Ok(s) => s.with_origin(),
            Err(e) => {
                println!("{name:<12} (supports: {e})");
                continue;
            }
        };
        let started = Instant::now();
        let mut attempt = 0;
        let result = loop {
            let lifting = random_lifting(&supports, seed, LIFTING_STREAM + attempt, LIFTING_RANGE);
            attempt += 1;
            if let Ok(dump) = std::env::var("MIXED_CELLS_DUMP") {
                let mut text = format!(
                    "{} {}\n",
                    supports.num_variables(),
                    supports.num_equations()
                );
                for (points, w) in supports.equations().iter().zip(&lifting) {
                    text += &format!("{}\n", points.len());
                    for (a, l) in points.iter().zip(w) {
                        let coords: Vec<String> = a.iter().map(|x| x.to_string()).collect();
                        text += &format!("{} {}\n", coords.join(" "), l);
                    }
                }
                std::fs::write(format!("{dump}/{name}.{attempt}.txt"), text).expect("dump");
            }
            match mixed_cells(&supports, &lifting) {
                Err(CellError::NonGenericLifting) if attempt < 16 => continue,
                other => break other,
            }
        };
        let seconds = started.elapsed().as_secs_f64();
        match result {
            Ok(s) => println!(
                "{name:<12} {:>3} {:>8} {:>7} {:>10} {:>9.3} {:016x}",
                supports.num_variables(),
                s.mixed_volume,
                s.cells.len(),
                s.lp_tests,
                seconds,
                hash(&s.cells)
            ),
            Err(e) => println!("{name:<12} error: {e}"),
        }
    }
}
