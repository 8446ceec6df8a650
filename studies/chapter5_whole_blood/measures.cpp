#include "measures.hpp"

#include "rbfib/cells/measure.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/series.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/sim/flow_profile.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace rbfib::whole_blood {

using namespace rbfib::scene;
using study::row;
const Vec3 flow_dir{std::sin(pi / 4), 0, std::cos(pi / 4)}, vorticity_dir{std::cos(pi / 4), 0, -std::sin(pi / 4)};

namespace {
const double um = units::um, ms = units::ms, Ly = 12 * um;
}  // namespace

std::vector<double> host(const dvec& v) {
  const host_vector<double> h = v;
  return std::vector<double>(h.begin(), h.end());
}

/// The angle of a vector in the shear plane of the final flow: counterclockwise from flow_dir toward e2 (rad).
double shear_plane_angle(const Vec3& v) { return std::atan2(v[1], v[0] * flow_dir[0] + v[2] * flow_dir[2]); }

/// Cell c's site i less its centre (cm), from a batch's layout X (n x 3N).
Vec3 from_center(const std::vector<double>& X, index_t n, index_t N, index_t c, index_t i, const Vec3& center) {
  Vec3 d;
  for (int k = 0; k < 3; ++k) d[std::size_t(k)] = X[std::size_t((k * N + c) * n + i)] - center[std::size_t(k)];
  return d;
}

/// Per red cell, the data site tracked for its tank-treading: its rim in the shear plane.
std::vector<index_t> tracked_sites(const std::vector<double>& X, index_t n, index_t N) {
  std::vector<index_t> site(std::size_t(N), 0);
  for (index_t c = 0; c < N; ++c) {
    const cells::CellShape shape = cells::cell_shape(X, n, N, c);
    double best = -1;
    for (index_t i = 0; i < n; ++i) {
      const Vec3 d = from_center(X, n, N, c, i, shape.center);
      const double a = d[0] * flow_dir[0] + d[2] * flow_dir[2], q = a * a + d[1] * d[1];
      if (q > best) best = q, site[std::size_t(c)] = i;
    }
  }
  return site;
}

// The sample row's columns: per platelet (after t and its centre, short axis and extents), then the red cells'.
namespace col {
enum { distance = 9, clearance, min_speed, volume, headroom, per_platelet };
}
const std::size_t red_at = 1 + 2 * col::per_platelet, material_at = red_at + 4, axis_at = material_at + red_count, profile_at = axis_at + red_count;

std::vector<double> sample(const sim::ImmersedBoundary& ib, bool red, const Domain& box, const std::vector<index_t>& tracked) {
  std::vector<double> row{ib.time()}, R(4 + 2 * red_count, NAN);
  const cells::Batch& P = ib.batch(red ? 1 : 0);
  const index_t n = P.type().n_data(), N = P.size();
  const std::vector<double> S = P.state().to_host(), E = host(ib.points(0).X);  // S: n x 6N, X then U
  const std::vector<double> X(S.begin(), S.begin() + long(3 * N * n)), XR = red ? ib.batch(0).positions_host() : std::vector<double>{};
  const index_t nr = red ? ib.batch(0).type().n_data() : 0, Nr = red ? ib.batch(0).size() : 0;
  if (red) R[1] = INFINITY;
  for (index_t c = 0; c < 2; ++c) {
    const cells::CellShape shape = cells::cell_shape(X, n, N, c);
    const std::vector<double> Y = cells::cell_points(X, n, N, c);
    if (red) R[1] = std::min(R[1], distance_to_red_cells(Y, n, XR, nr, box));
    double lowest = INFINITY, slowest = INFINITY, top = INFINITY;  // clearance, min speed, headroom
    for (index_t i = 0; i < n; ++i) {
      lowest = std::min(lowest, Y[std::size_t(n + i)] - box.endothelium.height(Y[std::size_t(i)], Y[std::size_t(2 * n + i)]));
      double v2 = 0;
      for (int d = 0; d < 3; ++d) v2 += std::pow(S[std::size_t((3 * N + d * N + c) * n + i)], 2);
      slowest = std::min(slowest, std::sqrt(v2));
    }
    // Headroom: the lowest red-cell site over the platelet (within its radius across the flow
    // plane) above its centre; negative when a red cell has come between it and the wall.
    const std::size_t m = XR.size() / 3;
    const double radius = 1.55 * um;
    for (std::size_t i = 0; i < m; ++i) {
      const double dx = std::remainder(XR[i] - shape.center[0], box.Lx), dz = std::remainder(XR[2 * m + i] - shape.center[2], box.Lz);
      if (dx * dx + dz * dz < radius * radius) top = std::min(top, XR[m + i] - shape.center[1]);
    }
    const auto& vol = ib.diagnostics(red ? 1 : 0).volume;
    for (const Vec3& v : {shape.center, shape.axes[0], shape.extent}) row.insert(row.end(), v.begin(), v.end());
    row.insert(row.end(), {sheet_distance(Y, n, E, box), lowest, slowest, vol.empty() ? NAN : vol[std::size_t(c)] / std::pow(um, 3), top});
  }
  if (red) {
    for (index_t c = 0; c < Nr && c < red_count; ++c) {
      const cells::CellShape shape = cells::cell_shape(XR, nr, Nr, c);
      R[std::size_t(4 + c)] = shear_plane_angle(from_center(XR, nr, Nr, c, tracked.at(std::size_t(c)), shape.center));
      R[std::size_t(4 + red_count + c)] = shear_plane_angle(shape.axes[0]);
    }
    R[0] = closest_cells(XR, nr, Nr, box);
    const auto& vol = ib.diagnostics(0).volume;
    if (!vol.empty()) R[2] = *std::min_element(vol.begin(), vol.end()) / std::pow(um, 3), R[3] = *std::max_element(vol.begin(), vol.end()) / std::pow(um, 3);
  }
  const std::vector<double> u = sim::velocity_profile(ib, flow_dir);
  row.insert(row.end(), R.begin(), R.end());
  row.insert(row.end(), u.begin(), u.end());
  return row;
}

