#include "rbfib/scene/checkpoint.hpp"

#include "rbfib/core/error.hpp"

#include <hdf5.h>

#include <cstdio>
#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

namespace rbfib::scene {

namespace {

constexpr const char* format = "rbfib checkpoint 1";

/// An HDF5 identifier closed on scope exit.
struct Id {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Id() {
    if (id >= 0) close(id);
  }
  operator hid_t() const { return id; }
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: " + what + " failed");
}

void write_array(hid_t where, const char* name, const dvec& v) {
  const host_vector<double> h = v;
  const hsize_t n = h.size();
  Id space{H5Screate_simple(1, &n, nullptr), H5Sclose};
  Id set{H5Dcreate2(where, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose};
  if (set < 0) throw std::runtime_error(std::string("HDF5: cannot create ") + name);
  if (n > 0) check(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, h.data()), std::string("writing ") + name);
}

template <class T>
void write_attribute(hid_t where, const char* name, hid_t type, const T& value) {
  Id space{H5Screate(H5S_SCALAR), H5Sclose};
  Id a{H5Acreate2(where, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  check(H5Awrite(a, type, &value), std::string("writing attribute ") + name);
}

void write_string_attribute(hid_t where, const char* name, const std::string& text) {
  Id type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type, text.size() + 1);
  Id space{H5Screate(H5S_SCALAR), H5Sclose};
  Id a{H5Acreate2(where, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  check(H5Awrite(a, type, text.c_str()), std::string("writing attribute ") + name);
}

void write_bytes(hid_t where, const char* name, const std::string& text) {
  const hsize_t n = text.size();
  Id space{H5Screate_simple(1, &n, nullptr), H5Sclose};
  Id set{H5Dcreate2(where, name, H5T_NATIVE_CHAR, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose};
  if (n > 0) check(H5Dwrite(set, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()), std::string("writing ") + name);
}

void fsync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw std::runtime_error("cannot open " + path + " to sync it");
  ::fsync(fd);
  ::close(fd);
}

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {}
  [[noreturn]] void fail(const std::string& what) const { throw InputError("checkpoint " + path_, what, "missing or malformed"); }
  dvec array(hid_t where, const char* name) const {
    if (H5Lexists(where, name, H5P_DEFAULT) <= 0) fail(name);
    Id set{H5Dopen2(where, name, H5P_DEFAULT), H5Dclose};
    Id space{H5Dget_space(set), H5Sclose};
    if (H5Sget_simple_extent_ndims(space) != 1) fail(name);
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space, &n, nullptr);
    std::vector<double> h(n);
    if (n > 0 && H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, h.data()) < 0) fail(name);
    return dvec(h.begin(), h.end());
  }
  std::string bytes(hid_t where, const char* name) const {
    if (H5Lexists(where, name, H5P_DEFAULT) <= 0) fail(name);
    Id set{H5Dopen2(where, name, H5P_DEFAULT), H5Dclose};
    Id space{H5Dget_space(set), H5Sclose};
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space, &n, nullptr);
    std::string s(n, '\0');
    if (n > 0 && H5Dread(set, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, s.data()) < 0) fail(name);
    return s;
  }
  template <class T>
  T attribute(hid_t where, const char* name, hid_t type) const {
    if (H5Aexists(where, name) <= 0) fail(std::string("attribute ") + name);
    Id a{H5Aopen(where, name, H5P_DEFAULT), H5Aclose};
    T v{};
    if (H5Aread(a, type, &v) < 0) fail(std::string("attribute ") + name);
    return v;
  }
  std::string string_attribute(hid_t where, const char* name) const {
    if (H5Aexists(where, name) <= 0) fail(std::string("attribute ") + name);
    Id a{H5Aopen(where, name, H5P_DEFAULT), H5Aclose};
    Id type{H5Aget_type(a), H5Tclose};
    const std::size_t n = H5Tget_size(type);
    std::string s(n, '\0');
    if (H5Aread(a, type, s.data()) < 0) fail(std::string("attribute ") + name);
    s.resize(s.find('\0') == std::string::npos ? n : s.find('\0'));
    return s;
  }

 private:
  std::string path_;
};

}  // namespace

