//! A small seeded random number generator, the same on every platform (native and wasm), so
//! that anything drawn from a seed (DefOp's training samples) is reproducible bit for bit.
//!
//! SplitMix64 (Steele, Lea and Flood 2014): a 64-bit counter stepped by the golden-ratio
//! increment and passed through a bijective mixing function. It passes BigCrush, needs no
//! warm-up, and any seed (0 too) gives a full-period stream; plenty for sampling, not for
//! cryptography.

/// A SplitMix64 generator.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rng {
    state: u64,
}

impl Rng {
    /// A generator whose stream is determined by `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number uniform in `[0, 1)`: the top 53 bits, so every value is a multiple of 2^-53.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A whole number uniform in `0..n` (`n` at least 1), without modulo bias.
    pub fn below(&mut self, n: u64) -> u64 {
        assert!(n > 0, "below(0) has no value to return");
        // Lemire's multiply-and-reject: the high half of a 128-bit product, retried in the
        // rare case that lands in the biased low part.
        let threshold = n.wrapping_neg() % n;
        loop {
            let product = u128::from(self.next_u64()) * u128::from(n);
            if (product as u64) >= threshold {
                return (product >> 64) as u64;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_reference_stream() {
        // SplitMix64 from seed 1234567, as published with the algorithm (Vigna's splitmix64.c
        // test values).
        let mut rng = Rng::new(1234567);
        let expected = [
            6457827717110365317u64,
            3203168211198807973,
            9817491932198370423,
            4593380528125082431,
            16408922859458223821,
        ];
        for e in expected {
            assert_eq!(rng.next_u64(), e);
        }
    }

    #[test]
    fn uniform_and_below_stay_in_range_and_are_balanced() {
        let mut rng = Rng::new(7);
        let mut counts = [0u32; 10];
        let mut sum = 0.0;
        let n = 100_000;
        for _ in 0..n {
            let u = rng.uniform();
            assert!((0.0..1.0).contains(&u));
            sum += u;
            counts[rng.below(10) as usize] += 1;
        }
        // Mean of U(0, 1): 1/2 with standard error 1/sqrt(12 n) ~ 9e-4.
        assert!((sum / n as f64 - 0.5).abs() < 5e-3, "{}", sum / n as f64);
        // Each of 10 bins: 10,000 expected, standard deviation ~95.
        assert!(counts.iter().all(|&c| (9_500..10_500).contains(&c)), "{counts:?}");
    }
}