Json Measures::analyse(const std::string& tag, bool flat, bool with_red, const std::vector<std::vector<double>>& rows, Json::Array out,
                       const study::Options& opt) {
  // The profile averaged over the second half of the run (Fig. 5.4).
  const std::size_t first = rows.size() / 2, ny = rows.front().size() - profile_at;
  std::vector<double> y(ny), u(ny, 0.0), u0(rows.front().begin() + long(profile_at), rows.front().end()), times;
  for (std::size_t j = 0; j < ny; ++j) y[j] = (double(j) + 0.5) * Ly / double(ny);
  for (std::size_t i = first; i < rows.size(); ++i)
    for (std::size_t j = 0; j < ny; ++j) u[j] += rows[i][profile_at + j] / double(rows.size() - first);
  for (std::size_t j = 0; j < ny; ++j) profiles["rows"].push(row({tag, y[j] / um, u[j] * 10}));
  const double gdot = shear[tag] = fit_line(y, u, 1 * um, 4 * um).slope;
  const LineFit fit = fit_line(y, u, 3 * um, 11.5 * um), fit0 = fit_line(y, u0, 3 * um, 11.5 * um);  // Couette above the platelet layer
  if (!with_red) worst_couette = std::max(worst_couette, fit.max_departure / wall_speed), no_slip_sum += fit.x_intercept(), ++free_runs;
  // Platelets (Figs. 5.5, 5.6).
  double unicycling = 0, room = INFINITY, vol_change = 0, red_min = INFINITY, plt_red = INFINITY, longest_uni = 0, max_dist = 0, max_asp = 0;
  for (const auto& r : rows) times.push_back(r[0]);
  for (std::size_t o : {std::size_t(1), std::size_t(1 + col::per_platelet)}) {
    auto aspect = [&](const std::vector<double>& r) { return r[o + 6] / std::max(r[o + 7], r[o + 8]); };
    std::vector<bool> uni_flags;
    for (const auto& r : rows) {
      const bool uni = cells::angle_between_axes(Vec3{r[o + 3], r[o + 4], r[o + 5]}, vorticity_dir) < pi / 4;
      const double change = aspect(r) / aspect(rows.front()) - 1, distance = r[o + col::distance] / um;
      platelets["rows"].push(row({tag + " platelet " + to_text(o == 1 ? 1 : 2), r[0] / ms, distance, 2 * h / um, uni ? 1.0 : 0.0, r[o + col::min_speed] * 10, change}));
      uni_flags.push_back(uni);
      unicycling += (uni ? 1.0 : 0.0) / double(2 * rows.size());
      min_platelet_endothelium = std::min(min_platelet_endothelium, distance), max_dist = std::max(max_dist, distance);
      min_clearance = std::min(min_clearance, r[o + col::clearance] / um);
      room = std::min(room, r[o + col::headroom]);
      max_asp = std::max(max_asp, std::abs(change));
      if (r[o + col::volume] > 0) vol_change = std::max(vol_change, std::abs(r[o + col::volume] / v_plt_ref - 1));
    }
    longest_uni = std::max(longest_uni, longest_interval(times, uni_flags));
  }
  max_aspect = std::max(max_aspect, max_asp);
  double period_median = NAN;
  if (with_red) {
    for (const auto& r : rows) {
      red_min = std::min(red_min, r[red_at] / h), plt_red = std::min(plt_red, r[red_at + 1] / h);
      if (r[red_at + 2] > 0) vol_change = std::max({vol_change, std::abs(r[red_at + 2] / v_ref - 1), std::abs(r[red_at + 3] / v_ref - 1)});
    }
    closest_red = std::min(closest_red, red_min), closest_platelet_red = std::min(closest_platelet_red, plt_red);
    min_headroom = std::min(min_headroom, room), max_distance_red = std::max(max_distance_red, max_dist);
    if (flat) longest_unicycling_flat = std::max(longest_unicycling_flat, longest_uni);
    // Tank-treading: the tracked site's mean turning about the centre, less the short axis's, in
    // turns per second; the shear turns shear_plane_angle negatively (d(angle)/dt = -gdot sin^2),
    // so a membrane that lags its body, or none that turns, tank-treads at 0 per second.
    std::vector<double> run_frequencies;
    for (std::size_t c = 0; c < red_count; ++c) {
      std::vector<double> m, a;
      for (const auto& r : rows) m.push_back(r[material_at + c]), a.push_back(r[axis_at + c]);
      m = unwrap(m, 2 * pi), a = unwrap(a, pi);
      const double dm = m.back() - m.front(), da = a.back() - a.front(), span = times.back() - times.front();
      const double frequency = std::max(0.0, da - dm) / (2 * pi * span);
      run_frequencies.push_back(frequency), frequencies.push_back(frequency);
      treading["rows"].push(row({tag, double(c + 1), dm * 180 / pi, da * 180 / pi, (dm - da) * 180 / pi, 1 / frequency / ms}));
    }
    period_median = 1 / study::median(run_frequencies);
  }
  worst_volume = std::max(worst_volume, vol_change);
  study::log(opt, tag + ": shear in the platelet layer " + to_text(gdot) + " 1/s (start of the run: " + to_text(fit_line(y, u0, 1 * um, 4 * um).slope) +
                   "), deviation from Couette " + to_text(fit0.max_departure / wall_speed) + " -> " + to_text(fit.max_departure / wall_speed) +
                   ", no-slip height " + to_text(fit.x_intercept() / um) + " um, closest red cells " + to_text(red_min) + " h, platelet-red " +
                   to_text(plt_red) + " h, volume change " + to_text(vol_change));
  for (double x : {gdot, fit0.max_departure / wall_speed, fit.max_departure / wall_speed, fit.x_intercept() / um, red_min, plt_red, room / um, unicycling,
                   longest_uni / ms, max_dist, max_asp, period_median / ms, vol_change})
    out.push_back(x);
  return Json(out);
}

