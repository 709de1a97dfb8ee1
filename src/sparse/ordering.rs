//! The ordering policy: how the unknowns of a system are ordered before its analysis, in
//! one place. [`super::Symbolic::analyse`] is told an [`Ordering`](super::Ordering)
//! (natural, minimum degree, minimum fill, or an order computed apart, such as one from
//! here); this module chooses among the orders of a graph's nodes (such as a mesh's
//! vertices) for systems with `block` unknowns per node:
//!
//! - [`order_flops`]: the flops an order of the nodes will need, from the elimination tree
//!   and column counts of the node graph alone, so that orders are compared before any is
//!   analysed;
//! - [`cheaper_order`]: whichever of two orders needs fewer flops;
//! - [`DISSECTION_MIN_NODES`], [`dissection_if_large`]: nested dissection is worth trying
//!   from 12,000 nodes;
//! - [`fill_or_dissection`]: minimum fill, or a dissection order where it needs fewer flops;
//!   [`fill_reducing_order`]: the same, with the dissection computed here when the graph is
//!   large;
//! - [`expand_blocks`]: a node order to the order of the unknowns, `block` per node.
//!
//! The orders themselves are computed by `amd` ([`super::amd_order`], [`super::amf_order`])
//! and `nested_dissection` ([`super::nested_dissection_order`]).

use super::amd::amf_order;
use super::nested_dissection::nested_dissection_order;
use super::symbolic::order_column_counts;

/// The flops ([`super::Symbolic::flops`]) of factoring a matrix with `block` unknowns per
/// node of a graph, every pair of adjacent nodes coupled by a full `block x block` block (as
/// the AKAP matrices couple the velocities of neighbouring vertices), eliminated node by
/// node in `order` and each node's unknowns consecutively ([`expand_blocks`]).
///
/// Much cheaper than [`super::Symbolic::analyse`] on the expanded matrix (the elimination
/// tree and column counts of the node graph only), so that several orders can be compared
/// before one is analysed: the column of L of the k-th unknown of a node with `c` entries
/// in its column of the node graph's factor has `block * c - k` entries. The graph is given
/// by symmetric adjacency lists (`adj[ptr[v]..ptr[v + 1]]`, without self-loops).
///
/// # Panics
/// If `order` is not a permutation of the nodes (a broken internal invariant of callers).
pub fn order_flops(ptr: &[usize], adj: &[usize], order: &[usize], block: usize) -> f64 {
    order_column_counts(ptr, adj, order)
        .iter()
        .map(|&c| (0..block).map(|k| ((block * c - k) * (block * c - k)) as f64).sum::<f64>())
        .sum()
}

/// Graphs with fewer nodes than this are ordered by minimum fill alone: below it, our
/// nested dissection saved few flops or none on the meshes measured (relative to AMD's
/// flops, averaged over relabellings: 1.3-1.4x at 1k vertices, 1.0-1.07x at 5k, 0.91-0.93x
/// at 10k, where minimum fill needs 0.86-0.90x; at 16k 0.85-0.91x against 0.86-0.88x, at
/// 50k 0.78-0.80x against 0.81-0.85x; `cargo run --release --example orderings -- --relabel
/// 4`), and it takes 3-4x minimum fill's time (5-8x AMD's).
pub const DISSECTION_MIN_NODES: usize = 12_000;

/// A nested-dissection order of a graph of at least [`DISSECTION_MIN_NODES`] nodes (`None`
/// for a smaller one, where it is not worth its time). The graph is given by symmetric
/// adjacency lists; `positions` has one point per node.
pub fn dissection_if_large(ptr: &[usize], adj: &[usize], positions: &[[f64; 2]]) -> Option<Vec<usize>> {
    let n = ptr.len() - 1;
    (n >= DISSECTION_MIN_NODES).then(|| nested_dissection_order(ptr, adj, positions))
}

/// Approximate minimum fill ([`super::amf_order`]), or `dissection` when one is given and
/// needs fewer flops ([`cheaper_order`], with `block` unknowns per node). The dissection
/// may come from elsewhere: a larger graph's order restricted to this one's nodes (as
/// AKAP's step 2 takes its interior vertices in the order of the whole mesh's).
pub fn fill_or_dissection(ptr: &[usize], adj: &[usize], block: usize, dissection: Option<Vec<usize>>) -> Vec<usize> {
    let by_fill = amf_order(ptr.len() - 1, ptr, adj);
    match dissection {
        Some(order) => cheaper_order(ptr, adj, block, by_fill, order),
        None => by_fill,
    }
}

/// A fill-reducing order of the nodes of a graph with `block` unknowns per node (as
/// [`order_flops`] counts them): approximate minimum fill ([`super::amf_order`]), or, for
/// graphs of at least [`DISSECTION_MIN_NODES`] nodes, nested dissection when it needs fewer
/// flops. The graph is given by symmetric adjacency lists; `positions` has one point per
/// node.
pub fn fill_reducing_order(ptr: &[usize], adj: &[usize], positions: &[[f64; 2]], block: usize) -> Vec<usize> {
    fill_or_dissection(ptr, adj, block, dissection_if_large(ptr, adj, positions))
}

/// Whichever of two orders of a graph's nodes needs fewer flops ([`order_flops`]); the
/// first on a tie.
///
/// # Panics
/// If an order is not a permutation of the nodes (a broken internal invariant of callers).
pub fn cheaper_order(ptr: &[usize], adj: &[usize], block: usize, first: Vec<usize>, second: Vec<usize>) -> Vec<usize> {
    if order_flops(ptr, adj, &second, block) < order_flops(ptr, adj, &first, block) {
        second
    } else {
        first
    }
}

/// Expands an order of nodes to `block` unknowns per node, numbered `block * v + k`: each
/// node's unknowns stay together, in the node's place.
pub fn expand_blocks(order: &[usize], block: usize) -> Vec<usize> {
    order.iter().flat_map(|&v| (0..block).map(move |k| block * v + k)).collect()
}
