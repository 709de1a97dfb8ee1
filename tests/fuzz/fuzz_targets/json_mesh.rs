//! Our JSON mesh format: reading never panics or hangs; a mesh that reads writes back to
//! JSON that reads to the same mesh and texture coordinates.
#![no_main]

use akap::import::mesh_file::{read_json, write_json};
use akap::import::Limits;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let limits = Limits { max_vertices: 10_000, ..Limits::default() };
    let Ok(file) = read_json(text, &limits) else { return };
    let written =
        write_json(&file.mesh, file.uvs.as_deref(), file.stiffness.as_deref(), file.puppet.as_ref(), &limits).expect("a read mesh writes within the same limits");
    let again = read_json(&written, &limits).expect("a written mesh reads");
    assert_eq!(again, file);
});
