use akap::import::raster::{trace_image, TraceOptions};
fn main() {
    let (w, h) = (20, 10);
    let mut rgba = vec![0u8; w * h * 4];
    for y in 2..8 { for x in 5..15 { rgba[4 * (y * w + x) + 3] = 255; } }
    for tol in [0.0, 0.5, 1.0] {
        let o = trace_image(&rgba, w, h, &TraceOptions { tolerance: tol, ..TraceOptions::default() }).unwrap();
        println!("tol {tol}: area {} {:?}", o[0].area(), o[0].outer);
    }
}
