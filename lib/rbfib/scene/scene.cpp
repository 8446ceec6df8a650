#include "rbfib/scene/scene.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/core/quantity.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/grid/box.hpp"
#include "rbfib/ib/kernels.hpp"
#include "rbfib/surface/contact.hpp"
#include "rbfib/surface/point_sets.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace rbfib::scene {

namespace {


/// A type's reference shape at its data sites, n x 3 column-major (cm), without building it.
std::vector<double> reference_sites(const CellTypeEntry& t) {
  const surface::SphereSites& z = t.spec.data_sites;
  std::vector<double> r(static_cast<std::size_t>(3 * z.size()));
  for (index_t i = 0; i < z.size(); ++i) {
    double x[3];
    t.spec.shape.position(z.lambda[i], z.theta[i], x);
    for (int d = 0; d < 3; ++d) r[std::size_t(d * z.size() + i)] = x[d];
  }
  return r;
}

const char* axis_name[3] = {"x", "y", "z"};

/// One YAML map being read: every key must be read, or finish() reports it as unknown; every
/// value is checked for type, dimension and range, and errors name the path of the field.
class Fields {
 public:
  Fields(YAML::Node node, std::string path) : node_(std::move(node)), path_(std::move(path)) {
    if (!node_.IsMap()) throw InputError(path_.empty() ? "scene" : path_, text(node_), "expected a map of keys and values");
  }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& path() const { return path_; }
  bool has(const std::string& key) const { return bool(node_[key]); }

  YAML::Node get(const std::string& key) const {
    read_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) throw InputError(at(key), "(missing)", "required");
    return n;
  }
  Fields map(const std::string& key) const { return Fields(get(key), at(key)); }
  std::vector<Fields> list_of_maps(const std::string& key) const {
    const YAML::Node n = get(key);
    if (!n.IsSequence()) throw InputError(at(key), text(n), "expected a list");
    std::vector<Fields> out;
    for (std::size_t i = 0; i < n.size(); ++i) out.emplace_back(n[i], at(key) + "[" + std::to_string(i) + "]");
    return out;
  }
  std::string string(const std::string& key) const { return scalar(get(key), at(key)); }
  std::string choice(const std::string& key, const std::vector<std::string>& options) const {
    const std::string v = string(key);
    if (std::find(options.begin(), options.end(), v) == options.end()) {
      std::string list;
      for (const auto& o : options) list += (list.empty() ? "" : ", ") + o;
      throw InputError(at(key), v, "must be one of: " + list);
    }
    return v;
  }
  double quantity(const std::string& key, const std::string& unit) const {
    return parse_quantity(scalar(get(key), at(key)), unit, at(key));
  }
  double positive(const std::string& key, const std::string& unit) const {
    const double v = quantity(key, unit);
    if (!(v > 0)) throw InputError(at(key), scalar(node_[key], at(key)), "must be positive");
    return v;
  }
  double nonnegative(const std::string& key, const std::string& unit) const {
    const double v = quantity(key, unit);
    if (!(v >= 0)) throw InputError(at(key), scalar(node_[key], at(key)), "must be >= 0");
    return v;
  }
  std::array<double, 3> triple(const std::string& key, const std::string& unit) const {
    const YAML::Node n = get(key);
    if (!n.IsSequence() || n.size() != 3) throw InputError(at(key), text(n), "expected a list of 3 values");
    std::array<double, 3> v{};
    for (int d = 0; d < 3; ++d) {
      const std::string f = at(key) + "[" + std::to_string(d) + "]";
      v[d] = parse_quantity(scalar(n[d], f), unit, f);
    }
    return v;
  }
  long integer(const std::string& key, long lo, long hi) const {
    const std::string v = scalar(get(key), at(key));
    const long x = to_integer(v, at(key));
    if (x < lo || x > hi) throw InputError(at(key), v, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return x;
  }
  /// A list of `count` integers, each in [lo, hi].
  std::vector<long> integers(const std::string& key, std::size_t count, long lo, long hi) const {
    const YAML::Node n = get(key);
    if (!n.IsSequence() || n.size() != count)
      throw InputError(at(key), text(n), "expected a list of " + std::to_string(count) + " integers");
    std::vector<long> out;
    for (std::size_t i = 0; i < count; ++i) {
      const std::string field = at(key) + "[" + std::to_string(i) + "]";
      const std::string v = scalar(n[i], field);
      const long x = to_integer(v, field);
      if (x < lo || x > hi) throw InputError(field, v, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      out.push_back(x);
    }
    return out;
  }
  static long to_integer(const std::string& v, const std::string& field) {
    char* end = nullptr;
    const long x = std::strtol(v.c_str(), &end, 10);
    if (end == v.c_str() || *end != '\0') throw InputError(field, v, "expected an integer");
    return x;
  }
  /// Throws naming the first key that was never read.
  void finish() const {
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) throw InputError(path_.empty() ? "scene" : path_, text(kv.first), "a key must be a name");
      const std::string k = kv.first.Scalar();
      if (!read_.count(k)) throw InputError(at(k), text(kv.second), "unknown key here");
    }
  }

  static std::string text(const YAML::Node& n) {
    if (n.IsScalar()) return n.Scalar();
    std::ostringstream s;
    s << YAML::Dump(n);
    std::string t = s.str();
    std::replace(t.begin(), t.end(), '\n', ' ');
    return t.size() > 60 ? t.substr(0, 57) + "..." : t;
  }
  static std::string scalar(const YAML::Node& n, const std::string& field) {
    if (!n.IsScalar()) throw InputError(field, text(n), "expected a single value");
    return n.Scalar();
  }

 private:
  YAML::Node node_;
  std::string path_;
  mutable std::set<std::string> read_;
};

void read_domain(const Fields& f, Scene& s) {
  const std::array<double, 3> L = f.triple("size", "um");
  for (int d = 0; d < 3; ++d)
    if (!(L[d] > 0)) throw InputError(f.at("size") + "[" + std::to_string(d) + "]", to_text(L[d] / units::um) + " um", "must be positive");
  std::array<bool, 3> periodic{false, false, false};
  const YAML::Node p = f.get("periodic");
  if (!p.IsSequence()) throw InputError(f.at("periodic"), Fields::text(p), "expected a list of axis names, e.g. [x, z]");
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::string field = f.at("periodic") + "[" + std::to_string(i) + "]";
    const std::string a = Fields::scalar(p[i], field);
    const auto it = std::find(axis_name, axis_name + 3, a);
    if (it == axis_name + 3) throw InputError(field, a, "must be an axis name: x, y or z");
    periodic[it - axis_name] = true;
  }
  bool any_wall = false;
  for (int d = 0; d < 3; ++d) any_wall = any_wall || !periodic[d];
  if (any_wall) {
    const Fields walls = f.map("walls");
    for (int d = 0; d < 3; ++d) {
      if (periodic[d]) continue;
      const Fields w = walls.map(axis_name[d]);
      for (int side = 0; side < 2; ++side) {
        const char* key = side ? "upper" : "lower";
        WallMotion& m = s.walls[d][side];
        m.axis = d;
        if (w.has(key) && w.get(key).IsMap()) {
          const Fields t = w.map(key);
          m.turning = true;
          m.speed = t.nonnegative("speed", "cm/s");
          const Fields turn = t.map("turn");
          m.from = turn.quantity("from", "");
          m.to = turn.quantity("to", "");
          m.over = turn.positive("over", "s");
          turn.finish();
          t.finish();
          continue;
        }
        m.velocity = w.triple(key, "cm/s");
        if (m.velocity[d] != 0)
          throw InputError(w.at(key) + "[" + std::to_string(d) + "]", to_text(m.velocity[d]) + " cm/s",
                           "a wall moves in its own plane: its normal velocity must be 0");
      }
      w.finish();
    }
    walls.finish();
  }
  if (f.has("initial_flow")) s.initial_shear = f.choice("initial_flow", {"rest", "shear"}) == "shear";
  if (s.initial_shear && !any_wall) throw InputError(f.at("initial_flow"), "shear", "needs walls to shear between");
  s.grid.length = L;
  for (int d = 0; d < 3; ++d) s.grid.lower[d] = s.grid.upper[d] = periodic[d] ? MacBoundary::periodic : MacBoundary::dirichlet;
  f.finish();
}

