#include "rbfib/models/shell_relaxation.hpp"

#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/mechanics/net_force.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/radial_extent.hpp"

#include <filesystem>
#include <map>
#include <optional>

namespace rbfib::chapter3 {

const char* to_string(Method m) { return m == Method::shvd ? "SHVD" : "LDSM"; }

const surface::SphereSites& interpolation_sites(int M) {
  static std::map<int, surface::SphereSites> cache;
  auto it = cache.find(M);
  if (it == cache.end()) it = cache.emplace(M, surface::max_determinant_points(M).sites).first;
  return it->second;
}

std::string RelaxationSpec::label(const std::string& tag) const {
  const std::string kind = shape_name + (md_degree >= 0 ? "_MD" : "") +
                           (point == Point::rightmost ? "_rightmost" : point == Point::axis_site ? "_driver_loop" : "") + tag;
  return std::string(to_string(method)) + "_" + kind + "_eta" + to_text(eta) + "_n" + to_text(n) +
         (method == Method::shvd ? "_M" + to_text(M) : std::string()) + "_dt1over" + to_text(std::lround(1 / dt)) +
         "_steps" + to_text(steps) + "_every" + to_text(record_every);
}

RelaxationSpec dynamic_test(Method method, int eta, double t, int M, int records) {
  RelaxationSpec s;
  s.method = method;
  s.shape = surface::ellipsoid(1.2, 1 / std::sqrt(1.2), 1 / std::sqrt(1.2));
  s.eta = eta;
  s.dt = 1.0 / (2 * eta);
  s.steps = int(std::lround(t / s.dt));
  s.M = M;
  s.record_every = records > 0 ? std::max(1, s.steps / records) : 0;
  s.n = spiral_sites(eta);
  return s;
}

struct Relaxation::Impl {
  RelaxationSpec spec;
  EvaluationSet eval;
  index_t measure_site = -1;  // SHVD: d_max at this evaluation site instead of at its interpolant
  std::shared_ptr<const surface::SurfaceOperators> axis_ops;  // SHVD: the interpolant at (0, 0)
  cells::CellGeometry geometry;
  std::optional<run::Run> loop;

