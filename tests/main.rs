//! Integration tests: one binary, one module per area, shared checks in `common`.

mod common;
mod triangulation;
