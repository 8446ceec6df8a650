#pragma once
// Snapshots of a run for ParaView: one HDF5 file per snapshot and one XDMF file describing the
// whole time series (docs/output.md). Per snapshot (CGS units, each dataset with a "units"
// attribute; the file's attributes t (s) and step):
//   /fluid/velocity      nz x ny x nx x 3, the MAC velocity averaged to the cell centres (cm/s)
//   /fluid/pressure      nz x ny x nx (dyn/cm^2)
//   /cells/<b>/points    M x 3, the sample sites of every cell of batch b (cm), cell after cell
//   /cells/<b>/triangles T x 3, their triangulation (the convex hull of the sites on the sphere,
//                        repeated per cell with its offset), 0-based indices
//   /cells/<b>/velocity  M x 3, the fluid velocity interpolated at the sample sites (cm/s)
//   /cells/<b>/force_density  M, |force density per reference area| (dyn/cm^2)
//   /cells/<b>/mean_curvature M, H (1/cm; -1/r on a sphere of radius r)
//   /points/<p>/points   n x 3, each tethered point set's positions (cm)
#include "rbfib/ib/interaction.hpp"
#include "rbfib/scene/scene.hpp"

#include <string>
#include <vector>

namespace rbfib::io {

class SnapshotWriter {
 public:
  /// Writes into dir/snapshots/ and dir/run.xmf. The triangulations of the types are made here
  /// once.
  SnapshotWriter(const std::string& dir, const sim::ImmersedBoundary& ib);

  /// Writes the state of ib as the next snapshot and rewrites run.xmf to list all of them.
  void write(const sim::ImmersedBoundary& ib);

  /// Lists snapshots already in dir (a restarted run appends to them); those after time t are
  /// dropped from the series.
  void resume(double t);

 private:
  void write_xdmf() const;
  std::string dir_;
  std::vector<std::vector<std::array<index_t, 3>>> triangles_;  // per batch, one cell
  ib::Interaction probe_;  // the run's kernel on its grid: interpolates at the sample sites
  struct Entry {
    std::string file;
    double t;
  };
  std::vector<Entry> written_;
  // Shapes for the XDMF.
  std::array<int, 3> cells_{};
  std::array<double, 3> h_{};
  std::vector<std::string> batch_names_, point_names_;
  std::vector<index_t> batch_points_, batch_triangles_, point_counts_;
};

}  // namespace rbfib::io
