//! Dense kernels on column-major blocks, written so that the inner loops are contiguous
//! `y += a * x` updates that compilers vectorise (SSE/AVX natively, simd128 in wasm).

/// `y[i] += a * x[i]` for all i (the slices have equal length).
#[inline(always)]
fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// `sum_i a[i] b[i]` over the shorter length, with four partial sums: a single running
/// sum is one chain of dependent additions (wasm cannot reorder it), four chains keep
/// the adder busy and let the compiler use f64x2 lanes.
#[inline]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    let (a4, a_rest) = a.as_chunks::<4>();
    let (b4, b_rest) = b.as_chunks::<4>();
    for (x, y) in a4.iter().zip(b4) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = a_rest.iter().zip(b_rest).map(|(x, y)| x * y).sum();
    (acc[0] + acc[2]) + (acc[1] + acc[3]) + tail
}

/// In-place Cholesky of the `height x width` trapezoid `b` (column-major, leading
/// dimension `height`, `height >= width`): on return its first `width` rows hold the lower
/// triangle of L for the diagonal block and the rows below hold the off-diagonal block,
/// `L21 = A21 L11^-T`. Returns the failing column and its pivot if one is not positive.
/// Entries above the diagonal are scratch and may be overwritten.
///
/// Left-looking by panels of four columns (the last one of two or one): a panel is first
/// updated by all columns to its left with a register-blocked kernel (with plain `axpy`s
/// for a single column), then factored column by column.
pub(super) fn cholesky_trapezoid(b: &mut [f64], height: usize, width: usize) -> Result<(), (usize, f64)> {
    let mut j0 = 0;
    while j0 < width {
        let panel = (width - j0).min(4);
        let (done, rest) = b.split_at_mut(j0 * height);
        if panel == 4 {
            subtract_panel_update::<4>(rest, done, height, j0);
        } else if panel == 2 {
            subtract_panel_update::<2>(rest, done, height, j0);
        } else {
            for j in 0..panel {
                let col = &mut rest[j * height + j0 + j..(j + 1) * height];
                for t in 0..j0 {
                    let prev = &done[t * height + j0 + j..(t + 1) * height];
                    axpy(col, -prev[0], prev);
                }
            }
        }
        for j in 0..panel {
            let (left, right) = rest.split_at_mut(j * height);
            let col = &mut right[j0 + j..height];
            for t in 0..j {
                let prev = &left[t * height + j0 + j..(t + 1) * height];
                axpy(col, -prev[0], prev);
            }
            let pivot = col[0];
            if !(pivot > 0.0 && pivot.is_finite()) {
                return Err((j0 + j, pivot));
            }
            let d = pivot.sqrt();
            col[0] = d;
            let inv = 1.0 / d;
            for x in &mut col[1..] {
                *x *= inv;
            }
        }
        j0 += panel;
    }
    Ok(())
}

/// `panel[r, c] -= sum_{t < j0} done[r, t] done[j0 + c, t]` for the `P` panel columns c
/// and rows `r >= j0` (all column-major with leading dimension `height`): four rows by `P`
/// columns at a time in registers.
fn subtract_panel_update<const P: usize>(panel: &mut [f64], done: &[f64], height: usize, j0: usize) {
    // Stated once, so that the compiler can drop the bounds checks of the inner loop.
    assert!(j0 + P <= height && done.len() >= j0 * height);
    let mut r = j0;
    while r + 4 <= height {
        let mut acc = [[0.0f64; 4]; P];
        for col in done.chunks_exact(height).take(j0) {
            let x: [f64; 4] = col[r..r + 4].try_into().expect("four rows");
            let b: [f64; P] = col[j0..j0 + P].try_into().expect("P columns");
            for (acc_c, bc) in acc.iter_mut().zip(b) {
                for (acc_cr, xr) in acc_c.iter_mut().zip(x) {
                    *acc_cr += xr * bc;
                }
            }
        }
        for (c, acc_c) in acc.iter().enumerate() {
            for (target, a) in panel[c * height + r..c * height + r + 4].iter_mut().zip(acc_c) {
                *target -= a;
            }
        }
        r += 4;
    }
    for r in r..height {
        for c in 0..P {
            let mut sum = 0.0;
            for t in 0..j0 {
                sum += done[t * height + r] * done[t * height + j0 + c];
            }
            panel[c * height + r] -= sum;
        }
    }
}

/// The update one supernode sends to an ancestor: for the `m x k` block `a` (column-major,
/// leading dimension `lda`), `c = a a[..q]^T` on its lower trapezoid, i.e.
/// `c[r + i * m] = sum_t a[r, t] a[i, t]` for `i < q`, `i <= r < m` (entries above that
/// may be overwritten with partial sums: callers read only the trapezoid).
///
/// Register-blocked: four columns of `c` and four rows at a time accumulate over `t`, so
/// each element of `a` loaded serves four multiply-adds and `c` is written once.
pub(super) fn update_block(c: &mut [f64], a: &[f64], lda: usize, m: usize, q: usize, k: usize) {
    // Stated once, so that the compiler can drop the bounds checks of the inner loops.
    assert!(q <= m && m <= lda);
    let mut i0 = 0;
    while i0 + 4 <= q {
        update_columns::<4>(c, a, lda, m, i0, k);
        i0 += 4;
    }
    // Two columns left (as with 2x2 vertex blocks): four rows by two columns at a time.
    if i0 + 2 <= q {
        update_columns::<2>(c, a, lda, m, i0, k);
        i0 += 2;
    }
    for i in i0..q {
        let out = &mut c[i * m + i..i * m + m];
        out.fill(0.0);
        for t in 0..k {
            let src = &a[t * lda + i..t * lda + m];
            axpy(out, src[0], src);
        }
    }
}

/// [`update_block`] for the `C` columns `i0..i0 + C` of `c` and rows `i0..m`: four rows by
/// `C` columns accumulate in registers over the `k` columns of `a`.
#[inline(always)]
fn update_columns<const C: usize>(c: &mut [f64], a: &[f64], lda: usize, m: usize, i0: usize, k: usize) {
    let mut r = i0;
    while r + 4 <= m {
        let mut acc = [[0.0f64; 4]; C];
        for t in 0..k {
            let col = &a[t * lda..t * lda + m];
            let x: [f64; 4] = col[r..r + 4].try_into().expect("four rows");
            let b: [f64; C] = col[i0..i0 + C].try_into().expect("C columns");
            for (acc_c, bc) in acc.iter_mut().zip(b) {
                for (acc_cr, xr) in acc_c.iter_mut().zip(x) {
                    *acc_cr += xr * bc;
                }
            }
        }
        for (j, acc_c) in acc.iter().enumerate() {
            c[(i0 + j) * m + r..(i0 + j) * m + r + 4].copy_from_slice(acc_c);
        }
        r += 4;
    }
    for r in r..m {
        let mut acc = [0.0f64; C];
        for t in 0..k {
            let col = &a[t * lda..t * lda + m];
            for (j, acc_j) in acc.iter_mut().enumerate() {
                *acc_j += col[r] * col[i0 + j];
            }
        }
        for (j, acc_j) in acc.iter().enumerate() {
            c[(i0 + j) * m + r] = *acc_j;
        }
    }
}
