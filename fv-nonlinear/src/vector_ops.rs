//! Dense vector kernels of the Krylov solver, parallel over fixed chunks so
//! that the results are the same to the bit whatever the number of threads
//! (each chunk's partial sum is formed alone, the partial sums are added in
//! chunk order); and [`release_pages`] for work vectors whose contents are
//! dead between uses.
use rayon::prelude::*;

/// Entries per chunk.
const CHUNK: usize = 8192;
/// Vectors shorter than this are handled on the calling thread.
const PARALLEL_LEN: usize = 4 * CHUNK;

fn parallel(n: usize) -> bool {
    n >= PARALLEL_LEN && rayon::current_num_threads() > 1
}

/// Σ a_i b_i.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    debug_assert_eq!(a.len(), b.len());
    let chunk = |(x, y): (&[f64], &[f64])| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    if parallel(a.len()) {
        let parts: Vec<f64> = a
            .par_chunks(CHUNK)
            .zip(b.par_chunks(CHUNK))
            .map(chunk)
            .collect();
        parts.iter().sum()
    } else {
        a.chunks(CHUNK).zip(b.chunks(CHUNK)).map(chunk).sum()
    }
}

/// ‖a‖₂.
pub fn norm(a: &[f64]) -> f64 {
    let squares = dot(a, a);
    // the sum of squares under- or overflows where the entries are below
    // about 1e-154 or above 1e154 (a probe's E = 1e-200: every residual
    // norm 0, an increment "converged" in no iteration): then again,
    // scaled by the largest entry
    if squares.is_nan() || (squares.is_normal() && squares < f64::MAX) {
        return squares.sqrt();
    }
    let largest = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest == 0.0 || !largest.is_finite() {
        return largest;
    }
    largest * a.iter().map(|x| (x / largest).powi(2)).sum::<f64>().sqrt()
}

/// y ← y + α x.
pub fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    debug_assert_eq!(x.len(), y.len());
    let kernel = |(yc, xc): (&mut [f64], &[f64])| {
        for (yi, xi) in yc.iter_mut().zip(xc) {
            *yi += alpha * xi;
        }
    };
    if parallel(y.len()) {
        y.par_chunks_mut(CHUNK)
            .zip(x.par_chunks(CHUNK))
            .for_each(kernel);
    } else {
        y.chunks_mut(CHUNK).zip(x.chunks(CHUNK)).for_each(kernel);
    }
}

/// y ← α y.
pub fn scale(alpha: f64, y: &mut [f64]) {
    let kernel = |yc: &mut [f64]| yc.iter_mut().for_each(|v| *v *= alpha);
    if parallel(y.len()) {
        y.par_chunks_mut(CHUNK).for_each(kernel);
    } else {
        kernel(y);
    }
}

/// Returns the whole pages inside `v` to the operating system: they read
/// as zeros afterwards, and are resident again once written (for work
/// vectors whose contents are dead between uses).
#[cfg(unix)]
pub fn release_pages(v: &mut [f64]) {
    const PAGE: usize = 4096;
    let start = v.as_mut_ptr() as usize;
    let end = start + std::mem::size_of_val(v);
    let (first, last) = (start.next_multiple_of(PAGE), end / PAGE * PAGE);
    if last > first {
        // SAFETY: [first, last) lies inside `v`, which is borrowed mutably
        // and holds plain f64s (any bit pattern, zeros included, is one);
        // MADV_DONTNEED on private anonymous memory only replaces those
        // pages by zero-filled ones on the next access (a failure, e.g.
        // pages of another kind, leaves them as they are).
        unsafe {
            libc::madvise(
                first as *mut libc::c_void,
                last - first,
                libc::MADV_DONTNEED,
            );
        }
    }
}

/// No-op where pages cannot be returned.
#[cfg(not(unix))]
pub fn release_pages(_v: &mut [f64]) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn norm_of_tiny_and_huge_entries() {
        for scale in [1e-200, 1.0, 1e200] {
            let n = norm(&[3.0 * scale, 4.0 * scale]);
            assert!((n / (5.0 * scale) - 1.0).abs() < 1e-15, "{scale}: {n}");
        }
        assert_eq!(norm(&[0.0, 0.0]), 0.0);
        assert!(norm(&[1.0, f64::NAN]).is_nan());
        assert_eq!(norm(&[1.0, f64::INFINITY]), f64::INFINITY);
    }

    #[test]
    fn kernels_match_the_plain_loops() {
        let n = 5 * PARALLEL_LEN + 17;
        let a: Vec<f64> = (0..n)
            .map(|i| ((i * 7919) % 1000) as f64 * 1e-3 - 0.5)
            .collect();
        let b: Vec<f64> = (0..n).map(|i| ((i * 104729) % 997) as f64 * 1e-3).collect();
        let plain: f64 = a
            .chunks(CHUNK)
            .zip(b.chunks(CHUNK))
            .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>())
            .sum();
        assert_eq!(dot(&a, &b), plain);
        let mut y = b.clone();
        axpy(2.0, &a, &mut y);
        assert!(y
            .iter()
            .zip(&a)
            .zip(&b)
            .all(|((y, a), b)| *y == b + 2.0 * a));
        scale(0.5, &mut y);
        assert!((norm(&[3.0, 4.0]) - 5.0).abs() < 1e-15);
    }
}
