//! Shared helpers of the pipeline tests: start solutions cached on disk between test
//! processes (`target/start-cache/STEM.json`) when no embedded file exists, so the
//! on-the-fly ab-initio computation runs once per machine, not once per test binary.

#![allow(dead_code)]

use singdist::pipeline::ab_initio;
use singdist::pipeline::start_file::StartSolutions;
use singdist::problem::ProblemId;
use std::path::PathBuf;
use std::sync::Arc;

fn cache_path(id: ProblemId) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("start-cache")
        .join(format!("{}.json", id.file_stem()))
}

/// Start solutions of `id`: embedded file, else the disk cache, else computed by the
/// ab-initio stage and written to the cache.
pub fn cached_start_solutions(id: ProblemId) -> Result<Arc<StartSolutions>, String> {
    if let Some(file) = ab_initio::embedded_start_solutions(id) {
        return file.map(Arc::new).map_err(|e| e.to_string());
    }
    let path = cache_path(id);
    // A non-finite trace residual is written as `null`; read it back as infinity.
    if let Ok(text) = std::fs::read_to_string(&path)
        && let Ok(file) = serde_json::from_str::<StartSolutions>(
            &text.replace("\"trace_residual\":null", "\"trace_residual\":1e999"),
        )
    {
        return Ok(Arc::new(file));
    }
    let file = ab_initio::start_solutions(id).map_err(|e| e.to_string())?;
    if let Some(dir) = path.parent() {
        let _ = std::fs::create_dir_all(dir);
    }
    if let Ok(text) = serde_json::to_string(&*file) {
        let _ = std::fs::write(&path, text);
    }
    Ok(file)
}
