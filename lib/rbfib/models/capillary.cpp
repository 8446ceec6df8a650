#include "rbfib/models/capillary.hpp"

#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/io/hdf5.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/sim/capillary.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/shape_measures.hpp"

#include <thrust/copy.h>
#include <thrust/extrema.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <optional>

namespace rbfib::capillary {

const char* to_string(Region r) { return r == Region::core ? "core" : "segment"; }

struct Run::Impl {
  Model m;
  const chapter3::EvaluationSet* eval;
  surface::CylinderPoints cap;
  std::vector<double> Zc, W0;  // LDSM: reference vertices and their area weights
  std::vector<mechanics::EnergyDensity> energies;
  std::optional<run::Run> loop;
  std::vector<surface::Triangle> no_tris;
  std::vector<Sample> samples;  // the accessors' copies of the run's series
  std::vector<View> kept_views;
  double seconds = 0;

  Impl(const Model& model, const chapter3::EvaluationSet* e, const std::string& checkpoint, double sitting)
      : m(model), eval(e) {
    require(m.eta >= 8, "grid size eta", m.eta, "must be >= 8");
    require(m.mu > 0, "viscosity mu (P)", m.mu, "must be > 0");
    require(m.dt > 0, "time step dt (s)", m.dt, "must be > 0");
    require(m.steps >= 0, "steps", m.steps, "must be >= 0");
    require(m.R_cap > 0 && m.R_cap < m.L, "capillary radius (cm)", m.R_cap, "must lie in (0, L)");
    require(m.k_bend >= 0, "k_bend (erg)", m.k_bend, "must be >= 0");
    require(m.record_every > 0 && m.view_every > 0, "record_every, view_every", m.record_every, "must be > 0");
    MacGrid g = make_mac_grid(3, {m.eta, m.eta, m.eta}, {2 * m.L, 2 * m.L, 2 * m.L},
                              {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
    g.origin = {-m.L, -m.L, -m.L};
    auto fluid = std::make_unique<PeriodicStokesStep>(g, FluidParameters{1.0, m.mu}, m.dt, true);
    sim::IbOptions o;
    o.coupling = sim::Coupling::forward_euler;
    o.kernel = m.kernel;
    o.stopping_condition = false;
    const bool segment = m.region == Region::segment;
    o.body_force_density = sim::capillary_driving_force(fluid->operators(), m.R_cap, m.f_in,
                                                        segment ? m.x0_cap : -INFINITY, segment ? m.x1_cap : INFINITY);
    sim::ImmersedBoundary ib(std::move(fluid), o);
    if (m.with_cell) add_cell(ib);
    cap = surface::cylinder_points(m.R_cap, m.x0_cap, m.x1_cap, m.cap_spacing > 0 ? m.cap_spacing : m.h() / 2);
    ib.add(sim::tethered_capillary("capillary", cap, m.k_teth));
    run::Options ro;
    ro.t_end = m.steps * m.dt;
    ro.checkpoint = checkpoint;
    ro.sitting = sitting;
    ro.sample_every = run::Cadence{};  // the hook records at its own steps
    run::Hooks hooks;
    hooks.after_step = [this](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& s) {
      after_step(ib, r, s);
    };
    loop.emplace(describe(), std::move(ib), ro, std::move(hooks));
    collect();
  }

  /// The setup as text: what a checkpoint must match.
  std::string describe() const {
    std::string d = "chapter3_capillary run\n";
    for (double x : {m.L, double(m.eta), m.mu, m.f_in, double(int(m.region)), m.R_cap, m.x0_cap, m.x1_cap, m.k_teth,
                     m.cap_spacing, double(m.with_cell), double(int(m.method)), double(m.M), m.R_cell, m.Gs, m.A, m.k_bend,
                     m.start[0], m.start[1], m.start[2], m.dt, double(m.steps), double(m.record_every), double(m.view_every),
                     double(int(m.kernel))})
      d += to_text(x) + "\n";
    if (eval) d += eval->family + " " + to_text(eval->size()) + "\n";
    return d;
  }

  void add_cell(sim::ImmersedBoundary& ib) {
    require(eval != nullptr, "evaluation set", "none", "a run with a cell needs its evaluation sites");
    const cells::ReferenceShape shape = cells::chapter3_red_cell_shape(m.R_cell);
    energies = {mechanics::EnergyDensity::neo_hookean_paper(m.Gs, m.A)};
    if (m.method == chapter3::Method::shvd) {
      cells::CellTypeSpec ts;
      ts.name = "red cell (eq. 92), SHVD m = " + to_text((m.M + 1) * (m.M + 1));
      ts.shape = shape;
      ts.data_sites = chapter3::interpolation_sites(m.M);
      ts.sample_sites = eval->sites;
      ts.interpolant = cells::Interpolant::spherical_harmonics;
      ts.sh_degree = m.M;
      ts.sphere_weights = eval->w;
      ts.model.elastic = energies;
      ts.model.kappa = 2 * m.k_bend;  // E = k_bend int (2H)^2 dA = 2 kappa int H^2 dA
      cells::Placement pl;
      pl.center = m.start;
      ib.add(cells::Batch(std::make_shared<const cells::CellType>(ts), std::vector<cells::Placement>{pl}));
      return;
    }
    require(m.k_bend == 0, "LDSM k_bend (erg)", m.k_bend, "must be 0: LDSM has no bending model (paper Sec. 2.6.3 and 5.1.2)");
    const index_t n = eval->size();
    Zc.assign(static_cast<std::size_t>(3 * n), 0.0);
    std::vector<double> X = Zc;
    for (index_t i = 0; i < n; ++i) {
      double x[3];
      shape.position(eval->sites.lambda[i], eval->sites.theta[i], x);
      for (int d = 0; d < 3; ++d) {
        Zc[d * n + i] = x[d];
        X[d * n + i] = x[d] + m.start[d];
      }
    }
    W0 = mechanics::ldsm_area_weights(eval->tris, Zc);
    ib.add(sim::LdsmShell{"red cell (LDSM)", eval->tris, Zc, X, energies});
  }

  bool record_due(long k) const { return k % m.record_every == 0 || k == m.steps; }
  bool view_due(long k) const { return k % m.view_every == 0 || k == m.steps; }

  /// After step k - 1 (or at the start, r null): the step's frame velocity and peak flow go into
  /// the row recorded at X^{k-1}; then X^k is measured when due (a force call of its own, the same
  /// as the step's: the forces of Sec. 3.3 act at X^k).
  void after_step(const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& s) {
    const long k = ib.step_count();
    if (r) {
      std::vector<std::vector<double>>& rows = s["samples"].rows;
      if (!rows.empty() && std::abs(rows.back()[0] - (k - 1) * m.dt) <= 1e-9 * m.dt) {
        const dvec& u0 = ib.fluid_state().u[0];
        for (int d = 0; d < 3; ++d) rows.back()[6 + d] = r->frame_velocity[d];
        rows.back()[9] = *thrust::max_element(u0.begin(), u0.end()) + r->frame_velocity[0];
      }
      s["frame"].rows = {{r->frame_velocity[0], r->frame_velocity[1], r->frame_velocity[2]}};
      auto& ph = s["phases"].rows;
      if (ph.empty()) ph = {std::vector<double>(5, 0.0)};
      const double add[5] = {r->seconds_forces, r->seconds_spreading, r->seconds_fluid, r->seconds_interpolation,
                             r->seconds_update};
      for (int i = 0; i < 5; ++i) ph[0][i] += add[i];
    }
    if (!record_due(k) && !view_due(k)) return;
    double c[3] = {0, 0, 0}, area = NAN, volume = NAN, max_density = NAN;
    View v;
    v.t = k * m.dt;
    if (m.with_cell) {
      if (m.method == chapter3::Method::shvd) {
        cells::CellForces out;
        cells::compute_forces(ib.batch(0), out);
        for (int d = 0; d < 3; ++d) c[d] = out.cells.centroid[0][d];
        area = out.cells.area[0];
        volume = out.cells.volume[0];
        if (view_due(k)) shvd_view(ib.batch(0), out, v);
      } else {
        const std::vector<double>& X = ib.shell(0).shell().X;
        const surface::PolyhedronMeasures pm = surface::polyhedron_measures(eval->tris, X);
        volume = pm.volume;
        area = pm.area;
        for (int d = 0; d < 3; ++d) c[d] = pm.centroid[d];
        if (view_due(k)) ldsm_view(X, mechanics::ldsm_forces("red cell (LDSM)", eval->tris, Zc, X, energies).F, v);
      }
      if (view_due(k)) {
        max_density = *std::max_element(v.f.begin(), v.f.end());
        std::vector<double> row{v.t, double(v.f.size())};
        for (const std::vector<double>* part : {&v.X, &v.f, &v.H, &v.normal}) row.insert(row.end(), part->begin(), part->end());
        s["views"].rows.push_back(std::move(row));
      }
    }
    if (!record_due(k)) return;
    const std::vector<double> X(ib.points(0).X.begin(), ib.points(0).X.end());
    const std::size_t ncap = X.size() / 3;
    double cap_disp = 0;
    for (std::size_t q = 0; q < ncap; ++q) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += (X[d * ncap + q] - cap.X[d * ncap + q]) * (X[d * ncap + q] - cap.X[d * ncap + q]);
      cap_disp = std::max(cap_disp, std::sqrt(d2));
    }
    s["samples"].columns = {"t (s)", "cx (cm)", "cy (cm)", "cz (cm)", "area (cm^2)", "volume (cm^3)", "ucx (cm/s)",
                            "ucy (cm/s)", "ucz (cm/s)", "u_max (cm/s)", "cap_disp (cm)", "max_density (dyn/cm^2)"};
    s["samples"].rows.push_back({v.t, c[0], c[1], c[2], area, volume, NAN, NAN, NAN, NAN, cap_disp, max_density});
  }

  static double norm(const std::vector<double>& F, std::size_t n, std::size_t i) {
    return std::sqrt(F[i] * F[i] + F[n + i] * F[n + i] + F[2 * n + i] * F[2 * n + i]);
  }

  /// The SHVD surface at its n evaluation sites: positions, |density|, normals and H.
  void shvd_view(const cells::Batch& batch, const cells::CellForces& out, View& v) const {
    v.X = out.positions.to_host();
    const std::vector<double> D = out.density.to_host();
    const std::size_t n = v.X.size() / 3;
    const std::vector<surface::Jet> jets = surface::jets_from_operators(batch.type().to_sample(), batch.positions_host());
    v.f.resize(n);
    v.H.resize(n);
    v.normal.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      v.f[i] = norm(D, n, i);
      const surface::PointGeometry g = surface::point_geometry(jets[i]);
      v.H[i] = g.H;
      for (int d = 0; d < 3; ++d) v.normal[d * n + i] = g.n[d];
    }
  }

