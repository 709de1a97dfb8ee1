//! A trained operator evaluated on the GPU: what a vertex shader needs to pose each vertex
//! itself (paper eq. 3, `D(v, Q) = Σ_i φ_i(v) Σ_j X_ij ψ_j(Q)`), split so that a frame
//! computes on the CPU only a short vector:
//!
//! - a **reduced** spatial basis (|Φ| = k functions): the frame is `X Ψ(Q)` (k numbers per
//!   coordinate) and the basis texture holds D (k numbers per vertex), so the shader forms
//!   `x_v = D_vᵀ (X^x Ψ)`, `y_v = D_vᵀ (X^y Ψ)`;
//! - the **hat** basis (one function per vertex): the frame is `Ψ(Q)` (|Ψ| numbers) and the
//!   basis texture holds each vertex's coefficient rows X^x_v, X^y_v, so the shader forms
//!   `x_v = X^x_v · Ψ`, `y_v = X^y_v · Ψ`.
//!
//! Both are laid out in texels of four `f32` numbers (an RGBA32F texture), described by a
//! [`GpuLayout`]: vertex v's texels are `v stride .. (v + 1) stride`; its x sum runs over
//! texels `v stride + t` against frame texels `RIGID_TEXELS + t`, its y sum over
//! `v stride + basis_y + t` against `RIGID_TEXELS + frame_y + t`, for `t < terms` (unused
//! lanes are 0). The frame's first [`RIGID_TEXELS`] texels hold the rigid motion of
//! canonical coordinates (`(cos, sin, from_x, from_y)`, `(to_x, to_y, 0, 0)`; the identity
//! otherwise), which the shader applies last: `R (p − from) + to`.
//!
//! The frame is computed as [`super::SinglePrecision`] computes its first stage (Ψ(Q) in
//! double, rounded, `X Ψ` in `f32` on the same kernels), so a GPU pose differs from that
//! copy's only by the order of the last sums. Computing a frame allocates nothing. The
//! positions of a few chosen vertices (an outline drawn over the mesh, the handles) can be
//! had from each frame on the CPU ([`GpuRig::watch`]), equal to the single-precision copy's
//! at those vertices; the whole pose in double precision is the operator's.

use super::basis::HandleBasis;
use super::fit_error::{check_finite, check_length, FitError};
use super::kernels;
use super::operator::{canonical_scratch, Operator};
use super::single::rounded_psi;

/// Numbers per texel (RGBA).
pub const TEXEL: usize = 4;

/// Texels at the head of a frame: the rigid motion.
pub const RIGID_TEXELS: usize = 2;

/// How a rig's basis texture and frame are laid out (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GpuLayout {
    /// A reduced spatial basis (frame `X Ψ`, texture D), or the hat basis (frame `Ψ`,
    /// texture X).
    pub reduced: bool,
    /// The number of vertices N.
    pub vertex_count: usize,
    /// Texels of one coordinate's sum: ⌈k / 4⌉ (reduced) or ⌈|Ψ| / 4⌉ (hat).
    pub terms: usize,
    /// Texels per vertex in the basis texture: `terms` (reduced) or `2 terms` (hat).
    pub stride: usize,
    /// Where a vertex's y row starts among its texels: 0 (reduced: x and y share D_v) or
    /// `terms` (hat).
    pub basis_y: usize,
    /// Where the y vector starts in the frame, after the head: `terms` (reduced) or 0 (hat:
    /// x and y share Ψ).
    pub frame_y: usize,
    /// Texels of a frame: [`RIGID_TEXELS`] and `2 terms` (reduced) or `terms` (hat).
    pub frame_texels: usize,
}

impl GpuLayout {
    /// The layout of `operator`'s texture and frames.
    pub fn of(operator: &Operator) -> Self {
        let reduced = !operator.reduction().is_empty();
        let len = if reduced { operator.spatial_len() } else { operator.handle_basis().len() };
        let terms = len.div_ceil(TEXEL);
        let (stride, basis_y, frame_y) = if reduced { (terms, 0, terms) } else { (2 * terms, terms, 0) };
        let frame_texels = RIGID_TEXELS + if reduced { 2 * terms } else { terms };
        Self { reduced, vertex_count: operator.vertex_count(), terms, stride, basis_y, frame_y, frame_texels }
    }

    /// Texels of the basis texture: `vertex_count stride`.
    pub fn basis_texels(&self) -> usize {
        self.vertex_count * self.stride
    }
}

