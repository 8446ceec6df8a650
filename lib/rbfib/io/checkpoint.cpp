#include "rbfib/io/checkpoint.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/io/hdf5.hpp"

#include <hdf5.h>

#include <filesystem>
#include <vector>

namespace rbfib::io {

namespace {

constexpr const char* format = "rbfib checkpoint 2";
constexpr const char* format_1 = "rbfib checkpoint 1";  // no series, no run attributes

using h5::Id;

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {}
  [[noreturn]] void fail(const std::string& what) const { throw InputError("checkpoint " + path_, what, "missing or malformed"); }
  dvec array(hid_t where, const char* name) const {
    std::vector<double> h;
    if (!h5::read(where, name, h)) fail(name);
    return dvec(h.begin(), h.end());
  }
  std::string bytes(hid_t where, const char* name) const {
    std::string s;
    if (!h5::read_bytes(where, name, s)) fail(name);
    return s;
  }
  template <class T>
  T attribute(hid_t where, const char* name, hid_t type) const {
    T v{};
    if (!h5::read_attribute(where, name, type, &v)) fail(std::string("attribute ") + name);
    return v;
  }
  std::string string_attribute(hid_t where, const char* name) const {
    std::string s;
    if (!h5::read_attribute(where, name, s)) fail(std::string("attribute ") + name);
    return s;
  }

 private:
  std::string path_;
};

Cause cause_named(const std::string& name, const Reader& r) {
  for (Cause c : {Cause::stopping_condition, Cause::non_finite, Cause::degenerate_site, Cause::inverted_cell, Cause::solver})
    if (name == to_string(c)) return c;
  r.fail(std::string("attribute stop_cause: ").append(name));
}

RunStatus status_named(const std::string& name, const Reader& r) {
  for (RunStatus s : {RunStatus::running, RunStatus::finished, RunStatus::stopped})
    if (name == to_string(s)) return s;
  r.fail(std::string("attribute status: ").append(name));
}

std::string join_lines(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& c : v) s += c + "\n";
  return s;
}

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> v;
  std::size_t a = 0;
  for (std::size_t b; (b = s.find('\n', a)) != std::string::npos; a = b + 1) v.push_back(s.substr(a, b - a));
  return v;
}

}  // namespace

const char* to_string(RunStatus s) {
  switch (s) {
    case RunStatus::running: return "running";
    case RunStatus::finished: return "finished";
    case RunStatus::stopped: return "stopped";
  }
  return "unknown";
}

