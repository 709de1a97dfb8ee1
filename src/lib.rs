//! As-Killing-As-Possible 2D shape deformation (Solomon, Ben-Chen, Butscher, Guibas,
//! SGP 2011), in Rust for native use and WebAssembly.
//!
//! The pipeline starts with a shape [`Outline`] (a polygon with holes), which
//! [`triangulate()`] turns into a validated [`Mesh`]: constrained Delaunay, refined to a
//! target triangle size and minimum angle. The deformers work on that mesh.
//!
//! ```
//! use akap::{shapes, triangulate, TriangulationOptions};
//!
//! let figure = shapes::gingerbread();
//! let mesh = triangulate(&figure, &TriangulationOptions::default().with_target_edge_length(0.05))?;
//! assert!(mesh.triangle_count() > 100);
//! // Triangulation covers exactly the outline minus its holes.
//! assert!((mesh.area() - figure.area()).abs() < 1e-9);
//! # Ok::<(), akap::Error>(())
//! ```
//!
//! Module map (see ARCHITECTURE.md): [`geometry`] (planar helpers), [`outline`] (input
//! shapes and their validation), [`triangulate`](mod@triangulate) (the only user of spade),
//! [`mesh`] (the validated mesh shared by every solver), [`shapes`] (built-in shapes),
//! [`sparse`] (our sparse Cholesky and eigensolver), [`random`] (a seeded generator),
//! [`deform`] (AKAP and ARAP), [`defop`] (the deformation operators of the DefOp paper),
//! [`session`] (recorded interaction sessions and their replay), [`import`] (SVG
//! documents, images and mesh files in), [`animation`] (animations out: GIF, APNG, ZIP,
//! the `akap-animation` JSON and sprite tables), and `wasm` (the JavaScript bindings, compiled for
//! wasm32 only).

pub mod animation;
pub mod defop;
pub mod deform;
pub mod error;
mod error_code;
pub mod geometry;
pub mod import;
pub mod mesh;
mod message;
pub mod outline;
pub mod pose;
pub mod random;
pub mod session;
pub mod shapes;
pub mod sparse;
pub(crate) mod sweep;
pub mod triangulate;

#[cfg(target_arch = "wasm32")]
pub mod wasm;
#[cfg(all(target_arch = "wasm32", feature = "bench"))]
mod wasm_bench;

pub use error::{Error, ErrorCode};
pub use mesh::{Mesh, MeshError, MeshPoint};
pub use outline::{Outline, OutlineError, Ring};
pub use triangulate::{triangulate, TriangulationError, TriangulationOptions};
