//! Paired ratios: two calls timed in alternation inside every criterion sample, reported as the
//! ratio of their throughputs.
//!
//! A row of the ordinary groups is timed in a window of its own (two seconds), so the ratio of two
//! rows compares two windows. On the shared development host the speed moves between states
//! about 35–40% apart that last from half a second to several seconds (a 60-second trace of one
//! `shade_batch` call on 2026-12-07: 6.6 µs or 8.7–10.4 µs, in runs of one to six half-second
//! bins), so two rows of one run can be timed in different states, and a ratio of one run moves
//! by ±10–20% (docs/performance.md, "This run's noise"). Here each sample of criterion's usual
//! hundred times both calls alternately, a few milliseconds in all, so both sides of a sample see
//! the same state, and the row's median is the median of those per-sample ratios. A state need
//! not slow both sides alike (SSE2 and AVX-512 code, say), so a paired ratio still moves between
//! runs: by 1–17% a row across four runs on 2026-12-07, against tens of percent for the same
//! ratios from the ordinary rows.

use std::time::{Duration, Instant};

use criterion::Throughput;
use criterion::measurement::{Measurement, ValueFormatter};

/// A criterion measurement whose value is a throughput ratio, filled in by [`ratio`] through
/// `iter_custom` (its `start`/`end` are not used: criterion's own `iter` would read 0).
pub(crate) struct PairedRatio;

/// Prints the ratio as it is, with a `×`.
pub(crate) struct RatioFormatter;

impl ValueFormatter for RatioFormatter {
    fn scale_values(&self, _typical: f64, _values: &mut [f64]) -> &'static str {
        "×"
    }
    fn scale_throughputs(
        &self,
        _typical: f64,
        _throughput: &Throughput,
        _values: &mut [f64],
    ) -> &'static str {
        "×"
    }
    fn scale_for_machines(&self, _values: &mut [f64]) -> &'static str {
        "ratio"
    }
}

impl Measurement for PairedRatio {
    type Intermediate = ();
    type Value = f64;
    fn start(&self) {}
    fn end(&self, _: ()) -> f64 {
        0.0
    }
    fn add(&self, a: &f64, b: &f64) -> f64 {
        a + b
    }
    fn zero(&self) -> f64 {
        0.0
    }
    fn to_f64(&self, v: &f64) -> f64 {
        *v
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &RatioFormatter
    }
}

/// A criterion instance for paired rows, configured from the command line like the others (its
/// filter, `--save-baseline`, and so on), with the usual hundred samples.
pub(crate) fn criterion() -> criterion::Criterion<PairedRatio> {
    criterion::Criterion::default()
        .with_measurement(PairedRatio)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .configure_from_args()
}

/// `iters` calls of `subject` and of `baseline` in alternation (the order swapped every
/// iteration), on the shared `state`; returns `iters` times the baseline's total time over the
/// subject's, so that criterion's per-iteration value is the subject's throughput ÷ the
/// baseline's within this sample.
pub(crate) fn ratio<S>(
    iters: u64,
    state: &mut S,
    mut subject: impl FnMut(&mut S),
    mut baseline: impl FnMut(&mut S),
) -> f64 {
    let (mut ts, mut tb) = (Duration::ZERO, Duration::ZERO);
    let time = |f: &mut dyn FnMut(&mut S), state: &mut S, total: &mut Duration| {
        let t = Instant::now();
        f(state);
        *total += t.elapsed();
    };
    for i in 0..iters {
        if i % 2 == 0 {
            time(&mut subject, state, &mut ts);
            time(&mut baseline, state, &mut tb);
        } else {
            time(&mut baseline, state, &mut tb);
            time(&mut subject, state, &mut ts);
        }
    }
    iters as f64 * tb.as_secs_f64() / ts.as_secs_f64().max(f64::MIN_POSITIVE)
}
