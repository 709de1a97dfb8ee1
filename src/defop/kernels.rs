//! The dense kernels of an operator's evaluation (paper eq. 3: `X Ψ`, then `Dᵀ (X Ψ)`):
//! blocks of dot products, four rows against one or two vectors at once, so that each
//! vector element is loaded once per four rows.
//!
//! Every product is summed in the same order on every target: two partial sums (the
//! elements of even index, and of odd index), added, then the last element if the length
//! is odd. In wasm the two sums are the lanes of one `f64x2` (`core::arch::wasm32`, simd128,
//! which `.cargo/config.toml` enables): LLVM keeps the scalar form scalar for wasm32 (its
//! cost model does not vectorise these reductions there), which made the evaluation three
//! times slower than native. Elsewhere the portable form runs, which compilers vectorise
//! natively; both round alike, so an operator gives the same bits natively and in wasm.
//!
//! Measured in wasm (Node 20, the octopus-sized operator): blocks of two elements with
//! one accumulator per product beat blocks of four with two (fewer live registers), and
//! four rows per block beat two or eight.
//!
//! The same blocks exist in single precision ([`dots_f32`]: four partial sums, the lanes of
//! one `f32x4`) for an operator's single-precision copy (`super::single`); [`Element`] picks
//! the kernel by number type.

/// `out[r][c] = rows[r] · vectors[c]` over the first `len` elements of each slice, for `R`
/// rows and `C` vectors at once. Every slice must hold at least `len` numbers.
#[inline(always)]
pub(crate) fn dots<const R: usize, const C: usize>(
    rows: [&[f64]; R],
    vectors: [&[f64]; C],
    len: usize,
) -> [[f64; C]; R] {
    #[cfg(target_arch = "wasm32")]
    {
        simd::dots(rows, vectors, len)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        portable_dots(rows, vectors, len)
    }
}

/// The portable form of [`dots`], in the same summation order.
#[cfg(any(test, not(target_arch = "wasm32")))]
#[inline(always)]
pub(crate) fn portable_dots<const R: usize, const C: usize>(
    rows: [&[f64]; R],
    vectors: [&[f64]; C],
    len: usize,
) -> [[f64; C]; R] {
    let pairs = len / 2;
    let rows = rows.map(|r| r[..len].split_at(2 * pairs));
    let vectors = vectors.map(|v| v[..len].split_at(2 * pairs));
    let row_pairs = rows.map(|(body, _)| body.as_chunks::<2>().0);
    let vector_pairs = vectors.map(|(body, _)| body.as_chunks::<2>().0);
    let mut sums = [[[0.0f64; 2]; C]; R];
    for b in 0..pairs {
        for (sum, row) in sums.iter_mut().zip(&row_pairs) {
            let x = &row[b];
            for (s, vector) in sum.iter_mut().zip(&vector_pairs) {
                let y = &vector[b];
                s[0] += x[0] * y[0];
                s[1] += x[1] * y[1];
            }
        }
    }
    let mut out = [[0.0; C]; R];
    for ((o, s), (_, row_tail)) in out.iter_mut().zip(&sums).zip(&rows) {
        for ((o, s), (_, vector_tail)) in o.iter_mut().zip(s).zip(&vectors) {
            let mut total = s[0] + s[1];
            for (x, y) in row_tail.iter().zip(*vector_tail) {
                total += x * y;
            }
            *o = total;
        }
    }
    out
}

#[cfg(target_arch = "wasm32")]
mod simd {
    use core::arch::wasm32::{
        f32x4, f32x4_add, f32x4_extract_lane, f32x4_mul, f32x4_splat, f64x2, f64x2_add, f64x2_extract_lane, f64x2_mul,
        f64x2_splat,
    };