  /// The LDSM surface at its vertices: positions, |force| over the area weight, vertex normals.
  void ldsm_view(const std::vector<double>& X, const std::vector<double>& F, View& v) const {
    const std::size_t n = X.size() / 3;
    v.X = X;
    v.f.resize(n);
    for (std::size_t i = 0; i < n; ++i) v.f[i] = norm(F, n, i) / W0[i];
    v.H.assign(n, NAN);
    v.normal = surface::vertex_normals(eval->tris, X);
  }

  /// The accessors' copies of the run's series.
  void collect() {
    const run::SeriesSet& s = loop->series();
    samples.clear();
    kept_views.clear();
    seconds = 0;
    if (auto it = s.find("samples"); it != s.end())
      for (const std::vector<double>& r : it->second.rows)
        samples.push_back(Sample{r[0], {r[1], r[2], r[3]}, r[4], r[5], {r[6], r[7], r[8]}, r[9], r[10], r[11]});
    if (auto it = s.find("views"); it != s.end())
      for (const std::vector<double>& r : it->second.rows) {
        const std::size_t n = std::size_t(r[1]);
        auto part = [&](std::size_t from, std::size_t count) {
          return std::vector<double>(r.begin() + std::ptrdiff_t(2 + from), r.begin() + std::ptrdiff_t(2 + from + count));
        };
        kept_views.push_back(View{r[0], part(0, 3 * n), part(3 * n, n), part(4 * n, n), part(5 * n, 3 * n)});
      }
    if (auto it = s.find("phases"); it != s.end() && !it->second.rows.empty())
      for (double x : it->second.rows[0]) seconds += x;
  }
};

Run::Run(const Model& model, const chapter3::EvaluationSet* eval, const std::string& checkpoint, double sitting)
    : impl_(std::make_unique<Impl>(model, eval, checkpoint, sitting)) {}
Run::~Run() = default;

bool Run::advance() {
  impl_->loop->evolve();
  impl_->collect();
  return done();
}

int Run::step() const { return int(impl_->loop->ib().step_count()); }
bool Run::done() const { return impl_->loop->progress().ended(); }
std::string Run::failure() const { return impl_->loop->progress().stop_message; }
bool Run::continued() const { return impl_->loop->continued(); }
const std::vector<Sample>& Run::series() const { return impl_->samples; }
const std::vector<View>& Run::views() const { return impl_->kept_views; }
double Run::seconds() const { return impl_->seconds; }
double Run::seconds_per_step() const {
  const long n = impl_->loop->progress().steps_timed;
  return n > 0 ? impl_->seconds / double(n) : NAN;
}
const Model& Run::model() const { return impl_->m; }
const surface::CylinderPoints& Run::capillary() const { return impl_->cap; }
const std::vector<surface::Triangle>& Run::triangles() const { return impl_->eval ? impl_->eval->tris : impl_->no_tris; }

std::vector<std::array<double, 2>> Run::profile_x(double x_probe) const {
  const Impl& s = *impl_;
  const sim::ImmersedBoundary& ib = s.loop->ib();
  require(ib.step_count() > 0, "profile_x", "a run at step 0", "needs the flow of a step");
  const run::SeriesSet& series = s.loop->series();
  const auto frame = series.find("frame");
  const double ucx = frame == series.end() || frame->second.rows.empty() ? 0.0 : frame->second.rows[0][0];
  const double h = s.m.h();
  const int nz = int(std::lround(2 * s.m.L / (h / 2)));
  std::vector<double> P(static_cast<std::size_t>(3 * nz));
  for (int j = 0; j < nz; ++j) {
    P[j] = x_probe;
    P[nz + j] = 0;
    P[2 * nz + j] = -s.m.L + (j + 0.5) * h / 2;
  }
  dvec Pd(P.begin(), P.end()), Ud;
  const MacOperators& ops = ib.fluid().operators();
  ib::Interaction probe({ops.component_box(0), ops.component_box(1), ops.component_box(2)}, s.m.kernel);
  probe.interpolate(Pd, ib.fluid_state().u, Ud);
  std::vector<double> Uh(Ud.size());
  thrust::copy(Ud.begin(), Ud.end(), Uh.begin());
  std::vector<std::array<double, 2>> out;
  for (int j = 0; j < nz; ++j) out.push_back({P[2 * nz + j], Uh[j] + ucx});
  return out;
}

void write_snapshots(const Run& run, const std::string& dir, const std::string& label) {
  namespace h5 = rbfib::io::h5;
  std::filesystem::create_directories(dir);
  // points n x 3 (um) and triangles of one surface into group g of file
  auto write_surface = [](h5::Id& file, const char* g, const std::vector<double>& X,
                          const std::vector<surface::Triangle>& tris) {
    const std::size_t n = X.size() / 3;
    std::vector<double> P(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) P[3 * i + d] = X[d * n + i] / um;
    std::vector<long long> T;
    for (const auto& t : tris) T.insert(T.end(), {(long long)t[0], (long long)t[1], (long long)t[2]});
    h5::Id group = h5::create_group(file, g);
    h5::write(group, "points", P.data(), {hsize_t(n), 3}, "um");
    h5::write(group, "triangles", T.data(), {hsize_t(tris.size()), 3});
    return group;
  };
  auto item = [](std::size_t rows, bool triple, const std::string& type, const std::string& path) {
    return "<DataItem Dimensions=\"" + to_text(rows) + (triple ? " 3" : "") + "\" NumberType=\"" + type +
           "\" Precision=\"8\" Format=\"HDF\">" + path + "</DataItem>";
  };
  auto grid = [&](const std::string& name, const std::string& file, std::size_t n, std::size_t nt) {
    return "    <Grid Name=\"" + name + "\" GridType=\"Uniform\">\n     <Topology TopologyType=\"Triangle\" NumberOfElements=\"" +
           to_text(nt) + "\">" + item(nt, true, "Int", file + ":/" + name + "/triangles") +
           "</Topology>\n     <Geometry GeometryType=\"XYZ\">" + item(n, true, "Float", file + ":/" + name + "/points") +
           "</Geometry>\n";
  };
  const surface::CylinderPoints& cap = run.capillary();
  const std::vector<surface::Triangle> cap_tris = surface::cylinder_triangles(cap);
  const std::string capfile = "capillary_eta" + to_text(run.model().eta) + ".h5";
  {
    h5::Id f = h5::create_file(dir + "/" + capfile);
    write_surface(f, "capillary", cap.X, cap_tris);
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"" << label << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const auto& tris = run.triangles();
  for (std::size_t s = 0; s < run.views().size(); ++s) {
    const View& v = run.views()[s];
    const std::size_t n = v.X.size() / 3;
    const std::string file = label + "_" + to_text(s) + ".h5";
    {
      std::vector<double> f(n), H(n);
      for (std::size_t i = 0; i < n; ++i) {
        f[i] = v.f[i] * 1e-3;
        H[i] = v.H[i] * um;
      }
      h5::Id fh = h5::create_file(dir + "/" + file);
      h5::attribute(fh, "t", v.t);
      h5::Id g = write_surface(fh, "cell", v.X, tris);
      h5::write(g, "force_density", f.data(), {hsize_t(n)}, "pN/um^2");
      h5::write(g, "mean_curvature", H.data(), {hsize_t(n)}, "1/um");
    }
    x << "   <Grid Name=\"t" << s << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "    <Time Value=\"" << v.t << "\"/>\n"
      << grid("cell", file, n, tris.size())
      << "     <Attribute Name=\"force_density_pN_per_um2\" AttributeType=\"Scalar\" Center=\"Node\">"
      << item(n, false, "Float", file + ":/cell/force_density") << "</Attribute>\n"
      << "     <Attribute Name=\"mean_curvature_per_um\" AttributeType=\"Scalar\" Center=\"Node\">"
      << item(n, false, "Float", file + ":/cell/mean_curvature") << "</Attribute>\n"
      << "    </Grid>\n"
      << grid("capillary", capfile, std::size_t(cap.size()), cap_tris.size()) << "    </Grid>\n   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  std::ofstream(dir + "/" + label + ".xmf") << x.str();
}

}  // namespace rbfib::capillary
