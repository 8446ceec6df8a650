#pragma once
// A thin layer over the HDF5 C API for the files of scene/ (checkpoints, snapshots): identifiers
// closed on scope exit, datasets written from host arrays with their shape and units, scalar
// attributes. Errors throw std::runtime_error naming what failed.
#include <hdf5.h>

#include <string>
#include <vector>

namespace rbfib::io::h5 {

/// An HDF5 identifier closed on scope exit.
class Id {
 public:
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Id(Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id& operator=(Id&&) = delete;
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

Id create_file(const std::string& path);
/// Opens an existing file for reading; an invalid Id (no HDF5 error stack printed) when it is
/// missing or not HDF5.
Id open_file(const std::string& path);
Id create_group(hid_t where, const std::string& name);

/// A dataset of doubles (or 64-bit integers) of the given shape (row-major, last index fastest),
/// with a "units" attribute unless units is empty.
void write(hid_t where, const std::string& name, const double* data, const std::vector<hsize_t>& shape,
           const std::string& units = "");
void write(hid_t where, const std::string& name, const long long* data, const std::vector<hsize_t>& shape);
void write_bytes(hid_t where, const std::string& name, const std::string& bytes);

void attribute(hid_t where, const std::string& name, double value);
void attribute(hid_t where, const std::string& name, long value);
void attribute(hid_t where, const std::string& name, int value);
void attribute(hid_t where, const std::string& name, const std::string& value);

/// Reads a scalar attribute of the given type into value; false if it is missing or unreadable
/// (checked first, so HDF5 prints no error stack).
bool read_attribute(hid_t where, const std::string& name, hid_t type, void* value);

/// Reads a one-dimensional dataset of doubles, a dataset of bytes, a string attribute; false if it
/// is missing or malformed (checked first, so HDF5 prints no error stack).
bool read(hid_t where, const std::string& name, std::vector<double>& values);
bool read_bytes(hid_t where, const std::string& name, std::string& bytes);
bool read_attribute(hid_t where, const std::string& name, std::string& value);

/// Flushes the file, then fsyncs path.
void flush_and_sync(hid_t file, const std::string& path);
/// Renames tmp over path and fsyncs the directory: the atomic replacement of a file.
void replace(const std::string& tmp, const std::string& path);

}  // namespace rbfib::io::h5