/// The basis texture of `operator` (`layout.basis_texels()` texels of four numbers), its
/// numbers rounded to `f32`: D by vertex (reduced), or each vertex's rows X^x_v and X^y_v
/// (hat), each row padded with zeros to whole texels. Made once per rig.
pub fn basis_texture(operator: &Operator) -> Vec<f32> {
    let layout = GpuLayout::of(operator);
    let mut out = vec![0.0f32; TEXEL * layout.basis_texels()];
    let width = TEXEL * layout.terms;
    if layout.reduced {
        let k = operator.spatial_len();
        for (row, d) in out.chunks_exact_mut(width).zip(operator.reduction().chunks_exact(k)) {
            round_into(&mut row[..k], d);
        }
    } else {
        // The coefficients hold row i of X^x then row i of X^y, for every vertex i: the
        // texture's layout, each row padded.
        let len = operator.handle_basis().len();
        for (row, x) in out.chunks_exact_mut(width).zip(operator.coefficients().chunks_exact(len)) {
            round_into(&mut row[..len], x);
        }
    }
    out
}

fn round_into(out: &mut [f32], values: &[f64]) {
    for (o, &v) in out.iter_mut().zip(values) {
        *o = v as f32;
    }
}

/// What a frame of a rig on the GPU computes on the CPU: see the module documentation.
/// Made from an operator by [`GpuRig::new`]; [`GpuRig::frame`] allocates nothing.
#[derive(Debug, Clone)]
pub struct GpuRig {
    layout: GpuLayout,
    basis: HandleBasis,
    /// A reduced basis: X rounded (row i of X^x then of X^y, as the operator keeps them).
    /// Empty for the hat basis, whose coefficients are the texture's.
    coefficients: Vec<f32>,
    /// The length of a sum: k (reduced) or |Ψ| (hat).
    len: usize,
    /// Scratch: Ψ(Q) in double, then rounded.
    psi: Vec<f64>,
    psi32: Vec<f32>,
    /// Scratch for a reduced basis: X^x Ψ then X^y Ψ, each padded to whole texels.
    nodal: Vec<f32>,
    /// Scratch for canonical coordinates: the canonical targets Q̂ (else empty).
    canonical: Vec<f64>,
    /// The frame: `TEXEL frame_texels` numbers.
    frame: Vec<f32>,
    /// The watched vertices, their rows (reduced: D_v, k numbers each; hat: X^x_v then X^y_v,
    /// |Ψ| each) rounded, and the positions of the last frame (2N numbers, fresh at the
    /// watched vertices only).
    watched: Vec<u32>,
    watched_rows: Vec<f32>,
    watched_positions: Vec<f64>,
}

impl GpuRig {
    /// The CPU side of `operator` on the GPU, watching no vertex.
    pub fn new(operator: &Operator) -> Self {
        let layout = GpuLayout::of(operator);
        let coefficients = match layout.reduced {
            true => operator.coefficients().iter().map(|&x| x as f32).collect(),
            false => Vec::new(),
        };
        let basis = operator.handle_basis().clone();
        let mut frame = vec![0.0f32; TEXEL * layout.frame_texels];
        frame[0] = 1.0; // the identity until a frame is computed
        let len = if layout.reduced { operator.spatial_len() } else { basis.len() };
        let nodal = if layout.reduced { vec![0.0; 2 * TEXEL * layout.terms] } else { Vec::new() };
        Self {
            layout,
            len,
            nodal,
            psi: vec![0.0; basis.len()],
            psi32: vec![0.0; basis.len()],
            canonical: canonical_scratch(&basis),
            basis,
            coefficients,
            frame,
            watched: Vec::new(),
            watched_rows: Vec::new(),
            watched_positions: vec![0.0; 2 * operator.vertex_count()],
        }
    }

    /// The layout of the texture and the frames.
    pub fn layout(&self) -> GpuLayout {
        self.layout
    }

    /// The last frame (`TEXEL frame_texels` numbers; the rest pose's until the first).
    pub fn frame_values(&self) -> &[f32] {
        &self.frame
    }