namespace {

/// The file itself (atomically: PATH.tmp, then renamed over PATH).
void write_file(const std::string& path, const std::string& scene_yaml, const sim::ImmersedBoundary::Carried& c,
                const RunRecord& record, bool keep_fluid) {
  if (!keep_fluid && record.status == RunStatus::running)
    throw InputError("checkpoint " + path, "without its fluid", "only a run that has ended may leave out its fluid: a running one continues from it");
  const std::string tmp = path + ".tmp";
  auto array = [](hid_t where, const std::string& name, const dvec& v) {
    const host_vector<double> h = v;
    h5::write(where, name, h.data(), {hsize_t(h.size())});
  };
  {
    Id file = h5::create_file(tmp);
    h5::attribute(file, "format", std::string(format));
    h5::attribute(file, "steps", c.clock.step);
    h5::attribute(file, "dt", c.clock.dt);
    h5::attribute(file, "level", c.clock.level);
    h5::attribute(file, "allowing", c.clock.allowing);
    h5::attribute(file, "cap", c.clock.cap);
    h5::attribute(file, "status", std::string(to_string(record.status)));
    h5::attribute(file, "stop_message", record.stop_message);
    h5::attribute(file, "stop_cause", std::string(to_string(record.stop_cause)));
    h5::attribute(file, "wall_seconds", record.wall_seconds);
    h5::attribute(file, "steps_timed", record.steps_timed);
    h5::attribute(file, "label", record.label);
    h5::write_bytes(file, "scene", scene_yaml);
    {
      Id series = h5::create_group(file, "series");
      for (const auto& [name, s] : record.series) {
        Id g = h5::create_group(series, name);
        h5::attribute(g, "columns", join_lines(s.columns));
        std::vector<double> values;
        std::vector<long long> widths;
        for (const std::vector<double>& row : s.rows) {
          values.insert(values.end(), row.begin(), row.end());
          widths.push_back((long long)row.size());
        }
        h5::write(g, "values", values.data(), {hsize_t(values.size())});
        h5::write(g, "widths", widths.data(), {hsize_t(widths.size())});
      }
    }
    {
      Id fluid = h5::create_group(file, "fluid");
      h5::attribute(fluid, "t", c.fluid.t);
      if (keep_fluid) {
        const char* u[3] = {"u0", "u1", "u2"};
        for (int a = 0; a < 3; ++a) array(fluid, u[a], c.fluid.u[a]);
        array(fluid, "p", c.fluid.p);
        array(fluid, "phi0", c.fluid.phi[0]);
        array(fluid, "phi1", c.fluid.phi[1]);
      }
    }
    {
      Id batches = h5::create_group(file, "batches");
      for (std::size_t b = 0; b < c.batches.size(); ++b) array(batches, std::to_string(b), c.batches[b]);
      Id points = h5::create_group(file, "points");
      for (std::size_t p = 0; p < c.points.size(); ++p) array(points, std::to_string(p), c.points[p]);
      Id shells = h5::create_group(file, "shells");
      for (std::size_t q = 0; q < c.shells.size(); ++q)
        h5::write(shells, std::to_string(q), c.shells[q].data(), {hsize_t(c.shells[q].size())});
      if (!c.cortices.empty()) {  // written only when there are any: other checkpoints stay as they were
        Id cortices = h5::create_group(file, "cortices");
        for (std::size_t q = 0; q < c.cortices.size(); ++q)
          h5::write(cortices, std::to_string(q), c.cortices[q].data(), {hsize_t(c.cortices[q].size())});
      }
    }
    h5::flush_and_sync(file, tmp);
  }
  h5::replace(tmp, path);
}

/// The scene, the clock, the run's attributes and whether the fluid's arrays are there.
CheckpointHeader read_header(const Reader& r, hid_t file) {
  const std::string version = r.string_attribute(file, "format");
  if (version != format && version != format_1) r.fail("format (expected '" + std::string(format) + "')");
  CheckpointHeader h;
  h.scene_yaml = r.bytes(file, "scene");
  h.clock.step = r.attribute<long>(file, "steps", H5T_NATIVE_LONG);
  h.clock.dt = r.attribute<double>(file, "dt", H5T_NATIVE_DOUBLE);
  h.clock.level = r.attribute<int>(file, "level", H5T_NATIVE_INT);
  h.clock.allowing = r.attribute<int>(file, "allowing", H5T_NATIVE_INT);
  // The growth guard's cap (written since the stability criterion; none in older checkpoints).
  h.clock.cap = H5Aexists(file, "cap") > 0 ? r.attribute<int>(file, "cap", H5T_NATIVE_INT) : -1;
  if (H5Lexists(file, "fluid", H5P_DEFAULT) <= 0) r.fail("fluid");
  {
    Id fluid{H5Gopen2(file, "fluid", H5P_DEFAULT), H5Gclose};
    h.clock.t = r.attribute<double>(fluid, "t", H5T_NATIVE_DOUBLE);
    h.fluid_kept = H5Lexists(fluid, "u0", H5P_DEFAULT) > 0;
  }
  if (version == format_1) {
    if (!h.fluid_kept) r.fail("fluid/u0");
    return h;
  }
  h.record.status = status_named(r.string_attribute(file, "status"), r);
  h.record.stop_message = r.string_attribute(file, "stop_message");
  h.record.stop_cause = cause_named(r.string_attribute(file, "stop_cause"), r);
  h.record.wall_seconds = r.attribute<double>(file, "wall_seconds", H5T_NATIVE_DOUBLE);
  h.record.steps_timed = r.attribute<long>(file, "steps_timed", H5T_NATIVE_LONG);
  h.record.label = r.string_attribute(file, "label");
  if (!h.fluid_kept && h.record.status == RunStatus::running) r.fail("fluid/u0 (a running run continues from its fluid)");
  return h;
}

Id open_checkpoint(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError("checkpoint", path, "does not exist");
  Id file = h5::open_file(path);
  if (!file.valid()) throw InputError("checkpoint", path, "is not a readable HDF5 file");
  return file;
}

}  // namespace

