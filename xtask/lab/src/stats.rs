//! Small statistics: medians of timing repeats, and the Pareto front of
//! the speed-against-accuracy chart.

/// The median of `values` (the mean of the middle two for an even count),
/// or `None` when there are none. NaNs sort last.
pub fn median(values: &[f64]) -> Option<f64> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(sorted[n / 2]),
        _ => Some((sorted[n / 2 - 1] + sorted[n / 2]) / 2.0),
    }
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
