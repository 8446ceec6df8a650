#include "rbfib/io/snapshot.hpp"

#include "rbfib/io/hdf5.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/geometry_kernels.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace rbfib::io {

namespace {

/// The MAC velocity averaged to the cell centres, row-major (z, y, x, component): each
/// component is the mean of the two faces along its own axis, the wall's normal velocity (0)
/// standing in for a face on a wall.
std::vector<double> centred_velocity(const sim::ImmersedBoundary& ib) {
  const MacGrid& g = ib.fluid().grid();
  const int n[3] = {g.cells[0], g.cells[1], g.cells[2]};
  std::vector<double> out(std::size_t(n[0]) * n[1] * n[2] * 3);
  for (int a = 0; a < 3; ++a) {
    const host_vector<double> u = ib.fluid_state().u[a];
    const Box& box = ib.fluid().operators().component_box(a);
    const bool periodic = g.periodic(a);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          int idx[3] = {i, j, k};
          // Unknown m along axis a is the face at h (m + 1): the upper face of cell m.
          auto face = [&](int m) -> double {
            if (periodic) m = (m + n[a]) % n[a];
            else if (m < 0 || m >= box.n(a)) return 0.0;  // a wall
            int q[3] = {idx[0], idx[1], idx[2]};
            q[a] = m;
            return u[q[0] + index_t(box.n(0)) * (q[1] + index_t(box.n(1)) * q[2])];
          };
          const double v = 0.5 * (face(idx[a]) + face(idx[a] - 1));
          out[((std::size_t(k) * n[1] + j) * n[0] + i) * 3 + a] = v;
        }
  }
  return out;
}

/// Device vector in component-major layout (x..., y..., z...) of m points -> m x 3 row-major.
std::vector<double> rows_of(const std::vector<double>& soa, std::size_t m) {
  std::vector<double> out(3 * m);
  for (std::size_t i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d) out[3 * i + d] = soa[d * m + i];
  return out;
}

}  // namespace

SnapshotWriter::SnapshotWriter(const std::string& dir, const sim::ImmersedBoundary& ib)
    : dir_(dir),
      probe_({ib.fluid().operators().component_box(0), ib.fluid().operators().component_box(1),
              ib.fluid().operators().component_box(2)},
             ib.interaction().kernel()) {
  std::filesystem::create_directories(dir_ + "/snapshots");
  const MacGrid& g = ib.fluid().grid();
  for (int d = 0; d < 3; ++d) {
    cells_[d] = g.cells[d];
    h_[d] = g.h(d);
  }
  for (index_t b = 0; b < ib.batches(); ++b) {
    const cells::Batch& batch = ib.batch(b);
    triangles_.push_back(surface::sphere_triangulation(batch.type().spec().sample_sites));
    batch_names_.push_back(batch.type().name());
    batch_points_.push_back(batch.type().n_sample() * batch.size());
    batch_triangles_.push_back(index_t(triangles_.back().size()) * batch.size());
  }
  for (index_t p = 0; p < ib.point_sets(); ++p) {
    point_names_.push_back(ib.points(p).name);
    point_counts_.push_back(index_t(ib.points(p).X.size()) / 3);
  }
}

