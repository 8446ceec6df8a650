#pragma once
// chapter3_forces' setup (the JCP 2018 paper, Sec. 4.1): the shapes, energies, evaluation sets
// with their weights and quadrature error, and the exact forces every figure compares against.
#include "common/study.hpp"
#include "rbfib/mechanics/shell.hpp"
#include "rbfib/surface/evaluation_sets.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/shapes.hpp"

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace rbfib::forces {

using namespace rbfib::surface;
using namespace rbfib::mechanics;
using study::Json;

struct Energy {
  std::string name, tag;
  EnergyDensity W;
};

/// The problem of Sec. 4.1 and what the experiments share: shapes, energies, evaluation sets
/// ("MD", "MD_rbf_weights", "spiral" by n) and the SHVD interpolation sites by degree M. The MD
/// sets stop at n = 4624 (N = 90, n = 8281, takes hours to generate).
struct Setup {
  explicit Setup(bool full)
      : point_sets{{"MD", md_n}, {"MD_rbf_weights", md_n}, {"spiral", full ? spiral_n : md_n}},
        nd_list(full ? std::vector<index_t>{100, 200, 400, 800, 1600} : std::vector<index_t>{100, 200, 400, 800}) {}
  const std::vector<index_t> md_n = {529, 2025, 4624}, spiral_n = {529, 2025, 4624, 8281};
  PerturbedEllipsoid ell = ellipsoid(1.1, 1 / std::sqrt(1.1), 1 / std::sqrt(1.1)), pert = paper_perturbed_ellipsoid();
  std::vector<Energy> energies = {{"tension", "tension", EnergyDensity::surface_tension(1.0)},
                                  {"neo-Hookean", "neo_hookean", EnergyDensity::neo_hookean_paper(1.0, 1.0)}};
  std::vector<std::pair<std::string, std::vector<index_t>>> point_sets;
  std::vector<index_t> nd_list;
  std::vector<int> M_list = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14};  // m = 4 .. 225
  index_t n_shvd = 4624;  ///< the MD set on which SHVD and RBF are evaluated
  int repeats = 11;
  std::map<std::pair<std::string, index_t>, EvaluationSet> sets;
  std::map<int, SphereSites> md;
  std::vector<Jet> Z;  ///< unit-sphere jets at the SHVD/RBF evaluation sites
  const EvaluationSet& eval() const { return sets.at({"MD", n_shvd}); }
};

/// The parameters, echoed in the results.
void describe(const Setup& S, Json& P);

/// The exact force F^_E = F_E dA0 (eqs. 35, 52) of the map s at the sites of e.
std::vector<double> exact_forces(const PerturbedEllipsoid& s, const EvaluationSet& e, const EnergyDensity& W);

/// The evaluation sets (into S.sets), their weight ranges and the force integral (quadrature error) of each.
Json evaluation_sets(const study::Options& opt, Setup& S);

}  // namespace rbfib::forces
