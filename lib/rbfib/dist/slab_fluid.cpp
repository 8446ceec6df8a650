#include "rbfib/dist/slab_fluid.hpp"

#include "rbfib/core/error.hpp"

#include <thrust/copy.h>
#include <thrust/functional.h>
#include <thrust/inner_product.h>
#include <thrust/transform_reduce.h>

#include <algorithm>
#include <cmath>

namespace rbfib::dist {

namespace {
/// This rank's planes of `grid` with `ghosts` planes a side.
MacGrid slab_of(const MacGrid& grid, const Slabs& slabs, int ghosts) {
  MacGrid g = grid;
  const double h = grid.h(2);
  g.cells[2] = slabs.planes() + 2 * ghosts;
  g.length[2] = g.cells[2] * h;
  g.origin[2] = grid.origin[2] + (slabs.first() - ghosts) * h;
  return g;
}
}  // namespace

SlabFluid::SlabFluid(const MacGrid& grid, const Comm& comm, int ghosts)
    : grid_(grid), comm_(comm), slabs_(grid.scalar(), comm, "grid"), wide_ghosts_(std::max(ghosts, int(fluid_reach))) {
  require(grid.dims == 3 && grid.periodic(0) && grid.periodic(2), "grid.boundary", "walls across x or z",
          "a fluid on several ranks needs x and z periodic (the Fourier solvers); walls across x or z need the "
          "multigrid path, which runs on one process");
  halo_ = std::make_unique<Halo>(slabs_, ghosts_, "grid.cells.z");
  wide_halo_ = std::make_unique<Halo>(slabs_, wide_ghosts_, "grid.cells.z");
  local_ = slab_of(grid, slabs_, ghosts_);
  wide_ = slab_of(grid, slabs_, wide_ghosts_);
}

void SlabFluid::widen(const dvec& local, dvec& wide) const {
  const index_t n = slabs_.planes(), g = ghosts_, G = wide_ghosts_;
  const index_t ps = halo_->plane_size_of(local, "SlabFluid::widen");
  wide.resize(static_cast<std::size_t>((n + 2 * G) * ps));
  thrust::copy(local.begin() + g * ps, local.begin() + (g + n) * ps, wide.begin() + G * ps);
  wide_halo_->fill(wide);
}

void SlabFluid::narrow_sum(dvec& wide, dvec& local) const {
  const index_t n = slabs_.planes(), g = ghosts_, G = wide_ghosts_;
  const index_t ps = wide_halo_->plane_size_of(wide, "SlabFluid::narrow_sum");
  wide_halo_->sum(wide);
  local.assign(static_cast<std::size_t>((n + 2 * g) * ps), 0.0);
  thrust::copy(wide.begin() + G * ps, wide.begin() + (G + n) * ps, local.begin() + g * ps);
}

Box SlabFluid::global_box(const Box& local_box) const {
  Box b = local_box;
  b.axes[2].cells = grid_.cells[2];
  b.axes[2].length = grid_.length[2];
  b.axes[2].origin = grid_.origin[2];
  return b;
}

int SlabFluid::owner(double z) const {
  const int nz = grid_.cells[2];
  const int plane = int(std::floor((z - grid_.origin[2]) / grid_.h(2)));
  return slabs_.owner((plane % nz + nz) % nz);
}

namespace {
/// A distributed solver with the slabs of its own box (the solver keeps a reference to them).
struct SlabSolve {
  Slabs slabs;
  FourierSolver solver;
  SlabSolve(const Box& box, const Comm& comm, Correction c, double alpha, double beta, const std::string& name)
      : slabs(box, comm, name), solver(slabs, c, alpha, beta, name) {}
};
}  // namespace

DirectSolve SlabFluid::fourier(const Box& local_box, Correction correction, double alpha, double beta,
                               const std::string& name) const {
  auto s = std::make_shared<SlabSolve>(global_box(local_box), comm_, correction, alpha, beta, name);
  const index_t ps = s->slabs.plane_size(), offset = ghosts_ * ps, owned = s->slabs.local_size();
  const index_t extended = owned + 2 * offset;
  const Halo* halo = halo_.get();
  return [s, offset, extended, halo, name](const dvec& b, dvec& x) {
    require(static_cast<index_t>(b.size()) == extended, name + ": right-hand side size", b.size(),
            "must be this rank's extended slab, " + to_text(extended));
    x.resize(static_cast<std::size_t>(extended));  // b's size: b may be x
    s->solver.solve(b, offset, x, offset);
    halo->fill(x);
  };
}


double SlabFluid::dot(const std::vector<std::pair<const dvec*, const dvec*>>& pairs) const {
  double sum = 0;
  for (const auto& [a, b] : pairs) {
    const auto [lo, hi] = halo_->owned(*a, "SlabFluid::dot");
    require(a->size() == b->size(), "SlabFluid::dot: field sizes", b->size(), "must be equal");
    sum += thrust::inner_product(a->begin() + lo, a->begin() + hi, b->begin() + lo, 0.0);
  }
  return comm_.sum(sum);
}

double SlabFluid::max_abs(const std::vector<const dvec*>& v) const {
  double m = 0;
  for (const dvec* f : v) {
    const auto [lo, hi] = halo_->owned(*f, "SlabFluid::max_abs");
    m = std::max(m, thrust::transform_reduce(f->begin() + lo, f->begin() + hi, [] RBFIB_HD (double a) { return std::abs(a); }, 0.0,
                                             thrust::maximum<double>()));
  }
  return comm_.max(m);
}

dvec SlabFluid::extend(const Box& local_box, const dvec& global) const {
  const Box whole = global_box(local_box);
  require(static_cast<index_t>(global.size()) == whole.size(), "SlabFluid::extend: field size", global.size(),
          "must be the whole box's " + to_text(whole.size()));
  const index_t ps = index_t(whole.n(0)) * whole.n(1);
  const int nz = whole.n(2), planes = slabs_.planes() + 2 * ghosts_;
  host_vector<double> g = global, e(static_cast<std::size_t>(planes * ps));
  for (int p = 0; p < planes; ++p) {
    const int z = ((slabs_.first() - ghosts_ + p) % nz + nz) % nz;
    for (index_t q = 0; q < ps; ++q) e[p * ps + q] = g[z * ps + q];
  }
  return dvec(e);
}

dvec SlabFluid::gather(const Box& local_box, const dvec& local) const {
  const Slabs whole(global_box(local_box), comm_, "SlabFluid::gather");
  const index_t offset = ghosts_ * whole.plane_size();
  require(static_cast<index_t>(local.size()) == whole.local_size() + 2 * offset, "SlabFluid::gather: field size",
          local.size(), "must be this rank's extended slab");
  return whole.gather(dvec(local.begin() + offset, local.begin() + offset + whole.local_size()));
}

}  // namespace rbfib::dist
