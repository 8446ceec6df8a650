#include "rbfib/linalg/multigrid.hpp"

namespace rbfib {

namespace {

/// The coarse cells (up to 2) that fine cell j interpolates from, with their weights (eq. in header).
struct Transfer1D {
  int nf, nc;
  bool periodic;
  /// Neighbour of coarse cell I0 on the side of fine cell j (j even: below, odd: above).
  RBFIB_HD int neighbour(int j) const {
    const int I0 = j / 2;
    int In = (j % 2 == 0) ? I0 - 1 : I0 + 1;
    if (In < 0) In = periodic ? nc - 1 : I0;
    if (In >= nc) In = periodic ? 0 : I0;
    return In;
  }
};

struct ProlongAdd {
  int dims;
  Transfer1D t[3];
  index_t cs[3];  // coarse strides
  index_t nf0, nf1;
  const double* coarse;
  double* fine;
  RBFIB_HD void operator()(index_t p) const {
    int j[3];
    j[0] = int(p % nf0);
    const index_t q = p / nf0;
    j[1] = int(q % nf1);
    j[2] = int(q / nf1);
    int I[3][2];
    double w[3][2];
    for (int d = 0; d < 3; ++d) {
      if (d < dims) {
        I[d][0] = j[d] / 2;
        I[d][1] = t[d].neighbour(j[d]);
        w[d][0] = 0.75;
        w[d][1] = 0.25;
      } else {
        I[d][0] = I[d][1] = 0;
        w[d][0] = 1.0;
        w[d][1] = 0.0;
      }
    }
    double sum = 0.0;
    for (int c = 0; c < 2; ++c)
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const double ww = w[0][a] * w[1][b] * w[2][c];
          if (ww != 0.0) sum += ww * coarse[I[0][a] * cs[0] + I[1][b] * cs[1] + I[2][c] * cs[2]];
        }
    fine[p] += sum;
  }
};

struct Restrict {
  int dims;
  Transfer1D t[3];
  index_t fs[3];  // fine strides
  index_t nc0, nc1;
  double scale;
  const double* fine;
  double* coarse;
  RBFIB_HD void operator()(index_t p) const {
    int I[3];
    I[0] = int(p % nc0);
    const index_t q = p / nc0;
    I[1] = int(q % nc1);
    I[2] = int(q / nc1);
    // Fine cells whose interpolation uses coarse cell I: 2I - 1 .. 2I + 2 (wrapped on periodic axes).
    int J[3][4];
    double w[3][4];
    int m[3];
    for (int d = 0; d < 3; ++d) {
      if (d >= dims) {
        J[d][0] = 0;
        w[d][0] = 1.0;
        m[d] = 1;
        continue;
      }
      m[d] = 0;
      for (int o = -1; o <= 2; ++o) {
        int j = 2 * I[d] + o;
        if (j < 0 || j >= t[d].nf) {
          if (!t[d].periodic) continue;
          j = (j + t[d].nf) % t[d].nf;
        }
        double wt = (j / 2 == I[d] ? 0.75 : 0.0) + (t[d].neighbour(j) == I[d] ? 0.25 : 0.0);
        if (wt == 0.0) continue;
        // a wrapped j may coincide with one already listed (tiny periodic axes): merge.
        bool merged = false;
        for (int k = 0; k < m[d]; ++k)
          if (J[d][k] == j) merged = true;
        if (merged) continue;
        J[d][m[d]] = j;
        w[d][m[d]] = wt;
        ++m[d];
      }
    }
    double sum = 0.0;
    for (int c = 0; c < m[2]; ++c)
      for (int b = 0; b < m[1]; ++b)
        for (int a = 0; a < m[0]; ++a)
          sum += w[0][a] * w[1][b] * w[2][c] * fine[J[0][a] * fs[0] + J[1][b] * fs[1] + J[2][c] * fs[2]];
    coarse[p] = scale * sum;
  }
};

void make_1d(const CellCentredTransfer& t, Transfer1D out[3]) {
  for (int d = 0; d < 3; ++d) out[d] = Transfer1D{t.fine[d], t.coarse[d], t.periodic[d]};
}

}  // namespace

void prolong_add(const CellCentredTransfer& t, const dvec& coarse, dvec& fine) {
  require(index_t(coarse.size()) == t.coarse_size(), "multigrid.prolong.coarse.size", coarse.size(), "does not match");
  require(index_t(fine.size()) == t.fine_size(), "multigrid.prolong.fine.size", fine.size(), "does not match");
  ProlongAdd k;
  k.dims = t.dims;
  make_1d(t, k.t);
  k.cs[0] = 1;
  k.cs[1] = t.coarse[0];
  k.cs[2] = index_t(t.coarse[0]) * t.coarse[1];
  k.nf0 = t.fine[0];
  k.nf1 = t.fine[1];
  k.coarse = ptr(coarse);
  k.fine = ptr(fine);
  for_each_index(t.fine_size(), k);
}

void restrict_to_coarse(const CellCentredTransfer& t, const dvec& fine, dvec& coarse) {
  require(index_t(fine.size()) == t.fine_size(), "multigrid.restrict.fine.size", fine.size(), "does not match");
  coarse.resize(t.coarse_size());
  Restrict k;
  k.dims = t.dims;
  make_1d(t, k.t);
  k.fs[0] = 1;
  k.fs[1] = t.fine[0];
  k.fs[2] = index_t(t.fine[0]) * t.fine[1];
  k.nc0 = t.coarse[0];
  k.nc1 = t.coarse[1];
  k.scale = 1.0 / double(1 << t.dims);
  k.fine = ptr(fine);
  k.coarse = ptr(coarse);
  for_each_index(t.coarse_size(), k);
}

Multigrid::Multigrid(std::vector<MultigridLevel> levels) : levels_(std::move(levels)) {
  require(!levels_.empty(), "multigrid.levels", 0, "needs at least one level");
  r_.resize(levels_.size());
  bc_.resize(levels_.size());
  xc_.resize(levels_.size());
}

void Multigrid::vcycle(const dvec& b, dvec& x) const { cycle(0, b, x); }

void Multigrid::cycle(int l, const dvec& b, dvec& x) const {
  const MultigridLevel& L = levels_[l];
  if (l + 1 == int(levels_.size())) {
    L.smoother.solve(L.apply, b, x, true);  // coarsest level: Chebyshev as the solver
    return;
  }
  L.smoother.solve(L.apply, b, x, true);  // pre-smoothing
  dvec& r = r_[l];
  L.apply(x, r);
  blas::xpby(b, -1.0, r);  // r = b - A x
  restrict_to_coarse(L.to_coarse, r, bc_[l + 1]);
  cycle(l + 1, bc_[l + 1], xc_[l + 1]);
  prolong_add(L.to_coarse, xc_[l + 1], x);
  L.smoother.solve(L.apply, b, x, false);  // post-smoothing (the adjoint of the pre-smoother)
}

}  // namespace rbfib
