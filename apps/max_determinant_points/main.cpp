// Generates maximal-determinant-like sites on S^2 for harmonic degree N ((N+1)^2 sites) and writes
// them as unit vectors (format: rbfib/surface/point_sets.hpp). The stored sets under
// reference/point_sets (N = 22, 44, 67: n = 529, 2025, 4624, the paper's evaluation sizes, Sec. 4.1)
// were written by this tool; `make point-sets` regenerates them.
//
// Usage: max_determinant_points --degree N --out FILE [--max-iterations K]
// Cost: about 3 m^3 flops per iteration (LU and inverse of the m x m harmonic matrix, m = (N+1)^2),
// a few hundred iterations: seconds at N = 22, minutes at N = 44, most of an hour at N = 67 on two
// cores.
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

using namespace rbfib;
using namespace rbfib::surface;

namespace {
int parse_int(const std::string& field, const char* text) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0') throw InputError(field, text, "must be an integer");
  return static_cast<int>(v);
}
}  // namespace

int main(int argc, char** argv) {
  try {
    int degree = -1, max_iterations = 2000;
    std::string out;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        std::cout << "usage: max_determinant_points --degree N --out FILE [--max-iterations K]\n";
        return 0;
      }
      if (i + 1 >= argc) throw InputError("argument", a, "needs a value");
      if (a == "--degree") degree = parse_int("--degree", argv[++i]);
      else if (a == "--out") out = argv[++i];
      else if (a == "--max-iterations") max_iterations = parse_int("--max-iterations", argv[++i]);
      else throw InputError("argument", a, "is not one of --degree, --out, --max-iterations");
    }
    require(degree >= 1 && degree <= 120, "--degree", degree, "must be in 1..120");
    if (out.empty()) throw InputError("--out", "(missing)", "a file to write is required");
    const auto t0 = std::chrono::steady_clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    std::cout << "maximal-determinant-like sites: degree " << degree << ", n = " << sh_count(degree) << std::endl;
    const MaxDetResult r = max_determinant_points(degree, max_iterations, [&](int it, double log_det) {
      std::printf("  iteration %5d  log|det Y| = %.9f  (%.0f s)\n", it, log_det, seconds());
      std::fflush(stdout);
    });
    const NnlsWeights w = nnls_sh_weights(r.sites, degree);
    const double wmin = *std::min_element(w.w.begin(), w.w.end());
    const double wmax = *std::max_element(w.w.begin(), w.w.end());
    char line[256];
    std::snprintf(line, sizeof line, "log|det Y| %.9f from the spiral's %.9f; %d iterations, %s; %.0f s",
                  r.log_det, r.log_det_start, r.iterations, r.converged ? "converged" : "NOT converged", seconds());
    std::vector<std::string> header = {
        "maximal-determinant-like sites on S^2, harmonic degree N = " + to_text(degree) +
            ", n = (N+1)^2 = " + to_text(sh_count(degree)),
        "generator: rbfib max_determinant_points (L-BFGS on log|det Y| from the Bauer spiral)", line};
    std::snprintf(line, sizeof line, "eq. (45) weights: min %.6g, max %.6g (times n / 4 pi: %.4f .. %.4f), residual %.3g",
                  wmin, wmax, wmin * sh_count(degree) / (4 * rbfib::pi),
                  wmax * sh_count(degree) / (4 * rbfib::pi), w.residual);
    header.push_back(line);
    header.push_back("format: one unit vector x y z per line");
    write_sphere_sites(out, r.sites, header);
    for (const std::string& h : header) std::cout << "  " << h << '\n';
    std::cout << "written: " << out << std::endl;
    return r.converged ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "max_determinant_points: " << e.what() << std::endl;
    return 2;
  }
}
