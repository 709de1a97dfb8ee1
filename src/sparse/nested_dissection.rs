//! Nested dissection: a fill-reducing order for sparse symmetric patterns such as the
//! vertex graphs of triangle meshes (when to use it: [`super::ordering`]).
//!
//! The separators are those of George's nested dissection (1973) found as in METIS's
//! `NodeND` (Karypis and Kumar 1998): each connected part of the graph is split by a
//! multilevel vertex separator ([`super::separator`]) into two halves, which are split in
//! turn (each of their connected components on its own) until parts have at most
//! [`LEAF_SIZE`] vertices. The order itself is a multisection (Ashcraft and Liu, "Robust
//! ordering of sparse matrices using multisection", SIAM J. Matrix Anal. Appl. 19(3),
//! 1998): constrained approximate minimum fill ([`super::amd::constrained_order`],
//! [`super::amf_order`]) eliminates first all the leaves (the domains), with the separators
//! around them counted in the degrees, then the union of all separators (the multisector).
//! Measured on the built-in shapes (`lab/sparse/orderings.rs`), this needs clearly fewer
//! flops than both pure minimum degree and the strict nested-dissection order (each
//! separator after both of its halves), which the multisector's greedy order is free to
//! improve on; minimum fill there instead of minimum degree saves another 2-8%.

use super::amd::constrained_order;
use super::amf_order;
use super::priority::Score;
use super::separator::{bisect, Refiner, WGraph, NONE, SEPARATOR};

/// Parts with at most this many vertices are not split further.
const LEAF_SIZE: usize = 128;

/// A nested-dissection (multisection) elimination order of a graph: `order[k]` is the
/// k-th vertex to eliminate. The neighbours of vertex `i` are `indices[ptr[i]..ptr[i + 1]]`
/// (symmetric; self-loops and repeated entries are ignored). `positions.len()` is the
/// number of vertices; the separators are found from the graph alone.
///
/// # Panics
/// If `ptr.len() != positions.len() + 1` or an index is not below `positions.len()`.
pub fn nested_dissection_order(ptr: &[usize], indices: &[usize], positions: &[[f64; 2]]) -> Vec<usize> {
    let n = positions.len();
    assert_eq!(ptr.len(), n + 1, "ptr must have one entry per vertex plus one");
    if n <= LEAF_SIZE || n >= NONE as usize {
        return amf_order(n, ptr, indices);
    }
    // The graph without self-loops and repeated entries.
    let mut graph = WGraph { ptr: Vec::with_capacity(n + 1), adj: Vec::new(), ewgt: Vec::new(), vwgt: vec![1; n] };
    graph.ptr.push(0);
    for v in 0..n {
        let start = graph.adj.len();
        graph.adj.extend(indices[ptr[v]..ptr[v + 1]].iter().filter(|&&u| u != v).map(|&u| u as u32));
        graph.adj[start..].sort_unstable();
        let mut kept = start;
        for k in start..graph.adj.len() {
            if kept == start || graph.adj[k] != graph.adj[kept - 1] {
                graph.adj[kept] = graph.adj[k];
                kept += 1;
            }
        }
        graph.adj.truncate(kept);
        graph.ptr.push(kept);
    }
    graph.ewgt = vec![1; graph.adj.len()];
    let mut dissection =
        Dissection { class: vec![0; n], label: vec![NONE; n], local: vec![NONE; n], refiner: Refiner::default() };
    let all: Vec<u32> = (0..n as u32).collect();
    dissection.split(&graph, &all);
    constrained_order(n, ptr, indices, dissection.class, Score::MeanFill)
}

/// The subgraph of `g` induced by `vertices` (its vertex `k` is `vertices[k]`), with
/// unit weights. `local` is scratch space over `g`'s vertices, all `NONE`, and left so.
fn subgraph(g: &WGraph, vertices: &[u32], local: &mut [u32]) -> WGraph {
    for (k, &v) in vertices.iter().enumerate() {
        local[v as usize] = k as u32;
    }
    // At most all of their edges stay: one allocation.
    let edges: usize = vertices.iter().map(|&v| g.ptr[v as usize + 1] - g.ptr[v as usize]).sum();
    let mut sub = WGraph {
        ptr: Vec::with_capacity(vertices.len() + 1),
        adj: Vec::with_capacity(edges),
        ewgt: Vec::new(),
        vwgt: Vec::new(),
    };
    sub.ptr.push(0);
    for &v in vertices {
        sub.adj.extend(g.neighbors(v as usize).iter().map(|&u| local[u as usize]).filter(|&k| k != NONE));
        sub.ptr.push(sub.adj.len());
    }
    sub.ewgt = vec![1; sub.adj.len()];
    sub.vwgt = vec![1; vertices.len()];
    for &v in vertices {
        local[v as usize] = NONE;
    }
    sub
}

/// The recursive splitting, with scratch space over the vertices (of any part; all
/// `NONE` between uses).
struct Dissection {
    /// 0 for the vertices of leaves, 1 for those of separators.
    class: Vec<usize>,
    label: Vec<u32>,
    local: Vec<u32>,
    refiner: Refiner,
}

impl Dissection {
    /// Splits the part `g`, whose vertex `k` is `global[k]`, marking its separators.
    fn split(&mut self, g: &WGraph, global: &[u32]) {
        let n = g.len();
        if n <= LEAF_SIZE {
            return;
        }
        let components = self.components(g);
        if components.len() > 1 {
            for component in components {
                if component.len() > LEAF_SIZE {
                    let sub = subgraph(g, &component, &mut self.local);
                    let vertices: Vec<u32> = component.iter().map(|&k| global[k as usize]).collect();
                    self.split(&sub, &vertices);
                }
            }
            return;
        }
        let where_ = bisect(g, &mut self.refiner);
        let mut parts: [Vec<u32>; 3] = Default::default();
        for (k, &p) in where_.iter().enumerate() {
            parts[p as usize].push(k as u32);
        }
        if parts[0].len() == n || parts[1].len() == n {
            // No split (cannot happen for a connected graph of more than one vertex).
            return;
        }
        for &k in &parts[SEPARATOR as usize] {
            self.class[global[k as usize] as usize] = 1;
        }
        for part in &parts[..2] {
            let sub = subgraph(g, part, &mut self.local);
            let vertices: Vec<u32> = part.iter().map(|&k| global[k as usize]).collect();
            self.split(&sub, &vertices);
        }
    }

    /// The connected components of `g`, as lists of its vertices.
    fn components(&mut self, g: &WGraph) -> Vec<Vec<u32>> {
        let n = g.len();
        let label = &mut self.label;
        let mut components = Vec::new();
        for s in 0..n {
            if label[s] != NONE {
                continue;
            }
            let id = components.len() as u32;
            let mut queue = vec![s as u32];
            label[s] = id;
            let mut head = 0;
            while head < queue.len() {
                let v = queue[head] as usize;
                head += 1;
                for &u in g.neighbors(v) {
                    if label[u as usize] == NONE {
                        label[u as usize] = id;
                        queue.push(u);
                    }
                }
            }
            components.push(queue);
        }
        label[..n].fill(NONE);
        components
    }
}
