//! Wall-clock timing of a computation: the median over repeated runs.

use std::hint::black_box;
use std::time::{Duration, Instant};

/// How often to repeat a timed computation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Repeats {
    /// Stop after this many runs...
    pub runs: usize,
    /// ...or once the runs so far took this long, whichever comes first (at least one run).
    pub budget: Duration,
}

/// Runs `work` as `repeats` says and returns the median run time in seconds and the first
/// run's result.
pub fn median_seconds<T>(repeats: Repeats, mut work: impl FnMut() -> T) -> (f64, T) {
    let started = Instant::now();
    let mut times = vec![];
    let mut first = None;
    while times.is_empty() || (times.len() < repeats.runs && started.elapsed() < repeats.budget) {
        let start = Instant::now();
        let result = black_box(work());
        times.push(start.elapsed().as_secs_f64());
        first.get_or_insert(result);
    }
    times.sort_by(f64::total_cmp);
    let middle = times.len() / 2;
    let median = if times.len() % 2 == 1 { times[middle] } else { 0.5 * (times[middle - 1] + times[middle]) };
    (median, first.expect("at least one run"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stops_at_the_run_count_or_the_budget() {
        let mut calls = 0;
        let (median, first) = median_seconds(Repeats { runs: 5, budget: Duration::from_secs(60) }, || {
            calls += 1;
            calls
        });
        assert_eq!((calls, first), (5, 1));
        assert!(median >= 0.0);
        let mut calls = 0;
        median_seconds(Repeats { runs: 1000, budget: Duration::ZERO }, || calls += 1);
        assert_eq!(calls, 1);
    }
}
