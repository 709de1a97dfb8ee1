//! Issue 21's spike: the hand-written SVG importer against the usvg-based one
//! (`import_svg_usvg`: fills and strokes) on every `.svg` under the given folders: how many
//! each imports, where their areas differ, and the time of each.
//!
//! cargo run --release --example usvg_spike -- www/gallery path/to/resvg/tests

use std::path::{Path, PathBuf};
use std::time::Instant;

use akap::import::svg::{import_svg, import_svg_usvg, SvgOptions};

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
    let options = SvgOptions::default();
    let (mut same, mut differ, mut only_old, mut only_new, mut neither) = (0, 0, 0, 0, 0);
    let (mut old_ms, mut new_ms, mut parse_ms) = (0.0, 0.0, 0.0);
    let mut slowest = Vec::new();
    let mut differences = Vec::new();
    for path in &all {
        let Ok(text) = std::fs::read_to_string(path) else { continue };
        let t0 = Instant::now();
        let old = import_svg(&text, &options);
        let t1 = Instant::now();
        let new = std::panic::catch_unwind(|| import_svg_usvg(&text, &options));
        let t2 = Instant::now();
        old_ms += (t1 - t0).as_secs_f64() * 1e3;
        new_ms += (t2 - t1).as_secs_f64() * 1e3;
        let t3 = Instant::now();
        let _ = usvg::Tree::from_str(&text, &usvg::Options::default());
        parse_ms += t3.elapsed().as_secs_f64() * 1e3;
        slowest.push(((t2 - t1).as_secs_f64() * 1e3, path.display().to_string()));
        let area = |s: &akap::import::svg::SvgShape| s.outlines.iter().map(|o| o.area()).sum::<f64>();
        let name = path.display().to_string();
        match (old, new) {
            (Ok(a), Ok(Ok(b))) => {
                let (x, y) = (area(&a), area(&b));
                let relative = (x - y).abs() / x.max(y).max(f64::MIN_POSITIVE);
                if relative < 1e-3 {
                    same += 1;
                } else {
                    differ += 1;
                    differences.push((relative, name, x, y));
                }
            }
            (Ok(_), Ok(Err(e))) => {
                only_old += 1;
                println!("usvg refused {name}: {e}");
            }
            (Ok(_), Err(_)) => {
                only_old += 1;
                println!("usvg PANICKED on {name}");
            }
            (Err(_), Ok(Ok(_))) => only_new += 1,
            (Err(_), _) => neither += 1,
        }
    }
    differences.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (relative, name, x, y) in differences.iter().take(25) {
        println!("{:>8.1}%  {name}: {x:.4} -> {y:.4}", 100.0 * relative);
    }
    println!(
        "{} files: same area {same}, different {differ}, only the old imports {only_old}, only usvg {only_new}, neither {neither}",
        all.len()
    );
    println!("time: old {old_ms:.0} ms, usvg {new_ms:.0} ms (of which usvg's parse about {parse_ms:.0} ms)");
    slowest.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (ms, name) in slowest.iter().take(8) {
        println!("{ms:>8.0} ms  {name}");
    }
}
