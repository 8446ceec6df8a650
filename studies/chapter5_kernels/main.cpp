// The IB kernels phi = delta_1 of the seed's Fig. 5.1 (Sec. 5.1: the 3-point kernel of Roma et
// al. [82], the 4-point B-spline B_3, the 4-point cosine kernel [81]) beside Peskin's 4-point
// kernel of Chapter 3, and their properties: phi(r) on [-2.5, 2.5]; over 1000 offsets r in [0, 1)
// the support s (eq. 4.3), sum_j phi(r - j) (partition of unity), the first and second moments
// sum_j (r - j)^m phi(r - j), sum_j phi(r - j)^2 and the even-odd condition; and the error and
// time of interpolating a smooth periodic f at 1000 random points by the tensor-product kernel
// delta_h (eq. 4.4) on the MAC grid of the 16 um box, h = 16 um / N.
//
// Interpolation is measured twice: by the solver's interpolation (ib::Interaction, binned
// Alg. 4.3, all three MAC components, N up to 128, 256 at full) with its time per call, and by the
// literal sum of eq. 4.4, f(x) prod_a phi((x_a - X_a)/h) over the nodes x near X with f evaluated
// there, which needs no stored grid and so reaches N = 2048: the asymptotic orders (the cosine
// kernel's first moment M(r) = r - 1/2 + (cos(pi r/2) - sin(pi r/2))/2 is at most 0.021 while its
// second moment is about 0.5, so its first-order term dominates only for N >> 80).
//
// Run:   build/studies/study_chapter5_kernels --scale quick --out runs/chapter5_kernels
#include "common/study.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/ib/kernels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

using namespace rbfib;
using namespace rbfib::ib;
namespace st = rbfib::study;
using st::Json;

