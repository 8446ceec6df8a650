#include "rbfib/run/phase_times.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::run {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

double median_of(const io::Series& s, std::size_t column) {
  std::vector<double> v;
  for (const std::vector<double>& q : s.rows) v.push_back(q.at(column));
  return median(std::move(v));
}

}  // namespace

void append_phases(io::Series& phases, const sim::IbStepReport& r) {
  phases.columns = {"forces (s)", "products (s)", "spread (s)", "solve (s)", "interpolate (s)", "update (s)"};
  phases.rows.push_back({r.seconds_forces, r.seconds_force_products, r.seconds_spreading, r.seconds_fluid,
                         r.seconds_interpolation, r.seconds_update});
}

PhaseTimes phase_sums(const io::Series& phases) {
  PhaseTimes p;
  for (const std::vector<double>& q : phases.rows) {
    p.forces += q.at(0);
    p.force_products += q.at(1);
    p.spread += q.at(2);
    p.solve += q.at(3);
    p.interpolate += q.at(4);
    p.update += q.at(5);
  }
  return p;
}

PhaseTimes phase_medians(const io::Series& phases) {
  PhaseTimes p;
  p.forces = median_of(phases, 0);
  p.force_products = median_of(phases, 1);
  p.spread = median_of(phases, 2);
  p.solve = median_of(phases, 3);
  p.interpolate = median_of(phases, 4);
  p.update = median_of(phases, 5);
  return p;
}

double block_ratio_std(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.size() < 2) return NAN;
  std::vector<double> r;
  for (std::size_t j = 0; j < a.size(); ++j) r.push_back((a[j] - (j ? a[j - 1] : 0)) / (b[j] - (j ? b[j - 1] : 0)));
  double mean = 0, s2 = 0;
  for (double x : r) mean += x / double(r.size());
  for (double x : r) s2 += (x - mean) * (x - mean);
  return std::sqrt(s2 / double(r.size() - 1));
}

}  // namespace rbfib::run
