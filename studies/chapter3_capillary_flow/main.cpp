// Chapter 3 capillary flow without the cell (the JCP 2018 paper, Sec. 5.1.1): the peak flow speed
// of the empty tethered capillary (eqs. 93-95) driven by the background force, in steady Stokes
// flow on a periodic 24 um box, against the paper's 750 um/s and Poiseuille's f R^2 / (4 mu), in
// the capillary's frame (u_c of eq. 95 added, the wall at rest) and in the solver's (the periodic
// solution with zero mean velocity), for two readings of "inside the capillary" (the cylinder
// through the box, or the tethered segment only) and on three grids: table capillary_flow, and the
// profile u_x(z) through (0, 0) against Poiseuille's (figure profile). The model: common/capillary.hpp.
//
// Scales. Quick (CI): eta = 32, 48, 64 (and the segment reading on 48). Full: eta = 64, 96, 128
// (the segment reading on 64). 100 steps of dt = 1e-4 s each: the flow is steady within a few.
//
// Run:  build/studies/study_chapter3_capillary_flow --scale quick --out runs/chapter3_capillary_flow/quick
//       (or python3 -m harness run chapter3_capillary_flow --scale quick)
#include "common/capillary.hpp"

using namespace rbfib;
using namespace rbfib::capillary;
namespace st = rbfib::study;
using st::number;
using st::row;

int main(int argc, char** argv) {
  return st::run_main("chapter3_capillary_flow", [&] {
    // ---- 1. Parameters ---------------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(argc, argv, "chapter3_capillary_flow",
                                                   "Chapter 3 Sec. 5.1.1: the empty capillary's peak flow speed");
    Runner runner(opt);
    Model base;
    base.eta = study_eta(opt);
    const std::vector<int> etas = opt.scale == st::Scale::full ? std::vector<int>{64, 96, 128} : std::vector<int>{32, 48, 64};
    st::Json results = st::make_results(opt);
    write_parameters(results["parameters"], base);
    st::Json& V = results["values"];
    const double poiseuille = base.f_in * base.R_cap * base.R_cap / (4 * base.mu);  // cm/s
    V["poiseuille_um_s"] = poiseuille / um;

    // ---- 2. The empty capillary on the grids (the study's grid under the id the checks name) -----
    st::Json flow = st::table({"region", "eta", "h_um", "capillary_nodes", "u_max_um_s", "u_max_zero_mean_um_s",
                               "u_axis_x0_um_s", "u_max_change_last_half", "poiseuille_um_s", "paper_um_s",
                               "rel_diff_paper", "rel_diff_paper_zero_mean", "cap_disp_um", "seconds"},
                              {"", "", "um", "", "um/s", "um/s", "um/s", "", "um/s", "um/s", "", "", "um", "s"});
    st::Json profile = st::table({"series", "z_um", "u_um_s"}, {"", "um", "um/s"});
    std::vector<std::pair<Region, int>> cases;
    for (int e : etas) cases.emplace_back(Region::core, e);
    cases.emplace_back(Region::segment, base.eta);
    for (const auto& [region, eta] : cases) {
      Model m = base;
      m.eta = eta;
      const bool study_grid = region == Region::core && eta == base.eta;
      const EmptyFlow e = empty_capillary(runner, results, m, region, study_grid ? "empty_core" : "");
      // ---- 3. Measures -----------------------------------------------------------------------------
      flow["rows"].push(row({to_string(region), eta, e.h / um, e.nodes, number(e.u_max / um), number(e.u_zero_mean / um),
                             number(e.u_axis / um), number(std::abs(e.u_max - e.u_half) / e.u_max), poiseuille / um,
                             750, number((e.u_max / um - 750) / 750), number((e.u_zero_mean / um - 750) / 750),
                             number(e.cap_disp / um), e.seconds}));
      for (const auto& zu : e.profile)
        profile["rows"].push(row({std::string(to_string(region)) + " eta = " + to_text(eta), zu[0] / um, zu[1] / um}));
      if (!study_grid) continue;
      V["u_max_empty_um_s"] = number(e.u_max / um);
      V["u_max_empty_zero_mean_um_s"] = number(e.u_zero_mean / um);
      V["u_axis_empty_um_s"] = number(e.u_axis / um);
      V["u_max_over_poiseuille"] = number(e.u_max / poiseuille);
      V["u_max_rel_diff_paper"] = number((e.u_max / um - 750) / 750);
      V["u_max_zero_mean_rel_diff_paper"] = number((e.u_zero_mean / um - 750) / 750);
      V["empty_seconds"] = e.seconds;
    }
    for (double z = -5; z <= 5.0001; z += 0.125)
      profile["rows"].push(row({"Poiseuille f R^2/(4 mu) (1 - r^2/R^2)", z, poiseuille / um * (1 - z * z / 25)}));

    // ---- 4. Results ------------------------------------------------------------------------------
    results["tables"]["capillary_flow"] = flow;
    results["tables"]["profile"] = profile;
    V["wall_seconds"] = runner.elapsed();
    st::write_results(opt, results);
    return 0;
  });
}
