// Chapter 3, Table 1 (the JCP 2018 paper, Sec. 4.2): the SHVD / LDSM wall-time ratio of the
// ellipsoidal contraction of the dynamic test (common/chapter3_relaxation.hpp: eq. 88, dt =
// 1/(2 eta), n = 2 eta^2 + 1) for m = 64 and 225, with each method's time split into forces,
// spreading, Stokes solve, interpolation and update. The three runs of a grid (LDSM, SHVD m = 64,
// SHVD m = 225) advance in lockstep, one step of each in turn, so that a change of load on the
// shared machine falls on all three alike; their timing noise is the spread of the ratio over 10
// blocks of steps. Also: the jets' products of one SHVD force call as one GEMM (ours) against
// three matrix-vector products (the paper's description, Sec. 3.1).
//
// Scales. Quick: eta = 32, 48 for a 1 s contraction (the ratio is one of per-step costs). Full:
// the paper's eta = 32, 48, 64, 72 for the 15 s contraction, each run kept in the run directory
// (run_<label>.h5) so that the full scale continues over sittings (--sitting).
//
// Run:  build/studies/study_chapter3_table1 --scale quick --out runs/chapter3_table1/quick
#include "common/chapter3_relaxation.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/surface/operators.hpp"

using namespace rbfib;
using namespace rbfib::chapter3;
namespace st = rbfib::study;
using st::Json, st::number, st::row;

