//! AKAP-like test matrices for the Cholesky benchmarks, built in one place.
//!
//! Included by path (`#[path = ...] mod common;`) from `lab/sparse/cholesky.rs`,
//! `lab/sparse/cholesky_table.rs` and, for the wasm benchmark, `src/wasm_bench.rs`: the crate
//! root may only gain the one `mod wasm_bench;` line, so the library cannot export these
//! helpers to the native targets, and a file included by path serves both.
//!
//! A matrix is the `2n x 2n` Killing-energy matrix of a triangle mesh
//! ([`KillingMatrix`]) with either a soft-constraint penalty on four handle vertices
//! ([`Variant::Penalty`]) or the boundary vertices eliminated ([`Variant::Dirichlet`]);
//! both are symmetric positive definite.

use sprs::CsMat;

#[cfg(target_arch = "wasm32")]
use crate::{
    deform::akap::killing::KillingMatrix,
    shapes,
    sparse::{expand_blocks, fill_reducing_order, Ordering},
    triangulate::triangulate_to_about,
    Mesh, Outline, TriangulationOptions,
};
#[cfg(not(target_arch = "wasm32"))]
use akap::{
    deform::akap::killing::KillingMatrix,
    shapes,
    sparse::{expand_blocks, fill_reducing_order, Ordering},
    triangulate::triangulate_to_about,
    Mesh, Outline, TriangulationOptions,
};

pub(crate) mod faer_llt;

/// The penalty weight added to the diagonal of each handle vertex's 2 x 2 block.
pub(crate) const PENALTY: f64 = 100.0;

/// The target vertex counts of the standard cases.
pub(crate) const SIZES: [usize; 5] = [1_000, 5_000, 10_000, 50_000, 100_000];

/// The shape that is meshed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shape {
    /// A 10 x 1 rectangle.
    Bar,
    /// The built-in gingerbread figure (about 1.4 tall, four holes).
    Gingerbread,
}

impl Shape {
    /// Both shapes.
    pub(crate) const ALL: [Shape; 2] = [Shape::Bar, Shape::Gingerbread];

    /// The name used in tables and on the command line.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Shape::Bar => "bar",
            Shape::Gingerbread => "gingerbread",
        }
    }

    /// The shape of a name, if it is one.
    pub(crate) fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The outline.
    pub(crate) fn outline(self) -> Outline {
        match self {
            Shape::Bar => Outline::new(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 1.0], [0.0, 1.0]]),
            Shape::Gingerbread => shapes::gingerbread(),
        }
    }
}

/// Which constraints make the Killing matrix definite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Variant {
    /// The full matrix plus [`PENALTY`] on the diagonal of four handle vertices.
    Penalty,
    /// The submatrix of the interior vertices' unknowns (boundary fixed).
    Dirichlet,
}

impl Variant {
    /// Both variants.
    pub(crate) const ALL: [Variant; 2] = [Variant::Penalty, Variant::Dirichlet];

    /// The name used in tables.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Variant::Penalty => "penalty",
            Variant::Dirichlet => "dirichlet",
        }
    }
}

/// How our factorisation orders the unknowns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OrderChoice {
    /// AMD on the matrix ([`Ordering::Amd`], on the graph compressed to 2x2 blocks).
    Amd,
    /// What the deformer uses: [`fill_reducing_order`] on the vertex graph (AMD, or from
    /// 8000 vertices nested dissection when it needs fewer flops), expanded to blocks.
    Best,
}

impl OrderChoice {
    /// The name used in tables and on the command line.
    pub(crate) fn name(self) -> &'static str {
        match self {
            OrderChoice::Amd => "amd",
            OrderChoice::Best => "best",
        }
    }

    /// The choice of a name, if it is one.
    pub(crate) fn from_name(name: &str) -> Option<Self> {
        [OrderChoice::Amd, OrderChoice::Best].into_iter().find(|c| c.name() == name)
    }
}

/// One benchmark matrix: what it was made from and the matrix (full symmetric, CSC).
#[derive(Debug, Clone)]
pub(crate) struct Problem {
    /// The meshed shape.
    pub(crate) shape: Shape,
    /// The constraints.
    pub(crate) variant: Variant,
    /// The vertex count asked for.
    pub(crate) target_vertices: usize,
    /// The mesh's actual vertex count.
    pub(crate) vertices: usize,
    /// The matrix, both triangles stored.
    pub(crate) matrix: CsMat<f64>,
    /// The graph of the vertices whose unknowns the matrix has (adjacency lists) and their
    /// positions, for vertex orderings.
    graph: (Vec<usize>, Vec<usize>, Vec<[f64; 2]>),
}

impl Problem {
    /// Builds the matrix of one case.
    pub(crate) fn new(shape: Shape, target_vertices: usize, variant: Variant) -> Self {
        let mesh = mesh_with_about(shape, target_vertices);
        let matrix = match variant {
            Variant::Penalty => penalty_matrix(&mesh),
            Variant::Dirichlet => dirichlet_matrix(&mesh),
        };
        let keep = |v: usize| variant == Variant::Penalty || !mesh.is_boundary_vertex(v);
        let mut index = vec![usize::MAX; mesh.vertex_count()];
        let mut points = Vec::new();
        for v in (0..mesh.vertex_count()).filter(|&v| keep(v)) {
            index[v] = points.len();
            points.push(mesh.positions()[v]);
        }
        let (ptr, adj) = mesh.relabelled_vertex_graph(&index);
        Self { shape, variant, target_vertices, vertices: mesh.vertex_count(), matrix, graph: (ptr, adj, points) }
    }