void read_grid(const Fields& f, Scene& s) {
  if (f.has("h") == f.has("cells"))
    throw InputError(f.at("h"), f.has("h") ? "(with grid.cells)" : "(missing, and no grid.cells)", "give exactly one of grid.h and grid.cells");
  for (int d = 0; d < 3; ++d) {
    int n = 0;
    if (f.has("h")) {
      const double h = f.positive("h", "um");
      const double c = s.grid.length[d] / h;
      n = int(std::lround(c));
      if (std::abs(c - n) > 1e-9 * c)
        throw InputError(f.at("h"), to_text(h / units::um) + " um",
                         "must divide the box: " + std::string(axis_name[d]) + " length / h = " + to_text(c) + " is not an integer");
    } else {
      n = int(f.integers("cells", 3, -1000000, 1000000)[d]);
    }
    if (n < MacGrid::min_cells || n > 4096)
      throw InputError(f.at(f.has("h") ? "h" : "cells"), to_text(n) + " cells along " + axis_name[d],
                       "each axis needs between " + to_text(MacGrid::min_cells) + " and 4096 cells");
    s.grid.cells[d] = n;
  }
  s.grid.dims = 3;
  f.finish();
}

void read_time(const Fields& f, Scene& s) {
  const std::string integrator = f.choice("integrator", {"backward_forward_euler", "peskin_two_stage"});
  s.fluid_options.integrator =
      integrator == "peskin_two_stage" ? TimeIntegrator::peskin_two_stage : TimeIntegrator::backward_forward_euler;
  if (f.has("coupling")) s.ib.coupling = f.choice("coupling", {"seed", "midpoint"}) == "midpoint" ? sim::Coupling::midpoint : sim::Coupling::seed;
  if (s.ib.coupling == sim::Coupling::midpoint && s.fluid_options.integrator != TimeIntegrator::peskin_two_stage)
    throw InputError(f.at("coupling"), "midpoint", "needs time.integrator = peskin_two_stage");
  s.fluid_options.dt = f.positive("dt", "s");
  s.t_end = f.positive("end", "s");
  if (s.t_end < s.fluid_options.dt)
    throw InputError(f.at("end"), to_text(s.t_end) + " s", "must be at least one step (dt = " + to_text(s.fluid_options.dt) + " s)");
  // Eq. 5.4 as a stop condition (on by default); off only for studies of the coupling's stability
  // (a non-finite force or velocity and an inverted cell still stop the run).
  if (f.has("stopping_condition")) s.ib.stopping_condition = f.choice("stopping_condition", {"eq54", "off"}) == "eq54";
  if (f.has("adaptive")) {
    const Fields a = f.map("adaptive");
    s.ib.adaptive.enabled = true;
    s.ib.adaptive.dt_min = a.positive("dt_min", "s");
    s.ib.adaptive.max_level = int(a.integer("max_level", 0, 30));
    sim::AdaptiveStep& A = s.ib.adaptive;
    if (a.has("criterion"))
      A.criterion = a.choice("criterion", {"inertial", "stability"}) == "stability" ? sim::StepCriterion::stability : sim::StepCriterion::inertial;
    const bool stability = A.criterion == sim::StepCriterion::stability;
    A.grow_after = a.has("grow_after") ? int(a.integer("grow_after", 1, 1000000)) : stability ? 4 : 16;
    if (a.has("ratio")) {
      A.ratio = a.quantity("ratio", "");
      if (!(A.ratio > 1 && A.ratio <= 2)) throw InputError(a.at("ratio"), to_text(A.ratio), "must lie in (1, 2]");
    }
    if (a.has("guard_growth")) {
      if (!stability) throw InputError(a.at("guard_growth"), "given", "the growth guard belongs to criterion: stability");
      A.guard_growth = a.quantity("guard_growth", "");
      if (!(A.guard_growth >= 1)) throw InputError(a.at("guard_growth"), to_text(A.guard_growth), "must be at least 1");
    }
    if (a.has("guard_steps")) {
      if (!stability) throw InputError(a.at("guard_steps"), "given", "the growth guard belongs to criterion: stability");
      A.guard_steps = int(a.integer("guard_steps", 1, 1000));
    }
    const double k = std::log(s.fluid_options.dt / A.dt_min) / std::log(A.ratio);
    if (std::abs(k - std::round(k)) > 1e-9 || k < -1e-9 || k > A.max_level + 1e-9)
      throw InputError(f.at("dt"), to_text(s.fluid_options.dt) + " s",
                       "with the adaptive step, dt must be ratio^k dt_min (ratio " + to_text(A.ratio) + ") with k in [0, max_level]");
    a.finish();
  }
  f.finish();
}

void read_ib(const Fields& f, Scene& s) {
  const std::vector<std::string> kernels = ib::kernel_names();
  s.ib.kernel = ib::kernel_named(f.choice("kernel", kernels), f.at("kernel"));
  const int support = ib::kernel_support(s.ib.kernel);
  for (int d = 0; d < 3; ++d)
    if (s.grid.cells[d] < support + 1)
      throw InputError(f.at("kernel"), ib::to_string(s.ib.kernel),
                       "spans " + to_text(support) + " cells, more than the grid's " + to_text(s.grid.cells[d]) + " along " +
                           axis_name[d] + " allow (at least support + 1)");
  if (f.has("body_force")) s.ib.body_force = f.triple("body_force", "dyn/cm^3");
  f.finish();
}

cells::ForceModel read_model(const Fields& f) {
  cells::ForceModel m;
  if (f.has("elastic")) {
    for (const Fields& e : f.list_of_maps("elastic")) {
      const std::string law = e.choice("law", {"skalak", "neo_hookean", "neo_hookean_paper", "tension"});
      if (law == "skalak") m.elastic.push_back(mechanics::EnergyDensity::skalak(e.positive("E", "dyn/cm"), e.positive("G", "dyn/cm")));
      if (law == "neo_hookean")
        m.elastic.push_back(mechanics::EnergyDensity::neo_hookean_dissertation(e.positive("E", "dyn/cm"), e.positive("G", "dyn/cm")));
      if (law == "neo_hookean_paper")
        m.elastic.push_back(mechanics::EnergyDensity::neo_hookean_paper(e.positive("Gs", "dyn/cm"), e.positive("A", "")));
      if (law == "tension") m.elastic.push_back(mechanics::EnergyDensity::surface_tension(e.positive("sigma", "dyn/cm")));
      e.finish();
    }
    if (int(m.elastic.size()) > cells::ForceModel::max_elastic_energies)
      throw InputError(f.at("elastic"), to_text(m.elastic.size()) + " energies",
                       "at most " + to_text(cells::ForceModel::max_elastic_energies));
  }
  if (f.has("kappa")) m.kappa = f.nonnegative("kappa", "erg");
  if (f.has("H0")) {
    const std::string v = f.string("H0");
    if (v == "reference") m.H0_reference = true;
    else m.H0 = parse_quantity(v, "1/cm", f.at("H0"));
  }
  if (f.has("nu")) m.nu = f.nonnegative("nu", "dyn s/cm");
  f.finish();
  return m;
}

