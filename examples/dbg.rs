//! dbg
use akap::import::svg::{import_svg, SvgOptions};
fn main() {
    let t = std::fs::read_to_string(std::env::args().nth(1).unwrap()).unwrap();
    match import_svg(&t, &SvgOptions::default()) {
        Ok(s) => { for o in &s.outlines { println!("area {} holes {}", o.area(), o.holes.len()); } for p in &s.paths { println!("{:?} {:?} {:?} {:?}", p.part, p.fill, p.element, p.path.points); } }
        Err(e) => println!("error {e}"),
    }
}
