//! faer's sparse Cholesky (`LL^T` with faer's own AMD ordering), wrapped the way the
//! benchmarks use ours: analyse once, refactor and solve many times, single-threaded.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};
use sprs::CsMat;

/// A faer factorisation of one matrix pattern, with its buffers.
pub(crate) struct FaerLlt {
    pattern: SymbolicSparseColMat<usize>,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    factor_memory: MemBuffer,
    solve_memory: MemBuffer,
    supernodal: bool,
}

impl FaerLlt {
    /// Orders (AMD) and analyses the lower triangle of `a` (a full symmetric CSC matrix),
    /// as a supernodal or a simplicial factorisation, and allocates the buffers.
    pub(crate) fn analyse(a: &CsMat<f64>, supernodal: bool) -> Self {
        let n = a.cols();
        assert!(a.is_csc() && a.rows() == n, "a square CSC matrix");
        let pattern =
            SymbolicSparseColMat::new_checked(n, n, a.indptr().to_proper().into_owned(), None, a.indices().to_vec());
        let symbolic = symbolic_of(&pattern, supernodal);
        let values = vec![0.0; symbolic.len_val()];
        let factor_memory = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()));
        let solve_memory = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Self { pattern, symbolic, values, factor_memory, solve_memory, supernodal }
    }

    /// Runs the ordering and symbolic analysis again (for timing it); returns the number of
    /// values it would store.
    pub(crate) fn reanalyse(&self) -> usize {
        symbolic_of(&self.pattern, self.supernodal).len_val()
    }

    /// Factors the values of `a`, which must have the analysed pattern.
    pub(crate) fn factor(&mut self, a: &CsMat<f64>) {
        let matrix = SparseColMatRef::new(self.pattern.as_ref(), a.data());
        self.symbolic
            .factorize_numeric_llt(
                &mut self.values,
                matrix,
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut self.factor_memory),
                Default::default(),
            )
            .expect("faer's numeric factorisation");
    }

    /// Solves `A x = b` in place.
    pub(crate) fn solve_in_place(&mut self, b: &mut [f64]) {
        let n = b.len();
        let llt = LltRef::new(&self.symbolic, &self.values);
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, n, 1),
            Par::Seq,
            MemStack::new(&mut self.solve_memory),
        );
    }

    /// Values stored for L: for the simplicial variant exactly the entries of L (diagonal
    /// included); the supernodal variant stores more (relaxed supernodes keep zeros).
    pub(crate) fn stored_values(&self) -> usize {
        self.symbolic.len_val()
    }
}

fn symbolic_of(pattern: &SymbolicSparseColMat<usize>, supernodal: bool) -> SymbolicCholesky<usize> {
    let threshold =
        if supernodal { SupernodalThreshold::FORCE_SUPERNODAL } else { SupernodalThreshold::FORCE_SIMPLICIAL };
    let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
    factorize_symbolic_cholesky(pattern.as_ref(), Side::Lower, SymmetricOrdering::Amd, params)
        .expect("faer's symbolic analysis")
}
