#include "rbfib/models/blebbing.hpp"

#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/surface/geometry.hpp"

#include <thrust/copy.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace rbfib::blebbing {

long Model::steps() const { return std::lround((t_equilibrate + t_bleb) / dt); }

namespace {
std::vector<double> unit_sites(const chapter3::EvaluationSet& e, double r, const std::array<double, 3>& c) {
  const std::size_t n = std::size_t(e.size());
  std::vector<double> X(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) X[d * n + i] = c[d] + r * e.Z[d * n + i];
  return X;
}
}  // namespace

struct Run::Impl {
  Model m;
  const chapter3::EvaluationSet& eval;
  std::vector<char> detached, ring;  // per site: link removed at the bleb; attached next to a removed one
  std::vector<mechanics::EnergyDensity> energies;
  std::optional<run::Run> loop;
  sim::CortexSet* cortex = nullptr;  // owned by the step (a stable address), detached at t_equilibrate
  bool bleb_started = false;
  std::vector<Sample> samples;
  std::vector<View> kept_views;
  double seconds = 0;

  Impl(const Model& model, const chapter3::EvaluationSet& e, const std::string& checkpoint, double sitting,
       std::function<void(const std::string&)> progress)
      : m(model), eval(e) {
    require(m.eta >= 8, "grid size eta", m.eta, "must be >= 8");
    require(m.mu > 0, "viscosity mu (P)", m.mu, "must be > 0");
    require(m.dt > 0, "time step dt (s)", m.dt, "must be > 0");
    require(m.t_equilibrate >= 0 && m.t_bleb >= 0, "t_equilibrate, t_bleb (s)", m.t_equilibrate, "must be >= 0");
    require(m.r_cortex > 0 && m.r_cortex < m.r_mem && m.r_mem < m.box / 2, "radii r_cortex < r_mem (cm)", m.r_cortex,
            "must satisfy 0 < r_cortex < r_mem < box / 2");
    require(m.record_every > 0 && m.view_every > 0, "record_every, view_every", m.record_every, "must be > 0");
    require(m.Gs > 0 && m.K >= 0 && m.gamma >= 0, "membrane moduli G_S, K, gamma (dyn/cm)", m.Gs, "must be G_S > 0, K, gamma >= 0");
    const std::size_t n = std::size_t(eval.size());
    detached.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) detached[i] = std::acos(std::clamp(eval.Z[2 * n + i], -1.0, 1.0)) <= m.phi_bleb;
    ring.assign(n, 0);
    for (const surface::Triangle& t : eval.tris)
      for (int a = 0; a < 3; ++a)
        if (detached[t[a]])
          for (int b = 0; b < 3; ++b) ring[t[b]] = ring[t[b]] || !detached[t[b]];
    require(std::count(detached.begin(), detached.end(), 1) > 0, "bleb region phi <= " + to_text(m.phi_bleb), "no site",
            "holds no site of the evaluation set: too few sites");
    MacGrid g = make_mac_grid(3, {m.eta, m.eta, m.eta}, {m.box, m.box, m.box},
                              {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
    auto fluid = std::make_unique<PeriodicStokesStep>(g, FluidParameters{1.0, m.mu}, m.dt, true);
    sim::IbOptions o;
    o.coupling = sim::Coupling::forward_euler;
    o.kernel = ib::Kernel::peskin4;
    o.stopping_condition = false;
    sim::ImmersedBoundary ib(std::move(fluid), o);
    // Eq. (71) with K and G_S is eq. (68) with A = K / G_S; plus surface tension, eq. (72).
    energies = {mechanics::EnergyDensity::neo_hookean_paper(m.Gs, m.K / m.Gs), mechanics::EnergyDensity::surface_tension(m.gamma)};
    const sim::LagrangianSet& membrane = add_membrane(ib);
    sim::Cortex c{"cortex", eval.tris, unit_sites(eval, m.r_cortex, {0, 0, 0}), unit_sites(eval, m.r_cortex, m.center),
                  m.k_cortex, m.k_adh, m.xi, {}};
    cortex = &ib.cortex(ib.add(std::move(c), membrane));
    run::Options ro;
    ro.t_end = m.steps() * m.dt;
    ro.checkpoint = checkpoint;
    ro.sitting = sitting;
    ro.sample_every = run::Cadence{};  // the hook records at its own steps
    run::Hooks hooks;
    hooks.after_step = [this](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& s) {
      after_step(ib, r, s);
    };
    if (progress) hooks.progress = [progress](const run::Progress& p) { progress(p.describe()); };
    loop.emplace(describe(), std::move(ib), ro, std::move(hooks));
    bleb_if_due(loop->ib().step_count());  // a continued run past equilibration
    collect();
  }

  std::string describe() const {
    std::string d = "chapter3_blebbing run\n";
    for (double x : {m.box, double(m.eta), m.mu, m.r_mem, m.r_cortex, m.center[0], m.center[1], m.center[2], m.gamma, m.K,
                     m.Gs, m.k_cortex, m.k_adh, m.xi, m.phi_bleb, double(int(m.method)), double(m.M), m.dt, m.t_equilibrate,
                     m.t_bleb, double(m.record_every), double(m.view_every)})
      d += to_text(x) + "\n";
    return d + eval.family + " " + to_text(eval.size()) + "\n";
  }

  const sim::LagrangianSet& add_membrane(sim::ImmersedBoundary& ib) {
    if (m.method == chapter3::Method::ldsm) {
      const std::vector<double> Z = unit_sites(eval, m.r_mem, {0, 0, 0});
      return ib.shell(ib.add(sim::LdsmShell{"membrane (LDSM)", eval.tris, Z, unit_sites(eval, m.r_mem, m.center), energies}));
    }
    const index_t mm = index_t(m.M + 1) * (m.M + 1);
    cells::CellTypeSpec ts;
    ts.name = "membrane, SHVD m = " + to_text(mm);
    ts.shape = cells::ellipsoid_shape(m.r_mem, m.r_mem, m.r_mem);
    ts.data_sites = mm == eval.size() ? eval.sites : chapter3::interpolation_sites(m.M);  // m = n: the sites interpolate
    ts.sample_sites = eval.sites;
    ts.interpolant = cells::Interpolant::spherical_harmonics;
    ts.sh_degree = m.M;
    ts.sphere_weights = eval.w;
    ts.model.elastic = energies;
    cells::Placement pl;
    pl.center = m.center;
    return ib.batch_set(ib.add(cells::Batch(std::make_shared<const cells::CellType>(ts), std::vector<cells::Placement>{pl})));
  }

  /// After step k: the links of the bleb region go once the cell has equilibrated.
  void bleb_if_due(long k) {
    if (bleb_started || k * m.dt < m.t_equilibrate * (1 - 1e-12)) return;
    std::vector<char> attached(detached.size());
    for (std::size_t i = 0; i < attached.size(); ++i) attached[i] = !detached[i];
    cortex->set_attached(std::move(attached));
    bleb_started = true;
  }

  bool record_due(long k) const { return k % m.record_every == 0 || k == m.steps(); }
  bool view_due(long k) const { return k % m.view_every == 0 || k == m.steps(); }

  /// The membrane now: its n sites, volume and area (SHVD: a force call's quadrature; LDSM: the
  /// polyhedron), and H (SHVD) when asked.
  void membrane_now(const sim::ImmersedBoundary& ib, std::vector<double>& X, double& volume, double& area,
                    std::vector<double>* H) const {
    if (m.method == chapter3::Method::ldsm) {
      X = ib.shell(0).shell().X;
      const surface::PolyhedronMeasures pm = surface::polyhedron_measures(eval.tris, X);
      volume = pm.volume, area = pm.area;
      if (H) H->assign(X.size() / 3, NAN);
      return;
    }
    cells::CellForces out;
    cells::compute_forces(ib.batch(0), out);
    X = out.positions.to_host();
    volume = out.cells.volume[0], area = out.cells.area[0];
    if (!H) return;
    const std::vector<surface::Jet> jets = surface::jets_from_operators(ib.batch(0).type().to_sample(), ib.batch(0).positions_host());
    H->resize(jets.size());
    for (std::size_t i = 0; i < jets.size(); ++i) (*H)[i] = surface::point_geometry(jets[i]).H;
  }

  /// The largest and the root-mean-square |S* u| over the sites X (cm/s).
  std::array<double, 2> boundary_speed(const sim::ImmersedBoundary& ib, const std::vector<double>& X) const {
    const MacOperators& ops = ib.fluid().operators();
    ib::Interaction probe({ops.component_box(0), ops.component_box(1), ops.component_box(2)}, ib::Kernel::peskin4);
    dvec Xd(X.begin(), X.end()), Ud;
    probe.interpolate(Xd, ib.fluid_state().u, Ud);
    std::vector<double> U(Ud.size());
    thrust::copy(Ud.begin(), Ud.end(), U.begin());
    const std::size_t n = X.size() / 3;
    double v = 0, v2 = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double s = std::hypot(U[i], U[n + i], U[2 * n + i]);
      v = std::max(v, s);
      v2 += s * s;
    }
    return {v, std::sqrt(v2 / double(n))};
  }

