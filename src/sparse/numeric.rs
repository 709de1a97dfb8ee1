//! Numeric factorisation and solves on a [`Symbolic`] analysis.
//!
//! Left-looking supernodal Cholesky: supernodes are factored in order; before supernode J
//! is factored, every descendant K whose rows reach J's columns sends its update
//! `L_K[rows >= J] L_K[rows in J]^T` (a dense product, [`dense::update_block`]), which is
//! scattered into J's block through relative row positions (two rows and two columns at a
//! time when the matrix has 2x2 vertex blocks kept together); then J's dense trapezoid is
//! factored ([`dense::cholesky_trapezoid`]). Descendants wait in linked lists keyed by the
//! next supernode they update (as in Ng and Peyton's left-looking scheme), so each
//! K -> J update is found in constant time. Cost: [`Symbolic::flops`] multiply-adds, about.
//!
//! Every buffer is sized once in [`Numeric::new`]; [`Numeric::refactor`] and
//! [`Numeric::solve_in_place`] allocate nothing.

use std::sync::Arc;

use super::dense;
use super::{CsMatView, FactorError, Symbolic};

const NONE: usize = usize::MAX;

/// A numeric Cholesky factor for one symbolic analysis, reusable for new values.
#[derive(Debug, Clone)]
pub struct Numeric {
    symbolic: Arc<Symbolic>,
    values: Vec<f64>,
    /// Whether `values` holds a complete factor (false before the first success and after
    /// a failed refactorisation, so that a failed factor is never used).
    valid: bool,
    update: Vec<f64>,
    relative: Vec<usize>,
    positions: Vec<usize>,
    next_row: Vec<usize>,
    list_head: Vec<usize>,
    list_next: Vec<usize>,
    solve_work: Vec<f64>,
    /// The off-diagonal part of one supernode's rows during a solve.
    solve_rows: Vec<f64>,
}

impl Numeric {
    /// Allocates every buffer for factorisations on `symbolic`'s pattern.
    pub fn new(symbolic: Arc<Symbolic>) -> Self {
        Self::try_new(symbolic).unwrap_or_else(|e| panic!("{e}"))
    }

    /// [`Self::new`], with the two large buffers (the factor's values and the update
    /// block) allocated fallibly: [`FactorError::OutOfMemory`] instead of an abort when
    /// memory is short (in wasm, where memory is limited and an abort kills the instance).
    pub fn try_new(symbolic: Arc<Symbolic>) -> Result<Self, FactorError> {
        let n = symbolic.n;
        let ns = symbolic.supernode_count();
        let max_height = (0..ns).map(|s| symbolic.row_start[s + 1] - symbolic.row_start[s]).max().unwrap_or(0);
        let zeros = |len: usize| -> Result<Vec<f64>, FactorError> {
            let mut buffer = Vec::new();
            buffer.try_reserve_exact(len).map_err(|_| FactorError::OutOfMemory { bytes: 8 * len })?;
            buffer.resize(len, 0.0);
            Ok(buffer)
        };
        Ok(Self {
            values: zeros(symbolic.stored_values())?,
            valid: false,
            update: zeros(symbolic.max_update)?,
            relative: vec![0; n],
            positions: vec![0; max_height],
            next_row: vec![0; ns],
            list_head: vec![NONE; ns],
            list_next: vec![NONE; ns],
            solve_work: vec![0.0; n],
            solve_rows: vec![0.0; max_height],
            symbolic,
        })
    }

    /// Analysis and buffers in one: `new` followed by `refactor`.
    pub fn factor(symbolic: Arc<Symbolic>, a: CsMatView<'_>) -> Result<Self, FactorError> {
        let mut numeric = Self::new(symbolic);
        numeric.refactor(a)?;
        Ok(numeric)
    }

    /// The symbolic analysis this factor uses.
    pub fn symbolic(&self) -> &Arc<Symbolic> {
        &self.symbolic
    }

