#include "rbfib/fluid/fourier_solver.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/fluid/poisson.hpp"
#include "rbfib/fluid/wall_modes.hpp"

#include <thrust/transform.h>

#include <cmath>

namespace rbfib {

namespace {
std::array<int, 3> extents(const Box& box) { return {box.n(0), box.n(1), box.n(2)}; }
std::array<bool, 3> transformed(const Box& box) {
  std::array<bool, 3> t{false, false, false};
  for (int d = 0; d < box.dims; ++d) t[d] = box.axes[d].periodic();
  return t;
}
}  // namespace

bool FourierSolver::applies(const Box& box) {
  if (box.dims < 1 || box.n(0) < 2) return false;
  for (int d = 0; d < box.dims; ++d)
    if (d != 1 && !box.axes[d].periodic()) return false;
  return linalg::RealFourierTransform::supported(extents(box), transformed(box));
}

FourierSolver::FourierSolver(const Box& box, Correction correction, double alpha, double beta, const std::string& name)
    : lap_(box, correction), alpha_(alpha), beta_(beta), name_(name) {
  require(applies(box), name + ": box", "walls on an axis other than y",
          "the Fourier solver needs x (and z) periodic; use the multigrid solver");
  require(alpha >= 0 && std::isfinite(alpha), name + ": alpha (coefficient of I~)", alpha, "must be finite and >= 0");
  require(beta <= 0 && std::isfinite(beta), name + ": beta (coefficient of L)", beta, "must be finite and <= 0");
  require(alpha > 0 || beta < 0, name + ": alpha, beta", "0, 0", "the operator must not vanish");
  const kernels::LaplacianStencil& s = lap_.stencil();
  wall_ = box.dims >= 2 && !box.axes[1].periodic();
  const bool neumann_both = wall_ && s.axis[1].lo.ghost == 1.0 && s.axis[1].hi.ghost == 1.0;
  singular_ = alpha == 0 && (!wall_ || neumann_both);
  for (int d = 0; d < 3; ++d)
    mu_[d] = d < box.dims ? kernels::periodic_eigenvalues(s.axis[d], box.n(d)) : host_vector<double>(1, 0.0);
  fft_ = std::make_unique<linalg::RealFourierTransform>(extents(box), transformed(box));
  work_.resize(static_cast<std::size_t>(fft_->spectrum_size()));
  if (wall_) thomas_.resize(static_cast<std::size_t>(fft_->spectrum_size()));
}

void FourierSolver::solve(const dvec& b, dvec& x) const {
  const index_t n = lap_.size();
  require(static_cast<index_t>(b.size()) == n, name_ + ": right-hand side size", b.size(), "must be " + to_text(n));
  const dvec* rhs = &b;
  if (singular_) {
    mean_free_ = b;
    remove_mean(mean_free_);
    rhs = &mean_free_;
  }
  fft_->forward(*rhs, work_);

  const kernels::LaplacianStencil s = lap_.stencil();
  const double alpha = alpha_, beta = beta_;
  const bool singular = singular_;
  const double *mux = ptr(mu_[0]), *muy = ptr(mu_[1]), *muz = ptr(mu_[2]);
  linalg::complex* w = thrust::raw_pointer_cast(work_.data());
  const int hx = fft_->half(), ny = s.shape.n[1], nz = s.shape.n[2];  // the spectrum: k_x < hx
  if (!wall_) {
    // Diagonal in (k_x, k_y, k_z); the zero mode of a singular operator is set to zero.
    for_each_index(fft_->spectrum_size(), [=] RBFIB_HD (index_t p) {
      const index_t i = p % hx, q = p / hx, j = q % ny, k = q / ny;
      const double a = alpha + beta * (mux[i] + muy[j] + muz[k]);
      w[p] = (singular && p == 0) ? linalg::complex(0.0, 0.0) : w[p] / a;
    });
  } else {
    // One tridiagonal system in y per (k_x, k_z): the Thomas algorithm (wall_modes.hpp).
    const kernels::WallModes modes{s.axis[1], alpha, beta};
    double* cp = ptr(thomas_);
    for_each_index(index_t(hx) * nz, [=] RBFIB_HD (index_t m) {
      const index_t i = m % hx, k = m / hx;
      modes.solve(mux[i] + muz[k], singular && m == 0, w, cp, i + index_t(hx) * ny * k, hx);
    });
  }

  fft_->backward(work_, x);
  const double inv = 1.0 / fft_->scale();
  thrust::transform(x.begin(), x.end(), x.begin(), [=] RBFIB_HD (double v) { return v * inv; });
  if (singular_) remove_mean(x);
}

}  // namespace rbfib