    /// [`super::dots`] in simd128: the two partial sums of a product are one register's lanes.
    #[inline(always)]
    pub(super) fn dots<const R: usize, const C: usize>(
        rows: [&[f64]; R],
        vectors: [&[f64]; C],
        len: usize,
    ) -> [[f64; C]; R] {
        let pairs = len / 2;
        let rows = rows.map(|r| r[..len].split_at(2 * pairs));
        let vectors = vectors.map(|v| v[..len].split_at(2 * pairs));
        let row_pairs = rows.map(|(body, _)| body.as_chunks::<2>().0);
        let vector_pairs = vectors.map(|(body, _)| body.as_chunks::<2>().0);
        // LLVM loads each pair with two lane loads rather than one `v128.load` (it does not
        // merge them for wasm32); a `v128_load` through a pointer, which needs unsafe code,
        // measured no faster.
        let mut sums = [[f64x2_splat(0.0); C]; R];
        for b in 0..pairs {
            let y = vector_pairs.map(|v| f64x2(v[b][0], v[b][1]));
            for (sum, row) in sums.iter_mut().zip(&row_pairs) {
                let x = f64x2(row[b][0], row[b][1]);
                for (s, y) in sum.iter_mut().zip(&y) {
                    *s = f64x2_add(*s, f64x2_mul(x, *y));
                }
            }
        }
        let mut out = [[0.0; C]; R];
        for ((o, s), (_, row_tail)) in out.iter_mut().zip(&sums).zip(&rows) {
            for ((o, s), (_, vector_tail)) in o.iter_mut().zip(s).zip(&vectors) {
                let mut total = f64x2_extract_lane::<0>(*s) + f64x2_extract_lane::<1>(*s);
                for (x, y) in row_tail.iter().zip(*vector_tail) {
                    total += x * y;
                }
                *o = total;
            }
        }
        out
    }

    /// [`super::dots_f32`] in simd128: the four partial sums of a product are one register's
    /// lanes.
    #[inline(always)]
    pub(super) fn dots_f32<const R: usize, const C: usize>(
        rows: [&[f32]; R],
        vectors: [&[f32]; C],
        len: usize,
    ) -> [[f32; C]; R] {
        let blocks = len / 4;
        let rows = rows.map(|r| r[..len].split_at(4 * blocks));
        let vectors = vectors.map(|v| v[..len].split_at(4 * blocks));
        let row_blocks = rows.map(|(body, _)| body.as_chunks::<4>().0);
        let vector_blocks = vectors.map(|(body, _)| body.as_chunks::<4>().0);
        let load = |x: &[f32; 4]| f32x4(x[0], x[1], x[2], x[3]);
        let mut sums = [[f32x4_splat(0.0); C]; R];
        for b in 0..blocks {
            let y = vector_blocks.map(|v| load(&v[b]));
            for (sum, row) in sums.iter_mut().zip(&row_blocks) {
                let x = load(&row[b]);
                for (s, y) in sum.iter_mut().zip(&y) {
                    *s = f32x4_add(*s, f32x4_mul(x, *y));
                }
            }
        }
        let mut out = [[0.0; C]; R];
        for ((o, s), (_, row_tail)) in out.iter_mut().zip(&sums).zip(&rows) {
            for ((o, s), (_, vector_tail)) in o.iter_mut().zip(s).zip(&vectors) {
                let mut total = (f32x4_extract_lane::<0>(*s) + f32x4_extract_lane::<2>(*s))
                    + (f32x4_extract_lane::<1>(*s) + f32x4_extract_lane::<3>(*s));
                for (x, y) in row_tail.iter().zip(*vector_tail) {
                    total += x * y;
                }
                *o = total;
            }
        }
        out
    }
}

/// `out[r][c] = rows[r] · vectors[c]` in single precision, as [`dots`]: four partial sums
/// per product (element k of each block of four into sum k, the lanes of one `f32x4` in
/// wasm), combined as `(s0 + s2) + (s1 + s3)`, then the last `len % 4` elements.
#[inline(always)]
pub(crate) fn dots_f32<const R: usize, const C: usize>(
    rows: [&[f32]; R],
    vectors: [&[f32]; C],
    len: usize,
) -> [[f32; C]; R] {
    #[cfg(target_arch = "wasm32")]
    {
        simd::dots_f32(rows, vectors, len)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        portable_dots_f32(rows, vectors, len)
    }
}