    /// The ordering for our analysis (computing it, for [`OrderChoice::Best`]; time it with
    /// the analysis).
    pub(crate) fn ordering(&self, choice: OrderChoice) -> Ordering {
        match choice {
            OrderChoice::Amd => Ordering::Amd,
            OrderChoice::Best => {
                let (ptr, adj, points) = &self.graph;
                Ordering::Given(expand_blocks(&fill_reducing_order(ptr, adj, points, 2), 2))
            }
        }
    }

    /// A short label: `bar/10k/penalty`.
    pub(crate) fn label(&self) -> String {
        format!("{}/{}/{}", self.shape.name(), size_label(self.target_vertices), self.variant.name())
    }

    /// Unknowns.
    pub(crate) fn n(&self) -> usize {
        self.matrix.cols()
    }

    /// Stored entries of the lower triangle, diagonal included.
    pub(crate) fn nnz_lower(&self) -> usize {
        self.matrix.iter().filter(|(_, (row, col))| row >= col).count()
    }

    /// `b - A x` relative to `b`, in the 2-norm.
    pub(crate) fn relative_residual(&self, x: &[f64], b: &[f64]) -> f64 {
        let mut r = b.to_vec();
        for (&value, (row, col)) in self.matrix.iter() {
            r[row] -= value * x[col];
        }
        norm(&r) / norm(b)
    }
}

/// `1k`, `50k`, ...
pub(crate) fn size_label(vertices: usize) -> String {
    if vertices.is_multiple_of(1000) {
        format!("{}k", vertices / 1000)
    } else {
        vertices.to_string()
    }
}

/// Triangulates `shape` to about `target` vertices (within 3%, the library's rule:
/// [`triangulate_to_about`]).
pub(crate) fn mesh_with_about(shape: Shape, target: usize) -> Mesh {
    let options = TriangulationOptions::default().with_max_vertices(4 * target + 10_000);
    triangulate_to_about(&shape.outline(), target, &options).expect("the benchmark shapes triangulate").0
}

/// The Killing matrix at rest plus [`PENALTY`] on the two diagonal entries of each of four
/// handle vertices: those nearest the corners of the bounding box.
pub(crate) fn penalty_matrix(mesh: &Mesh) -> CsMat<f64> {
    let mut killing = KillingMatrix::new(mesh);
    killing.assemble(mesh.positions());
    let mut matrix = killing.matrix().clone();
    for v in handles(mesh) {
        let [[first, _], [_, second]] = killing.block_slots(v, v).expect("diagonal blocks are in the pattern");
        let data = matrix.data_mut();
        data[first] += PENALTY;
        data[second] += PENALTY;
    }
    matrix
}

/// The Killing matrix at rest restricted to the unknowns of the interior vertices.
pub(crate) fn dirichlet_matrix(mesh: &Mesh) -> CsMat<f64> {
    let mut killing = KillingMatrix::new(mesh);
    killing.assemble(mesh.positions());
    let full = killing.matrix();
    // New index of each old unknown (usize::MAX for boundary ones); increasing, so the
    // rows of each column stay sorted.
    let mut index = vec![usize::MAX; full.cols()];
    let mut n = 0;
    for v in 0..mesh.vertex_count() {
        if !mesh.is_boundary_vertex(v) {
            index[2 * v] = n;
            index[2 * v + 1] = n + 1;
            n += 2;
        }
    }
    let (mut indptr, mut indices, mut data) = (vec![0], Vec::new(), Vec::new());
    for (col, column) in full.outer_iterator().enumerate() {
        if index[col] == usize::MAX {
            continue;
        }
        for (row, &value) in column.iter() {
            if index[row] != usize::MAX {
                indices.push(index[row]);
                data.push(value);
            }
        }
        indptr.push(indices.len());
    }
    CsMat::new_csc((n, n), indptr, indices, data)
}

/// The vertices nearest the four corners of the mesh's bounding box.
fn handles(mesh: &Mesh) -> Vec<usize> {
    let p = mesh.positions();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in p {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let mut chosen = Vec::new();
    for corner in [[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]] {
        let distance = |v: usize| (p[v][0] - corner[0]).powi(2) + (p[v][1] - corner[1]).powi(2);
        let nearest = (0..p.len()).min_by(|&a, &b| distance(a).total_cmp(&distance(b))).expect("a non-empty mesh");
        if !chosen.contains(&nearest) {
            chosen.push(nearest);
        }
    }
    chosen
}

/// A reproducible right-hand side with entries in [-1, 1) (xorshift64*).
pub(crate) fn random_vector(n: usize, seed: u64) -> Vec<f64> {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..n)
        .map(|_| {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            let bits = state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
            bits as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect()
}

/// The 2-norm.
pub(crate) fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// `||x - y|| / ||y||`.
pub(crate) fn relative_difference(x: &[f64], y: &[f64]) -> f64 {
    let diff: Vec<f64> = x.iter().zip(y).map(|(a, b)| a - b).collect();
    norm(&diff) / norm(y)
}

/// The median of some timings (the mean of the middle two for an even count).
pub(crate) fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let m = values.len() / 2;
    if values.len().is_multiple_of(2) {
        0.5 * (values[m - 1] + values[m])
    } else {
        values[m]
    }
}

/// Repetitions for a case: many for small matrices, few for the big ones.
pub(crate) fn default_repeats(target_vertices: usize) -> usize {
    match target_vertices {
        0..=10_000 => 15,
        10_001..=50_000 => 7,
        _ => 5,
    }
}