CellTypeEntry read_type(const Fields& f) {
  const std::string preset = f.choice("preset", {"red_cell", "platelet", "skalak_sphere", "chapter3_red_cell"});
  auto sites = [&](const char* key) { return f.has(key) ? index_t(f.integer(key, 16, 200000)) : index_t(0); };
  const index_t data = preset == "chapter3_red_cell" ? 0 : sites("data_sites"), sample = sites("sample_sites");
  const double radius = preset == "skalak_sphere" ? f.positive("radius", "um") : 0.0;
  const int degree = preset == "chapter3_red_cell" && f.has("degree") ? int(f.integer("degree", 1, 40)) : 19;
  CellTypeEntry t = cell_type(f.string("name"), preset, data, sample, radius, degree);
  if (f.has("model")) t.spec.model = read_model(f.map("model"));
  if (f.has("products")) t.spec.single_precision_products = f.choice("products", {"double", "single"}) == "single";
  f.finish();
  return t;
}

CellEntry read_cell(const Fields& f, const Scene& s) {
  CellEntry c;
  c.type = f.string("type");
  const bool known = std::any_of(s.types.begin(), s.types.end(), [&](const CellTypeEntry& t) { return t.spec.name == c.type; });
  if (!known) throw InputError(f.at("type"), c.type, "is not the name of an entry of cell_types");
  c.placement.center = f.triple("center", "um");
  for (int d = 0; d < 3; ++d) {
    const double x = c.placement.center[d], L = s.grid.length[d];
    if (!s.grid.periodic(d) && !(x > 0 && x < L))
      throw InputError(f.at("center") + "[" + std::to_string(d) + "]", to_text(x / units::um) + " um",
                       "lies outside the walls (0, " + to_text(L / units::um) + " um)");
  }
  if (f.has("axis")) {
    c.placement.axis = f.triple("axis", "");
    const double n = std::hypot(c.placement.axis[0], c.placement.axis[1], c.placement.axis[2]);
    if (!(n > 0)) throw InputError(f.at("axis"), "[0, 0, 0]", "a rotation axis must be nonzero");
  }
  if (f.has("angle")) c.placement.angle = f.quantity("angle", "");
  if (f.has("stretch")) {
    c.placement.stretch = f.triple("stretch", "");
    for (int d = 0; d < 3; ++d)
      if (!(c.placement.stretch[d] > 0.1 && c.placement.stretch[d] < 10))
        throw InputError(f.at("stretch") + "[" + std::to_string(d) + "]", to_text(c.placement.stretch[d]), "must lie in (0.1, 10)");
  }
  if (f.has("force")) c.force = f.triple("force", "dyn");
  // The placed reference shape at the type's data sites must lie between the walls.
  const CellTypeEntry& t = *std::find_if(s.types.begin(), s.types.end(), [&](const CellTypeEntry& e) { return e.spec.name == c.type; });
  const index_t n = t.spec.data_sites.size();
  const std::vector<double> X = cells::placed(reference_sites(t), n, c.placement, f.path());
  for (int d = 0; d < 3; ++d) {
    if (s.grid.periodic(d)) continue;
    for (index_t i = 0; i < n; ++i)
      if (!(X[d * n + i] > 0 && X[d * n + i] < s.grid.length[d]))
        throw InputError(f.path(), "a cell of type '" + c.type + "' at [" + to_text(c.placement.center[0] / units::um) + ", " +
                                       to_text(c.placement.center[1] / units::um) + ", " + to_text(c.placement.center[2] / units::um) + "] um",
                         std::string("reaches through a wall: its surface crosses ") + axis_name[d] + " = 0 or " +
                             to_text(s.grid.length[d] / units::um) + " um");
  }
  f.finish();
  return c;
}

/// The surface a tethered point set lies on: normal axis, tangential axes p < q, and the points.
/// `plane: {y: 1 um, points: [n1, n2]}`: a cell-centred lattice, (i + 1/2) L / n on each
/// tangential axis. `spiral: {y: 0.75 um, bump: 1 um, points: 16000}`: the toroidal spiral of
/// Appendix B, (theta_i, phi_i) = (mod(ceil(sqrt N) phi_i, 2 pi), 2 pi (i - 1)/N), on the surface
/// of eq. 5.5, X = (L_p theta / 2 pi, y(theta, phi), L_q phi / 2 pi) with
/// y = y0 + bump cos^2(theta - phi) sin^2(phi / 2) (bump 0, the default: the flat wall y = y0).
PointSurface read_point_surface(const Fields& f, const Scene& s) {
  PointSurface p;
  p.spiral = f.has("spiral");
  if (p.spiral == f.has("plane"))
    throw InputError(f.path(), p.spiral ? "both plane and spiral" : "(neither)", "give a plane or a spiral");
  const Fields g = f.map(p.spiral ? "spiral" : "plane");
  p.normal = -1;
  for (int d = 0; d < 3; ++d)
    if (g.has(axis_name[d])) {
      if (p.normal >= 0) throw InputError(g.at(axis_name[d]), "", "the surface's position is given by one coordinate (x, y or z)");
      p.normal = d;
    }
  if (p.normal < 0) throw InputError(g.at("y"), "(missing)", "give the surface's position along one axis, e.g. y: 1 um");
  p.at = g.quantity(axis_name[p.normal], "um");
  if (!(p.at >= 0 && p.at <= s.grid.length[p.normal]))
    throw InputError(g.at(axis_name[p.normal]), to_text(p.at / units::um) + " um", "lies outside the box");
  if (!p.spiral) {
    const std::vector<long> counts = g.integers("points", 2, 1, 4096);
    p.lattice = {int(counts[0]), int(counts[1])};
  } else {
    p.points = index_t(g.integer("points", 1, 4096L * 4096L));
    p.bump = g.has("bump") ? g.quantity("bump", "um") : 0.0;
    if (!(p.bump >= 0 && p.at + p.bump <= s.grid.length[p.normal]))
      throw InputError(g.at("bump"), to_text(p.bump / units::um) + " um", "must be >= 0 and keep the surface inside the box");
  }
  g.finish();
  return p;
}

}  // namespace

double EndotheliumSurface::height(double s, double t) const {
  const double theta = 2 * pi * s / Ls, phi = 2 * pi * t / Lt;
  const double c = std::cos(theta - phi), sh = std::sin(phi / 2);
  return y0 + bump * c * c * sh * sh;
}

std::array<double, 3> EndotheliumSurface::normal(double s, double t) const {
  const double theta = 2 * pi * s / Ls, phi = 2 * pi * t / Lt;
  const double c = std::cos(theta - phi), sh = std::sin(phi / 2), s2 = std::sin(2 * (theta - phi));
  // d height / d theta = -bump sin(2 (theta - phi)) sin^2(phi/2);
  // d height / d phi = bump (sin(2 (theta - phi)) sin^2(phi/2) + cos^2(theta - phi) sin(phi) / 2).
  const double ds = -bump * s2 * sh * sh * 2 * pi / Ls;
  const double dt = bump * (s2 * sh * sh + c * c * std::sin(phi) / 2) * 2 * pi / Lt;
  const double norm = std::sqrt(1 + ds * ds + dt * dt);
  return {-ds / norm, 1 / norm, -dt / norm};
}

