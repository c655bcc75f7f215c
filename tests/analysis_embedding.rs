//! Delay embedding (SPEC (4.1.1)).

use pdamp::analysis::embedding::vector_count;
use pdamp::analysis::DelayEmbedding;

#[test]
fn vectors_follow_the_definition() {
    // (4.1.1): vector labelled by its last time n is (s_{n−(m−1)τ}, …, s_n); pdamp labels it
    // by its first time i = n − (m−1)τ. Check against direct indexing.
    let x: Vec<f64> = (0..50).map(|i| (i * i) as f64).collect();
    for (m, tau) in [(1, 1), (2, 3), (4, 7), (7, 8)] {
        let e = DelayEmbedding::new(&x, m, tau).unwrap();
        assert_eq!(e.len(), 50 - (m - 1) * tau);
        for n in (m - 1) * tau..50 {
            let want: Vec<f64> = (0..m).rev().map(|k| x[n - k * tau]).collect();
            assert_eq!(e.vector(n - (m - 1) * tau), want);
        }
    }
}

#[test]
fn counts_saturate_at_zero() {
    assert_eq!(vector_count(10, 4, 3), 1);
    assert_eq!(vector_count(10, 5, 3), 0);
    assert!(DelayEmbedding::new(&[1.0; 10], 5, 3).is_err());
}
