//! `--shard K/N`: which points of a sweep one process computes.
//!
//! Shard K of N (0 ≤ K < N, numbered as Slurm numbers the tasks of `--array=0-(N-1)`) takes
//! the points i with i mod N = K: interleaved, so that slow and fast regions of the grid
//! (resonance, long transients) spread evenly over the shards, and the shards' sizes differ by
//! at most one point.

use crate::error::SceneError;

/// One share of a sweep's points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard's number K, 0 ≤ K < `count`.
    pub index: usize,
    /// Number of shards N ≥ 1.
    pub count: usize,
}

impl Shard {
    /// The whole sweep (shard 0 of 1).
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Parse `K/N` with 0 ≤ K < N.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming `--shard` for anything else.
    pub fn parse(text: &str) -> Result<Shard, SceneError> {
        let bad = |why: &str| SceneError::invalid("--shard", text, why);
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| bad("expected K/N, e.g. --shard 0/4 (K counts from 0 to N-1)"))?;
        let parse = |s: &str| s.trim().parse::<usize>().ok();
        match (parse(k), parse(n)) {
            (Some(index), Some(count)) if count >= 1 && index < count => Ok(Shard { index, count }),
            (Some(_), Some(_)) => Err(bad(
                "K must count from 0 to N-1 (N ≥ 1), as Slurm's SLURM_ARRAY_TASK_ID with \
                 --array=0-(N-1)",
            )),
            _ => Err(bad("K and N must be whole numbers, e.g. --shard 0/4")),
        }
    }

    /// Whether point `i` belongs to this shard.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index
    }

    /// The points of this shard among `n`, in increasing order.
    pub fn points(&self, n: usize) -> impl Iterator<Item = usize> {
        (self.index..n).step_by(self.count)
    }

    /// Whether this is the whole sweep.
    pub fn is_whole(&self) -> bool {
        self.count == 1
    }

    /// `K-of-N`, used in file names.
    pub fn label(&self) -> String {
        format!("{}-of-{}", self.index, self.count)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_grid_interleaved_and_balanced() {
        let n = 11;
        let mut seen = vec![0; n];
        for k in 0..3 {
            let s = Shard::parse(&format!("{k}/3")).unwrap();
            let pts: Vec<usize> = s.points(n).collect();
            // sizes 4, 4, 3: differ by at most one
            assert!(pts.len() == 3 || pts.len() == 4, "{pts:?}");
            for &i in &pts {
                assert!(s.contains(i));
                seen[i] += 1;
            }
            // interleaved: consecutive points of a shard are N apart
            assert!(pts.windows(2).all(|w| w[1] - w[0] == 3), "{pts:?}");
        }
        assert!(seen.iter().all(|&c| c == 1), "{seen:?}");
        assert_eq!(Shard::WHOLE.points(5).count(), 5);
    }

    #[test]
    fn bad_shards_name_the_flag() {
        for bad in ["3/3", "1", "a/2", "0/0", "-1/2"] {
            let e = Shard::parse(bad).unwrap_err().to_string();
            assert!(e.contains("--shard"), "{bad}: {e}");
        }
        assert_eq!(Shard::parse("2/5").unwrap(), Shard { index: 2, count: 5 });
    }
}