CellTypeEntry cell_type(const std::string& name, const std::string& preset, index_t data_sites, index_t sample_sites, double radius,
                        int degree) {
  auto or_default = [](index_t n, index_t fallback) { return n > 0 ? n : fallback; };
  CellTypeEntry t;
  t.preset = preset;
  if (preset == "red_cell") t.spec = cells::red_cell_spec(or_default(data_sites, 2500), or_default(sample_sites, 10000));
  else if (preset == "platelet") t.spec = cells::platelet_spec(or_default(data_sites, 900), or_default(sample_sites, 900));
  else if (preset == "skalak_sphere") {
    t.radius = radius;
    t.spec = cells::skalak_sphere_spec(radius, or_default(data_sites, 625), or_default(sample_sites, 880));
  } else if (preset == "chapter3_red_cell") {
    t.degree = degree;
    t.spec = cells::chapter3_red_cell_spec(degree, or_default(sample_sites, 8281));
  } else
    throw InputError("cell type '" + name + "'", preset, "is not a preset: red_cell, platelet, skalak_sphere, chapter3_red_cell");
  t.spec.name = name;
  return t;
}

std::vector<double> point_positions(const PointSurface& p, const std::array<double, 3>& L) {
  const int a = p.normal == 0 ? 1 : 0, b = p.normal == 2 ? 1 : 2;  // the tangential axes, a < b
  std::vector<double> X;
  if (!p.spiral) {
    const index_t total = index_t(p.lattice[0]) * p.lattice[1];
    X.resize(static_cast<std::size_t>(3 * total));
    for (int i = 0; i < p.lattice[0]; ++i)
      for (int j = 0; j < p.lattice[1]; ++j) {
        const index_t q = index_t(i) * p.lattice[1] + j;
        X[a * total + q] = (i + 0.5) * L[a] / p.lattice[0];
        X[b * total + q] = (j + 0.5) * L[b] / p.lattice[1];
        X[p.normal * total + q] = p.at;
      }
    return X;
  }
  const index_t N = p.points;
  const EndotheliumSurface surface{p.at, p.bump, L[a], L[b]};
  const surface::SphereSites t = surface::toroidal_spiral(N);  // lambda: theta, theta: phi
  X.resize(static_cast<std::size_t>(3 * N));
  for (index_t i = 0; i < N; ++i) {
    X[a * N + i] = L[a] * t.lambda[i] / (2 * pi);
    X[b * N + i] = L[b] * t.theta[i] / (2 * pi);
    X[p.normal * N + i] = surface.height(X[a * N + i], X[b * N + i]);
  }
  return X;
}

sim::TetheredPoints tethered_points(const PointSetEntry& e, const std::array<double, 3>& box) {
  sim::TetheredPoints p;
  p.name = e.name;
  const std::vector<double> X = point_positions(e.surface, box);
  p.X = dvec(X.begin(), X.end());
  p.anchors = p.X;
  p.k = e.k;
  p.eta = e.eta;
  return p;
}

sim::TetherSheet tether_sheet(const Scene& s, const PointSetEntry& e) {
  const PointSurface& f = e.surface;
  const int n = f.normal, p = n == 0 ? 1 : 0, q = n == 2 ? 1 : 2;
  if (s.grid.lower[n] != MacBoundary::dirichlet || s.grid.upper[n] != MacBoundary::dirichlet)
    throw InputError("tethered_points '" + e.name + "'", "(its normal axis)", "the sheet model of the tethers' bound needs walls at both ends of its normal axis");
  const double area = s.grid.length[p] * s.grid.length[q];
  const double count = f.spiral ? double(f.points) : double(f.lattice[0]) * double(f.lattice[1]);
  return {s.grid.h(n), s.grid.length[n], f.at - s.grid.origin[n] + (f.spiral ? f.bump : 0.0), count / area, s.fluid.density, s.fluid.viscosity, s.ib.kernel};
}

std::array<std::array<WallMotion, 2>, 3> walls_at_rest() {
  std::array<std::array<WallMotion, 2>, 3> w{};
  for (int d = 0; d < 3; ++d) w[d][0].axis = w[d][1].axis = d;
  return w;
}

namespace {

void read_start(const Fields& f, Scene& s) {
  s.start.checkpoint = f.string("checkpoint");
  if (s.start.checkpoint.empty()) throw InputError(f.at("checkpoint"), "(empty)", "name a checkpoint file");
  if (s.initial_shear) throw InputError("domain.initial_flow", "shear", "a scene with a start takes its flow from start.checkpoint");
  if (f.has("keep")) {
    const YAML::Node k = f.get("keep");
    if (!k.IsSequence()) throw InputError(f.at("keep"), Fields::text(k), "expected a list of cell type names");
    for (std::size_t i = 0; i < k.size(); ++i) {
      const std::string field = f.at("keep") + "[" + std::to_string(i) + "]", name = Fields::scalar(k[i], field);
      if (std::none_of(s.types.begin(), s.types.end(), [&](const CellTypeEntry& t) { return t.spec.name == name; }))
        throw InputError(field, name, "is not the name of an entry of cell_types");
      s.start.keep.push_back(name);
    }
  }
  f.finish();
}

PointSetEntry read_points(const Fields& f, const Scene& s) {
  PointSetEntry p;
  p.name = f.string("name");
  p.surface = read_point_surface(f, s);
  if (f.has("follow_step")) {
    for (const char* key : {"k", "eta"})
      if (f.has(key)) throw InputError(f.at(key), "(given)", "a point set whose constants follow the step (follow_step) takes no " + std::string(key));
    const Fields r = f.map("follow_step");
    p.follow_gain = r.quantity("gain", "");
    if (!(p.follow_gain > 0 && p.follow_gain < 1)) throw InputError(r.at("gain"), to_text(p.follow_gain), "must lie in (0, 1)");
    r.finish();
    if (s.ib.coupling != sim::Coupling::seed)
      throw InputError(f.at("follow_step"), "(given)", "the rule assumes the seed's coupling (the spring at X^n); this scene's coupling is " +
                                                           std::string(sim::to_string(s.ib.coupling)));
    tether_sheet(s, p);  // the model must apply: walls across the sheet
  } else {
    p.k = f.nonnegative("k", "dyn/cm");
    p.eta = f.nonnegative("eta", "dyn s/cm");
  }
  f.finish();
  return p;
}

}  // namespace

std::array<double, 3> WallMotion::at(double t) const {
  if (!turning) return velocity;
  const double alpha = from + (to - from) * std::clamp(t / over, 0.0, 1.0);
  const int p = axis == 0 ? 1 : 0, q = axis == 2 ? 1 : 2;  // the tangential axes, p < q
  std::array<double, 3> v{0, 0, 0};
  v[q] = speed * std::cos(alpha);
  v[p] = speed * std::sin(alpha);
  return v;
}

