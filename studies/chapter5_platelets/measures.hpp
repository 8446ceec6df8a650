#pragma once
// chapter5_platelets' measures (Sec. 5.2): a platelet's tilt against Jeffery's rigid spheroid, its
// flips, edge-on intervals, tumble and wobble frequencies, gap and volume, from the run's samples.
#include "common/study.hpp"

#include <cmath>
#include <vector>

namespace rbfib::platelets {

using study::Json;
inline constexpr double gaps_um[2] = {0.3, 0.5};  // the seed's two platelets

struct Platelet {
  std::vector<double> tilt, gap, height;  // rad (unwrapped), cm, cm
  double volume_change = NAN;              // NaN until two samples have measured the volume
  double tilt_rate = 0, jeffery_rate = 0;  // over the second half, / gdot
  double edge_on_seconds = 0;              // time with the short axis within 45 deg of the flow
  int flips = 0;                           // passes of the tilt through 90 deg + k 180 deg
  double min_gap = INFINITY;
  // The seed's three numbers (Sec. 5.2); NaN when the window holds no such event.
  double tumble_frequency = NAN;    // full orbits (2 pi) per s: 1 / (2 x the mean interval between flips)
  double edge_on_per_tumble = NAN;  // s, the mean contiguous edge-on interval (begun and ended in the window)
  double wobble_frequency = NAN;    // 1/s: 1 / (2 x the mean interval between crossings of the tilt's mean)
};

/// Platelet c's motion from the samples at times t, beside Jeffery's rigid spheroid from the same
/// axis (flow z, gradient y, shear gdot); its time series (every 200th of the run) into `series`.
Platelet analyse(const std::vector<std::vector<double>>& samples, const std::vector<double>& t, int c, double gdot, Json& series);

/// Platelet c's row of the summary and its values ("near" the wall, or "far").
void report(const Platelet& p, int c, double span, Json& summary, Json& values, const study::Options& opt);

}  // namespace rbfib::platelets