  void after_step(const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& s) {
    const long k = ib.step_count();
    if (r) {
      auto& ph = s["phases"].rows;
      if (ph.empty()) ph = {std::vector<double>(5, 0.0)};
      const double add[5] = {r->seconds_forces, r->seconds_spreading, r->seconds_fluid, r->seconds_interpolation,
                             r->seconds_update};
      for (int i = 0; i < 5; ++i) ph[0][i] += add[i];
    }
    bleb_if_due(k);
    if (!record_due(k) && !view_due(k)) return;
    std::vector<double> X, H;
    double volume = NAN, area = NAN;
    membrane_now(ib, X, volume, area, view_due(k) ? &H : nullptr);
    const double t = k * m.dt;
    if (view_due(k)) {
      std::vector<double> row{t, double(H.size())};
      row.insert(row.end(), X.begin(), X.end());
      row.insert(row.end(), H.begin(), H.end());
      s["views"].rows.push_back(std::move(row));
    }
    if (!record_due(k)) return;
    const std::size_t n = X.size() / 3;
    // The bleb (Fig. 12): the ring's centre and diameter, and the membrane's top above the centre.
    double c[3] = {0, 0, 0}, top = -INFINITY, diameter = 0;
    std::size_t nr = 0;
    for (std::size_t i = 0; i < n; ++i) {
      top = std::max(top, X[2 * n + i]);
      if (!ring[i]) continue;
      for (int d = 0; d < 3; ++d) c[d] += X[d * n + i];
      ++nr;
    }
    for (double& x : c) x /= double(nr);
    for (std::size_t i = 0; i < n; ++i)
      if (ring[i]) diameter += 2 * std::hypot(X[i] - c[0], X[n + i] - c[1]) / double(nr);
    const std::vector<double>& Xc = cortex->cortex().X;
    double rc = 0, link = 0;
    for (std::size_t i = 0; i < n; ++i) {
      rc += std::hypot(Xc[i] - m.center[0], Xc[n + i] - m.center[1], Xc[2 * n + i] - m.center[2]) / double(n);
      if (!bleb_started || !detached[i])
        link = std::max(link, std::hypot(X[i] - Xc[i], X[n + i] - Xc[n + i], X[2 * n + i] - Xc[2 * n + i]));
    }
    s["samples"].columns = {"t (s)", "volume (cm^3)", "area (cm^2)", "bleb size (cm)", "ring diameter (cm)",
                            "boundary speed (cm/s)", "boundary speed rms (cm/s)", "cortex radius (cm)", "link max (cm)"};
    const std::array<double, 2> speed = k > 0 ? boundary_speed(ib, X) : std::array<double, 2>{0, 0};
    s["samples"].rows.push_back({t, volume, area, top - c[2], diameter, speed[0], speed[1], rc, link});
  }

