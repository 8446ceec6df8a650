#pragma once
// chapter3_capillary's measures (the JCP 2018 paper, Sec. 5.1): what the checks read from the
// finished cell runs, and the pictures of Figs. 6-9 (side views of the cell at several times,
// |force density| seen from the front, side and back, H seen from the front, and cross-sections
// y = 0), each as a table of projected sites (common/point_pictures.hpp).
#include "common/capillary.hpp"
#include "common/study.hpp"

#include <map>
#include <memory>
#include <string>

namespace rbfib::capillary {

/// What the checks need from a finished cell run (CGS).
struct Summary {
  double v_cell, cv, std, rms, bumps, roughness, back, noise;
};

/// The values the checks read: ratios of the runs' measures (one-sided checks in the reference).
void write_values(study::Json& V, const std::map<std::string, Summary>& runs, int eta, double u_max_empty);

/// Figs. 6-9 into T["fig6"] ... T["fig9"] from the main runs (by label) on n_sites evaluation sites;
/// at most 900 sites per panel at full scale, 700 at quick.
void figures(const std::map<std::string, std::unique_ptr<Run>>& runs, index_t n_sites, bool full, study::Json& T);

}  // namespace rbfib::capillary