namespace {

/// Best time (of 11) of the jets' products of one SHVD force call for the degree-M interpolant
/// at the n sites: value and derivatives (6n x m) times the m x 3 coefficients as one product per
/// operator block, as the force call does (`gemm`), and as three matrix-vector products, one per
/// coordinate (`gemv`), the paper's "each derivative is a matrix-vector multiplication" (Sec. 3.1).
void product_times(const EvaluationSet& e, int M, double& t_gemm, double& t_gemv) {
  const auto ops = surface::sh_operators(interpolation_sites(M), e.sites, M);
  const index_t m = ops->value.cols(), n = ops->value.rows();
  std::vector<double> c(static_cast<std::size_t>(3 * m));
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = std::cos(double(i));  // any coefficients
  const linalg::DeviceMatrix B = linalg::DeviceMatrix::from_host(m, 3, c.data());
  linalg::DeviceMatrix V(n, 3), D(5 * n, 3);
  using linalg::Op;
  t_gemm = st::best_seconds(11, [&] {
    linalg::gemm(Op::none, Op::none, 1.0, ops->value.view(), B.view(), 0.0, V.view());
    linalg::gemm(Op::none, Op::none, 1.0, ops->derivatives.view(), B.view(), 0.0, D.view());
  });
  t_gemv = st::best_seconds(11, [&] {
    for (index_t k = 0; k < 3; ++k) {
      linalg::gemm(Op::none, Op::none, 1.0, ops->value.view(), B.view().block(0, k, m, 1), 0.0,
                   V.view().block(0, k, n, 1));
      linalg::gemm(Op::none, Op::none, 1.0, ops->derivatives.view(), B.view().block(0, k, m, 1), 0.0,
                   D.view().block(0, k, 5 * n, 1));
    }
  });
}

/// Table 1 on the grids etas for a contraction of t_end: ratio_* from the wall time of the steps
/// (the paper's measure), ratio_*_median from the per-step medians of each phase.
void table1(const std::vector<int>& etas, double t_end, Relaxations& runs, Json& T, Json& V) {
  Json t1 = st::table({"eta", "n", "t_contraction", "steps", "ldsm_seconds", "shvd_m64_seconds", "shvd_m225_seconds",
                       "ratio_m64", "ratio_m225", "ratio_m64_median", "ratio_m225_median", "blocks",
                       "ratio_m64_block_std", "ratio_m225_block_std"},
                      {"", "", "1", "", "s", "s", "s", "", "", "", "", "", "", ""});
  Json phases =
      st::table({"method", "eta", "n", "forces_seconds", "force_products_seconds", "spread_seconds", "solve_seconds",
                 "interpolate_seconds", "update_seconds", "step_seconds", "forces_share", "product_gflops"},
                {"", "", "", "s", "s", "s", "s", "s", "s", "s", "", "GFLOP/s"});
  Json products = st::table(
      {"eta", "n", "m", "gemm_seconds", "gemv_seconds", "gemv_over_gemm", "ratio_median", "ratio_median_with_gemv"},
      {"", "", "", "s", "s", "", "", ""});
  for (int eta : etas) {
    const index_t n = spiral_sites(eta);
    const std::vector<const RelaxationResult*> g = runs.lockstep(
        {dynamic_test(Method::ldsm, eta, t_end, 7, 0), dynamic_test(Method::shvd, eta, t_end, 7, 0),
         dynamic_test(Method::shvd, eta, t_end, 14, 0)},
        10);
    const RelaxationResult &L = *g[0], &S64 = *g[1], &S225 = *g[2];
    const double lt = L.phases.total(), lm = L.median.total();
    t1["rows"].push(row({eta, double(n), t_end, L.steps, lt, S64.phases.total(), S225.phases.total(),
                         number(S64.phases.total() / lt), number(S225.phases.total() / lt),
                         number(S64.median.total() / lm), number(S225.median.total() / lm), double(L.block_ends.size()),
                         number(run::block_ratio_std(S64.block_ends, L.block_ends)),
                         number(run::block_ratio_std(S225.block_ends, L.block_ends))}));
    for (const auto& [label, r] : std::initializer_list<std::pair<std::string, const RelaxationResult*>>{
             {"LDSM", &L}, {"SHVD m = 64", &S64}, {"SHVD m = 225", &S225}}) {
      const PhaseTimes& p = r->median;
      const double m = r == &S64 ? 64 : 225;  // the jets' products: (6n x m) times the m x 3 coefficients
      const Json rate = r == &L ? Json() : number(2 * 6 * double(n) * m * 3 / p.force_products / 1e9);
      phases["rows"].push(row({label, eta, double(n), p.forces, p.force_products, p.spread, p.solve, p.interpolate,
                               p.update, p.total(), p.forces / p.total(), rate}));
    }
    // what three matrix-vector products per force call instead of one product would cost
    for (const auto& [M, r] : {std::pair{7, &S64}, std::pair{14, &S225}}) {
      double t_gemm, t_gemv;
      product_times(runs.sites(n), M, t_gemm, t_gemv);
      const double with_gemv = (r->median.total() + r->median.force_products * (t_gemv / t_gemm - 1)) / lm;
      products["rows"].push(
          row({eta, double(n), (M + 1) * (M + 1), t_gemm, t_gemv, t_gemv / t_gemm, r->median.total() / lm, with_gemv}));
    }
    if (eta == etas.back()) {
      V["table1_ratio_m64_median_largest_eta"] = number(S64.median.total() / lm);
      V["table1_ratio_m225_minus_m64_median_largest_eta"] = number((S225.median.total() - S64.median.total()) / lm);
    }
  }
  T["table1"] = t1;
  T["table1_phases"] = phases;
  T["shvd_products"] = products;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_table1", [&] {
    // ---- 1. Parameters ---------------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter3_table1", "Chapter 3 Table 1: SHVD / LDSM wall time of an ellipsoidal contraction, by phase");
    const bool full = opt.scale == st::Scale::full;
    const std::vector<int> etas = full ? std::vector<int>{32, 48, 64, 72} : std::vector<int>{32, 48};
    const double t_end = full ? 15 : 1;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    describe_dynamic_test(P);
    P["table1"] = "eta = " + to_text(etas.front()) + ".." + to_text(etas.back()) + ", m = 64 and 225, contraction of " +
                  to_text(t_end) + " s" +
                  (full ? " (the paper's 15 s)" : " (quick: shortened from the paper's 15 s; the ratio is per step)");
    P["timing"] =
        "wall time of the steps' phases (the diagnostics excluded), one thread; Table 1: the three runs of a grid "
        "(LDSM, SHVD m = 64, SHVD m = 225) advanced in lockstep, one step of each in turn; per-step phase "
        "times: the median over the steps";
    // ---- 2. The lockstep runs of each grid, and the products of one force call ---------------------
    Relaxations runs(opt);
    runs.group("table1");
    table1(etas, t_end, runs, results["tables"], results["values"]);
    // ---- 3. Results -------------------------------------------------------------------------------
    runs.record(results);
    st::write_results(opt, results);
    return 0;
  });
}
