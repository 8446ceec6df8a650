#include "poisson_peers.hpp"

#include "common/machine.hpp"
#include "common/study.hpp"
#include "rbfib/fluid/fourier_solver.hpp"
#include "rbfib/fluid/poisson.hpp"
#include "rbfib/linalg/blas.hpp"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <random>

#if defined(RBFIB_HAVE_HYPRE)
#define OMPI_SKIP_MPICXX 1  // the C interface only (no MPI C++ bindings to link)
#define MPICH_SKIP_MPICXX 1
#include <HYPRE_struct_ls.h>
#include <mpi.h>
#endif

namespace rbfib::study {

namespace {
double residual(const StaggeredLaplacian& L, const dvec& q, const dvec& b) {
  dvec r;
  L.apply(q, r, 0.0, -1.0);  // -L q
  blas::axpy(-1.0, b, r);
  return blas::norm2(r) / blas::norm2(b);
}

#if defined(RBFIB_HAVE_HYPRE)
/// hypre: a 7-point Struct matrix of -L (cell centres; periodic x, z; the Neumann rows at the y
/// walls lose their outward coupling), PCG preconditioned by one PFMG V-cycle, stopping at
/// ||r|| <= rtol ||b||. Returns the median time of a solve from q = 0 and the solution.
PoissonPeer hypre_pfmg(const Box& box, const dvec& b, double rtol, int repeats, dvec& q_out) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    MPI_Init(nullptr, nullptr);
    std::atexit([] { MPI_Finalize(); });
  }
  const int nx = box.n(0), ny = box.n(1), nz = box.n(2);
  const double hx = box.axes[0].h(), hy = box.axes[1].h(), hz = box.axes[2].h();
  int lo[3] = {0, 0, 0}, hi[3] = {nx - 1, ny - 1, nz - 1};
  HYPRE_StructGrid grid;
  HYPRE_StructGridCreate(MPI_COMM_WORLD, 3, &grid);
  HYPRE_StructGridSetExtents(grid, lo, hi);
  int periodic[3] = {nx, 0, nz};
  HYPRE_StructGridSetPeriodic(grid, periodic);
  HYPRE_StructGridAssemble(grid);
  HYPRE_StructStencil stencil;
  HYPRE_StructStencilCreate(3, 7, &stencil);
  int offsets[7][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int e = 0; e < 7; ++e) HYPRE_StructStencilSetElement(stencil, e, offsets[e]);
  HYPRE_StructMatrix A;
  HYPRE_StructMatrixCreate(MPI_COMM_WORLD, grid, stencil, &A);
  HYPRE_StructMatrixSetSymmetric(A, 0);
  HYPRE_StructMatrixInitialize(A);
  const index_t n = box.size();
  std::vector<double> values(static_cast<std::size_t>(7 * n));
  int entries[7] = {0, 1, 2, 3, 4, 5, 6};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double* v = &values[7 * (i + index_t(nx) * (j + index_t(ny) * k))];
        const bool bottom = j == 0, top = j == ny - 1;
        v[1] = v[2] = -1 / (hx * hx);
        v[5] = v[6] = -1 / (hz * hz);
        v[3] = bottom ? 0.0 : -1 / (hy * hy);
        v[4] = top ? 0.0 : -1 / (hy * hy);
        v[0] = 2 / (hx * hx) + 2 / (hz * hz) + (2 - double(bottom) - double(top)) / (hy * hy);
      }
  HYPRE_StructMatrixSetBoxValues(A, lo, hi, 7, entries, values.data());
  HYPRE_StructMatrixAssemble(A);
  const host_vector<double> bh = b;
  std::vector<double> bv(bh.begin(), bh.end()), xv(static_cast<std::size_t>(n), 0.0);
  HYPRE_StructVector B, X;
  HYPRE_StructVectorCreate(MPI_COMM_WORLD, grid, &B);
  HYPRE_StructVectorCreate(MPI_COMM_WORLD, grid, &X);
  HYPRE_StructVectorInitialize(B);
  HYPRE_StructVectorInitialize(X);
  HYPRE_StructVectorSetBoxValues(B, lo, hi, bv.data());
  HYPRE_StructVectorAssemble(B);
  PoissonPeer r;
  r.solver = "hypre PFMG-PCG";
  // The setup (PFMG's coarse operators) once, as a time loop would; each solve from q = 0.
  HYPRE_StructSolver solver, precond;
  HYPRE_StructPCGCreate(MPI_COMM_WORLD, &solver);
  HYPRE_StructPCGSetTol(solver, rtol);
  HYPRE_StructPCGSetTwoNorm(solver, 1);
  HYPRE_StructPCGSetMaxIter(solver, 500);
  HYPRE_StructPFMGCreate(MPI_COMM_WORLD, &precond);
  HYPRE_StructPFMGSetMaxIter(precond, 1);
  HYPRE_StructPFMGSetTol(precond, 0.0);
  HYPRE_StructPFMGSetZeroGuess(precond);
  HYPRE_StructPFMGSetRelaxType(precond, 2);  // red-black Gauss-Seidel, symmetric
  HYPRE_StructPFMGSetNumPreRelax(precond, 1);
  HYPRE_StructPFMGSetNumPostRelax(precond, 1);
  HYPRE_StructPCGSetPrecond(solver, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, precond);
  HYPRE_StructVectorSetBoxValues(X, lo, hi, xv.data());
  HYPRE_StructVectorAssemble(X);
  HYPRE_StructPCGSetup(solver, A, B, X);
  r.seconds = median_seconds(repeats, [&] {
    std::fill(xv.begin(), xv.end(), 0.0);
    HYPRE_StructVectorSetBoxValues(X, lo, hi, xv.data());
    HYPRE_StructPCGSolve(solver, A, B, X);
  });
  int its = 0;
  HYPRE_StructPCGGetNumIterations(solver, &its);
  r.iterations = its;
  HYPRE_StructPCGDestroy(solver);
  HYPRE_StructPFMGDestroy(precond);
  HYPRE_StructVectorGetBoxValues(X, lo, hi, xv.data());
  q_out.assign(xv.begin(), xv.end());
  HYPRE_StructVectorDestroy(B);
  HYPRE_StructVectorDestroy(X);
  HYPRE_StructMatrixDestroy(A);
  HYPRE_StructStencilDestroy(stencil);
  HYPRE_StructGridDestroy(grid);
  return r;
}
#endif
}  // namespace

