#include "common/point_pictures.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>

namespace rbfib::study {

void project(std::vector<PictureRow>& rows, const std::string& panel, const std::vector<double>& X,
             const std::vector<double>& normal, const double toward[3], const double e1[3], const double e2[3],
             const double* centre, double unit, double ox, double oy, int cap,
             const std::function<std::string(std::size_t)>& label) {
  const std::size_t n = X.size() / 3;
  std::vector<std::size_t> vis;
  for (std::size_t i = 0; i < n; ++i)
    if (normal[i] * toward[0] + normal[n + i] * toward[1] + normal[2 * n + i] * toward[2] > 0) vis.push_back(i);
  if (vis.size() > std::size_t(cap)) {
    auto hash = [](std::size_t i) { return (std::uint64_t(i) * 2654435761u) % 4294967296u; };
    std::sort(vis.begin(), vis.end(), [&](std::size_t a, std::size_t b) { return hash(a) < hash(b); });
    vis.resize(std::size_t(cap));
  }
  for (std::size_t i : vis) {
    double p[3] = {X[i], X[n + i], X[2 * n + i]};
    if (centre)
      for (int d = 0; d < 3; ++d) p[d] -= centre[d];
    const double a = (p[0] * e1[0] + p[1] * e1[1] + p[2] * e1[2]) / unit + ox;
    const double b = (p[0] * e2[0] + p[1] * e2[1] + p[2] * e2[2]) / unit + oy;
    rows.push_back(PictureRow{panel, label(i), a, b});
  }
}

std::string bin_label(double x, const std::vector<double>& edges, const std::string& name, const std::string& unit) {
  if (!std::isfinite(x)) return name + " n/a";
  std::ostringstream s;
  s.precision(3);
  std::size_t k = 0;
  while (k < edges.size() && !(x < edges[k])) ++k;
  if (k == 0) s << "0: " << name << " < " << edges.front();
  else if (k == edges.size()) s << k << ": " << name << " >= " << edges.back();
  else s << k << ": " << name << " " << edges[k - 1] << " to " << edges[k];
  s << " " << unit;
  return s.str();
}

void push_sorted(Json& table, std::vector<PictureRow> rows) {
  std::stable_sort(rows.begin(), rows.end(), [](const PictureRow& p, const PictureRow& q) { return p.label < q.label; });
  for (const PictureRow& r : rows) table["rows"].push(row({r.panel, r.label, r.a, r.b}));
}

}  // namespace rbfib::study
