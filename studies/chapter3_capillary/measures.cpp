#include "measures.hpp"

#include "common/point_pictures.hpp"
#include "rbfib/core/units.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace rbfib::capillary {

using study::number;

namespace {

/// The kept view at time t (the nearest when none is exactly there).
const View* view_at(const Run& r, double t) {
  const View* best = nullptr;
  for (const View& v : r.views())
    if (!best || std::abs(v.t - t) < std::abs(best->t - t)) best = &v;
  return best && std::abs(best->t - t) <= 1e-9 ? best : nullptr;
}

/// The mean of the view's sites (the centre of the pictures; the volume centroid is in the series).
std::array<double, 3> mean_point(const View& v) {
  const std::size_t n = v.X.size() / 3;
  std::array<double, 3> c{0, 0, 0};
  for (int d = 0; d < 3; ++d) {
    for (std::size_t i = 0; i < n; ++i) c[d] += v.X[d * n + i];
    c[d] /= double(n);
  }
  return c;
}

/// The capillary wall's trace in the plane y = 0: z = +-R for x in [x0, x1] (um), shifted by oy.
void wall_rows(std::vector<study::PictureRow>& t, const std::string& panel, const Model& m, double oy) {
  for (int s : {-1, 1})
    for (int i = 0; i <= 64; ++i)
      t.push_back({panel, "capillary wall", (m.x0_cap + (m.x1_cap - m.x0_cap) * i / 64) / um + 0, s * m.R_cap / um + oy});
}

std::string time_label(double t) {
  std::ostringstream l;
  l << "t = " << t << " s";
  return l.str();
}

study::Json picture(const char* a, const char* b, std::vector<study::PictureRow> rows) {
  study::Json t = study::table({"panel", "label", a, b}, {"", "", "um", "um"});
  study::push_sorted(t, std::move(rows));
  return t;
}

}  // namespace

void figures(const std::map<std::string, std::unique_ptr<Run>>& runs, index_t n_sites, bool full, study::Json& T) {
  const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1}, mx[3] = {-1, 0, 0}, my[3] = {0, -1, 0};
  const int cap = full ? 900 : 700;  // sites per panel (results.json stays about 1 MB)
  std::vector<study::PictureRow> rows;
  // Fig. 6: side views (from -y) at several times, absolute x; the capillary's wall.
  int p = 0;
  for (const std::string lab : {"LDSM_kb0", "SHVD_m625_kb0", "SHVD_m400_kb0"}) {
    const Run& r = *runs.at(lab);
    const double oy = -14.0 * p++;
    wall_rows(rows, lab, r.model(), oy);
    for (double t : {0.0, 0.01, 0.025, 0.05})
      if (const View* v = view_at(r, t))
        study::project(rows, lab, v->X, v->normal, my, ex, ez, nullptr, um, 0, oy, cap / 2,
                    [l = time_label(t)](std::size_t) { return l; });
  }
  T["fig6"] = picture("x_um", "z_um", std::move(rows));
  // Fig. 7: |force density| on the front (from +x), side (from -y), back (from -x) at the end.
  std::vector<double> all, edges;
  for (const std::string lab : {"LDSM_kb0", "SHVD_m400_kb0"})
    if (!runs.at(lab)->views().empty()) {
      const std::vector<double>& f = runs.at(lab)->views().back().f;
      all.insert(all.end(), f.begin(), f.end());
    }
  std::sort(all.begin(), all.end());
  const double top = all.empty() ? 1 : all[std::size_t(0.95 * double(all.size() - 1))] * 1e-3;
  const double step = std::max(1e-3, std::round(top / 5 * 1000) / 1000);
  for (int k = 0; k <= 5; ++k) edges.push_back(k * step);
  rows.clear();
  p = 0;
  for (const std::string lab : {"LDSM_kb0", "SHVD_m400_kb0"}) {
    if (runs.at(lab)->views().empty()) continue;
    const View& v = runs.at(lab)->views().back();
    const std::array<double, 3> c = mean_point(v);
    const double oy = -12.0 * p++;
    auto lf = [&](std::size_t i) { return study::bin_label(v.f[i] * 1e-3, edges, "|f|", "pN/um^2"); };
    study::project(rows, lab + " front", v.X, v.normal, ex, ey, ez, c.data(), um, 0, oy, cap, lf);
    study::project(rows, lab + " side", v.X, v.normal, my, ex, ez, c.data(), um, 11, oy, cap, lf);
    study::project(rows, lab + " back", v.X, v.normal, mx, my, ez, c.data(), um, 22, oy, cap, lf);
  }
  T["fig7"] = picture("x_um", "z_um", std::move(rows));
  // Fig. 8: H from the front for k_bend = 0, 0.1, 1.
  const std::vector<double> H_edges = {-0.6, -0.45, -0.3, -0.15, 0.0, 0.15};
  const std::vector<std::string> bending = {"SHVD_m400_kb0", "SHVD_m400_kb0.1", "SHVD_m400_kb1"};
  rows.clear();
  p = 0;
  for (const std::string& lab : bending) {
    if (runs.at(lab)->views().empty()) continue;
    const View& v = runs.at(lab)->views().back();
    const std::array<double, 3> c = mean_point(v);
    study::project(rows, lab, v.X, v.normal, ex, ey, ez, c.data(), um, 11.0 * p++, 0, cap,
                [&](std::size_t i) { return study::bin_label(v.H[i] * um, H_edges, "H", "1/um"); });
  }
  T["fig8"] = picture("y_um", "z_um", std::move(rows));
  // Fig. 9: cross-sections y = 0 at t = 0.005, 0.025, 0.05 s, one panel per k_bend (stacked).
  rows.clear();
  const double slab = 0.6 * std::sqrt(135.0 / double(n_sites)) * um;  // ~0.6 site spacings
  p = 0;
  for (const std::string& lab : bending) {
    const Run& r = *runs.at(lab);
    const double oy = -13.0 * p++;
    wall_rows(rows, lab, r.model(), oy);
    for (double t : {0.005, 0.025, 0.05})
      if (const View* v = view_at(r, t)) {
        const std::size_t n = v->X.size() / 3;
        for (std::size_t i = 0; i < n; ++i)
          if (std::abs(v->X[n + i]) < slab) rows.push_back({lab, time_label(t), v->X[i] / um, v->X[2 * n + i] / um + oy});
      }
  }
  T["fig9"] = picture("x_um", "z_um", std::move(rows));
}