void write_checkpoint(const std::string& path, const std::string& scene_yaml, const sim::ImmersedBoundary& ib,
                      const RunRecord& record, bool keep_fluid) {
  const sim::ImmersedBoundary::Carried c = ib.carried();  // on a split fluid: the whole run's, on every process
  if (const FluidDecomposition* parts = ib.fluid().parts(); parts && parts->process() != 0) return;  // process 0 writes
  write_file(path, scene_yaml, c, record, keep_fluid);
}

CheckpointHeader read_checkpoint_header(const std::string& path) {
  const Reader r(path);
  const Id file = open_checkpoint(path);
  return read_header(r, file);
}

Checkpoint read_checkpoint(const std::string& path) {
  const Reader r(path);
  const Id file = open_checkpoint(path);
  CheckpointHeader h = read_header(r, file);
  Checkpoint k;
  k.scene_yaml = std::move(h.scene_yaml);
  k.state.clock = h.clock;
  k.record = std::move(h.record);
  k.fluid_kept = h.fluid_kept;
  k.state.fluid.t = h.clock.t;
  if (k.fluid_kept) {
    Id fluid{H5Gopen2(file, "fluid", H5P_DEFAULT), H5Gclose};
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
  // Absent: none (shells before LDSM shells joined the step; cortices unless a scene has one).
  for (const char* group : {"shells", "cortices"}) {
    if (H5Lexists(file, group, H5P_DEFAULT) <= 0) continue;
    Id g{H5Gopen2(file, group, H5P_DEFAULT), H5Gclose};
    H5G_info_t info;
    H5Gget_info(g, &info);
    auto& into = std::string(group) == "shells" ? k.state.shells : k.state.cortices;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const dvec x = r.array(g, std::to_string(i).c_str());
      into.emplace_back(x.begin(), x.end());
    }
  }
  if (H5Lexists(file, "series", H5P_DEFAULT) <= 0) {
    if (r.string_attribute(file, "format") == format_1) return k;  // format 1: no series
    r.fail("series");
  }
  Id series{H5Gopen2(file, "series", H5P_DEFAULT), H5Gclose};
  H5G_info_t info;
  H5Gget_info(series, &info);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256];
    if (H5Lget_name_by_idx(series, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT) < 0) r.fail("series names");
    Id g{H5Gopen2(series, name, H5P_DEFAULT), H5Gclose};
    Series& s = k.record.series[name];
    s.columns = split_lines(r.string_attribute(g, "columns"));
    const dvec values = r.array(g, "values"), widths = r.array(g, "widths");
    const host_vector<double> v = values, w = widths;
    std::size_t at = 0;
    for (double width : w) {
      const auto n = static_cast<std::size_t>(width);
      if (width < 0 || at + n > v.size()) r.fail(std::string("series ") + name + " (widths)");
      s.rows.emplace_back(v.begin() + std::ptrdiff_t(at), v.begin() + std::ptrdiff_t(at + n));
      at += n;
    }
    if (at != v.size()) r.fail(std::string("series ") + name + " (widths)");
  }
  return k;
}

bool slim_checkpoint(const std::string& path) {
  const Checkpoint k = read_checkpoint(path);
  if (!k.fluid_kept) return false;
  write_file(path, k.scene_yaml, k.state, k.record, false);
  return true;
}

scene::StartingState read_starting_state(const scene::Scene& s) {
  Checkpoint k = read_checkpoint(s.start.checkpoint);
  if (!k.fluid_kept)
    throw InputError("start checkpoint", s.start.checkpoint, "keeps no fluid (an ended run's, written without it): a scene starts from the fluid too");
  const scene::Scene from = scene::parse_scene(k.scene_yaml, s.start.checkpoint);
  scene::StartingState start;
  start.state = std::move(k.state);
  start.batch_types = scene::batch_types(from);
  start.cells = from.grid.cells;
  return start;
}

sim::ImmersedBoundary build_scene(const scene::Scene& s, std::shared_ptr<const FluidDecomposition> parts) {
  if (s.start.checkpoint.empty()) return scene::build(s, nullptr, std::move(parts));
  const scene::StartingState start = read_starting_state(s);
  return scene::build(s, &start, std::move(parts));
}

}  // namespace rbfib::io