Scene parse_scene(const std::string& yaml, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw InputError(origin, "(YAML)", std::string("not valid YAML: ") + e.what());
  }
  if (!root || root.IsNull()) throw InputError(origin, "(empty)", "a scene file needs at least domain, fluid, grid, time, ib");
  const Fields f(root, "");
  Scene s;
  s.source = yaml;
  s.name = f.has("name") ? f.string("name") : origin;
  read_domain(f.map("domain"), s);
  {
    const Fields fl = f.map("fluid");
    s.fluid.density = fl.positive("density", "g/cm^3");
    s.fluid.viscosity = fl.positive("viscosity", "P");
    fl.finish();
  }
  read_grid(f.map("grid"), s);
  read_time(f.map("time"), s);
  read_ib(f.map("ib"), s);
  if (f.has("cell_types"))
    for (const Fields& t : f.list_of_maps("cell_types")) {
      CellTypeEntry e = read_type(t);
      for (const CellTypeEntry& o : s.types)
        if (o.spec.name == e.spec.name) throw InputError(t.at("name"), e.spec.name, "names another cell type too");
      s.types.push_back(std::move(e));
    }
  if (f.has("start")) read_start(f.map("start"), s);
  if (f.has("cells"))
    for (const Fields& c : f.list_of_maps("cells")) {
      s.cells.push_back(read_cell(c, s));
      if (std::find(s.start.keep.begin(), s.start.keep.end(), s.cells.back().type) != s.start.keep.end())
        throw InputError(c.at("type"), s.cells.back().type, "its cells come from start.checkpoint (start.keep): add cells of another type");
    }
  if (f.has("tethered_points"))
    for (const Fields& p : f.list_of_maps("tethered_points")) s.point_sets.push_back(read_points(p, s));
  if (f.has("held_walls"))
    for (const Fields& w : f.list_of_maps("held_walls")) {
      HeldWallEntry e{w.string("name"), read_point_surface(w, s)};
      w.finish();
      s.held_walls.push_back(std::move(e));
    }
  if (f.has("output")) {
    const Fields o = f.map("output");
    if (o.has("diagnostics_every")) s.diagnostics_every = int(o.integer("diagnostics_every", 1, 1000000000));
    if (o.has("checkpoint_every")) s.checkpoint_every = o.positive("checkpoint_every", "s");
    if (o.has("snapshot_every")) s.snapshot_every = o.positive("snapshot_every", "s");
    if (o.has("stability")) s.ib.watch_stability = o.choice("stability", {"yes", "no"}) == "yes";
    o.finish();
  }
  f.finish();
  return s;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("scene file", path, "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  std::string name = path.substr(path.find_last_of('/') + 1);
  return parse_scene(text.str(), name);
}

BoundaryVelocity boundary_velocity(const Scene& s) {
  const auto walls = s.walls;
  return [walls](int a, int d, int side, double t, double, double, double) { return walls[d][side].at(t)[a]; };
}

std::vector<std::string> batch_types(const Scene& s) {
  std::vector<std::string> out;
  for (const CellTypeEntry& t : s.types) {
    const bool kept = std::find(s.start.keep.begin(), s.start.keep.end(), t.spec.name) != s.start.keep.end();
    const bool placed = std::any_of(s.cells.begin(), s.cells.end(), [&](const CellEntry& c) { return c.type == t.spec.name; });
    if (kept || placed) out.push_back(t.spec.name);
  }
  return out;
}

namespace {

/// The batch of a starting state that holds the cells of type `type` (InputError if none does).
const dvec& kept_batch(const StartingState& start, const std::string& type) {
  const auto it = std::find(start.batch_types.begin(), start.batch_types.end(), type);
  if (it == start.batch_types.end()) throw InputError("start.keep", type, "the starting state has no cells of this type");
  return start.state.batches.at(std::size_t(it - start.batch_types.begin()));
}

/// The starting state must fit the scene: the same grid and the same tethered point sets.
void check_start(const Scene& s, const StartingState& start) {
  for (int d = 0; d < 3; ++d)
    if (start.cells[d] != s.grid.cells[d])
      throw InputError("start.checkpoint", s.start.checkpoint,
                       "its grid has " + to_text(start.cells[d]) + " cells along " + axis_name[d] + ", the scene " + to_text(s.grid.cells[d]));
  if (start.state.points.size() != s.point_sets.size())
    throw InputError("start.checkpoint", s.start.checkpoint,
                     "holds " + to_text(start.state.points.size()) + " tethered point sets, the scene " + to_text(s.point_sets.size()));
  for (std::size_t k = 0; k < s.point_sets.size(); ++k)
    if (start.state.points[k].size() != point_positions(s.point_sets[k].surface, s.grid.length).size())
      throw InputError("tethered_points[" + to_text(k) + "]", s.point_sets[k].name, "has another number of points than in start.checkpoint");
}

}  // namespace