void write_values(study::Json& V, const std::map<std::string, Summary>& runs, int eta, double u_max_empty) {
  auto get = [&runs](const std::string& label, double Summary::*field) {
    auto it = runs.find(label);
    return it == runs.end() ? NAN : it->second.*field;
  };
  auto ratio = [&get](const std::string& a, const std::string& b, double Summary::*f) {
    return number(get(a, f) / get(b, f));
  };
  auto excess = [&get](const std::string& a, const std::string& b) {
    return number(get(a, &Summary::bumps) - get(b, &Summary::bumps));
  };
  V["v_cell_um_s"] = number(get("SHVD_m400_kb0.1", &Summary::v_cell) / um);
  V["v_cell_over_u_max"] = number(get("SHVD_m400_kb0.1", &Summary::v_cell) / um / u_max_empty);
  V["front_H_std_ratio_kb0.1_over_kb0"] = ratio("SHVD_m400_kb0.1", "SHVD_m400_kb0", &Summary::std);
  V["front_H_std_ratio_kb1_over_kb0.1"] = ratio("SHVD_m400_kb1", "SHVD_m400_kb0.1", &Summary::std);
  V["front_H_cv_ratio_kb0.1_over_kb0"] = ratio("SHVD_m400_kb0.1", "SHVD_m400_kb0", &Summary::cv);
  V["front_H_cv_ratio_kb1_over_kb0.1"] = ratio("SHVD_m400_kb1", "SHVD_m400_kb0.1", &Summary::cv);
  V["bumps_m625_minus_m400"] = excess("SHVD_m625_kb0", "SHVD_m400_kb0");
  V["nonaxisymmetric_rms_ratio_m625_over_m400"] = ratio("SHVD_m625_kb0", "SHVD_m400_kb0", &Summary::rms);
  V["nonaxisymmetric_rms_ratio_LDSM_over_m400"] = ratio("LDSM_kb0", "SHVD_m400_kb0", &Summary::rms);
  for (const std::string m : {"m900", "m1024"}) {  // Sec. 5.1.2: "even more bumps" above m = 625
    const std::string lab = "SHVD_" + m + "_kb0_eta" + to_text(eta);
    V["nonaxisymmetric_rms_ratio_" + m + "_over_m625"] = ratio(lab, "SHVD_m625_kb0", &Summary::rms);
    V["bumps_" + m + "_minus_m625"] = excess(lab, "SHVD_m625_kb0");
  }
  const std::string md = "_kb0_MD4624_eta" + to_text(eta);
  V["nonaxisymmetric_rms_ratio_m625_over_m400_MD4624"] = ratio("SHVD_m625" + md, "SHVD_m400" + md, &Summary::rms);
  V["nonaxisymmetric_rms_ratio_LDSM_over_m400_MD4624"] = ratio("LDSM" + md, "SHVD_m400" + md, &Summary::rms);
  V["bumps_m625_minus_m400_MD4624"] = excess("SHVD_m625" + md, "SHVD_m400" + md);
  V["f_roughness_ratio_LDSM_over_m400"] = ratio("LDSM_kb0", "SHVD_m400_kb0", &Summary::roughness);
  V["f_noise_ratio_LDSM_over_m400"] = ratio("LDSM_kb0", "SHVD_m400_kb0", &Summary::noise);
  V["f_back_ratio_LDSM_over_m400"] = ratio("LDSM_kb0", "SHVD_m400_kb0", &Summary::back);
}

}  // namespace rbfib::capillary
