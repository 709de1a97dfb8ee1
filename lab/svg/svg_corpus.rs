//! The SVG importer on every `.svg` under the given folders: how many import, how many are
//! refused (and why, by kind), whether any panicked, and the time per file, fills and
//! strokes and fills only.
//!
//! cargo run --release --example svg_corpus -- www/gallery path/to/resvg/tests

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use akap::import::svg::{import_svg, SvgOptions};

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "svg") {
            out.push(path);
        }
    }
}

fn main() {
    let mut all = Vec::new();
    for dir in std::env::args().skip(1) {
        files(Path::new(&dir), &mut all);
    }
    all.sort();
    let texts: Vec<(String, String)> =
        all.iter().filter_map(|p| Some((p.display().to_string(), std::fs::read_to_string(p).ok()?))).collect();
    for strokes in [true, false] {
        let options = SvgOptions { strokes, ..SvgOptions::default() };
        let (mut imported, mut panicked) = (0, 0);
        let mut refused: BTreeMap<String, usize> = BTreeMap::new();
        let mut times = Vec::new();
        for (name, text) in &texts {
            let start = Instant::now();
            let result = std::panic::catch_unwind(|| import_svg(text, &options));
            times.push((start.elapsed().as_secs_f64() * 1e3, name.clone()));
            match result {
                Ok(Ok(_)) => imported += 1,
                Ok(Err(e)) => *refused.entry(e.code().to_string() + ": " + kind(&e.to_string())).or_default() += 1,
                Err(_) => {
                    panicked += 1;
                    println!("PANICKED on {name}");
                }
            }
        }
        let total: f64 = times.iter().map(|t| t.0).sum();
        times.sort_by(|a, b| b.0.total_cmp(&a.0));
        println!(
            "strokes {strokes}: {} files, {imported} imported, {} refused, {panicked} panicked; {total:.0} ms in all, {:.3} ms per file, median {:.3} ms",
            texts.len(),
            refused.values().sum::<usize>(),
            total / texts.len().max(1) as f64,
            times.get(times.len() / 2).map_or(0.0, |t| t.0),
        );
        for (why, n) in &refused {
            println!("  {n:>5}  {why}");
        }
        for (ms, name) in times.iter().take(5) {
            println!("  {ms:>8.2} ms  {name}");
        }
    }
}

/// The kind of a refusal: its message up to the first detail.
fn kind(message: &str) -> &str {
    let end = message.find([':', '(', '<']).unwrap_or(message.len());
    &message[..end.min(60)]
}