    /// Computes the frame for the handle targets Q (2n numbers), and the positions of the
    /// watched vertices. Allocates nothing. Refuses a wrong length and NaN or infinite
    /// targets, and a frame whose numbers overflow single precision (a pose no GPU can
    /// draw), changing nothing.
    pub fn frame(&mut self, targets: &[f64]) -> Result<&[f32], FitError> {
        check_length("targets", targets, self.basis.rest().len())?;
        check_finite("targets", targets)?;
        let rigid = rounded_psi(&self.basis, targets, &mut self.canonical, &mut self.psi, &mut self.psi32);
        check_finite_f32("handle basis", &self.psi32)?;
        let head = TEXEL * RIGID_TEXELS;
        let terms = TEXEL * self.layout.terms;
        let (cos, sin, from, to) = rigid.map_or((1.0, 0.0, [0.0; 2], [0.0; 2]), |r| (r.cos, r.sin, r.from, r.to));
        if self.layout.reduced {
            let (x, y) = self.nodal.split_at_mut(terms);
            kernels::pairs_times_vector(&self.coefficients, &self.psi32, |i, a, b| (x[i], y[i]) = (a, b));
            check_finite_f32("frame", &self.nodal)?;
            self.frame[head..].copy_from_slice(&self.nodal);
        } else {
            self.frame[head..head + self.len].copy_from_slice(&self.psi32);
        }
        self.frame[..head].copy_from_slice(&[cos, sin, from[0], from[1], to[0], to[1], 0.0, 0.0].map(|x| x as f32));
        self.pose_watched(rigid);
        Ok(&self.frame)
    }

    /// The positions of the watched vertices from the frame, as the single-precision copy
    /// computes them (the rigid motion applied in double to the rounded sums).
    fn pose_watched(&mut self, rigid: Option<super::Rigid>) {
        let head = TEXEL * RIGID_TEXELS;
        let (k, terms) = (self.len, TEXEL * self.layout.terms);
        if self.watched.is_empty() || k == 0 {
            return;
        }
        for (&v, row) in self.watched.iter().zip(self.watched_rows.chunks_exact(self.row_len())) {
            let [x, y] = if self.layout.reduced {
                let (nx, ny) = self.frame[head..].split_at(terms);
                let [[x, y]] = kernels::dots_f32([row], [nx, ny], k);
                [x, y]
            } else {
                let (rx, ry) = row.split_at(k);
                let [[x], [y]] = kernels::dots_f32([rx, ry], [&self.psi32], k);
                [x, y]
            };
            let [x, y] = match &rigid {
                Some(rigid) => rigid.apply([f64::from(x), f64::from(y)]).map(|c| f64::from(c as f32)),
                None => [f64::from(x), f64::from(y)],
            };
            let v = v as usize;
            self.watched_positions[2 * v] = x;
            self.watched_positions[2 * v + 1] = y;
        }
    }

    /// Numbers per watched row: k (reduced: D_v) or 2 |Ψ| (hat: X^x_v and X^y_v).
    fn row_len(&self) -> usize {
        if self.layout.reduced {
            self.len
        } else {
            2 * self.len
        }
    }

    /// Watches these vertices of `operator` (the one this was made from): each frame gives
    /// their positions ([`Self::watched_positions`]), replacing any watched before. Refuses
    /// a vertex out of range, changing nothing.
    pub fn watch(&mut self, operator: &Operator, vertices: &[u32]) -> Result<(), FitError> {
        let n = operator.vertex_count();
        if let Some(&v) = vertices.iter().find(|&&v| v as usize >= n) {
            return Err(FitError::InvalidOption {
                name: "watched vertex",
                value: f64::from(v),
                expected: "the index of a vertex of the rig's mesh",
            });
        }
        let len = self.row_len();
        let source = if self.layout.reduced { operator.reduction() } else { operator.coefficients() };
        let mut rows = vec![0.0f32; len * vertices.len()];
        for (row, &v) in rows.chunks_exact_mut(len).zip(vertices) {
            let v = v as usize;
            round_into(row, &source[v * len..(v + 1) * len]);
        }
        self.watched = vertices.to_vec();
        self.watched_rows = rows;
        Ok(())
    }

    /// The watched vertices.
    pub fn watched(&self) -> &[u32] {
        &self.watched
    }

    /// Positions (2N numbers, x and y interleaved) fresh at the watched vertices as of the
    /// last frame; the other entries hold what they held (0 at first).
    pub fn watched_positions(&self) -> &[f64] {
        &self.watched_positions
    }
}

fn check_finite_f32(what: &'static str, values: &[f32]) -> Result<(), FitError> {
    match values.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(FitError::NonFinite { what, index }),
        None => Ok(()),
    }
}