  void collect() {
    const run::SeriesSet& s = loop->series();
    samples.clear();
    kept_views.clear();
    seconds = 0;
    if (auto it = s.find("samples"); it != s.end())
      for (const std::vector<double>& r : it->second.rows) samples.push_back(Sample{r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]});
    if (auto it = s.find("views"); it != s.end())
      for (const std::vector<double>& r : it->second.rows) {
        const std::size_t n = std::size_t(r[1]);
        kept_views.push_back(View{r[0], std::vector<double>(r.begin() + 2, r.begin() + std::ptrdiff_t(2 + 3 * n)),
                                  std::vector<double>(r.begin() + std::ptrdiff_t(2 + 3 * n), r.begin() + std::ptrdiff_t(2 + 4 * n))});
      }
    if (auto it = s.find("phases"); it != s.end() && !it->second.rows.empty())
      for (double x : it->second.rows[0]) seconds += x;
  }
};

Run::Run(const Model& model, const chapter3::EvaluationSet& eval, const std::string& checkpoint, double sitting,
         std::function<void(const std::string&)> progress)
    : impl_(std::make_unique<Impl>(model, eval, checkpoint, sitting, std::move(progress))) {}
Run::~Run() = default;

bool Run::advance() {
  impl_->loop->evolve();
  impl_->collect();
  return done();
}

long Run::step() const { return impl_->loop->ib().step_count(); }
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
double Run::hours_to_go() const { return impl_->loop->progress().hours_to_go(); }
const Model& Run::model() const { return impl_->m; }
const std::vector<surface::Triangle>& Run::triangles() const { return impl_->eval.tris; }
const std::vector<char>& Run::detached() const { return impl_->detached; }

}  // namespace rbfib::blebbing