namespace {
const double L = 16 * units::um;  // the periodic box [0, L)^3
const double k = 2 * pi / L;

/// The smooth periodic function interpolated (dimensionless, |f| <= 2).
double f(double x, double y, double z) { return std::sin(k * x) * std::cos(k * y) + std::sin(k * y) * std::cos(k * z); }

/// Staggering g of MAC component c along axis a (grid.hpp): nodes at h (i + g).
double stagger(int c, int a) { return a == c ? 1.0 : 0.5; }

/// One row of the properties table: sums over j of phi(r - j) for r = m / 1000, m = 0..999.
template <class K>
Json properties() {
  double pou = 0, m1 = 0, sq_min = INFINITY, sq_max = 0, m2_min = INFINITY, m2_max = 0, even_odd = 0;
  int support = 0;
  for (int m = 0; m < 1000; ++m) {
    const double r = m / 1000.0;
    double s0 = 0, s1 = 0, s2 = 0, sq = 0, even = 0;
    int nonzero = 0;
    for (int j = -3; j <= 4; ++j) {
      const double p = K::phi(r - j);
      s0 += p;
      s1 += (r - j) * p;
      s2 += (r - j) * (r - j) * p;
      sq += p * p;
      if (j % 2 == 0) even += p;
      nonzero += p != 0.0;
    }
    pou = std::max(pou, std::abs(s0 - 1));
    m1 = std::max(m1, std::abs(s1));
    sq_min = std::min(sq_min, sq), sq_max = std::max(sq_max, sq);
    m2_min = std::min(m2_min, s2), m2_max = std::max(m2_max, s2);
    even_odd = std::max(even_odd, std::abs(even - 0.5));
    support = std::max(support, nonzero);
  }
  return st::row({K::name, support, pou, m1, sq_min, sq_max, m2_min, m2_max, K::phi(0.0), even_odd});
}

/// delta_h interpolation of f at X for MAC component c by the literal sum of eq. 4.4.
template <class K>
double direct_sum(const double* X, int N, int c) {
  const double h = L / N;
  double node[3][6], w[3][6];
  int count[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    const double u = X[a] / h - stagger(c, a);
    for (int i = int(std::floor(u)) - 2; i <= int(std::floor(u)) + 3; ++i) {
      const double p = K::phi(i - u);
      if (p != 0.0) node[a][count[a]] = h * (i + stagger(c, a)), w[a][count[a]++] = p;
    }
  }
  double sum = 0;
  for (int i = 0; i < count[0]; ++i)
    for (int j = 0; j < count[1]; ++j)
      for (int l = 0; l < count[2]; ++l) sum += w[0][i] * w[1][j] * w[2][l] * f(node[0][i], node[1][j], node[2][l]);
  return sum;
}

/// max over points and components of |direct_sum - f(X)|, and the values (U[c n + p]).
template <class K>
double direct_error(const std::vector<double>& X, int N, std::vector<double>& U) {
  const size_t n = X.size() / 3;
  U.assign(3 * n, 0.0);
  double err = 0;
  for (size_t p = 0; p < n; ++p) {
    const double Xp[3] = {X[p], X[n + p], X[2 * n + p]};
    for (int c = 0; c < 3; ++c) {
      U[c * n + p] = direct_sum<K>(Xp, N, c);
      err = std::max(err, std::abs(U[c * n + p] - f(Xp[0], Xp[1], Xp[2])));
    }
  }
  return err;
}

/// Fig. 5.1 (phi(r) on [-2.5, 2.5]) and the properties over 1000 offsets, every kernel.
void kernel_shapes(Json& results) {
  Json fig = st::table({"kernel", "figure", "r", "phi"}, {"", "", "h", ""});
  Json props = st::table({"kernel", "support", "partition_err", "first_moment", "sumsq_min", "sumsq_max", "second_moment_min",
                          "second_moment_max", "phi0", "even_odd_err"},
                         {"", "h", "", "h", "", "", "h^2", "h^2", "", ""});
  for (const std::string& name : kernel_names())
    with_kernel(kernel_named(name), [&](auto kernel) {
      using K = decltype(kernel);
      for (int m = 0; m <= 500; ++m) {
        const double r = (m - 250) / 100.0;
        fig["rows"].push(st::row({K::name, name == "peskin4" ? "Chapter 3" : "Fig. 5.1", r, K::phi(r)}));
      }
      props["rows"].push(properties<K>());
    });
  results["tables"]["fig51"] = fig;
  results["tables"]["properties"] = props;
}

/// The literal sum of eq. 4.4 on N = 16 ... 2048, every kernel.
Json direct_sums(const std::vector<double>& Xh) {
  Json direct = st::table({"kernel", "N", "h_um", "err_inf"}, {"", "", "um", ""});
  std::vector<double> Ud;
  for (const std::string& name : kernel_names())
    with_kernel(kernel_named(name), [&](auto kernel) {
      for (int N : {16, 32, 64, 128, 256, 512, 1024, 2048})
        direct["rows"].push(st::row({name, N, L / N / units::um, direct_error<decltype(kernel)>(Xh, N, Ud)}));
    });
  return direct;
}

/// The solver's interpolation on each grid and kernel: error, time per call, and its difference to
/// the literal sum.
Json solver_interpolation(const st::Options& opt, const std::vector<double>& Xh, const std::vector<int>& grids, int repeats) {
  const int points = int(Xh.size() / 3);
  const dvec X(Xh.begin(), Xh.end());
  Json interp = st::table({"kernel", "N", "h_um", "err_inf", "seconds", "diff_vs_direct"}, {"", "", "um", "", "s", ""});
  std::vector<double> Ud;
  for (int N : grids) {
    const auto boxes = mac_boxes({N, N, N}, {L, L, L}, {true, true, true});
    std::array<dvec, 3> u;
    for (int c = 0; c < 3; ++c) u[c] = sample(boxes[c], f);
    for (const std::string& name : kernel_names()) {
      Interaction ib(boxes, kernel_named(name));
      dvec U;
      ib.interpolate(X, u, U);
      const double seconds = st::median_seconds(repeats, [&] { ib.interpolate(X, u, U); });
      const host_vector<double> Uh = U;
      with_kernel(kernel_named(name), [&](auto kernel) { direct_error<decltype(kernel)>(Xh, N, Ud); });
      double err = 0, diff = 0;
      for (int c = 0; c < 3; ++c)
        for (int p = 0; p < points; ++p) {
          err = std::max(err, std::abs(Uh[c * points + p] - f(Xh[p], Xh[points + p], Xh[2 * points + p])));
          diff = std::max(diff, std::abs(Uh[c * points + p] - Ud[c * points + p]));
        }
      interp["rows"].push(st::row({name, N, L / N / units::um, err, seconds, diff}));
      st::log(opt, "3. " + name + ", N = " + to_text(N) + ": err_inf " + to_text(err) + ", " + to_text(seconds * 1e6) +
                       " us per call, |solver - eq. 4.4 sum| " + to_text(diff));
    }
  }
  return interp;
}
}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_kernels", [&] {
    // ---- 1. Parameters ----------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_kernels",
                                                   "The IB kernels of Fig. 5.1: phi(r), moments, sums of squares, interpolation order and time");
    const bool full = opt.scale == st::Scale::full;
    const std::vector<int> grids = full ? std::vector<int>{16, 32, 64, 128, 256} : std::vector<int>{16, 32, 64, 128};
    const int points = 1000, repeats = full ? 31 : 11;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "[0, 16]^3, periodic";
    P["f"] = "sin(k x) cos(k y) + sin(k y) cos(k z), k = 2 pi / 16 um";
    P["points"] = points;
    P["offsets"] = "r = m / 1000, m = 0..999";
    P["interpolation"] = "ib::Interaction, binned Alg. 4.3, three MAC components";
    P["repeats"] = repeats;

    // ---- 2. Fig. 5.1 and the kernels' properties ----------------------------------------------
    kernel_shapes(results);
    st::log(opt, "1-2. phi(r) and the properties of " + to_text(kernel_names().size()) + " kernels");

    // ---- 3. Interpolation at random points: the literal sum and the solver's ----------------
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U01(0.0, L);
    std::vector<double> Xh(3 * points);
    for (double& x : Xh) x = U01(rng);
    const Json direct = direct_sums(Xh);
    results["tables"]["interpolation"] = solver_interpolation(opt, Xh, grids, repeats);
    results["tables"]["direct_sum"] = direct;
    st::write_results(opt, results);
    return 0;
  });
}
