//! `--shard I/N`: one of N interleaved parts of a sweep, for spreading it over machines (a job array).
//!
//! Shard I (1-based, 1 <= I <= N) takes the rows whose global index satisfies `index % N == I - 1`. Interleaving
//! rather than contiguous blocks spreads the costly corners of a grid (small e with the 1/e maps, say) over all
//! shards. Every shard has the same header and carries the global index of each row, so `impact merge` can check
//! that the shards make up the whole sweep and put the rows back in order.

use super::SweepError;
use crate::text::{MESSAGE_CHARS, cut};
use std::fmt;

/// Shard `number` of `count` (1-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub number: usize,
    pub count: usize,
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.number, self.count)
    }
}

impl Shard {
    /// Parses `I/N` with 1 <= I <= N.
    pub fn parse(spec: &str) -> Result<Shard, SweepError> {
        let bad = |why: &str| {
            let spec = cut(spec, MESSAGE_CHARS);
            SweepError::Usage(format!("--shard `{spec}`: {why}; expected I/N with 1 <= I <= N, e.g. --shard 2/8"))
        };
        let (number, count) = spec.split_once('/').ok_or_else(|| bad("no `/`"))?;
        let whole = |text: &str| text.trim().parse::<usize>().ok();
        let (Some(number), Some(count)) = (whole(number), whole(count)) else {
            return Err(bad("I and N must be whole numbers"));
        };
        if count == 0 {
            return Err(bad("N must be at least 1"));
        }
        // A sweep has at most MAX_ROWS rows, and `impact merge` reads no more shards than that.
        if count > super::MAX_ROWS {
            return Err(bad(&format!("N must be at most {}, the most rows a sweep may have", super::MAX_ROWS)));
        }
        if number == 0 || number > count {
            return Err(bad(&format!("I must be between 1 and {count} (shards count from 1)")));
        }
        Ok(Shard { number, count })
    }

    /// Whether the row with global index `index` belongs to this shard.
    pub fn takes(&self, index: usize) -> bool {
        index % self.count == self.number - 1
    }
}
