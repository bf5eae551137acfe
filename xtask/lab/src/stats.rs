//! Small statistics: the spread of timing repeats, the ratio of two
//! contenders' times from paired repeats with its interval, within a launch
//! and across launches, how far launches disagree, and the Pareto front of the speed-against-accuracy chart.
//! The order statistics, means, deviations and Student's t quantiles are
//! `statrs`'s.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};
use statrs::statistics::{Data, OrderStatistics, Statistics};

/// The confidence of every interval the lab reports.
pub const CONFIDENCE: f64 = 0.95;

/// The median of `values` (the mean of the middle two for an even count),
/// or `None` when there are none.
pub fn median(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| Data::new(values.to_vec()).median())
}

/// How a lane's repeats spread: their median, least and most.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spread {
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    /// The spread of `values`, or `None` when there are none.
    pub fn of(values: &[f64]) -> Option<Spread> {
        Some(Spread { median: median(values)?, min: values.min(), max: values.max() })
    }
}

/// One time over another, with its interval at [`CONFIDENCE`]: within a
/// launch, from repeats timed in turn ([`Ratio::paired`]); across launches,
/// from each launch's ratio ([`Ratio::across`]). Either way the figure is
/// the geometric mean of the ratios it is over, and the interval Student's
/// t on their logarithms with one degree of freedom fewer than there are
/// ratios.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ratio {
    pub ratio: f64,
    /// The interval's ends; `None` with fewer than two ratios.
    pub low: Option<f64>,
    pub high: Option<f64>,
    /// The ratios it is over: repeats paired, or launches.
    pub count: usize,
}

impl Ratio {
    /// `a` over `b`, repeat by repeat (`a[i]` and `b[i]` timed in the
    /// same repeat of one launch: a paired design, so a change in the
    /// machine's load that falls on both times of a repeat cancels); pairs
    /// where either time is not a positive number are left out. `None`
    /// without a pair.
    pub fn paired(a: &[f64], b: &[f64]) -> Option<Ratio> {
        let logs: Vec<f64> = a
            .iter()
            .zip(b)
            .filter(|(a, b)| a.is_finite() && b.is_finite() && **a > 0.0 && **b > 0.0)
            .map(|(a, b)| (a / b).ln())
            .collect();
        Self::of_logs(&logs)
    }

    /// The ratio over launches, from each launch's own ([`Ratio::paired`]
    /// within it): the geometric mean of the launches' ratios, and the t
    /// interval of the mean of their logarithms with `launches - 1`
    /// degrees of freedom, which holds the process (its code's layout in
    /// memory, its caches' and predictors' state, the clock's speed that
    /// day) as the unit that varies. `None` without a launch.
    pub fn across(launches: &[Ratio]) -> Option<Ratio> {
        Self::of_logs(&launches.iter().map(|r| r.ratio.ln()).collect::<Vec<f64>>())
    }

    /// The geometric mean of the ratios whose logarithms are `logs`, with
    /// the t interval of their mean.
    fn of_logs(logs: &[f64]) -> Option<Ratio> {
        let count = logs.len();
        if count == 0 {
            return None;
        }
        let mean = logs.iter().mean();
        let (low, high) = if count < 2 {
            (None, None)
        } else {
            let t = StudentsT::new(0.0, 1.0, (count - 1) as f64).expect("a positive number of degrees of freedom");
            let half = t.inverse_cdf(0.5 + CONFIDENCE / 2.0) * logs.iter().std_dev() / (count as f64).sqrt();
            (Some((mean - half).exp()), Some((mean + half).exp()))
        };
        Some(Ratio { ratio: mean.exp(), low, high, count })
    }

    /// Whether the whole interval lies above `x` (a ratio of one pair
    /// or one launch has no interval, and is above nothing).
    pub fn surely_above(&self, x: f64) -> bool {
        self.low.is_some_and(|low| low > x)
    }
}