/// The portable form of [`dots_f32`], in the same summation order.
#[cfg(any(test, not(target_arch = "wasm32")))]
#[inline(always)]
pub(crate) fn portable_dots_f32<const R: usize, const C: usize>(
    rows: [&[f32]; R],
    vectors: [&[f32]; C],
    len: usize,
) -> [[f32; C]; R] {
    let blocks = len / 4;
    let rows = rows.map(|r| r[..len].split_at(4 * blocks));
    let vectors = vectors.map(|v| v[..len].split_at(4 * blocks));
    let row_blocks = rows.map(|(body, _)| body.as_chunks::<4>().0);
    let vector_blocks = vectors.map(|(body, _)| body.as_chunks::<4>().0);
    let mut sums = [[[0.0f32; 4]; C]; R];
    for b in 0..blocks {
        for (sum, row) in sums.iter_mut().zip(&row_blocks) {
            let x = &row[b];
            for (s, vector) in sum.iter_mut().zip(&vector_blocks) {
                let y = &vector[b];
                for k in 0..4 {
                    s[k] += x[k] * y[k];
                }
            }
        }
    }
    let mut out = [[0.0; C]; R];
    for ((o, s), (_, row_tail)) in out.iter_mut().zip(&sums).zip(&rows) {
        for ((o, s), (_, vector_tail)) in o.iter_mut().zip(s).zip(&vectors) {
            let mut total = (s[0] + s[2]) + (s[1] + s[3]);
            for (x, y) in row_tail.iter().zip(*vector_tail) {
                total += x * y;
            }
            *o = total;
        }
    }
    out
}

/// The number types the kernels multiply: `f64` (the evaluation) and `f32` (its
/// single-precision copy for a GPU upload).
pub(crate) trait Element: Copy {
    /// [`dots`] or [`dots_f32`].
    fn dots<const R: usize, const C: usize>(rows: [&[Self]; R], vectors: [&[Self]; C], len: usize) -> [[Self; C]; R];
}

impl Element for f64 {
    #[inline(always)]
    fn dots<const R: usize, const C: usize>(rows: [&[f64]; R], vectors: [&[f64]; C], len: usize) -> [[f64; C]; R] {
        dots(rows, vectors, len)
    }
}

impl Element for f32 {
    #[inline(always)]
    fn dots<const R: usize, const C: usize>(rows: [&[f32]; R], vectors: [&[f32]; C], len: usize) -> [[f32; C]; R] {
        dots_f32(rows, vectors, len)
    }
}

/// An operator's positions from Ψ(Q) `psi`: X Ψ (`coefficients`: row i of X^x then of X^y,
/// for every spatial function i), then, for a reduced basis (`reduction`, D by vertex,
/// non-empty), Dᵀ through `nodal` (scratch, X^x Ψ then X^y Ψ); `write(v, x, y)` for every
/// vertex. The one evaluation of both precisions.
pub(crate) fn positions<T: Element>(
    coefficients: &[T],
    psi: &[T],
    reduction: &[T],
    nodal: &mut [T],
    mut write: impl FnMut(usize, T, T),
) {
    if reduction.is_empty() {
        pairs_times_vector(coefficients, psi, write);
    } else {
        let (nx, ny) = nodal.split_at_mut(nodal.len() / 2);
        pairs_times_vector(coefficients, psi, |i, x, y| (nx[i], ny[i]) = (x, y));
        rows_times_pair(reduction, nx, ny, &mut write);
    }
}