void Measures::side_view(const std::vector<double>& E, const std::vector<std::vector<double>>& positions, index_t n_red, index_t n_platelet,
                         double Lz) {
  const std::size_t m = E.size() / 3;
  for (std::size_t i = 0; i < m; i += 8) snapshot["rows"].push(row({"endothelium", E[2 * m + i] / um, E[m + i] / um}));
  for (std::size_t b = 0; b < positions.size(); ++b) {
    const std::vector<double>& X = positions[b];
    const index_t n = b == 0 ? n_red : n_platelet, N = index_t(X.size() / std::size_t(3 * n));
    for (index_t c = 0; c < N; ++c)
      for (index_t i = 0; i < n; i += (n > 1000 ? 4 : 1))
        snapshot["rows"].push(row({(b == 0 ? "red cell " : "platelet ") + to_text(c + 1), std::fmod(X[std::size_t((2 * N + c) * n + i)] + 16 * Lz, Lz) / um,
                                   X[std::size_t((N + c) * n + i)] / um}));
  }
}

void Measures::values(Json& V, const Finished& done, bool has_flat) const {
  const bool all_runs_done = done.red_runs && done.free_runs;
  auto put = [&](const std::string& name, double value, bool runs_finished) { V[name] = runs_finished ? value : NAN; };
  put("closest_red_cells_over_h", closest_red, done.inits && done.red_runs);
  put("closest_platelet_red_over_h", closest_platelet_red, done.red_runs);
  put("min_platelet_endothelium_um", min_platelet_endothelium, all_runs_done);
  put("min_platelet_clearance_um", min_clearance, all_runs_done);
  put("platelet_headroom_um", min_headroom / um, done.red_runs);
  put("no_slip_height_without_red_cells_um", no_slip_sum / std::max(free_runs, 1) / um, done.free_runs && free_runs > 0);
  put("couette_deviation_without_red_cells", worst_couette, done.free_runs && free_runs > 0);
  put("volume_change", worst_volume, all_runs_done);
  put("max_platelet_distance_um", max_distance_red, done.red_runs);
  put("max_aspect_change", max_aspect, all_runs_done);
  put("rbc_tank_treading_frequency_1_s", study::median(frequencies), done.red_runs);
  put("rbc_tank_treading_period_ms", 1 / study::median(frequencies) / ms, done.red_runs);  // infinite (null) for none
  put("longest_unicycling_ms_flat", longest_unicycling_flat / ms, has_flat && done.flat_runs);
  auto mean_shear = [&](const std::string& kind) {  // over the starting times of one kind of run
    double sum = 0;
    int n = 0;
    for (const auto& [tag, g] : shear)
      if (tag.rfind(kind, 0) == 0 && std::isdigit(static_cast<unsigned char>(tag[kind.size()]))) sum += g, ++n;
    return n > 0 ? sum / n : NAN;
  };
  const double with = mean_shear("bumpy_"), without = mean_shear("bumpy_no_red_cells_");
  put("shear_platelet_layer_bumpy", with, done.red_runs);
  put("shear_platelet_layer_bumpy_no_red_cells", without, done.free_runs);
  put("shear_ratio_with_over_without_red_cells", with / without, done.red_runs && done.free_runs);
  if (has_flat) put("shear_platelet_layer_flat", mean_shear("flat_"), done.flat_runs);
}

}  // namespace rbfib::whole_blood