/// How far `values` (one figure from each of several launches) disagree: the
/// largest over the smallest, less one; `None` with fewer than two.
pub fn disagreement(values: &[f64]) -> Option<f64> {
    (values.len() >= 2 && values.iter().all(|v| *v > 0.0)).then(|| values.max() / values.min() - 1.0)
}

/// A running mean of 2-D values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeanVector {
    sum: (f64, f64),
    count: u64,
}

impl MeanVector {
    pub fn add(&mut self, (x, y): (f64, f64)) {
        self.sum.0 += x;
        self.sum.1 += y;
        self.count += 1;
    }

    /// Adds every value `other` has seen.
    pub fn merge(&mut self, other: &MeanVector) {
        self.sum.0 += other.sum.0;
        self.sum.1 += other.sum.1;
        self.count += other.count;
    }

    /// The mean, or `None` before the first value.
    pub fn mean(&self) -> Option<(f64, f64)> {
        (self.count > 0).then(|| (self.sum.0 / self.count as f64, self.sum.1 / self.count as f64))
    }
}

/// Indices of the points not dominated by another point, where smaller is
/// better on both axes, in order of increasing `x` (and so decreasing `y`).
/// Of equal points only the first is kept.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)));
    let mut front = Vec::new();
    let mut best_y = f64::INFINITY;
    for i in order {
        if points[i].1 < best_y {
            best_y = points[i].1;
            front.push(i);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(&[]), None);
    }

    #[test]
    fn median_ignores_one_outlier() {
        assert_eq!(median(&[10.0, 11.0, 1e9, 12.0, 9.0]), Some(11.0));
    }

    #[test]
    fn a_spread_is_the_median_least_and_most() {
        assert_eq!(Spread::of(&[3.0, 9.0, 1.0, 4.0, 5.0]), Some(Spread { median: 4.0, min: 1.0, max: 9.0 }));
        assert_eq!(Spread::of(&[]), None);
    }

    /// Times that move together (the machine's load) give a ratio with a
    /// narrow interval; the interval is the t interval of the logarithms,
    /// worked out here by hand: ratios 2, 2.2, 1.8 have logarithms of mean
    /// m = 0.6871 and standard deviation s = 0.1004, and t(0.975, 2) =
    /// 4.3027, so the interval is exp(m ± 4.3027 s / sqrt 3).
    #[test]
    fn a_paired_ratio_has_the_t_interval_of_its_logarithms() {
        let a = [200.0, 440.0, 180.0];
        let b = [100.0, 200.0, 100.0];
        let r = Ratio::paired(&a, &b).unwrap();
        let logs = [2.0f64.ln(), 2.2f64.ln(), 1.8f64.ln()];
        let m = logs.iter().sum::<f64>() / 3.0;
        let s = (logs.iter().map(|l| (l - m).powi(2)).sum::<f64>() / 2.0).sqrt();
        let half = 4.302_652_7 * s / 3f64.sqrt();
        assert!((r.ratio - m.exp()).abs() < 1e-9, "{r:?}");
        assert!((r.low.unwrap() - (m - half).exp()).abs() < 1e-6, "{r:?}");
        assert!((r.high.unwrap() - (m + half).exp()).abs() < 1e-6, "{r:?}");
        assert_eq!(r.count, 3);
        assert!(r.surely_above(1.0) && !r.surely_above(2.0));
    }

    /// Across launches the interval is over the launches' ratios alone,
    /// whatever the repeats within each: ratios 2.0, 2.4 and 2.2 have
    /// logarithms of mean m = 0.7857 and standard deviation s = 0.0912
    /// (worked out here by hand), and t(0.975, 2) = 4.3027 for 3 launches,
    /// so the interval is exp(m ± 4.3027 s / sqrt 3) = 1.75–2.75.
    #[test]
    fn the_interval_across_launches_is_the_t_interval_of_their_ratios() {
        let launch = |ratio, count| Ratio { ratio, low: Some(ratio * 0.99), high: Some(ratio * 1.01), count };
        let r = Ratio::across(&[launch(2.0, 7), launch(2.4, 7), launch(2.2, 7)]).unwrap();
        let logs = [2.0f64.ln(), 2.4f64.ln(), 2.2f64.ln()];
        let m = logs.iter().sum::<f64>() / 3.0;
        let s = (logs.iter().map(|l| (l - m).powi(2)).sum::<f64>() / 2.0).sqrt();
        assert!((m - 0.785_7).abs() < 1e-4 && (s - 0.091_2).abs() < 1e-4, "{m} {s}");
        let half = 4.302_652_7 * s / 3f64.sqrt();
        assert!((r.ratio - m.exp()).abs() < 1e-9, "{r:?}");
        assert!((r.low.unwrap() - (m - half).exp()).abs() < 1e-6, "{r:?}");
        assert!((r.high.unwrap() - (m + half).exp()).abs() < 1e-6, "{r:?}");
        assert!((r.low.unwrap() - 1.75).abs() < 0.005 && (r.high.unwrap() - 2.75).abs() < 0.005, "{r:?}");
        assert_eq!(r.count, 3);
        // One launch has a ratio and no interval; none has no ratio.
        let one = Ratio::across(&[launch(2.0, 7)]).unwrap();
        assert_eq!((one.ratio, one.low, one.high, one.count), (2.0, None, None, 1));
        assert_eq!(Ratio::across(&[]), None);
    }

    #[test]
    fn a_load_that_falls_on_both_leaves_the_ratio_exact() {
        // The machine slows down tenfold between repeats; the ratio holds.
        let r = Ratio::paired(&[30.0, 300.0, 3000.0], &[10.0, 100.0, 1000.0]).unwrap();
        assert!((r.ratio - 3.0).abs() < 1e-9);
        assert!((r.high.unwrap() - r.low.unwrap()).abs() < 1e-9);
    }

    #[test]
    fn one_pair_has_no_interval_and_none_has_no_ratio() {
        let r = Ratio::paired(&[4.0, f64::NAN], &[2.0, 1.0]).unwrap();
        assert_eq!((r.ratio, r.low, r.high, r.count), (2.0, None, None, 1));
        assert!(!r.surely_above(1.0));
        assert_eq!(Ratio::paired(&[], &[]), None);
        assert_eq!(Ratio::paired(&[0.0], &[1.0]), None);
    }

    #[test]
    fn runs_disagree_by_their_largest_over_their_smallest() {
        assert!((disagreement(&[100.0, 110.0, 105.0]).unwrap() - 0.1).abs() < 1e-12);
        assert_eq!(disagreement(&[100.0]), None);
    }

    #[test]
    fn mean_vector_averages_each_axis() {
        let mut mean = MeanVector::default();
        assert_eq!(mean.mean(), None);
        mean.add((1.0, -2.0));
        mean.add((3.0, 4.0));
        assert_eq!(mean.mean(), Some((2.0, 1.0)));
        let mut other = MeanVector::default();
        other.add((5.0, 1.0));
        mean.merge(&other);
        assert_eq!(mean.mean(), Some((3.0, 1.0)));
    }

    #[test]
    fn pareto_front_keeps_only_undominated_points() {
        // (time, error): 1 is dominated by 0; 3 by 2; 4 is fastest.
        let points = [(2.0, 1.0), (3.0, 2.0), (5.0, 0.0), (6.0, 0.0), (1.0, 9.0)];
        assert_eq!(pareto_front(&points), vec![4, 0, 2]);
    }

    #[test]
    fn pareto_front_keeps_one_of_equal_points() {
        assert_eq!(pareto_front(&[(1.0, 1.0), (1.0, 1.0)]), vec![0]);
        assert!(pareto_front(&[]).is_empty());
    }
}
