//! Integration tests: one binary, one module per area, shared checks in `common`.

mod animation;
mod animation_file;
mod arap;
mod bones;
mod cauchy_green;
mod common;
mod defop_carry;
mod defop_coordinates;
mod defop_eval;
mod defop_file;
mod defop_fit;
mod defop_gpu;
mod defop_ground_truth;
mod defop_puppet;
mod defop_train;
mod deformer;
mod errors;
mod foldover;
mod gallery;
mod hostile;
mod import_mesh;
mod import_raster;
mod import_svg;
mod import_svg_art;
mod killing;
mod limits;
mod mesh;
mod mesh_file_puppet;
mod mls;
mod pose;
#[cfg(not(target_arch = "wasm32"))]
mod pose_obj;
mod pose_rig;
mod puppet;
mod puppet_import;
mod session;
mod sparse;
mod stiffness;
mod triangulation;
mod turning;
#[cfg(target_arch = "wasm32")]
mod wasm_animation;
#[cfg(target_arch = "wasm32")]
mod wasm_api;
#[cfg(target_arch = "wasm32")]
mod wasm_puppet;
