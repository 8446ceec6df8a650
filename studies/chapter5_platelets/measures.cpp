#include "measures.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/rotation.hpp"
#include "rbfib/core/series.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/models/jeffery.hpp"

#include <algorithm>

namespace rbfib::platelets {

using study::row;

Platelet analyse(const std::vector<std::vector<double>>& samples, const std::vector<double>& t, int c, double gdot, Json& series) {
  const std::size_t o = 1 + 8 * std::size_t(c), ns = t.size(), half = ns / 2;
  Platelet p;
  std::vector<double> angle;
  double v0 = NAN;
  for (const auto& r : samples) {
    angle.push_back(std::atan(r[o + 5] / r[o + 4]));  // tilt of the short axis from the wall normal (y) toward the flow (z)
    p.gap.push_back(r[o + 6]), p.height.push_back(r[o + 1]), p.min_gap = std::min(p.min_gap, r[o + 6]);
    if (!std::isfinite(r[o + 7])) continue;  // not measured in this sample
    if (!std::isfinite(v0)) {
      v0 = r[o + 7];
    } else {
      const double change = std::abs(r[o + 7] - v0) / v0;
      p.volume_change = std::isfinite(p.volume_change) ? std::max(p.volume_change, change) : change;
    }
  }
  p.tilt = unwrap(angle, pi);
  const std::vector<double>& r0 = samples.front();
  std::vector<double> jangle;
  for (const Vec3& a : models::jeffery_axis(Vec3{r0[o + 3], r0[o + 4], r0[o + 5]}, 0.5 / 1.55, gdot, 2, 1, t)) jangle.push_back(std::atan(a[2] / a[1]));
  const std::vector<double> jt = unwrap(jangle, pi), th(t.begin() + long(half), t.end());
  // The tilt grows in the sense of the shear: u = gdot y e_z turns the axis from y toward z.
  p.tilt_rate = study::slope(th, std::vector<double>(p.tilt.begin() + long(half), p.tilt.end())) / gdot;
  p.jeffery_rate = study::slope(th, std::vector<double>(jt.begin() + long(half), jt.end())) / gdot;
  // Edge-on: e = |tilt - the nearest k pi| - pi/4 > 0 (the short axis within 45 deg of the flow, the
  // edge pointing at the wall). A flip: the tilt passes 90 deg + k 180 deg, the middle of an edge-on interval.
  std::vector<double> e(ns), flip_times, edge_on;
  for (std::size_t i = 0; i < ns; ++i) e[i] = std::abs(std::remainder(p.tilt[i], pi)) - pi / 4;
  double entered = NAN;
  for (std::size_t i = 1; i < ns; ++i) {
    if (e[i] > 0) p.edge_on_seconds += t[i] - t[i - 1];
    const double k0 = std::floor(p.tilt[i - 1] / pi - 0.5), k1 = std::floor(p.tilt[i] / pi - 0.5);
    if (k0 != k1) {
      ++p.flips;
      const double at = (std::max(k0, k1) + 0.5) * pi;  // the 90 deg + k 180 deg passed
      flip_times.push_back(t[i - 1] + (t[i] - t[i - 1]) * (at - p.tilt[i - 1]) / (p.tilt[i] - p.tilt[i - 1]));
    }
    if (e[i - 1] <= 0 && e[i] > 0) entered = zero_crossing(t, e, i);
    if (e[i - 1] > 0 && e[i] <= 0 && std::isfinite(entered)) edge_on.push_back(zero_crossing(t, e, i) - entered), entered = NAN;
  }
  // One tumble end over end is a flip (pi); the seed's 30/s counts full orbits (2 pi): conventions.
  p.tumble_frequency = 1 / (2 * mean_interval(flip_times));
  if (!edge_on.empty()) {
    p.edge_on_per_tumble = 0;
    for (double d : edge_on) p.edge_on_per_tumble += d / double(edge_on.size());
  }
  p.wobble_frequency = oscillation_frequency(t, p.tilt, t.front() + 5 * units::ms);  // after the start-up response (a strain of 5)
  for (std::size_t i = 0; i < ns; i += std::max<std::size_t>(1, ns / 200))
    series["rows"].push(row({gaps_um[c], t[i] / units::ms, gdot * t[i], p.tilt[i] * 180 / pi, jt[i] * 180 / pi, p.gap[i] / units::um, p.height[i] / units::um}));
  return p;
}

void report(const Platelet& p, int c, double span, Json& summary, Json& values, const study::Options& opt) {
  const double ms = units::ms;
  summary["rows"].push(row({gaps_um[c], p.min_gap / units::um, p.tilt.back() * 180 / pi, p.tilt_rate, p.jeffery_rate, p.tilt_rate / p.jeffery_rate,
                            double(p.flips), span > 0 ? p.flips / span : NAN, p.edge_on_seconds / ms, p.tumble_frequency, p.edge_on_per_tumble / ms,
                            p.wobble_frequency, p.volume_change}));
  const std::string k = c == 0 ? "near" : "far";
  values["min_gap_um_" + k] = p.min_gap / units::um;
  values["rate_over_jeffery_" + k] = p.tilt_rate / p.jeffery_rate;
  values["volume_change_" + k] = p.volume_change;
  values["flips_" + k] = double(p.flips);
  values["edge_on_ms_" + k] = p.edge_on_seconds / ms;
  values["tumble_frequency_1_s_" + k] = p.tumble_frequency;
  values["edge_on_ms_per_tumble_" + k] = p.edge_on_per_tumble / ms;
  values["wobble_frequency_1_s_" + k] = p.wobble_frequency;
  study::log(opt, "platelet " + to_text(gaps_um[c]) + " um above the wall: min gap " + to_text(p.min_gap / units::um) + " um, tilt " +
                   to_text(p.tilt.back() * 180 / pi) + " deg, rate " + to_text(p.tilt_rate) + " gdot (Jeffery " + to_text(p.jeffery_rate) +
                   "), flips " + to_text(p.flips) + ", edge-on " + to_text(p.edge_on_seconds / ms) + " ms (" + to_text(p.edge_on_per_tumble / ms) +
                   " ms per tumble), tumbles " + to_text(p.tumble_frequency) + " /s, wobble " + to_text(p.wobble_frequency) + " /s, volume change " +
                   to_text(p.volume_change));
}

}  // namespace rbfib::platelets
