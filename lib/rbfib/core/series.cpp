#include "rbfib/core/series.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rbfib {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi) {
  std::vector<double> a, b;
  for (std::size_t j = 0; j < x.size() && j < y.size(); ++j)
    if (x[j] >= lo && x[j] <= hi) a.push_back(x[j]), b.push_back(y[j]);
  LineFit f;
  const std::size_t n = a.size();
  f.count = int(n);
  for (std::size_t i = 0; i < n; ++i) f.x_mean += a[i] / double(n), f.y_mean += b[i] / double(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) sxy += (a[i] - f.x_mean) * (b[i] - f.y_mean), sxx += (a[i] - f.x_mean) * (a[i] - f.x_mean);
  f.slope = n < 2 ? std::nan("") : sxy / sxx;
  for (std::size_t i = 0; i < n; ++i) f.max_departure = std::max(f.max_departure, std::abs(b[i] - (f.y_mean + f.slope * (a[i] - f.x_mean))));
  return f;
}

double longest_interval(const std::vector<double>& t, const std::vector<bool>& flag) {
  double longest = 0;
  std::size_t first = 0;
  bool in = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (flag[i] && !in) first = i, in = true;
    if (in && (!flag[i] || i + 1 == t.size())) {
      longest = std::max(longest, t[flag[i] ? i : i - 1] - t[first]);
      in = false;
    }
  }
  return longest;
}

double zero_crossing(const std::vector<double>& t, const std::vector<double>& x, std::size_t i) {
  return t[i - 1] + (t[i] - t[i - 1]) * x[i - 1] / (x[i - 1] - x[i]);
}

double rising_crossing_log(const std::vector<double>& x, const std::vector<double>& y, double level) {
  for (std::size_t i = 1; i < x.size() && i < y.size(); ++i)
    if (y[i] > level && y[i - 1] <= level) {
      if (!std::isfinite(y[i])) return x[i - 1];
      const double f = (level - y[i - 1]) / (y[i] - y[i - 1]);
      return std::exp(std::log(x[i - 1]) + f * (std::log(x[i]) - std::log(x[i - 1])));
    }
  return NAN;
}

double mean_interval(const std::vector<double>& times) {
  return times.size() < 2 ? NAN : (times.back() - times.front()) / double(times.size() - 1);
}

double oscillation_frequency(const std::vector<double>& t, const std::vector<double>& x0, double from) {
  std::vector<double> ts, x;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from) ts.push_back(t[i]), x.push_back(x0[i]);
  if (x.size() < 3) return NAN;
  double mean = 0, var = 0;
  for (double v : x) mean += v / double(x.size());
  for (double& v : x) v -= mean, var += v * v / double(x.size());
  const double band = std::sqrt(var) / 4;
  std::vector<double> crossings;
  int side = 0;            // +1 above mean + band, -1 below mean - band, 0 not yet either
  double last_zero = NAN;  // the latest passage through the mean
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i > 0 && (x[i - 1] < 0) != (x[i] < 0)) last_zero = zero_crossing(ts, x, i);
    const int now = x[i] > band ? 1 : (x[i] < -band ? -1 : side);
    if (side != 0 && now != side && std::isfinite(last_zero)) crossings.push_back(last_zero);
    side = now;
  }
  return 1 / (2 * mean_interval(crossings));
}

double successive_order(double ratio, int r) {
  auto g = [r](double p) { return std::abs(std::pow((r + 1.0) / r, p) - 1) / std::abs(std::pow((r + 2.0) / (r + 1.0), -p) - 1); };
  double lo = 1e-3, hi = 30;
  if (!(ratio > g(lo) && ratio < g(hi))) return NAN;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> unwrap(const std::vector<double>& angles, double period) {
  std::vector<double> out(angles);
  for (std::size_t i = 1; i < out.size(); ++i) {
    const double step = angles[i] - angles[i - 1];
    out[i] = out[i - 1] + step - period * std::round(step / period);
  }
  return out;
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2 || y.size() != n) return std::nan("");
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i] / double(n), my += y[i] / double(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxy / sxx;
}

double power_law_order(const std::vector<double>& x, const std::vector<double>& e) {
  std::vector<double> lx(x.size()), le(e.size());
  for (std::size_t i = 0; i < x.size(); ++i) lx[i] = std::log(x[i]);
  for (std::size_t i = 0; i < e.size(); ++i) le[i] = std::log(e[i]);
  return -slope(lx, le);
}

double median(std::vector<double> values) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const std::size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

}  // namespace rbfib
