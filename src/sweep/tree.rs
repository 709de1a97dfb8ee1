//! The sweep's status: the segments crossing the sweep line, bottom to top, in a treap
//! (a binary search tree kept balanced by random priorities, Seidel and Aragon 1996).
//!
//! Segments have no key that orders them at every position of the sweep, so a new one is
//! placed by a caller's comparison against the segments already in the tree (which may
//! instead report that the two meet); removal and neighbours go by node, through parent
//! links. Nodes are the segments' indices. Every operation is O(log n) expected; the
//! priorities are a hash of the node and of a seed taken from the input, so no fixed input
//! can make the tree deep.

const NIL: u32 = u32::MAX;

#[derive(Debug, Clone, Copy)]
struct Node {
    left: u32,
    right: u32,
    parent: u32,
    priority: u64,
}

/// An ordered set of nodes `0..n` (each inserted at most once at a time).
#[derive(Debug)]
pub(super) struct Treap {
    nodes: Vec<Node>,
    root: u32,
}

/// SplitMix64's finaliser: a well-mixed 64-bit hash.
pub(super) fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

impl Treap {
    /// An empty tree for nodes `0..n`.
    pub(super) fn new(n: usize, seed: u64) -> Self {
        let nodes = (0..n as u64).map(|i| Node { left: NIL, right: NIL, parent: NIL, priority: mix(seed ^ mix(i)) });
        Self { nodes: nodes.collect(), root: NIL }
    }

    /// Inserts `id` where `below(other)` says: `Ok(true)` when `id` goes below `other`,
    /// `Ok(false)` above; the first `Err` stops the insertion and is returned (the tree is
    /// unchanged).
    pub(super) fn insert<E>(&mut self, id: u32, mut below: impl FnMut(u32) -> Result<bool, E>) -> Result<(), E> {
        if self.root == NIL {
            self.root = id;
            return Ok(());
        }
        let mut current = self.root;
        loop {
            let go_left = below(current)?;
            let next = if go_left { self.nodes[current as usize].left } else { self.nodes[current as usize].right };
            if next == NIL {
                if go_left {
                    self.nodes[current as usize].left = id;
                } else {
                    self.nodes[current as usize].right = id;
                }
                self.nodes[id as usize].parent = current;
                break;
            }
            current = next;
        }
        while let Some(parent) = self.parent(id) {
            if self.nodes[parent as usize].priority >= self.nodes[id as usize].priority {
                break;
            }
            self.rotate_up(id);
        }
        Ok(())
    }

    /// Removes `id`, which must be in the tree.
    pub(super) fn remove(&mut self, id: u32) {
        // Rotate the node down (its higher-priority child up) until it is a leaf.
        loop {
            let Node { left, right, .. } = self.nodes[id as usize];
            let child = match (left, right) {
                (NIL, NIL) => break,
                (NIL, c) | (c, NIL) => c,
                (l, r) => {
                    if self.nodes[l as usize].priority > self.nodes[r as usize].priority {
                        l
                    } else {
                        r
                    }
                }
            };
            self.rotate_up(child);
        }
        match self.parent(id) {
            None => self.root = NIL,
            Some(parent) => {
                let p = &mut self.nodes[parent as usize];
                if p.left == id {
                    p.left = NIL;
                } else {
                    p.right = NIL;
                }
            }
        }
        self.nodes[id as usize].parent = NIL;
    }

    /// The node just below `id`.
    pub(super) fn below(&self, id: u32) -> Option<u32> {
        self.neighbour(id, |n| n.left, |n| n.right)
    }

    /// The node just above `id`.
    pub(super) fn above(&self, id: u32) -> Option<u32> {
        self.neighbour(id, |n| n.right, |n| n.left)
    }

    /// The in-order neighbour on the `near` side: the far-most node of the `near` subtree,
    /// or the first ancestor reached from its `far` side.
    fn neighbour(&self, id: u32, near: fn(&Node) -> u32, far: fn(&Node) -> u32) -> Option<u32> {
        let mut x = near(&self.nodes[id as usize]);
        if x != NIL {
            while far(&self.nodes[x as usize]) != NIL {
                x = far(&self.nodes[x as usize]);
            }
            return Some(x);
        }
        let mut child = id;
        while let Some(parent) = self.parent(child) {
            if far(&self.nodes[parent as usize]) == child {
                return Some(parent);
            }
            child = parent;
        }
        None
    }

