#pragma once
// Point pictures of a surface for the harness's figures (style ".", aspect: equal, group: label):
// rows (panel, label, a, b), the sites facing the viewer projected onto two screen axes, labelled
// by bins of a field so that the legend lists the bins in order.
#include "common/study.hpp"

#include <functional>
#include <string>
#include <vector>

namespace rbfib::study {

struct PictureRow {
  std::string panel, label;
  double a, b;
};

/// Appends the sites of X (n x 3 column-major) whose normal points toward the viewer
/// (normal . toward > 0), at most `cap` of them (picked by a fixed hash of the index: a stride
/// along a spiral would draw stripes), projected onto e1 and e2 in units of `unit`, after
/// subtracting `centre` (absolute positions when null), shifted by (ox, oy).
void project(std::vector<PictureRow>& rows, const std::string& panel, const std::vector<double>& X,
             const std::vector<double>& normal, const double toward[3], const double e1[3], const double e2[3],
             const double* centre, double unit, double ox, double oy, int cap,
             const std::function<std::string(std::size_t)>& label);

/// The label of x's bin among ascending edges, led by the bin's number ("2: |f| 0.1 to 0.2 pN/um^2").
std::string bin_label(double x, const std::vector<double>& edges, const std::string& name, const std::string& unit);

/// Appends the rows to a figure table (columns panel, label, a, b), stably ordered by label.
void push_sorted(Json& table, std::vector<PictureRow> rows);

}  // namespace rbfib::study