  Impl(const RelaxationSpec& s, const EvaluationSet& e, const std::string& checkpoint, const std::string& label,
       double sitting)
      : spec(s), eval(e) {
    require(spec.steps >= 1, "steps", spec.steps, "must be >= 1");
    require(spec.eta >= 4, "grid size eta", spec.eta, "must be >= 4");
    if (spec.point == Point::rightmost) eval.axis_site = surface::rightmost_site(eval.sites);
    if (spec.method == Method::shvd && spec.point != Point::material) measure_site = eval.axis_site;
    // The coupled step of Sec. 3.3: steady Stokes on the periodic MAC grid, forward Euler (eq. 87).
    MacGrid grid = make_mac_grid(3, {spec.eta, spec.eta, spec.eta}, {2 * spec.L, 2 * spec.L, 2 * spec.L},
                                 {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
    grid.origin = {-spec.L, -spec.L, -spec.L};
    sim::IbOptions o;
    o.coupling = sim::Coupling::forward_euler;
    o.kernel = spec.kernel;
    o.stopping_condition = false;
    sim::ImmersedBoundary ib(std::make_unique<PeriodicStokesStep>(grid, FluidParameters{1.0, spec.mu}, spec.dt, true), o);
    const std::vector<mechanics::EnergyDensity> energies = {mechanics::EnergyDensity::neo_hookean_paper(spec.Gs, spec.A),
                                                            mechanics::EnergyDensity::surface_tension(spec.sigma)};
    if (spec.method == Method::shvd) {
      cells::CellTypeSpec ts;
      ts.name = "SHVD m = " + to_text((spec.M + 1) * (spec.M + 1));
      ts.shape = cells::ellipsoid_shape(1, 1, 1);
      ts.data_sites = interpolation_sites(spec.M);
      ts.sample_sites = eval.sites;
      ts.interpolant = cells::Interpolant::spherical_harmonics;
      ts.sh_degree = spec.M;
      ts.sphere_weights = eval.w;
      ts.model.elastic = energies;
      cells::Batch batch(std::make_shared<const cells::CellType>(ts), std::vector<cells::Placement>{cells::Placement{}});
      const std::vector<double> X0 = spec.shape.points(ts.data_sites);  // eq. (88) or (89) at the m sites
      thrust::copy(X0.begin(), X0.end(), batch.state().storage().begin());
      ib.add(std::move(batch));
      surface::SphereSites axis;
      axis.lambda = {0.0};
      axis.theta = {0.0};
      axis_ops = surface::sh_operators(ts.data_sites, axis, spec.M);
    } else {
      ib.add(sim::LdsmShell{"LDSM", eval.tris, eval.Z, spec.shape.points(eval.sites), energies});
    }
    run::Options ro;
    ro.t_end = spec.steps * spec.dt;
    ro.checkpoint = checkpoint;
    ro.sitting = sitting;
    ro.label = label;
    ro.sample_every = run::Cadence{};  // the hook records at its own steps
    run::Hooks h;
    h.after_step = [this](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& series) {
      const long k = ib.step_count();
      if (r) {
        run::append_phases(series["phases"], *r);
        if (k == 1) {  // the forces of the first step act at X^0
          const std::vector<double> F0 =
              spec.method == Method::shvd ? ib.batch_set(0).forces().force.to_host() : ib.shell(0).force();
          series["start"].rows.at(0).push_back(mechanics::net_force_inf(F0));
          series["start"].rows.at(0).push_back(mechanics::max_force_inf(F0));
        }
      }
      if (k == 0 || k == spec.steps || (spec.record_every > 0 && k % spec.record_every == 0)) record(ib, k, series);
    };
    loop.emplace(describe(), std::move(ib), ro, std::move(h));
  }

  /// The run as text (what its checkpoint must match).
  std::string describe() const {
    std::string d = std::string("chapter3 relaxation ") + to_string(spec.method) + "\n";
    for (double x : {spec.shape.a, spec.shape.b, spec.shape.c, spec.shape.B, spec.shape.Vf, double(spec.eta), spec.L,
                     spec.mu, spec.dt, double(spec.steps), double(spec.record_every), double(spec.M), spec.Gs, spec.A,
                     spec.sigma, double(int(spec.kernel)), double(measure_site)})
      d += to_text(x) + "\n";
    return d + eval.family + " " + to_text(eval.size()) + " axis site " + to_text(eval.axis_site) + "\n";
  }

  /// The diagnostics of the header at X^k.
  void record(const sim::ImmersedBoundary& ib, long k, run::SeriesSet& series) {
    double c[3], volume, x_axis = 0;
    std::vector<double> Xs;
    if (spec.method == Method::shvd) {
      const cells::Batch& batch = ib.batch(0);
      cells::measure(batch, geometry);
      for (int d = 0; d < 3; ++d) c[d] = geometry.cells.centroid[0][d];
      volume = geometry.cells.volume[0];
      Xs = geometry.positions.to_host();
      x_axis = measure_site >= 0 ? Xs.at(std::size_t(measure_site))
                                 : surface::jets_from_operators(*axis_ops, batch.positions_host())[0].x[0];
    } else {
      Xs = ib.shell(0).shell().X;
      const surface::PolyhedronMeasures pm = surface::polyhedron_measures(eval.tris, Xs);
      volume = pm.volume;
      for (int d = 0; d < 3; ++d) c[d] = pm.centroid[d];
      if (eval.axis_site >= 0)
        x_axis = Xs[eval.axis_site];
      else
        for (int v = 0; v < 3; ++v) x_axis += eval.axis_weights[v] * Xs[eval.axis_triangle[v]];
    }
    if (k == 0) series["start"] = run::Series{{"axis0"}, {{x_axis - c[0]}}};
    const surface::RadialExtent r = surface::radial_extent(Xs, c);
    series["samples"].columns = {"t", "d_axis", "r_max", "r_min", "volume"};
    series["samples"].rows.push_back(
        {k * spec.dt, (x_axis - c[0]) - series.at("start").rows.at(0).at(0), r.max - 1, r.min - 1, volume});
  }
};

Relaxation::Relaxation(const RelaxationSpec& spec, const EvaluationSet& eval, const std::string& checkpoint,
                       const std::string& label, double sitting)
    : impl_(std::make_unique<Impl>(spec, eval, checkpoint, label, sitting)) {}
Relaxation::~Relaxation() = default;

bool Relaxation::advance() { return !impl_->loop->evolve(1).ended(); }

bool Relaxation::advance_all() { return impl_->loop->evolve().ended(); }

void Relaxation::mark_block() {
  run::Run& loop = *impl_->loop;
  loop.series()["blocks"].rows.push_back({run::phase_sums(loop.series()["phases"]).total()});
  if (loop.progress().ended()) loop.checkpoint();  // the run's last block, after its finishing checkpoint
}

int Relaxation::step() const { return int(impl_->loop->ib().step_count()); }

RelaxationResult Relaxation::result() const {
  const run::Run& loop = *impl_->loop;
  const run::Progress p = loop.progress();
  RelaxationResult r;
  r.steps = int(p.clock.step);
  r.finished = p.ended();
  r.continued = loop.continued();
  r.failed = p.status == run::RunStatus::stopped;
  if (r.failed)
    r.failure = std::string(to_string(impl_->spec.method)) + " at step " + to_text(p.clock.step) +
                " (t = " + to_text(p.clock.t) + "): " + p.stop_message;
  r.label = loop.label();
  r.seconds = p.wall_seconds;
  const run::SeriesSet& s = loop.series();
  if (auto it = s.find("samples"); it != s.end())
    for (const std::vector<double>& q : it->second.rows) r.series.push_back(Sample{q[0], q[1], q[2], q[3], q[4]});
  if (auto it = s.find("start"); it != s.end() && it->second.rows.at(0).size() == 3) {
    r.force_integral0 = it->second.rows[0][1];
    r.max_force0 = it->second.rows[0][2];
  }
  if (auto it = s.find("phases"); it != s.end()) {
    r.phases = run::phase_sums(it->second);
    r.median = run::phase_medians(it->second);
  }
  if (auto it = s.find("blocks"); it != s.end())
    for (const std::vector<double>& q : it->second.rows) r.block_ends.push_back(q.at(0));
  return r;
}

}  // namespace rbfib::chapter3