/// `X w` for coefficient rows stored in pairs (row i of X^x then row i of X^y, `2 len`
/// numbers per pair, as the operator keeps them): `write(i, X^x_i · w, X^y_i · w)` for every
/// pair i, two pairs at a time.
pub(crate) fn pairs_times_vector<T: Element>(pairs: &[T], w: &[T], mut write: impl FnMut(usize, T, T)) {
    let len = w.len();
    if len == 0 {
        return;
    }
    let mut blocks = pairs.chunks_exact(4 * len);
    let mut i = 0;
    for block in blocks.by_ref() {
        let (a, rest) = block.split_at(len);
        let (b, rest) = rest.split_at(len);
        let (c, d) = rest.split_at(len);
        let [[ax], [bx], [cx], [dx]] = T::dots([a, b, c, d], [w], len);
        write(i, ax, bx);
        write(i + 1, cx, dx);
        i += 2;
    }
    for pair in blocks.remainder().chunks_exact(2 * len) {
        let (a, b) = pair.split_at(len);
        let [[ax], [bx]] = T::dots([a, b], [w], len);
        write(i, ax, bx);
        i += 1;
    }
}

/// `Mᵀ (x, y)` for a matrix stored by rows of `x.len()` numbers (the reduction D by vertex):
/// `write(v, m_v · x, m_v · y)` for every row v, four rows at a time. `x` and `y` have equal
/// lengths.
pub(crate) fn rows_times_pair<T: Element>(rows: &[T], x: &[T], y: &[T], mut write: impl FnMut(usize, T, T)) {
    let len = x.len();
    if len == 0 {
        return;
    }
    let mut blocks = rows.chunks_exact(4 * len);
    let mut v = 0;
    for block in blocks.by_ref() {
        let (a, rest) = block.split_at(len);
        let (b, rest) = rest.split_at(len);
        let (c, d) = rest.split_at(len);
        for [mx, my] in T::dots([a, b, c, d], [x, y], len) {
            write(v, mx, my);
            v += 1;
        }
    }
    for row in blocks.remainder().chunks_exact(len) {
        let [[mx, my]] = T::dots([row], [x, y], len);
        write(v, mx, my);
        v += 1;
    }
}

#[cfg(test)]
mod tests {
    // Run in wasm too (`wasm-pack test --node -- --lib`), where `dots` is the simd128 form.
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    use super::*;

