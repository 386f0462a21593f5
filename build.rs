//! Embeds every start-solution file of `supplementary/start/` into the library
//! (`include_str!`), so the binary works without the source tree.

use std::fs;
use std::path::Path;

fn main() {
    let manifest = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let directory = Path::new(&manifest).join("supplementary").join("start");
    println!("cargo:rerun-if-changed={}", directory.display());
    let mut entries: Vec<(String, String)> = Vec::new();
    if let Ok(read) = fs::read_dir(&directory) {
        for entry in read.flatten() {
            let path = entry.path();
            println!("cargo:rerun-if-changed={}", path.display());
            if path.extension().is_some_and(|e| e == "json") {
                let stem = path
                    .file_stem()
                    .and_then(|s| s.to_str())
                    .unwrap_or_default()
                    .to_string();
                entries.push((stem, path.display().to_string()));
            }
        }
    }
    entries.sort();
    let mut code = String::from(
        "/// Embedded start-solution files: (file stem, JSON text), sorted by stem.\n\
         pub static EMBEDDED_START_FILES: &[(&str, &str)] = &[\n",
    );
    for (stem, path) in entries {
        code.push_str(&format!("    ({stem:?}, include_str!({path:?})),\n"));
    }
    code.push_str("];\n");
    let out =
        Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("start_files.rs");
    fs::write(out, code).expect("OUT_DIR is writable");
}