    /// Factors new values on the analysed pattern, in place. On error the factor is marked
    /// unusable until a later refactorisation succeeds.
    ///
    /// Checks that `a` has the analysed pattern, which costs a comparison of its indices
    /// (about 5% of a factorisation of a 2D Killing matrix); a caller that keeps the
    /// pattern fixed by construction can pass the values alone to [`Self::refactor_values`].
    pub fn refactor(&mut self, a: CsMatView<'_>) -> Result<(), FactorError> {
        self.valid = false;
        if !self.symbolic.same_pattern(a) {
            return Err(FactorError::PatternMismatch);
        }
        self.refactor_values(a.data())
    }

    /// Factors new values on the analysed pattern: `a_data` is the data array of a matrix
    /// with exactly the analysed pattern (the same entries in the same compressed sparse
    /// column order), or the source of [`Symbolic::reading_values_through`]. Only its length
    /// can be checked. On error the factor is marked unusable until a later refactorisation
    /// succeeds.
    pub fn refactor_values(&mut self, a_data: &[f64]) -> Result<(), FactorError> {
        self.valid = false;
        let sym = &*self.symbolic;
        if a_data.len() != sym.source_len {
            return Err(FactorError::PatternMismatch);
        }
        self.list_head.fill(NONE);
        let ns = sym.supernode_count();
        for j in 0..ns {
            let (first, end) = (sym.super_start[j], sym.super_start[j + 1]);
            let j_rows = &sym.rows[sym.row_start[j]..sym.row_start[j + 1]];
            let height = j_rows.len();
            for (pos, &r) in j_rows.iter().enumerate() {
                self.relative[r] = pos;
            }
            let (before, rest) = self.values.split_at_mut(sym.value_start[j]);
            let block = &mut rest[..sym.value_start[j + 1] - sym.value_start[j]];
            block.fill(0.0);
            for &(offset, p) in &sym.a_entries[sym.a_entry_start[j]..sym.a_entry_start[j + 1]] {
                block[offset] += a_data[p];
            }

            let mut k = self.list_head[j];
            while k != NONE {
                let after = self.list_next[k];
                let k_rows = &sym.rows[sym.row_start[k]..sym.row_start[k + 1]];
                let k_height = k_rows.len();
                let k_width = sym.super_start[k + 1] - sym.super_start[k];
                let p = self.next_row[k];
                let m = k_height - p;
                let q = k_rows[p..].iter().take_while(|&&r| r < end).count();
                let k_values = &before[sym.value_start[k]..sym.value_start[k + 1]];
                dense::update_block(&mut self.update, &k_values[p..], k_height, m, q, k_width);
                for (slot, &r) in self.positions.iter_mut().zip(&k_rows[p..]) {
                    *slot = self.relative[r];
                }
                if sym.paired {
                    // Columns i, i + 1 and rows in pairs: m and q are even, and the pair of
                    // rows (i, i + 1) lands on the target's diagonal block, whose entry above
                    // the diagonal (column i + 1, row i) is scratch.
                    for i in (0..q).step_by(2) {
                        let column = k_rows[p + i] - first;
                        let (left, right) = block.split_at_mut((column + 1) * height);
                        let (target_a, target_b) = (&mut left[column * height..], &mut right[..height]);
                        let (positions, _) = self.positions[i..m].as_chunks::<2>();
                        let (source_a, _) = self.update[i * m + i..(i + 1) * m].as_chunks::<2>();
                        let (source_b, _) = self.update[(i + 1) * m + i..(i + 2) * m].as_chunks::<2>();
                        for ((position, a), b) in positions.iter().zip(source_a).zip(source_b) {
                            let r = position[0];
                            let pair_a = &mut target_a[r..r + 2];
                            pair_a[0] -= a[0];
                            pair_a[1] -= a[1];
                            let pair_b = &mut target_b[r..r + 2];
                            pair_b[0] -= b[0];
                            pair_b[1] -= b[1];
                        }
                    }
                } else {
                    for i in 0..q {
                        let target = &mut block[(k_rows[p + i] - first) * height..(k_rows[p + i] - first + 1) * height];
                        let source = &self.update[i * m + i..(i + 1) * m];
                        for (&position, &value) in self.positions[i..m].iter().zip(source) {
                            target[position] -= value;
                        }
                    }
                }
                self.next_row[k] = p + q;
                if p + q < k_height {
                    let next = sym.col_to_super[k_rows[p + q]];
                    self.list_next[k] = self.list_head[next];
                    self.list_head[next] = k;
                }
                k = after;
            }

            let width = end - first;
            dense::cholesky_trapezoid(block, height, width)
                .map_err(|(col, pivot)| FactorError::NotPositiveDefinite { column: sym.perm[first + col], pivot })?;
            self.next_row[j] = width;
            if width < height {
                let next = sym.col_to_super[j_rows[width]];
                self.list_next[j] = self.list_head[next];
                self.list_head[next] = j;
            }
        }
        self.valid = true;
        Ok(())
    }

