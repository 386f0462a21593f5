//! `singdist curve --html`: a self-contained page (no network resources) whose slider
//! redraws K and each metric's K′, checked in headless Chromium where it is installed
//! (the browser part is skipped with a note where it is not).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod cli_support;
use cli_support::{assert_success, binary, temp_dir};

fn temp(name: &str) -> PathBuf {
    temp_dir("report-html").join(name)
}

/// `curve --poses 6 --quiet --html path --metric METRICS…`.
fn write_report(path: &Path, metrics: &[&str]) {
    run_html_report(&[], path, &[&["--metric"], metrics].concat());
}

/// `rrr curve --poses 6 --quiet --html path`.
fn write_rrr_report(path: &Path) {
    run_html_report(&["rrr"], path, &[]);
}

/// `singdist COMMAND… curve --poses 6 --quiet --html path EXTRA…`, which must succeed
/// (its stdout discarded).
fn run_html_report(command: &[&str], path: &Path, extra: &[&str]) {
    let html = ["curve", "--poses", "6", "--quiet", "--html"];
    let run = Command::new(binary())
        .args(command)
        .args(html)
        .arg(path)
        .args(extra)
        .stdout(Stdio::null())
        .output()
        .expect("the binary runs");
    assert_success(&run);
}

fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    for dir in std::env::split_paths(&path) {
        for name in ["chromium", "chromium-browser", "google-chrome"] {
            let candidate = dir.join(name);
            if candidate.is_file() {
                return Some(candidate);
            }
        }
    }
    None
}

/// `--dump-dom` of `page` (with the hash `#test`) in headless Chromium (killed after two minutes). The DOM
/// goes to a file: it is larger than a pipe's buffer.
fn dump_dom(browser: &Path, page: &Path) -> String {
    // One profile and DOM file per page: the tests run in parallel.
    let stem = page
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("page")
        .to_string();
    let profile = temp(&format!("chromium-profile-{stem}"));
    let dom_path = temp(&format!("dom-{stem}.html"));
    let url = format!("file://{}#test", page.display());
    let dom_file = std::fs::File::create(&dom_path).expect("DOM file");
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg("--dump-dom")
        .arg(&url)
        .stdout(dom_file)
        .stderr(Stdio::null())
        .spawn()
        .expect("chromium starts");
    let started = Instant::now();
    while child.try_wait().expect("wait on chromium").is_none() {
        if started.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("chromium did not finish within 120 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    std::fs::read_to_string(&dom_path).expect("the DOM was dumped")
}

/// The JSON the page's `#test` mode writes into `<pre id="test-result">`, and its text.
fn test_result(browser: &Path, path: &Path) -> (serde_json::Value, String) {
    let dom = dump_dom(browser, path);
    let start = dom
        .find(r#"<pre id="test-result">"#)
        .expect("the page was rendered")
        + r#"<pre id="test-result">"#.len();
    let end = start + dom[start..].find("</pre>").expect("test result closed");
    let text = dom[start..end]
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    assert!(
        !text.is_empty(),
        "the test script did not run (a script error before it?)"
    );
    let result: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    (result, text)
}

#[test]
fn report_page_is_self_contained() {
    let path = temp("static.html");
    write_report(&path, &["plate/plate", "bars/rigid"]);
    let html = std::fs::read_to_string(&path).expect("the page is written");
    assert!(html.starts_with("<!DOCTYPE html>"));
    for forbidden in ["<link", " src=", "https://", "url(http", "import("] {
        assert!(
            !html.contains(forbidden),
            "the page refers to an outside resource: `{forbidden}`"
        );
    }
    // Only the SVG namespace URI, which is a name, not a download.
    let http = html.matches("http://").count();
    assert_eq!(http, html.matches("http://www.w3.org/2000/svg").count());
    assert_eq!(html.matches(r#"id="tau-slider""#).count(), 1);
    assert_eq!(html.matches(r#"<polyline class="curve""#).count(), 2);
}

#[test]
fn slider_redraws_the_closest_configurations_in_headless_chromium() {
    let Some(browser) = chromium() else {
        println!("note: no chromium on PATH, the headless browser check is skipped");
        return;
    };
    let metrics = ["plate/plate", "bars/rigid", "rigid/rigid"];
    let path = temp("slider.html");
    write_report(&path, &metrics);
    let (result, text) = test_result(&browser, &path);
    assert_eq!(result["poses"], 6, "{text}");
    assert_eq!(result["slider"], 5, "{text}");
    assert_eq!(result["drawing_changed"], true, "{text}");
    assert_eq!(result["cursor_moved"], true, "{text}");
    assert_eq!(result["closest_drawn"], metrics.len(), "{text}");
    assert_eq!(result["legs_of_k"], 3, "{text}");
    assert_eq!(
        result["visible_after_untick"],
        metrics.len() - 1,
        "unticking a metric hides its K′: {text}"
    );
    assert_eq!(
        result["errors"],
        serde_json::json!([]),
        "console errors: {text}"
    );
}

#[test]
fn rrr_report_is_self_contained_and_its_slider_redraws_in_headless_chromium() {
    let path = temp("rrr.html");
    write_rrr_report(&path);
    let html = std::fs::read_to_string(&path).expect("the page is written");
    for forbidden in ["<link", " src=", "https://", "url(http", "import("] {
        assert!(!html.contains(forbidden), "outside resource: `{forbidden}`");
    }
    assert_eq!(html.matches(r#"<polyline class="curve""#).count(), 4);
    for label in ["parallel singular at", "leg 1 singular at"] {
        assert!(html.contains(label), "marker `{label}`");
    }
    let Some(browser) = chromium() else {
        println!("note: no chromium on PATH, the headless browser check is skipped");
        return;
    };
    let (result, text) = test_result(&browser, &path);
    assert_eq!(result["poses"], 6, "{text}");
    assert_eq!(result["slider"], 5, "{text}");
    assert_eq!(result["drawing_changed"], true, "{text}");
    assert_eq!(result["cursor_moved"], true, "{text}");
    // Parallel, leg 1, leg 2, leg 3; K has three proximal and three distal links.
    assert_eq!(result["closest_drawn"], 4, "{text}");
    assert_eq!(result["legs_of_k"], 6, "{text}");
    assert_eq!(result["visible_after_untick"], 3, "{text}");
    assert_eq!(
        result["errors"],
        serde_json::json!([]),
        "console errors: {text}"
    );
}
