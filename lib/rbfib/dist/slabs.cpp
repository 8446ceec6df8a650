#include "rbfib/dist/slabs.hpp"

#include "rbfib/core/error.hpp"

#include <thrust/copy.h>
#include <thrust/fill.h>

#include <algorithm>

namespace rbfib::dist {

Slabs::Slabs(const Box& box, const Comm& comm, const std::string& name) : box_(box), comm_(comm) {
  require(box.dims == 3, name + ": box dimensions", box.dims, "slabs along z need a 3D box");
  const int nz = box.n(2), p = comm.size();
  const int block = (nz + p - 1) / p;  // FFTW_MPI_DEFAULT_BLOCK
  planes_.resize(static_cast<std::size_t>(p));
  first_.resize(static_cast<std::size_t>(p));
  for (int r = 0; r < p; ++r) {
    first_[r] = std::min(nz, r * block);
    planes_[r] = std::min(nz, (r + 1) * block) - first_[r];
  }
}

dvec Slabs::scatter(const dvec& global) const {
  require(static_cast<index_t>(global.size()) == box_.size(), "slab scatter: field size", global.size(),
          "must be the box's " + to_text(box_.size()));
  const index_t begin = first() * plane_size();
  return dvec(global.begin() + begin, global.begin() + begin + local_size());
}

dvec Slabs::gather(const dvec& local) const {
  require(static_cast<index_t>(local.size()) == local_size(), "slab gather: field size", local.size(),
          "must be this rank's " + to_text(local_size()));
  std::vector<int> counts(planes_.size()), offsets(planes_.size());
  for (std::size_t r = 0; r < planes_.size(); ++r) {
    counts[r] = static_cast<int>(planes_[r] * plane_size());
    offsets[r] = static_cast<int>(first_[r] * plane_size());
  }
  host_vector<double> in = local, out(static_cast<std::size_t>(box_.size()));
  check(MPI_Allgatherv(in.data(), counts[comm_.rank()], MPI_DOUBLE, out.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                       comm_.get()),
        "slab gather (MPI_Allgatherv)");
  return dvec(out);
}

Halo::Halo(const Slabs& slabs, int ghosts, const std::string& name) : slabs_(slabs), ghosts_(ghosts) {
  require(ghosts >= 0, name + ": ghost planes", ghosts, "must be >= 0");
  const Comm& c = slabs.comm();
  int fewest = slabs.box().n(2);
  for (int r = 0; r < c.size(); ++r) fewest = std::min(fewest, slabs.planes(r));
  require(fewest >= ghosts, name + ": planes per rank",
          "n_z = " + to_text(slabs.box().n(2)) + " on " + to_text(c.size()) + " ranks leaves a rank " + to_text(fewest),
          "each rank must own at least the " + to_text(ghosts) + " ghost planes the stencil reaches; use fewer ranks");
  below_ = (c.rank() + c.size() - 1) % c.size();
  above_ = (c.rank() + 1) % c.size();
}

index_t Halo::plane_size_of(const dvec& extended, const char* what) const {
  const index_t planes = slabs_.planes() + 2 * ghosts_, size = static_cast<index_t>(extended.size());
  require(planes > 0 && size % planes == 0 && size > 0, std::string(what) + ": field size", size,
          "must be whole planes of the extended slab (" + to_text(planes) + " planes)");
  return size / planes;
}

void Halo::count_exchange(index_t count) const {
  if (slabs_.comm().size() == 1) return;  // to itself
  ++traffic().halo_exchanges;
  traffic().halo += 2.0 * double(count) * sizeof(double);
}

void Halo::fill(dvec& extended) const {
  const index_t ps = plane_size_of(extended, "halo fill");
  if (ghosts_ == 0) return;
  const int g = ghosts_, n = slabs_.planes();
  const index_t count = g * ps;
  double* e = ptr(extended);
  MPI_Comm comm = slabs_.comm().get();
  count_exchange(count);
  // My bottom planes are the upper ghosts of the rank below; the rank above's are mine.
  check(MPI_Sendrecv(e + g * ps, int(count), MPI_DOUBLE, below_, 0, e + (g + n) * ps, int(count), MPI_DOUBLE, above_, 0,
                     comm, MPI_STATUS_IGNORE),
        "halo fill (upper ghosts)");
  // My top planes are the lower ghosts of the rank above.
  check(MPI_Sendrecv(e + n * ps, int(count), MPI_DOUBLE, above_, 1, e, int(count), MPI_DOUBLE, below_, 1, comm,
                     MPI_STATUS_IGNORE),
        "halo fill (lower ghosts)");
}

void Halo::sum(dvec& extended) const {
  const index_t ps = plane_size_of(extended, "halo sum");
  if (ghosts_ == 0) return;
  const int g = ghosts_, n = slabs_.planes();
  const index_t count = g * ps;
  if (static_cast<index_t>(buffer_.size()) < count) buffer_.resize(static_cast<std::size_t>(count));
  double* e = ptr(extended);
  double* b = ptr(buffer_);
  MPI_Comm comm = slabs_.comm().get();
  count_exchange(count);
  // My lower ghosts belong to the rank below's top planes; the rank above's lower ghosts to mine.
  check(MPI_Sendrecv(e, int(count), MPI_DOUBLE, below_, 2, b, int(count), MPI_DOUBLE, above_, 2, comm, MPI_STATUS_IGNORE),
        "halo sum (lower ghosts)");
  double* top = e + n * ps;
  for_each_index(count, [=] RBFIB_HD (index_t p) { top[p] += b[p]; });
  // My upper ghosts belong to the rank above's bottom planes; the rank below's upper ghosts to mine.
  check(MPI_Sendrecv(e + (g + n) * ps, int(count), MPI_DOUBLE, above_, 3, b, int(count), MPI_DOUBLE, below_, 3, comm,
                     MPI_STATUS_IGNORE),
        "halo sum (upper ghosts)");
  double* bottom = e + g * ps;
  for_each_index(count, [=] RBFIB_HD (index_t p) { bottom[p] += b[p]; });
  thrust::fill(extended.begin(), extended.begin() + count, 0.0);
  thrust::fill(extended.begin() + (g + n) * ps, extended.end(), 0.0);
}

}  // namespace rbfib::dist