void SnapshotWriter::resume(double t) {
  std::vector<std::pair<double, std::string>> found;
  const std::regex snapshot_name("snapshot_[0-9]+\\.h5");
  for (const auto& e : std::filesystem::directory_iterator(dir_ + "/snapshots")) {
    const std::string name = e.path().filename().string();
    if (!std::regex_match(name, snapshot_name)) continue;
    h5::Id f(H5Fopen(e.path().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    double ts = 0;
    if (!f.valid() || !h5::read_attribute(f, "t", H5T_NATIVE_DOUBLE, &ts)) continue;
    if (ts <= t * (1 + 1e-12)) found.push_back({ts, "snapshots/" + name});
  }
  std::sort(found.begin(), found.end());
  written_.clear();
  for (const auto& [ts, file] : found) written_.push_back({file, ts});
}

void SnapshotWriter::write(const sim::ImmersedBoundary& ib) {
  char name[64];
  std::snprintf(name, sizeof name, "snapshots/snapshot_%06zu.h5", written_.size());
  const std::string path = dir_ + "/" + name, tmp = path + ".tmp";
  {
    h5::Id file = h5::create_file(tmp);
    h5::attribute(file, "t", ib.time());
    h5::attribute(file, "step", ib.step_count());
    {
      h5::Id fluid = h5::create_group(file, "fluid");
      const std::vector<double> u = centred_velocity(ib);
      const std::vector<hsize_t> grid{hsize_t(cells_[2]), hsize_t(cells_[1]), hsize_t(cells_[0])};
      h5::write(fluid, "velocity", u.data(), {grid[0], grid[1], grid[2], 3}, "cm/s");
      const host_vector<double> p = ib.fluid_state().p;
      h5::write(fluid, "pressure", p.data(), grid, "dyn/cm^2");
    }
    h5::Id cells_group = h5::create_group(file, "cells");
    for (index_t b = 0; b < ib.batches(); ++b) {
      const cells::Batch& batch = ib.batch(b);
      const cells::CellType& type = batch.type();
      cells::CellForces forces;
      cells::compute_forces(batch, forces);
      const index_t ns = type.n_sample(), nd = type.n_data(), N = batch.size();
      const std::size_t m = std::size_t(ns * N);
      h5::Id g = h5::create_group(cells_group, std::to_string(b));
      h5::attribute(g, "type", type.name());
      const std::vector<double> X = forces.positions.to_host();  // n_s x 3N, column d N + c
      std::vector<double> soa(3 * m);
      for (index_t c = 0; c < N; ++c)
        for (int d = 0; d < 3; ++d)
          for (index_t i = 0; i < ns; ++i) soa[d * m + c * ns + i] = X[(d * N + c) * ns + i];
      const std::vector<double> points = rows_of(soa, m);
      h5::write(g, "points", points.data(), {m, 3}, "cm");
      std::vector<long long> tri;
      for (index_t c = 0; c < N; ++c)
        for (const auto& t : triangles_[b])
          for (int v = 0; v < 3; ++v) tri.push_back(t[v] + c * ns);
      h5::write(g, "triangles", tri.data(), {tri.size() / 3, 3});
      dvec U;
      probe_.interpolate(dvec(soa.begin(), soa.end()), ib.fluid_state().u, U);
      std::vector<double> Uh(U.size());
      thrust::copy(U.begin(), U.end(), Uh.begin());
      const std::vector<double> velocity = rows_of(Uh, m);
      h5::write(g, "velocity", velocity.data(), {m, 3}, "cm/s");
      const std::vector<double> F = forces.density.to_host();
      std::vector<double> magnitude(m), H(m);
      for (index_t c = 0; c < N; ++c)
        for (index_t i = 0; i < ns; ++i) {
          double s = 0;
          for (int d = 0; d < 3; ++d) s += F[(d * N + c) * ns + i] * F[(d * N + c) * ns + i];
          magnitude[c * ns + i] = std::sqrt(s);
        }
      const std::vector<double> state = batch.state().to_host();
      for (index_t c = 0; c < N; ++c) {
        std::vector<double> Xc(3 * nd);
        for (int d = 0; d < 3; ++d)
          for (index_t i = 0; i < nd; ++i) Xc[d * nd + i] = state[(d * N + c) * nd + i];
        const std::vector<surface::Jet> J = surface::jets_from_operators(type.to_sample(), Xc);
        for (index_t i = 0; i < ns; ++i) H[c * ns + i] = surface::point_geometry(J[i]).H;
      }
      h5::write(g, "force_density", magnitude.data(), {m}, "dyn/cm^2");
      h5::write(g, "mean_curvature", H.data(), {m}, "1/cm");
    }
    h5::Id points_group = h5::create_group(file, "points");
    for (index_t p = 0; p < index_t(point_counts_.size()); ++p) {
      h5::Id g = h5::create_group(points_group, std::to_string(p));
      h5::attribute(g, "name", point_names_[p]);
      const host_vector<double> Xp = ib.points(p).X;
      const std::vector<double> soa(Xp.begin(), Xp.end());
      const std::vector<double> rows = rows_of(soa, std::size_t(point_counts_[p]));
      h5::write(g, "points", rows.data(), {hsize_t(point_counts_[p]), 3}, "cm");
    }
    h5::flush_and_sync(file, tmp);
  }
  h5::replace(tmp, path);
  written_.push_back({name, ib.time()});
  write_xdmf();
}

void SnapshotWriter::write_xdmf() const {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<!-- The snapshots of one rbfib run (docs/output.md); open in ParaView. Units: CGS. -->\n"
    << "<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\"run\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string nx = std::to_string(cells_[0]), ny = std::to_string(cells_[1]), nz = std::to_string(cells_[2]);
  for (const Entry& e : written_) {
    auto item = [&](const std::string& dims, const std::string& path, const char* type = "Float") {
      return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type + "\" Precision=\"8\" Format=\"HDF\">" + e.file + ":" +
             path + "</DataItem>";
    };
    x << "   <Grid Name=\"snapshot\" GridType=\"Collection\" CollectionType=\"Spatial\">\n    <Time Value=\"" << e.t << "\"/>\n";
    x << "    <Grid Name=\"fluid\" GridType=\"Uniform\">\n     <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\""
      << cells_[2] + 1 << " " << cells_[1] + 1 << " " << cells_[0] + 1 << "\"/>\n"
      << "     <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n      <DataItem Dimensions=\"3\" Format=\"XML\">0 0 0</DataItem>\n"
      << "      <DataItem Dimensions=\"3\" Format=\"XML\">" << h_[2] << " " << h_[1] << " " << h_[0] << "</DataItem>\n     </Geometry>\n"
      << "     <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Cell\">" << item(nz + " " + ny + " " + nx + " 3", "/fluid/velocity")
      << "</Attribute>\n"
      << "     <Attribute Name=\"pressure\" AttributeType=\"Scalar\" Center=\"Cell\">" << item(nz + " " + ny + " " + nx, "/fluid/pressure")
      << "</Attribute>\n    </Grid>\n";
    for (std::size_t b = 0; b < batch_names_.size(); ++b) {
      const std::string g = "/cells/" + std::to_string(b), m = std::to_string(batch_points_[b]), t = std::to_string(batch_triangles_[b]);
      x << "    <Grid Name=\"" << batch_names_[b] << "\" GridType=\"Uniform\">\n     <Topology TopologyType=\"Triangle\" NumberOfElements=\""
        << t << "\">" << item(t + " 3", g + "/triangles", "Int") << "</Topology>\n     <Geometry GeometryType=\"XYZ\">"
        << item(m + " 3", g + "/points") << "</Geometry>\n"
        << "     <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">" << item(m + " 3", g + "/velocity") << "</Attribute>\n"
        << "     <Attribute Name=\"force_density\" AttributeType=\"Scalar\" Center=\"Node\">" << item(m, g + "/force_density")
        << "</Attribute>\n"
        << "     <Attribute Name=\"mean_curvature\" AttributeType=\"Scalar\" Center=\"Node\">" << item(m, g + "/mean_curvature")
        << "</Attribute>\n    </Grid>\n";
    }
    for (std::size_t p = 0; p < point_names_.size(); ++p) {
      const std::string n = std::to_string(point_counts_[p]);
      x << "    <Grid Name=\"" << point_names_[p] << "\" GridType=\"Uniform\">\n     <Topology TopologyType=\"Polyvertex\" NumberOfElements=\""
        << n << "\"/>\n     <Geometry GeometryType=\"XYZ\">" << item(n + " 3", "/points/" + std::to_string(p) + "/points")
        << "</Geometry>\n    </Grid>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  const std::string path = dir_ + "/run.xmf", tmp = path + ".tmp";
  std::ofstream(tmp) << x.str();
  std::filesystem::rename(tmp, path);
}

}  // namespace rbfib::io
