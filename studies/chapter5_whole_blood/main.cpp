// Reproduces dissertation Sec. 5.2 (Figs. 5.4-5.6): whole blood over a flat and a bumpy
// endothelium, and over the bumpy one without red cells. The 16 x 12 x 16 um box, periodic in x
// and z, walls in y; the endothelium (eq. 5.5) as points on the toroidal spiral of Appendix B
// tethered with k = 2.5 dyn/cm and damped with eta = 2.5e-7 dyn s/cm (Sec. 2.2); red cells (Skalak +
// bending + dissipation) and platelets (neo-Hookean + bending about the reference curvature);
// B3 kernel, backward-forward Euler, plasma of 1 cP (the seed's code: at the 0.1 cP of Sec. 2.1
// its endothelium is unstable at 50 ns, reference/chapter4_cells.yaml).
// The procedure of Sec. 5.2.1 (scene/packing.hpp), for each endothelium:
//   init:  the endothelium and 8 red cells, the flow at rest, the top wall at 16 mm/s turning from
//          z toward x by 45 deg over 7.2 ms, run past the settling time (17 ms) to the last starting
//          time (a Poisson process of mean gap 3 ms); its state at each is kept (start_<wall>_<k>.h5);
//   runs:  from each starting state, two platelets placed against the red cells there; the same
//          with the red cells removed (bumpy wall only).
// Measured per run: the x-z averaged velocity against y (Fig. 5.4) and the shear rate in the
// platelet layer (y = 1-4 um); per platelet its distance to the endothelium, unicycling (short axis
// within 45 deg of the vorticity; Fig. 5.5), its smallest surface speed and aspect-ratio change
// (Fig. 5.6); per red cell a tracked site's turning about its centre in the shear plane less its
// short axis's (tank-treading, Sec. 5.2.2); closest approaches; volumes; the hematocrit.
//   full:  the seed's sizes (h = 0.2 um, red cells 2,500 / 10,000 sites, platelets 900 / 900,
//          16,000 endothelium points, dt = 50 ns), 4 starting times, runs of 40 ms (bumpy) and
//          60 ms (flat: the seed's unicycling 'lasted over 40 ms'), continued over sittings;
//   quick: h = 0.4 um, 400 / 1,600 and 400 / 400 sites, 4,096 points, dt = 100 ns (the tethers'
//          explicit limit is about 128 ns here); the wall turns over 20 us, settles to 30 us, one
//          starting time, 80 us per run; the bumpy wall only.
#include "common/study.hpp"
#include "procedure.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"

using namespace rbfib;
using namespace rbfib::whole_blood;
using st::Json;

namespace {
const double um = units::um, ms = units::ms, us = units::us;
}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_whole_blood", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_whole_blood",
                                                   "Sec. 5.2: whole blood over a flat and a bumpy endothelium (Figs. 5.4-5.6)");
    const bool full = opt.scale == st::Scale::full;
    // Full scale: the seed's ladder with the endothelium's constants following the step (gain 0.5;
    // docs/derivations/tether_stability, chapter5_tether_stability); quick: the seed's fixed ones.
    const Setup s = full ? Setup{0.2 * um, 50 * units::ns, 2500, 10000, 900, 16000, 7.2 * ms, 17 * ms, 3 * ms, 40 * ms, 60 * ms, 4, {flat, bumpy}, 400, 4, 0.5}
                         : Setup{0.4 * um, 100 * units::ns, 400, 1600, 400, 4096, 20 * us, 30 * us, 10 * us, 80 * us, 80 * us, 1, {bumpy}, 10};
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 12 x 16, periodic x and z, walls in y; the top wall at 16 mm/s turning from z toward x by 45 deg (Sec. 5.2.1)";
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; Sec. 2.1 says 0.1 cP)";
    P["h_um"] = s.h / um;
    P["dt_ns"] = s.dt / units::ns;
    P["red_cells"] = "8 at " + to_text(s.rbc_nd) + " / " + to_text(s.rbc_ns) + " sites (Skalak, bending, dissipation)";
    P["platelets"] = "2 at " + to_text(s.plt_n) + " / " + to_text(s.plt_n) + " sites (neo-Hookean, bending about the reference curvature)";
    P["endothelium"] = to_text(s.endothelium) + " points on the toroidal spiral (Appendix B), flat y = 1 um or bumpy y = 0.75 um + 1 um cos^2(theta - phi) sin^2(phi/2) (eq. 5.5); " +
                       (s.tether_gain > 0 ? "k and eta following the step by the seed's rule at gain " + to_text(s.tether_gain) + " (sim/tether_stability.hpp)"
                                          : std::string("k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm"));
    if (s.ladder > 0) P["step"] = "the seed's adaptive step: dt = 2^k x " + to_text(s.dt / units::ns) + " ns, k = 0.." + to_text(s.ladder) + ", by eq. 5.4";
    P["procedure"] = "wall turning over " + to_text(s.turn / us) + " us, settling " + to_text(s.settle / us) + " us, " + to_text(s.starts) +
                     " starting time(s) with exponential gaps of mean " + to_text(s.mean_gap / us) + " us, runs of " + to_text(s.window / us) +
                     " us" + (full ? " over the bumpy wall and " + to_text(s.flat_window / us) + " us over the flat one" : "");
    P["seed"] = double(seed);
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";
    WholeBlood study{opt, s, results};
    for (double y : {0.0, 12.0}) study.measures.profiles["rows"].push(row({"Couette between the walls", y, wall_speed * 10 * y / 12}));
    for (std::size_t wi = 0; wi < s.walls.size(); ++wi) study.wall(s.walls[wi], wi);
    study.summarize();
    st::write_results(opt, results);
    return 0;
  });
}