void write_checkpoint(const std::string& path, const std::string& scene_yaml, const sim::ImmersedBoundary& ib) {
  const sim::ImmersedBoundary::Carried c = ib.carried();
  const std::string tmp = path + ".tmp";
  {
    Id file{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose};
    if (file < 0) throw std::runtime_error("cannot create " + tmp);
    write_string_attribute(file, "format", format);
    write_attribute(file, "steps", H5T_NATIVE_LONG, c.steps);
    write_attribute(file, "dt", H5T_NATIVE_DOUBLE, c.dt);
    write_attribute(file, "level", H5T_NATIVE_INT, c.level);
    write_attribute(file, "allowing", H5T_NATIVE_INT, c.allowing);
    write_bytes(file, "scene", scene_yaml);
    {
      Id fluid{H5Gcreate2(file, "fluid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
      write_attribute(fluid, "t", H5T_NATIVE_DOUBLE, c.fluid.t);
      const char* u[3] = {"u0", "u1", "u2"};
      for (int a = 0; a < 3; ++a) write_array(fluid, u[a], c.fluid.u[a]);
      write_array(fluid, "p", c.fluid.p);
      write_array(fluid, "phi0", c.fluid.phi[0]);
      write_array(fluid, "phi1", c.fluid.phi[1]);
    }
    {
      Id batches{H5Gcreate2(file, "batches", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
      for (std::size_t b = 0; b < c.batches.size(); ++b) write_array(batches, std::to_string(b).c_str(), c.batches[b]);
      Id points{H5Gcreate2(file, "points", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
      for (std::size_t p = 0; p < c.points.size(); ++p) write_array(points, std::to_string(p).c_str(), c.points[p]);
    }
    check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flushing " + tmp);
  }
  fsync_path(tmp, O_RDONLY);
  std::filesystem::rename(tmp, path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  fsync_path(dir.empty() ? "." : dir, O_RDONLY | O_DIRECTORY);
}

Checkpoint read_checkpoint(const std::string& path) {
  const Reader r(path);
  if (!std::filesystem::exists(path)) throw InputError("checkpoint", path, "does not exist");
  H5E_auto2_t handler;
  void* data;
  H5Eget_auto2(H5E_DEFAULT, &handler, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // our messages, not HDF5's stack dumps
  Id file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  H5Eset_auto2(H5E_DEFAULT, handler, data);
  if (file < 0) throw InputError("checkpoint", path, "is not a readable HDF5 file");
  if (r.string_attribute(file, "format") != format) r.fail("format (expected '" + std::string(format) + "')");
  Checkpoint k;
  k.scene_yaml = r.bytes(file, "scene");
  k.state.steps = r.attribute<long>(file, "steps", H5T_NATIVE_LONG);
  k.state.dt = r.attribute<double>(file, "dt", H5T_NATIVE_DOUBLE);
  k.state.level = r.attribute<int>(file, "level", H5T_NATIVE_INT);
  k.state.allowing = r.attribute<int>(file, "allowing", H5T_NATIVE_INT);
  {
    if (H5Lexists(file, "fluid", H5P_DEFAULT) <= 0) r.fail("fluid");
    Id fluid{H5Gopen2(file, "fluid", H5P_DEFAULT), H5Gclose};
    k.state.fluid.t = r.attribute<double>(fluid, "t", H5T_NATIVE_DOUBLE);
    const char* u[3] = {"u0", "u1", "u2"};
    for (int a = 0; a < 3; ++a) k.state.fluid.u[a] = r.array(fluid, u[a]);
    k.state.fluid.p = r.array(fluid, "p");
    k.state.fluid.phi[0] = r.array(fluid, "phi0");
    k.state.fluid.phi[1] = r.array(fluid, "phi1");
  }
  for (const char* group : {"batches", "points"}) {
    if (H5Lexists(file, group, H5P_DEFAULT) <= 0) r.fail(group);
    Id g{H5Gopen2(file, group, H5P_DEFAULT), H5Gclose};
    H5G_info_t info;
    H5Gget_info(g, &info);
    auto& into = std::string(group) == "batches" ? k.state.batches : k.state.points;
    for (hsize_t i = 0; i < info.nlinks; ++i) into.push_back(r.array(g, std::to_string(i).c_str()));
  }
  return k;
}

}  // namespace rbfib::scene