std::vector<std::string> check_contacts(const Scene& s, const StartingState* start) {
  if (s.start.checkpoint.empty() != !start)
    throw InputError("start.checkpoint", s.start.checkpoint.empty() ? "(none)" : s.start.checkpoint,
                     start ? "a starting state was given for a scene without a start" : "was not read (io::read_starting_state)");
  if (start) check_start(s, *start);
  struct Placed {
    std::string who, type;
    std::vector<double> X;  // data sites, n x 3
    index_t n = 0;
    const std::vector<surface::Triangle>* tris = nullptr;
    std::array<double, 3> center{};
    double radius = 0;  // of the bounding sphere about center
  };
  std::map<std::string, std::vector<surface::Triangle>> tris;
  std::map<std::string, std::vector<double>> reference;
  for (const CellTypeEntry& t : s.types) {
    reference[t.spec.name] = reference_sites(t);
    tris[t.spec.name] = surface::sphere_triangulation(t.spec.data_sites);
  }
  const MacGrid& g = s.grid;
  auto um = [](double x) {
    std::ostringstream o;
    o.precision(4);
    o << x / units::um << " um";
    return o.str();
  };
  std::vector<Placed> cells;
  auto bound = [](Placed& p) {  // the radius of the bounding sphere about p.center
    for (index_t i = 0; i < p.n; ++i) {
      double r2 = 0;
      for (int d = 0; d < 3; ++d) r2 += std::pow(p.X[std::size_t(d * p.n + i)] - p.center[d], 2);
      p.radius = std::max(p.radius, std::sqrt(r2));
    }
  };
  if (start)
    for (const std::string& type : s.start.keep) {
      const dvec& kept = kept_batch(*start, type);
      const host_vector<double> state(kept.begin(), kept.end());
      const index_t n = index_t(reference.at(type).size() / 3), N = index_t(state.size()) / (6 * n);
      for (index_t c = 0; c < N; ++c) {
        Placed p;
        p.who = "start: " + type + " " + to_text(c);
        p.type = type;
        p.n = n;
        p.X.resize(std::size_t(3 * n));
        for (int d = 0; d < 3; ++d)  // column d N + c of the n x 6N state (docs/math.md)
          std::copy_n(state.begin() + std::ptrdiff_t((d * N + c) * n), n, p.X.begin() + std::ptrdiff_t(d * n));
        p.tris = &tris.at(type);
        for (index_t i = 0; i < n; ++i)  // about the centroid of its data sites
          for (int d = 0; d < 3; ++d) p.center[d] += p.X[std::size_t(d * n + i)] / double(n);
        bound(p);
        cells.push_back(std::move(p));
      }
    }
  for (std::size_t c = 0; c < s.cells.size(); ++c) {
    Placed p;
    p.who = "cells[" + std::to_string(c) + "]";
    p.type = s.cells[c].type;
    const std::vector<double>& ref = reference.at(s.cells[c].type);
    p.n = index_t(ref.size() / 3);
    p.X = cells::placed(ref, p.n, s.cells[c].placement, p.who);
    p.tris = &tris.at(s.cells[c].type);
    p.center = s.cells[c].placement.center;
    bound(p);  // (the reader has checked that the cell lies between the walls)
    cells.push_back(std::move(p));
  }
  const surface::PeriodicBox box{g.length, {g.periodic(0), g.periodic(1), g.periodic(2)}};
  // Inside c: within its bounding sphere, and a winding number above 1/2.
  auto inside = [](const Placed& c, const std::array<double, 3>& x) {
    double r2 = 0;
    for (int d = 0; d < 3; ++d) r2 += (x[d] - c.center[d]) * (x[d] - c.center[d]);
    return r2 <= c.radius * c.radius && std::abs(surface::winding_number(c.X, c.n, *c.tris, x)) > 0.5;
  };
  const double hmin = std::min({g.h(0), g.h(1), g.h(2)});
  std::vector<std::string> near;
  for (std::size_t a = 0; a < cells.size(); ++a)
    for (std::size_t b = a + 1; b < cells.size(); ++b) {
      const Placed &A = cells[a], &B = cells[b];
      const std::array<double, 3> shift = surface::nearest_image_shift(A.center, B.center, box);
      double dc = 0;
      for (int d = 0; d < 3; ++d) dc += std::pow(A.center[d] - B.center[d] - shift[d], 2);
      if (std::sqrt(dc) > A.radius + B.radius + 2 * hmin) continue;
      const std::string pair = A.who + " and " + B.who;
      // A's sites against B's image (B + shift), then the image's sites against A.
      for (int side = 0; side < 2; ++side) {
        const Placed &P = side ? B : A, &Q = side ? A : B;
        const double sign = side ? 1 : -1;
        index_t first = P.n;  // the first of P's sites inside Q
#pragma omp parallel for reduction(min : first) schedule(dynamic, 64)
        for (index_t i = 0; i < P.n; ++i) {
          std::array<double, 3> x;
          for (int d = 0; d < 3; ++d) x[d] = P.X[std::size_t(d * P.n + i)] + sign * shift[d];
          if (inside(Q, x)) first = std::min(first, i);
        }
        if (first < P.n)
          throw InputError(P.who, "its data site " + std::to_string(first), "lies inside " + Q.who + ": " + pair + " overlap");
      }
      const surface::Closest c = surface::closest_points(A.X, A.n, B.X, B.n, shift);
      if (c.distance < 2 * hmin)
        near.push_back(pair + " come within " + um(c.distance) + " of each other (less than 2h = " + um(2 * hmin) +
                       "): their kernels overlap and their forces mix");
    }
  for (std::size_t k = 0; k < s.point_sets.size(); ++k) {
    const PointSetEntry& P = s.point_sets[k];
    const std::vector<double> X =
        start ? std::vector<double>(start->state.points[k].begin(), start->state.points[k].end()) : point_positions(P.surface, g.length);
    const index_t n = index_t(X.size() / 3);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const Placed& C = cells[c];
      double closest = INFINITY;
      for (index_t i = 0; i < n; ++i) {
        std::array<double, 3> x{X[std::size_t(i)], X[std::size_t(n + i)], X[std::size_t(2 * n + i)]};
        const std::array<double, 3> shift = surface::nearest_image_shift(C.center, x, box);
        double r2 = 0;
        for (int d = 0; d < 3; ++d) x[d] += shift[d], r2 += std::pow(x[d] - C.center[d], 2);
        if (std::sqrt(r2) > C.radius + 2 * hmin) continue;
        if (inside(C, x))
          throw InputError(C.who, C.type,
                           "encloses point " + std::to_string(i) + " of tethered_points[" + std::to_string(k) + "] ('" + P.name + "')");
        for (index_t j = 0; j < C.n; ++j) {
          double e2 = 0;
          for (int d = 0; d < 3; ++d) e2 += std::pow(x[d] - C.X[std::size_t(d * C.n + j)], 2);
          closest = std::min(closest, std::sqrt(e2));
        }
      }
      if (closest < 2 * hmin)
        near.push_back(C.who + " comes within " + um(closest) + " of tethered_points[" + std::to_string(k) +
                       "] ('" + P.name + "') (less than 2h = " + um(2 * hmin) + ")");
    }
  }
  return near;
}

sim::ImmersedBoundary build(const Scene& s, const StartingState* start, std::shared_ptr<const FluidDecomposition> parts) {
  check_contacts(s, start);
  const auto& walls = s.walls;
  // The adaptive step's guard from tethers with fixed constants: no rung above their explicit
  // stability bound (sim/tether_stability.hpp), which eq. 5.4 does not see.
  sim::IbOptions options = s.ib;
  if (options.adaptive.enabled)
    for (const PointSetEntry& p : s.point_sets)
      if (p.follow_gain == 0 && (p.k > 0 || p.eta > 0) && s.grid.lower[p.surface.normal] == MacBoundary::dirichlet &&
          s.grid.upper[p.surface.normal] == MacBoundary::dirichlet)
        options.adaptive.dt_max = std::min(options.adaptive.dt_max, sim::tether_dt_limit(tether_sheet(s, p), p.k, p.eta, s.ib.coupling == sim::Coupling::midpoint));
  sim::ImmersedBoundary ib(std::make_unique<NavierStokesStep>(s.grid, s.fluid, s.fluid_options, boundary_velocity(s), parts),
                           options);
  if (s.initial_shear) {
    // The steady flow between the walls: linear in the wall-normal coordinate for each wall axis
    // (one wall axis at most carries a shear; with several, their profiles add).
    for (int a = 0; a < 3; ++a)
      ib.fluid_state().u[a] = sample(ib.fluid().operators().component_box(a), [&](double x, double y, double z) {
        const double p[3] = {x, y, z};
        double u = 0;
        for (int d = 0; d < 3; ++d)
          if (!s.grid.periodic(d)) {
            const double lo = walls[d][0].at(0)[a], hi = walls[d][1].at(0)[a];
            u += lo + (hi - lo) * p[d] / s.grid.length[d];
          }
        return u;
      });
  }
  std::vector<const dvec*> kept;  // per batch: its state in the start, or null
  for (const std::string& name : batch_types(s)) {
    const CellTypeEntry& t = *std::find_if(s.types.begin(), s.types.end(), [&](const CellTypeEntry& e) { return e.spec.name == name; });
    std::vector<cells::Placement> placements;
    std::vector<std::array<double, 3>> forces;
    const bool from_start = std::find(s.start.keep.begin(), s.start.keep.end(), name) != s.start.keep.end();
    kept.push_back(from_start ? &kept_batch(*start, name) : nullptr);
    if (from_start)  // as many cells as the start holds, placed by restore() below
      placements.resize(std::size_t(index_t(kept.back()->size()) / (6 * t.spec.data_sites.size())));
    for (const CellEntry& c : s.cells)
      if (c.type == t.spec.name) {
        placements.push_back(c.placement);
        forces.push_back(c.force);
      }
    const auto type = std::make_shared<const cells::CellType>(t.spec);
    cells::Batch batch(type, placements);
    for (std::size_t c = 0; c < forces.size(); ++c) batch.set_body_force(index_t(c), forces[c]);
    ib.add(std::move(batch));
  }
  for (const PointSetEntry& p : s.point_sets) {
    sim::TetheredPoints points = tethered_points(p, s.grid.length);
    if (p.follow_gain > 0) {  // the constants of the first step; the step sets them from then on
      points.follow = sim::TetherRule{tether_sheet(s, p), p.follow_gain};
      const sim::TetherConstants c = sim::tether_constants_for_step(points.follow->sheet, s.fluid_options.dt, p.follow_gain);
      points.k = c.k, points.eta = c.eta;
    }
    ib.add(std::move(points));
  }
  for (const HeldWallEntry& w : s.held_walls) {
    const std::vector<double> X = point_positions(w.surface, s.grid.length);
    ib.add(sim::HeldWall{w.name, dvec(X.begin(), X.end())});
  }
  if (start) {
    sim::ImmersedBoundary::Carried c = ib.carried();
    c.fluid = start->state.fluid;
    c.clock = start->state.clock;
    if (!s.ib.adaptive.enabled) {  // without a ladder the scene's dt is the step from the start's time on
      c.clock.dt = s.fluid_options.dt;
      c.clock.level = c.clock.allowing = 0, c.clock.cap = -1;
    }
    c.points = start->state.points;
    for (std::size_t b = 0; b < kept.size(); ++b)
      if (kept[b]) c.batches[b] = *kept[b];
    ib.restore(c);
  }
  return ib;
}