    fn parent(&self, id: u32) -> Option<u32> {
        let p = self.nodes[id as usize].parent;
        (p != NIL).then_some(p)
    }

    /// Rotates `x` above its parent, keeping the in-order sequence.
    fn rotate_up(&mut self, x: u32) {
        let p = self.nodes[x as usize].parent;
        let g = self.nodes[p as usize].parent;
        if self.nodes[p as usize].left == x {
            let moved = self.nodes[x as usize].right;
            self.nodes[p as usize].left = moved;
            if moved != NIL {
                self.nodes[moved as usize].parent = p;
            }
            self.nodes[x as usize].right = p;
        } else {
            let moved = self.nodes[x as usize].left;
            self.nodes[p as usize].right = moved;
            if moved != NIL {
                self.nodes[moved as usize].parent = p;
            }
            self.nodes[x as usize].left = p;
        }
        self.nodes[p as usize].parent = x;
        self.nodes[x as usize].parent = g;
        if g == NIL {
            self.root = x;
        } else if self.nodes[g as usize].left == p {
            self.nodes[g as usize].left = x;
        } else {
            self.nodes[g as usize].right = x;
        }
    }

    /// The nodes in order, bottom first (for tests).
    #[cfg(test)]
    fn in_order(&self) -> Vec<u32> {
        let mut out = Vec::new();
        let mut x = self.root;
        if x == NIL {
            return out;
        }
        while self.nodes[x as usize].left != NIL {
            x = self.nodes[x as usize].left;
        }
        out.push(x);
        while let Some(next) = self.above(x) {
            out.push(next);
            x = next;
        }
        out
    }

    /// The tree's height (for tests).
    #[cfg(test)]
    fn height(&self) -> usize {
        fn depth(t: &Treap, x: u32) -> usize {
            if x == NIL {
                0
            } else {
                1 + depth(t, t.nodes[x as usize].left).max(depth(t, t.nodes[x as usize].right))
            }
        }
        depth(self, self.root)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys give the order; the tree must match a sorted list through any mix of
    /// insertions and removals, and its neighbours the list's.
    #[test]
    fn matches_a_sorted_list() {
        let n = 2000u32;
        let keys: Vec<u64> = (0..n).map(|i| mix(u64::from(i) + 7) % 100_000).collect();
        let mut tree = Treap::new(n as usize, 42);
        let mut list: Vec<u32> = Vec::new();
        let mut present = vec![false; n as usize];
        let by_key = |a: &u32, b: &u32| (keys[*a as usize], *a).cmp(&(keys[*b as usize], *b));
        for step in 0..6_000u64 {
            let id = (mix(step) % u64::from(n)) as u32;
            if present[id as usize] {
                tree.remove(id);
                list.retain(|&x| x != id);
            } else {
                let result: Result<(), ()> = tree.insert(id, |other| Ok(by_key(&id, &other).is_lt()));
                result.unwrap();
                let at = list.partition_point(|x| by_key(x, &id).is_lt());
                list.insert(at, id);
            }
            present[id as usize] = !present[id as usize];
            if step % 1000 == 0 {
                assert_eq!(tree.in_order(), list);
            }
            if let Some(k) = list.iter().position(|&x| x == id) {
                assert_eq!(tree.below(id), k.checked_sub(1).map(|j| list[j]));
                assert_eq!(tree.above(id), list.get(k + 1).copied());
            }
        }
        assert_eq!(tree.in_order(), list);
        // Balanced: a sorted insertion order does not make it a list.
        let mut sorted = Treap::new(n as usize, 1);
        for id in 0..n {
            let result: Result<(), ()> = sorted.insert(id, |other| Ok(id < other));
            result.unwrap();
        }
        assert!(sorted.height() < 60, "height {}", sorted.height());
    }

    #[test]
    fn a_refused_insertion_changes_nothing() {
        let mut tree = Treap::new(4, 0);
        for id in 0..3 {
            let result: Result<(), ()> = tree.insert(id, |other| Ok(id < other));
            result.unwrap();
        }
        assert!(tree.insert(3, Err::<bool, u32>).is_err());
        assert_eq!(tree.in_order(), vec![0, 1, 2]);
    }
}
