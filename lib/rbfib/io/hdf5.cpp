#include "rbfib/io/hdf5.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>

namespace rbfib::io::h5 {

namespace {
void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: " + what + " failed");
}

void fsync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw std::runtime_error("cannot open " + path + " to sync it");
  ::fsync(fd);
  ::close(fd);
}

void write_typed(hid_t where, const std::string& name, hid_t type, const void* data, const std::vector<hsize_t>& shape) {
  Id space(H5Screate_simple(int(shape.size()), shape.data(), nullptr), H5Sclose);
  Id set(H5Dcreate2(where, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!set.valid()) throw std::runtime_error("HDF5: cannot create dataset " + name);
  hsize_t n = 1;
  for (hsize_t s : shape) n *= s;
  if (n > 0) check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "writing " + name);
}

void scalar_attribute(hid_t where, const std::string& name, hid_t type, const void* value) {
  Id space(H5Screate(H5S_SCALAR), H5Sclose);
  Id a(H5Acreate2(where, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  check(H5Awrite(a, type, value), "writing attribute " + name);
}
}  // namespace

Id create_file(const std::string& path) {
  Id f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) throw std::runtime_error("cannot create the HDF5 file " + path);
  return f;
}

Id open_file(const std::string& path) {
  if (!std::filesystem::exists(path)) return Id(-1, H5Fclose);
  H5E_auto2_t handler;
  void* data;
  H5Eget_auto2(H5E_DEFAULT, &handler, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the caller's message, not HDF5's stack dump
  Id f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  H5Eset_auto2(H5E_DEFAULT, handler, data);
  return f;
}

Id create_group(hid_t where, const std::string& name) {
  Id g(H5Gcreate2(where, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) throw std::runtime_error("HDF5: cannot create group " + name);
  return g;
}

void write(hid_t where, const std::string& name, const double* data, const std::vector<hsize_t>& shape, const std::string& units) {
  write_typed(where, name, H5T_NATIVE_DOUBLE, data, shape);
  if (!units.empty()) {
    Id set(H5Dopen2(where, name.c_str(), H5P_DEFAULT), H5Dclose);
    attribute(set, "units", units);
  }
}

void write(hid_t where, const std::string& name, const long long* data, const std::vector<hsize_t>& shape) {
  write_typed(where, name, H5T_NATIVE_LLONG, data, shape);
}

void write_bytes(hid_t where, const std::string& name, const std::string& bytes) {
  write_typed(where, name, H5T_NATIVE_CHAR, bytes.data(), {hsize_t(bytes.size())});
}

void attribute(hid_t where, const std::string& name, double value) { scalar_attribute(where, name, H5T_NATIVE_DOUBLE, &value); }
void attribute(hid_t where, const std::string& name, long value) { scalar_attribute(where, name, H5T_NATIVE_LONG, &value); }
void attribute(hid_t where, const std::string& name, int value) { scalar_attribute(where, name, H5T_NATIVE_INT, &value); }
void attribute(hid_t where, const std::string& name, const std::string& value) {
  Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, value.size() + 1);
  scalar_attribute(where, name, type, value.c_str());
}

bool read_attribute(hid_t where, const std::string& name, hid_t type, void* value) {
  if (H5Aexists(where, name.c_str()) <= 0) return false;
  Id a(H5Aopen(where, name.c_str(), H5P_DEFAULT), H5Aclose);
  return a.valid() && H5Aread(a, type, value) >= 0;
}

bool read(hid_t where, const std::string& name, std::vector<double>& values) {
  if (H5Lexists(where, name.c_str(), H5P_DEFAULT) <= 0) return false;
  Id set(H5Dopen2(where, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.valid()) return false;
  Id space(H5Dget_space(set), H5Sclose);
  if (H5Sget_simple_extent_ndims(space) != 1) return false;
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  values.assign(n, 0.0);
  return n == 0 || H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
}

bool read_bytes(hid_t where, const std::string& name, std::string& bytes) {
  if (H5Lexists(where, name.c_str(), H5P_DEFAULT) <= 0) return false;
  Id set(H5Dopen2(where, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.valid()) return false;
  Id space(H5Dget_space(set), H5Sclose);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  bytes.assign(n, '\0');
  return n == 0 || H5Dread(set, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) >= 0;
}

bool read_attribute(hid_t where, const std::string& name, std::string& value) {
  if (H5Aexists(where, name.c_str()) <= 0) return false;
  Id a(H5Aopen(where, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.valid()) return false;
  Id type(H5Aget_type(a), H5Tclose);
  const std::size_t n = H5Tget_size(type);
  value.assign(n, '\0');
  if (H5Aread(a, type, value.data()) < 0) return false;
  value.resize(value.find('\0') == std::string::npos ? n : value.find('\0'));
  return true;
}

void flush_and_sync(hid_t file, const std::string& path) {
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flushing " + path);
  fsync_path(path, O_RDONLY);
}

void replace(const std::string& tmp, const std::string& path) {
  std::filesystem::rename(tmp, path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  fsync_path(dir.empty() ? "." : dir, O_RDONLY | O_DIRECTORY);
}

}  // namespace rbfib::io::h5