    /// Numbers in [-1, 1) from a fixed stream (xorshift), with varied magnitudes.
    fn numbers(count: usize, seed: u64) -> Vec<f64> {
        let mut state = seed | 1;
        (0..count)
            .map(|i| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
                (2.0 * unit - 1.0) * [1.0, 1e-3, 1e3][i % 3]
            })
            .collect()
    }

    /// A dot product summed in order, and the sum of |terms| (its rounding scale).
    fn plain_dot(a: &[f64], b: &[f64]) -> (f64, f64) {
        a.iter().zip(b).fold((0.0, 0.0), |(s, m), (x, y)| (s + x * y, m + (x * y).abs()))
    }

    /// Each of the two sums is within about `n ε Σ|terms|` of the exact one (n products and
    /// n additions of terms whose magnitudes sum to `scale`; Higham, *Accuracy and Stability
    /// of Numerical Algorithms*, §3.1).
    fn assert_close(found: f64, (expected, scale): (f64, f64), len: usize, what: &str) {
        let bound = 2.0 * (len as f64 + 1.0) * f64::EPSILON * scale;
        assert!((found - expected).abs() <= bound, "{what}: {found} vs {expected} (bound {bound})");
    }

    #[test]
    fn dots_match_plain_dot_products_at_every_length() {
        for len in [0, 1, 2, 3, 4, 5, 7, 8, 9, 100, 1019] {
            let rows: Vec<Vec<f64>> = (0..4).map(|r| numbers(len, 11 + r)).collect();
            let vectors: Vec<Vec<f64>> = (0..2).map(|c| numbers(len, 101 + c)).collect();
            let out = dots([&rows[0], &rows[1], &rows[2], &rows[3]], [&vectors[0], &vectors[1]], len);
            for (r, row) in rows.iter().enumerate() {
                for (c, vector) in vectors.iter().enumerate() {
                    assert_close(out[r][c], plain_dot(row, vector), len, &format!("len {len}, row {r}, vector {c}"));
                }
            }
            // The portable form rounds exactly alike.
            let portable = portable_dots([&rows[0], &rows[1], &rows[2], &rows[3]], [&vectors[0], &vectors[1]], len);
            assert_eq!(out, portable, "len {len}");
        }
    }

    #[test]
    fn single_precision_dots_match_plain_dot_products_at_every_length() {
        for len in [0, 1, 3, 4, 5, 7, 8, 9, 100, 1019] {
            let rows: Vec<Vec<f32>> =
                (0..4).map(|r| numbers(len, 21 + r).iter().map(|&x| x as f32).collect()).collect();
            let vectors: Vec<Vec<f32>> =
                (0..2).map(|c| numbers(len, 201 + c).iter().map(|&x| x as f32).collect()).collect();
            let out = dots_f32([&rows[0], &rows[1], &rows[2], &rows[3]], [&vectors[0], &vectors[1]], len);
            for (r, row) in rows.iter().enumerate() {
                for (c, vector) in vectors.iter().enumerate() {
                    // The products of f32 numbers are exact in f64: the plain sum there is
                    // the exact one to f64 rounding; the f32 sum is within ~n ε_32 of it.
                    let wide: Vec<f64> = row.iter().map(|&x| f64::from(x)).collect();
                    let other: Vec<f64> = vector.iter().map(|&x| f64::from(x)).collect();
                    let (expected, scale) = plain_dot(&wide, &other);
                    let bound = 2.0 * (len as f64 + 1.0) * f64::from(f32::EPSILON) * scale;
                    let found = f64::from(out[r][c]);
                    assert!((found - expected).abs() <= bound, "len {len}: {found} vs {expected} (bound {bound})");
                }
            }
            let portable = portable_dots_f32([&rows[0], &rows[1], &rows[2], &rows[3]], [&vectors[0], &vectors[1]], len);
            assert_eq!(out, portable, "len {len}");
        }
    }

    #[test]
    fn only_the_first_len_elements_count() {
        let (a, b) = ([1.0, 2.0, 3.0, 4.0, 5.0, 100.0], [1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(dots([&a], [&b], 5), [[15.0]]);
        assert_eq!(dots([&a], [&b], 0), [[0.0]]);
    }

    #[test]
    fn pairs_and_rows_give_every_product_once() {
        for (pairs, len) in [(0, 5), (1, 5), (2, 3), (5, 9), (7, 1019), (3, 1)] {
            let coefficients = numbers(2 * pairs * len, 7);
            let w = numbers(len, 8);
            let mut seen = vec![None; pairs];
            pairs_times_vector(&coefficients, &w, |i, x, y| {
                assert!(seen[i].replace((x, y)).is_none(), "pair {i} twice");
            });
            for (i, found) in seen.iter().enumerate() {
                let (x, y) = found.unwrap_or_else(|| panic!("pair {i} missing"));
                let row = &coefficients[2 * i * len..];
                assert_close(x, plain_dot(&row[..len], &w), len, "x");
                assert_close(y, plain_dot(&row[len..2 * len], &w), len, "y");
            }
        }
        for (count, len) in [(0, 4), (1, 4), (2, 100), (7, 100), (2058, 3), (4, 1)] {
            let matrix = numbers(count * len, 9);
            let (x, y) = (numbers(len, 10), numbers(len, 12));
            let mut seen = vec![None; count];
            rows_times_pair(&matrix, &x, &y, |v, a, b| {
                assert!(seen[v].replace((a, b)).is_none(), "row {v} twice");
            });
            for (v, found) in seen.iter().enumerate() {
                let (a, b) = found.unwrap_or_else(|| panic!("row {v} missing"));
                let row = &matrix[v * len..(v + 1) * len];
                assert_close(a, plain_dot(row, &x), len, "x");
                assert_close(b, plain_dot(row, &y), len, "y");
            }
        }
    }
}
