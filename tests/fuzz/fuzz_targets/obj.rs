//! Wavefront OBJ: reading never panics or hangs; a mesh that reads writes back to a file
//! that reads to the same mesh and texture coordinates.
#![no_main]

use akap::import::mesh_file::{read_obj, write_obj};
use akap::import::Limits;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let limits = Limits { max_vertices: 10_000, ..Limits::default() };
    let Ok(file) = read_obj(text, &limits) else { return };
    let written =
        write_obj(&file.mesh, file.uvs.as_deref(), file.puppet.as_ref(), &limits).expect("a read mesh writes within the same limits");
    let again = read_obj(&written, &limits).expect("a written mesh reads");
    if file.puppet.is_none() {
        assert_eq!(again, file);
    } else {
        // Groups are written back to front, each part's faces together: the triangles may be
        // renumbered once, and then the file is a fixed point.
        let twice = write_obj(&again.mesh, again.uvs.as_deref(), again.puppet.as_ref(), &limits).expect("writes again");
        assert_eq!(twice, written);
    }
});