double shear_rate(const Scene& s) {
  double g = 0;
  for (int d = 0; d < 3; ++d)
    if (!s.grid.periodic(d))
      for (int a = 0; a < 3; ++a) g = std::max(g, std::abs(s.walls[d][1].at(0)[a] - s.walls[d][0].at(0)[a]) / s.grid.length[d]);
  return g;
}

std::vector<CellTypeGroups> dimensionless_groups(const Scene& s) {
  const double rho = s.fluid.density, mu = s.fluid.viscosity, gdot = shear_rate(s);
  std::vector<CellTypeGroups> out;
  for (const CellTypeEntry& t : s.types) {
    CellTypeGroups g;
    g.type = t.spec.name;
    for (index_t i = 0; i < t.spec.data_sites.size(); ++i) {
      double x[3];
      t.spec.shape.position(t.spec.data_sites.lambda[i], t.spec.data_sites.theta[i], x);
      g.radius = std::max(g.radius, std::hypot(x[0], x[1], x[2]));
    }
    g.reynolds = rho * gdot * g.radius * g.radius / mu;
    for (const mechanics::EnergyDensity& e : t.spec.model.elastic)  // the first law that resists shear
      if (e.shear_modulus() > 0) {
        g.shear_modulus = e.shear_modulus();
        g.modulus = e.name() + " " + e.parameters()[0].name;
        g.capillary = mu * gdot * g.radius / g.shear_modulus;
        break;
      }
    out.push_back(g);
  }
  return out;
}

namespace {

/// A name as a YAML scalar: plain when it can be, else double-quoted.
std::string yaml_name(const std::string& v) {
  const bool plain = !v.empty() && v.find_first_of(":,#[]{}&*!|>'\"%@`\\\n") == std::string::npos && v.front() != ' ' &&
                     v.back() != ' ' && v.front() != '-' && v.front() != '?';
  if (plain) return v;
  std::string q = "\"";
  for (char c : v) {
    if (c == '"' || c == '\\' || c == '\n') q.push_back('\\');
    q.push_back(c == '\n' ? 'n' : c);
  }
  return q + "\"";
}

/// The shortest text that reads back to the same double (std::to_chars).
std::string shortest(double x) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, r.ptr);
}

/// A quantity in the CGS unit given, exactly: it reads back to the same double.
std::string q(double x, const std::string& unit) { return unit.empty() ? shortest(x) : shortest(x) + " " + unit; }

std::string triple(const std::array<double, 3>& v, const std::string& unit) {
  return "[" + q(v[0], unit) + ", " + q(v[1], unit) + ", " + q(v[2], unit) + "]";
}

std::string model_yaml(const cells::ForceModel& m) {
  std::string o = "{";
  if (!m.elastic.empty()) {
    o += "elastic: [";
    for (std::size_t i = 0; i < m.elastic.size(); ++i) {
      const mechanics::EnergyDensity& e = m.elastic[i];
      const char* law = e.kind == mechanics::EnergyKind::skalak                    ? "skalak"
                        : e.kind == mechanics::EnergyKind::neo_hookean_dissertation ? "neo_hookean"
                        : e.kind == mechanics::EnergyKind::neo_hookean_paper        ? "neo_hookean_paper"
                                                                                    : "tension";
      o += std::string(i ? ", " : "") + "{law: " + law;
      for (const mechanics::EnergyDensity::Parameter& p : e.parameters()) o += std::string(", ") + p.name + ": " + q(p.value, p.units);
      o += "}";
    }
    o += "], ";
  }
  o += "kappa: " + q(m.kappa, "erg") + ", H0: " + (m.H0_reference ? std::string("reference") : q(m.H0, "1/cm")) +
       ", nu: " + q(m.nu, "dyn s/cm") + "}";
  return o;
}

}  // namespace

std::string to_yaml(const Scene& s, const std::string& comment) {
  std::ostringstream o;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) o << "# " << line << "\n";
  const MacGrid& g = s.grid;
  o << "name: " << yaml_name(s.name) << "\n";
  o << "domain:\n  size: " << triple(g.length, "cm") << "\n  periodic: [";
  bool first = true, any_wall = false;
  for (int d = 0; d < 3; ++d)
    if (g.periodic(d)) o << (first ? "" : ", ") << axis_name[d], first = false;
    else any_wall = true;
  o << "]\n";
  if (any_wall) {
    o << "  walls:\n";
    for (int d = 0; d < 3; ++d) {
      if (g.periodic(d)) continue;
      o << "    " << axis_name[d] << ": {";
      for (int side = 0; side < 2; ++side) {
        const WallMotion& m = s.walls[d][side];
        o << (side ? ", upper: " : "lower: ");
        if (m.turning)
          o << "{speed: " << q(m.speed, "cm/s") << ", turn: {from: " << q(m.from, "rad") << ", to: " << q(m.to, "rad")
            << ", over: " << q(m.over, "s") << "}}";
        else
          o << triple(m.velocity, "cm/s");
      }
      o << "}\n";
    }
    if (s.initial_shear) o << "  initial_flow: shear\n";
  }
  if (!s.start.checkpoint.empty()) {
    o << "start: {checkpoint: " << yaml_name(s.start.checkpoint) << ", keep: [";
    for (std::size_t i = 0; i < s.start.keep.size(); ++i) o << (i ? ", " : "") << yaml_name(s.start.keep[i]);
    o << "]}\n";
  }
  o << "fluid: {density: " << q(s.fluid.density, "g/cm^3") << ", viscosity: " << q(s.fluid.viscosity, "P") << "}\n";
  o << "grid: {cells: [" << g.cells[0] << ", " << g.cells[1] << ", " << g.cells[2] << "]}\n";
  if (s.ib.coupling == sim::Coupling::forward_euler)
    throw InputError("time.coupling", sim::to_string(s.ib.coupling), "has no scene form (seed or midpoint)");
  o << "time: {integrator: "
    << (s.fluid_options.integrator == TimeIntegrator::peskin_two_stage ? "peskin_two_stage" : "backward_forward_euler")
    << ", coupling: " << (s.ib.coupling == sim::Coupling::midpoint ? "midpoint" : "seed") << ", dt: " << q(s.fluid_options.dt, "s")
    << ", end: " << q(s.t_end, "s");
  if (!s.ib.stopping_condition) o << ", stopping_condition: off";
  if (s.ib.adaptive.enabled)
    o << ", adaptive: {" << (s.ib.adaptive.criterion == sim::StepCriterion::stability ? "criterion: stability, " : "")
      << "dt_min: " << q(s.ib.adaptive.dt_min, "s") << ", max_level: " << s.ib.adaptive.max_level
      << ", grow_after: " << s.ib.adaptive.grow_after
      << (s.ib.adaptive.ratio != 2 ? ", ratio: " + to_text(s.ib.adaptive.ratio) : std::string())
      << (s.ib.adaptive.criterion == sim::StepCriterion::stability
              ? ", guard_growth: " + to_text(s.ib.adaptive.guard_growth) + ", guard_steps: " + to_text(s.ib.adaptive.guard_steps)
              : std::string())
      << "}";
  o << "}\n";
  o << "ib: {kernel: " << ib::to_string(s.ib.kernel) << ", body_force: " << triple(s.ib.body_force, "dyn/cm^3") << "}\n";
  if (!s.types.empty()) o << "cell_types:\n";
  for (const CellTypeEntry& t : s.types) {
    o << "  - {name: " << yaml_name(t.spec.name) << ", preset: " << t.preset;
    if (t.preset == "chapter3_red_cell") o << ", degree: " << t.degree;
    else o << ", data_sites: " << t.spec.data_sites.size();
    o << ", sample_sites: " << t.spec.sample_sites.size();
    if (t.preset == "skalak_sphere") o << ", radius: " << q(t.radius, "cm");
    o << ", model: " << model_yaml(t.spec.model);
    if (t.spec.single_precision_products) o << ", products: single";
    o << "}\n";
  }
  if (!s.cells.empty()) o << "cells:\n";
  for (const CellEntry& c : s.cells) {
    const cells::Placement& p = c.placement;
    o << "  - {type: " << yaml_name(c.type) << ", center: " << triple(p.center, "cm") << ", axis: " << triple(p.axis, "")
      << ", angle: " << q(p.angle, "rad");
    if (p.stretch != std::array<double, 3>{1, 1, 1}) o << ", stretch: " << triple(p.stretch, "");
    if (c.force != std::array<double, 3>{0, 0, 0}) o << ", force: " << triple(c.force, "dyn");
    o << "}\n";
  }
  if (!s.point_sets.empty()) o << "tethered_points:\n";
  for (const PointSetEntry& p : s.point_sets) {
    const PointSurface& f = p.surface;
    o << "  - {name: " << yaml_name(p.name) << ", " << (f.spiral ? "spiral" : "plane") << ": {" << axis_name[f.normal] << ": "
      << q(f.at, "cm");
    if (f.spiral) o << ", bump: " << q(f.bump, "cm") << ", points: " << f.points;
    else o << ", points: [" << f.lattice[0] << ", " << f.lattice[1] << "]";
    if (p.follow_gain > 0) o << "}, follow_step: {gain: " << q(p.follow_gain, "") << "}}\n";
    else o << "}, k: " << q(p.k, "dyn/cm") << ", eta: " << q(p.eta, "dyn s/cm") << "}\n";
  }
  if (!s.held_walls.empty()) o << "held_walls:\n";
  for (const HeldWallEntry& w : s.held_walls) {
    const PointSurface& f = w.surface;
    o << "  - {name: " << yaml_name(w.name) << ", " << (f.spiral ? "spiral" : "plane") << ": {" << axis_name[f.normal] << ": " << q(f.at, "cm");
    if (f.spiral) o << ", bump: " << q(f.bump, "cm") << ", points: " << f.points;
    else o << ", points: [" << f.lattice[0] << ", " << f.lattice[1] << "]";
    o << "}}\n";
  }
  o << "output: {diagnostics_every: " << s.diagnostics_every;
  if (s.checkpoint_every > 0) o << ", checkpoint_every: " << q(s.checkpoint_every, "s");
  if (s.snapshot_every > 0) o << ", snapshot_every: " << q(s.snapshot_every, "s");
  if (s.ib.watch_stability) o << ", stability: yes";
  o << "}\n";
  return o.str();
}

