//! Output files: checked before the computation (known extension, existing and writable
//! folder) and written so that a failed write leaves no half-written file behind.

use anyhow::{Context, Result, anyhow, bail};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The extension of `path`, lower case (`None` without one).
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// Whether `path` ends in `.csv` (any case).
pub fn is_csv(path: &Path) -> bool {
    extension(path).as_deref() == Some("csv")
}

/// The folder `path` is written into (`.` for a bare file name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Checks that files can be created in the existing folder `folder`, by creating and
/// removing an empty probe file there; errors start with `prefix`.
fn check_folder_writable(prefix: &str, folder: &Path) -> Result<()> {
    match std::fs::metadata(folder) {
        Err(_) => bail!("{prefix}: the folder {} does not exist", folder.display()),
        Ok(m) if !m.is_dir() => bail!("{prefix}: {} is not a folder", folder.display()),
        Ok(_) => {}
    }
    let probe = folder.join(format!(".singdist-write-check-{}", std::process::id()));
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => bail!(
            "{prefix}: cannot write into the folder {}: {e}",
            folder.display()
        ),
    }
}

/// Checks an output file of option `option` before any work: its extension is one of
/// `extensions` (lower case, without the dot), it is not a folder, its folder exists
/// and is writable, and an existing file there can be overwritten.
pub fn check_output_file(option: &str, path: &Path, extensions: &[&str]) -> Result<()> {
    let ext = extension(path);
    if !ext.as_deref().is_some_and(|e| extensions.contains(&e)) {
        let given = ext.map_or("no file extension".to_string(), |e| {
            format!("the extension `.{e}`")
        });
        if extensions == ["svg"] {
            bail!(
                "{option}: {}: plots are written as SVG only (no raster backend is built in), got {given}; give a .svg file name",
                path.display()
            );
        }
        let list: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
        bail!(
            "{option}: {}: {given} is not written by this command (expected {})",
            path.display(),
            list.join(" or ")
        );
    }
    check_writable(option, path)
}

/// Checks that `path` can be written (folder exists and is writable, not a folder,
/// an existing file can be overwritten), whatever its extension.
pub fn check_writable(option: &str, path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!("{option}: {} is a folder, not a file", path.display());
    }
    check_folder_writable(&format!("{option}: {}", path.display()), &folder_of(path))?;
    if path.exists() {
        std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|e| anyhow!("{option}: {}: cannot be overwritten: {e}", path.display()))?;
    }
    Ok(())
}

/// Checks an output folder before any work: it exists (or, with `create`, its parent
/// does) and is writable.
pub fn check_output_folder(option: &str, folder: &Path, create: bool) -> Result<()> {
    if folder.is_dir() {
        return check_folder_writable(option, folder);
    }
    if create && !folder.exists() {
        return check_folder_writable(option, &folder_of(folder));
    }
    bail!("{option}: the folder {} does not exist", folder.display())
}

/// Writes `contents` to `path`; if the write fails, a half-written file is removed and
/// the error names the option, the file and the cause.
pub fn write_file(option: &str, path: &Path, contents: impl AsRef<[u8]>) -> Result<()> {
    std::fs::write(path, contents).map_err(|e| {
        let _ = std::fs::remove_file(path);
        anyhow!("{option}: {}: cannot write: {e}", path.display())
    })
}

/// `FILE.partial`: results appended as JSON lines while a run goes on, superseded by
/// `FILE` at the end. Created only after every input was checked.
pub struct PartialFile {
    path: PathBuf,
    file: std::sync::Mutex<std::fs::File>,
}

impl PartialFile {
    /// The partial file of the output `out` (`out` + `.partial`).
    pub fn path_for(out: &Path) -> PathBuf {
        let mut name = out.as_os_str().to_owned();
        name.push(".partial");
        PathBuf::from(name)
    }

    /// Creates (truncates) the partial file of `out`.
    pub fn create(option: &str, out: &Path) -> Result<Self> {
        let path = Self::path_for(out);
        let file = std::fs::File::create(&path).with_context(|| {
            format!(
                "{option}: {}: cannot create the partial file",
                path.display()
            )
        })?;
        Ok(PartialFile {
            path,
            file: std::sync::Mutex::new(file),
        })
    }

    /// Opens the partial file of `out` to continue it after its first `keep` bytes
    /// (what follows is cut off).
    pub fn reopen(option: &str, out: &Path, keep: u64) -> Result<Self> {
        let path = Self::path_for(out);
        let cannot = |e: std::io::Error| {
            anyhow!(
                "{option}: {}: cannot continue the partial file: {e}",
                path.display()
            )
        };
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(cannot)?;
        file.set_len(keep).map_err(cannot)?;
        Ok(PartialFile {
            path,
            file: std::sync::Mutex::new(file),
        })
    }

    /// Where the partial file is.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends `text` in one write; the error names the file.
    pub fn append(&self, text: &str) -> Result<()> {
        let mut file = self.file.lock().unwrap_or_else(|e| e.into_inner());
        file.write_all(text.as_bytes())
            .and_then(|()| file.flush())
            .map_err(|e| anyhow!("--out: {}: cannot write: {e}", self.path.display()))
    }

    /// The partial file is complete and becomes `out`.
    pub fn rename_to(self, option: &str, out: &Path) -> Result<()> {
        match std::fs::rename(&self.path, out) {
            Ok(()) => Ok(()),
            Err(e) => {
                let error = anyhow!("{option}: {}: cannot write: {e}", out.display());
                Err(self.abandon(error))
            }
        }
    }

    /// The final file was written: the partial one goes.
    pub fn finish(self) {
        let _ = std::fs::remove_file(&self.path);
    }

    /// The run failed: an empty partial file is removed; one with results is kept and
    /// named in the error.
    pub fn abandon(self, error: anyhow::Error) -> anyhow::Error {
        let empty = std::fs::metadata(&self.path).map_or(true, |m| m.len() == 0);
        if empty {
            let _ = std::fs::remove_file(&self.path);
            error
        } else {
            anyhow!(
                "{}; the results so far are kept in {} (JSON lines)",
                super::outcome::one_line_message(&error),
                self.path.display()
            )
        }
    }
}