    /// Solves `A x = b` in place (`b` becomes `x`), with the permutation applied.
    pub fn solve_in_place(&mut self, b: &mut [f64]) -> Result<(), FactorError> {
        let sym = &*self.symbolic;
        if b.len() != sym.n {
            return Err(FactorError::DimensionMismatch { expected: sym.n, found: b.len() });
        }
        if !self.valid {
            return Err(FactorError::NotFactored);
        }
        let y = &mut self.solve_work;
        let below = &mut self.solve_rows;
        for (k, &i) in sym.perm.iter().enumerate() {
            y[k] = b[i];
        }
        let ns = sym.supernode_count();
        // Forward, L y = P b: per supernode, a dense triangular solve on its own columns,
        // then the rows below get `L21 x` accumulated densely and subtracted once. A
        // supernode whose entries of y are all zero stays zero and sends nothing: skipped
        // (right-hand sides that live on a few unknowns, as the deformer's do, reach only
        // their ancestors in the elimination tree).
        for s in 0..ns {
            let (first, width, rows, range) = sym.supernode(s);
            if y[first..first + width].iter().all(|&v| v == 0.0) {
                continue;
            }
            let block = &self.values[range];
            let height = rows.len();
            let below = &mut below[..height - width];
            below.fill(0.0);
            for j in 0..width {
                let col = &block[j * height..(j + 1) * height];
                let x = y[first + j] / col[j];
                y[first + j] = x;
                for r in j + 1..width {
                    y[first + r] -= col[r] * x;
                }
                for (acc, l) in below.iter_mut().zip(&col[width..]) {
                    *acc += l * x;
                }
            }
            for (&r, acc) in rows[width..].iter().zip(below.iter()) {
                y[r] -= acc;
            }
        }
        // Backward, L^T z = y: gather the rows below once, then dot products.
        for s in (0..ns).rev() {
            let (first, width, rows, range) = sym.supernode(s);
            let block = &self.values[range];
            let height = rows.len();
            let below = &mut below[..height - width];
            for (g, &r) in below.iter_mut().zip(&rows[width..]) {
                *g = y[r];
            }
            for j in (0..width).rev() {
                let col = &block[j * height..(j + 1) * height];
                let mut sum = y[first + j];
                for r in j + 1..width {
                    sum -= col[r] * y[first + r];
                }
                sum -= dense::dot(&col[width..], below);
                y[first + j] = sum / col[j];
            }
        }
        for (k, &i) in sym.perm.iter().enumerate() {
            b[i] = y[k];
        }
        Ok(())
    }

    /// The factor as a dense lower-triangular matrix in the permuted order (row-major
    /// `n x n`), for tests on small matrices.
    pub fn to_dense_lower(&self) -> Vec<f64> {
        let sym = &*self.symbolic;
        let n = sym.n;
        let mut dense = vec![0.0; n * n];
        for s in 0..sym.supernode_count() {
            let (first, width, rows, range) = sym.supernode(s);
            let block = &self.values[range];
            for j in 0..width {
                for (r, &row) in rows.iter().enumerate().skip(j) {
                    dense[row * n + first + j] = block[j * rows.len() + r];
                }
            }
        }
        dense
    }
}