Scene checked(const Scene& scene, const std::string& comment) { return parse_scene(to_yaml(scene, comment), scene.name); }

std::string describe(const Scene& s) {
  std::ostringstream o;
  const MacGrid& g = s.grid;
  o << "scene '" << s.name << "'\n";
  o << "  box " << g.length[0] / units::um << " x " << g.length[1] / units::um << " x " << g.length[2] / units::um << " um;";
  for (int d = 0; d < 3; ++d) {
    o << " " << axis_name[d] << (g.periodic(d) ? " periodic" : " walls");
    if (!g.periodic(d))
      for (int side = 0; side < 2; ++side) {
        const WallMotion& m = s.walls[d][side];
        o << (side ? ", upper " : " (lower ");
        if (m.turning)
          o << m.speed * 10 << " mm/s turning from " << m.from * 180 / pi << " to "
            << m.to * 180 / pi << " deg over " << m.over / units::ms << " ms";
        else
          o << "[" << m.velocity[0] * 10 << ", " << m.velocity[1] * 10 << ", " << m.velocity[2] * 10 << "] mm/s";
        o << (side ? ")" : "");
      }
    o << (d < 2 ? "," : "\n");
  }
  o << "  grid " << g.cells[0] << " x " << g.cells[1] << " x " << g.cells[2] << ", h = " << g.h(0) / units::um << " x "
    << g.h(1) / units::um << " x " << g.h(2) / units::um << " um\n";
  o << "  fluid density " << s.fluid.density << " g/cm^3, viscosity " << s.fluid.viscosity / units::cP << " cP; flow at t = 0: "
    << (s.initial_shear ? "the steady shear" : "rest") << "\n";
  o << "  time " << to_string(s.fluid_options.integrator) << ", coupling " << sim::to_string(s.ib.coupling) << ", dt = "
    << s.fluid_options.dt / units::ns << " ns, end " << s.t_end / units::us << " us ("
    << std::llround(s.t_end / s.fluid_options.dt) << " steps at dt)";
  if (s.ib.adaptive.enabled)
    o << "; adaptive (" << sim::to_string(s.ib.adaptive.criterion) << "): dt = " << s.ib.adaptive.ratio << "^k x "
      << s.ib.adaptive.dt_min / units::ns << " ns, k <= " << s.ib.adaptive.max_level << ", growing after " << s.ib.adaptive.grow_after
      << " steps";
  o << "\n  kernel " << ib::to_string(s.ib.kernel) << "; body force [" << s.ib.body_force[0] << ", " << s.ib.body_force[1] << ", "
    << s.ib.body_force[2] << "] dyn/cm^3\n";
  for (const CellTypeEntry& t : s.types) {
    const auto n = std::count_if(s.cells.begin(), s.cells.end(), [&](const CellEntry& c) { return c.type == t.spec.name; });
    o << "  cell type '" << t.spec.name << "' (preset " << t.preset << "): " << t.spec.data_sites.size() << " data / "
      << t.spec.sample_sites.size() << " sample sites; " << t.spec.model.describe()
      << (t.spec.single_precision_products ? "; products in single precision" : "") << "; " << n << " cell(s)\n";
  }
  for (const PointSetEntry& p : s.point_sets) {
    o << "  tethered points '" << p.name << "': " << (p.surface.spiral ? p.surface.points : index_t(p.surface.lattice[0]) * p.surface.lattice[1]) << " points, ";
    if (p.follow_gain > 0) {
      const sim::TetherConstants c = sim::tether_constants_for_step(tether_sheet(s, p), s.fluid_options.dt, p.follow_gain);
      o << "k and eta following the step at gain " << p.follow_gain << " (at dt = " << s.fluid_options.dt << " s: k = " << c.k
        << " dyn/cm, eta = " << c.eta << " dyn s/cm)\n";
    } else {
      o << "k = " << p.k << " dyn/cm, eta = " << p.eta << " dyn s/cm";
      if (s.ib.adaptive.enabled && p.surface.normal == 1 && !s.grid.periodic(1))
        o << "; their explicit bound " << sim::tether_dt_limit(tether_sheet(s, p), p.k, p.eta, s.ib.coupling == sim::Coupling::midpoint)
          << " s caps the adaptive step";
      o << "\n";
    }
  }
  return o.str();
}

}  // namespace rbfib::scene
