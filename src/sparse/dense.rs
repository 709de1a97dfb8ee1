//! Dense kernels on column-major blocks, written so that the inner loops are contiguous
//! `y += a * x` updates that compilers vectorise (SSE/AVX natively, simd128 in wasm).

/// `y[i] += a * x[i]` for all i (the slices have equal length).
#[inline(always)]
fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// In-place Cholesky of the `height x width` trapezoid `b` (column-major, leading
/// dimension `height`, `height >= width`): on return its first `width` rows hold the lower
/// triangle of L for the diagonal block and the rows below hold the off-diagonal block,
/// `L21 = A21 L11^-T`. Returns the failing column and its pivot if one is not positive.
pub(super) fn cholesky_trapezoid(b: &mut [f64], height: usize, width: usize) -> Result<(), (usize, f64)> {
    for j in 0..width {
        let (done, rest) = b.split_at_mut(j * height);
        let col = &mut rest[j..height];
        for t in 0..j {
            let prev = &done[t * height + j..t * height + height];
            axpy(col, -prev[0], prev);
        }
        let pivot = col[0];
        if !(pivot > 0.0 && pivot.is_finite()) {
            return Err((j, pivot));
        }
        let d = pivot.sqrt();
        col[0] = d;
        let inv = 1.0 / d;
        for x in &mut col[1..] {
            *x *= inv;
        }
    }
    Ok(())
}

/// The update one supernode sends to an ancestor: for the `m x k` block `a` (column-major,
/// leading dimension `lda`), `c = a a[..q]^T` restricted to its lower trapezoid, i.e.
/// `c[r + i * m] = sum_t a[r, t] a[i, t]` for `i < q`, `i <= r < m`.
pub(super) fn update_block(c: &mut [f64], a: &[f64], lda: usize, m: usize, q: usize, k: usize) {
    for i in 0..q {
        let col = &mut c[i * m + i..i * m + m];
        col.fill(0.0);
        for t in 0..k {
            let src = &a[t * lda + i..t * lda + m];
            axpy(col, src[0], src);
        }
    }
}