bool have_hypre() {
#if defined(RBFIB_HAVE_HYPRE)
  return true;
#else
  return false;
#endif
}

std::vector<PoissonPeer> compare_poisson_solvers(const Box& box, int repeats, double rtol) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  host_vector<double> bh(static_cast<std::size_t>(box.size()));
  for (auto& v : bh) v = U(gen);
  dvec b = bh;
  remove_mean(b);
  std::vector<PoissonPeer> rows;

  FourierSolver F(box, Correction::none, 0.0, -1.0, "poisson (Fourier)");
  dvec q_ref;
  F.solve(b, q_ref);
  PoissonPeer f{"Fourier (direct)", median_seconds(repeats, [&] { F.solve(b, q_ref); }), 0, 0, 0};
  f.relative_residual = residual(F.laplacian(), q_ref, b);
  rows.push_back(f);

  PoissonOptions o;
  o.solver = SolverOptions{"poisson (multigrid PCG)", rtol, 500};
  PoissonSolver P(box, o);
  dvec q, bb;
  int its = 0;
  const double t = median_seconds(repeats, [&] {
    bb = b;
    q.assign(b.size(), 0.0);
    its = P.solve(bb, q).iterations;
  });
  rows.push_back({"multigrid PCG", t, double(its), residual(P.laplacian(), q, b), max_rel_diff({&q}, {&q_ref})});

#if defined(RBFIB_HAVE_HYPRE)
  dvec qh;
  PoissonPeer h = hypre_pfmg(box, b, rtol, repeats, qh);
  remove_mean(qh);  // hypre's solution of the singular problem differs by a constant
  h.relative_residual = residual(P.laplacian(), qh, b);
  h.max_rel_diff_vs_fourier = max_rel_diff({&qh}, {&q_ref});
  rows.push_back(h);
#endif
  return rows;
}

}  // namespace rbfib::study
