#pragma once
// Measures of a sampled series y(x): the least-squares line over a window of x (and its slope and a
// power law's order over all of it), the longest stretch of samples where a condition holds,
// crossings, oscillation frequencies, orders of convergence, medians, and angles unwrapped.
#include <cstddef>
#include <vector>

namespace rbfib {

/// The least-squares line through the samples with lo <= x <= hi: y = y_mean + slope (x - x_mean).
struct LineFit {
  double slope = 0, x_mean = 0, y_mean = 0;
  double max_departure = 0;  ///< the largest |y - line| over the window
  int count = 0;             ///< samples in the window (slope NaN for fewer than two)
  /// Where the line crosses y = 0: for a Couette profile, the height of the no-slip wall the flow sees.
  double x_intercept() const { return x_mean - y_mean / slope; }
};
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi);

/// The longest stretch of consecutive samples with flag set: the time from its first to its last
/// sample (0 for none, or a stretch of one sample).
double longest_interval(const std::vector<double>& t, const std::vector<bool>& flag);

/// Where x(t), sampled at t[i-1] and t[i], passes zero, linearly between the two samples.
double zero_crossing(const std::vector<double>& t, const std::vector<double>& x, std::size_t i);

/// The first x at which y(x), sampled at increasing x > 0, rises through `level`: interpolated
/// linearly in log x between the last sample at or below it and the first above; that last sample's
/// x when the one above is not finite (grown past all bounds); NaN when no pair brackets it.
double rising_crossing_log(const std::vector<double>& x, const std::vector<double>& y, double level);

/// Mean interval between successive entries of `times` (NaN for fewer than two).
double mean_interval(const std::vector<double>& times);

/// The frequency of an oscillation of x(t) after t = `from`: the times x crosses its mean there,
/// a crossing counted once x has moved a quarter of its standard deviation beyond the mean (so
/// that jitter about the mean is not an oscillation); 1 / (2 x their mean interval), NaN for
/// fewer than two crossings.
double oscillation_frequency(const std::vector<double>& t, const std::vector<double>& x, double from);

/// The order p of convergence from differences between successive grids h_r = h_1 / r (the seed's
/// formula, Sec. 5.1.1): eps_r / eps_{r+1} = |((r+1)/r)^p - 1| / |((r+2)/(r+1))^{-p} - 1|, exact for
/// eps_r = |u_r - u_{r+1}| when u_r = u + C h_r^p; solved by bisection (the right side grows with
/// p). NaN when the ratio is out of reach of p in [1e-3, 30].
double successive_order(double ratio, int r);

/// Continues a sequence of angles (rad) across the jumps of `period` (2 pi for a direction,
/// pi for an axis) so that it varies continuously.
std::vector<double> unwrap(const std::vector<double>& angles, double period);

/// Least-squares slope of y against x (NaN for fewer than two points).
double slope(const std::vector<double>& x, const std::vector<double>& y);

/// Least-squares power-law order p of e ~ c x^-p, -slope(log x, log e): the paper's "power law
/// function fits" of errors against resolution.
double power_law_order(const std::vector<double>& x, const std::vector<double>& e);

/// Median of a sample (the mean of the two middle values for an even count; NaN when empty).
double median(std::vector<double> values);

}  // namespace rbfib
