#include "common/chapter3_relaxation.hpp"

#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

namespace rbfib::chapter3 {

namespace {


/// The periodic MAC grid on [-L, L]^3 with eta cells per side.
MacGrid periodic_grid(int eta, double L) {
  require(eta >= 4, "grid size eta", eta, "must be >= 4");
  MacGrid g = make_mac_grid(3, {eta, eta, eta}, {2 * L, 2 * L, 2 * L},
                            {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
  g.origin = {-L, -L, -L};
  return g;
}

/// The coupled step of Sec. 3.3: steady Stokes (alpha = 0, the exact inverse of the MAC operators),
/// Chapter 3's forward Euler (eq. 87), the run's kernel, no stopping condition (the paper has none).
sim::ImmersedBoundary chapter3_step(int eta, double L, double mu, double dt, ib::Kernel kernel) {
  sim::IbOptions o;
  o.coupling = sim::Coupling::forward_euler;
  o.kernel = kernel;
  o.stopping_condition = false;
  return sim::ImmersedBoundary(std::make_unique<PeriodicStokesStep>(periodic_grid(eta, L), FluidParameters{1.0, mu}, dt, true), o);
}

/// The diagnostics of the header from the evaluation sites' positions Xs (n x 3), the x coordinate
/// x_axis of the material point (0, 0), and the centroid c.
Sample sample(double t, const std::vector<double>& Xs, double x_axis, const double c[3], double volume, double axis0) {
  const std::size_t n = Xs.size() / 3;
  Sample s{t, 0, 0, 0, volume};
  double rmax = 0, rmin = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = Xs[i] - c[0], dy = Xs[n + i] - c[1], dz = Xs[2 * n + i] - c[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    rmax = std::max(rmax, r);
    rmin = std::min(rmin, r);
  }
  s.r_max = rmax - 1;  // minus the reference radius (Fig. 4 caption)
  s.r_min = rmin - 1;
  s.d_axis = (x_axis - c[0]) - axis0;
  return s;
}

/// Per-step times of each phase, and their medians.
struct PhaseLog {
  std::vector<double> forces, products, spread, solve, interpolate, update;
  static double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t h = v.size() / 2;
    return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
  }
  PhaseTimes medians() const {
    PhaseTimes p;
    p.forces = median(forces);
    p.force_products = median(products);
    p.spread = median(spread);
    p.solve = median(solve);
    p.interpolate = median(interpolate);
    p.update = median(update);
    return p;
  }
};

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// |sum_i F^_i|_inf (F n x 3 column-major).
double force_integral(const std::vector<double>& F) {
  const std::size_t n = F.size() / 3;
  double s[3] = {0, 0, 0};
  for (std::size_t i = 0; i < F.size(); ++i) s[i / n] += F[i];
  return std::max({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])});
}

}  // namespace

const char* to_string(Method m) { return m == Method::shvd ? "SHVD" : "LDSM"; }

std::vector<mechanics::EnergyDensity> total_energy(double Gs, double A, double sigma) {
  return {mechanics::EnergyDensity::neo_hookean_paper(Gs, A), mechanics::EnergyDensity::surface_tension(sigma)};
}

const surface::SphereSites& interpolation_sites(int M) {
  static std::map<int, surface::SphereSites> cache;
  auto it = cache.find(M);
  if (it == cache.end()) it = cache.emplace(M, surface::max_determinant_points(M).sites).first;
  return it->second;
}

struct Relaxation::Impl {
  RelaxationSpec spec;
  const EvaluationSet& eval;
  std::vector<mechanics::EnergyDensity> energies;
  std::shared_ptr<const surface::SurfaceOperators> axis_ops;  // SHVD: the interpolant at (0, 0)
  cells::CellGeometry geometry;
  std::optional<run::Run> loop;

  Impl(const RelaxationSpec& s, const EvaluationSet& e, const std::string& checkpoint, const std::string& label, double sitting)
      : spec(s), eval(e), energies(total_energy(s.Gs, s.A, s.sigma)) {
    require(spec.steps >= 1, "steps", spec.steps, "must be >= 1");
    require(spec.measure_site < index_t(eval.size()), "measure_site", spec.measure_site, "must be a site of the evaluation set");
    sim::ImmersedBoundary ib = chapter3_step(spec.eta, spec.L, spec.mu, spec.dt, spec.kernel);
    if (spec.method == Method::shvd) {
      // The cell type: unit-sphere reference, the degree-M interpolant through the m sites (LU of
      // Y once), the n evaluation sites with their weights, the total energy of Sec. 4.2.
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
    run::Options o;
    o.t_end = spec.steps * spec.dt;
    o.checkpoint = checkpoint;
    o.sitting = sitting;
    o.label = label;
    o.sample_every = run::Cadence{};  // the hook records at its own steps
    run::Hooks h;
    h.after_step = [this](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& series) {
      after_step(ib, r, series);
    };
    loop.emplace(describe(), std::move(ib), o, std::move(h));
  }

  /// The run as text (what its checkpoint must match).
  std::string describe() const {
    std::string d = std::string("chapter3 relaxation ") + to_string(spec.method) + "\n";
    for (double x : {spec.shape.a, spec.shape.b, spec.shape.c, spec.shape.B, spec.shape.Vf, double(spec.eta), spec.L, spec.mu,
                     spec.dt, double(spec.steps), double(spec.record_every), double(spec.M), spec.Gs, spec.A, spec.sigma,
                     double(int(spec.kernel)), double(spec.measure_site)})
      d += to_text(x) + "\n";
    return d + eval.family + " " + to_text(eval.size()) + " axis site " + to_text(eval.axis_site) + "\n";
  }

  bool record_now(long k) const { return k == 0 || k == spec.steps || (spec.record_every > 0 && k % spec.record_every == 0); }

  void after_step(const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& series) {
    const long k = ib.step_count();
    if (r) {
      series["phases"].columns = {"forces (s)", "products (s)", "spread (s)", "solve (s)", "interpolate (s)", "update (s)"};
      series["phases"].rows.push_back({r->seconds_forces, r->seconds_force_products, r->seconds_spreading, r->seconds_fluid,
                                       r->seconds_interpolation, r->seconds_update});
      if (k == 1) {  // the forces of the first step act at X^0
        const std::vector<double> F0 =
            spec.method == Method::shvd ? ib.batch_set(0).forces().force.to_host() : ib.shell(0).force();
        std::vector<double>& start = series["start"].rows.at(0);
        start.push_back(force_integral(F0));
        start.push_back(max_abs(F0));
      }
    }
    if (record_now(k)) record(ib, k, series);
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
      // the material point (0, 0) on the interpolant (an evaluation site of the spirals), or the
      // evaluation site asked for
      x_axis = spec.measure_site >= 0 ? Xs.at(std::size_t(spec.measure_site))
                                      : surface::jets_from_operators(*axis_ops, batch.positions_host())[0].x[0];
    } else {
      Xs = ib.shell(0).shell().X;
      const surface::PolyhedronMeasures pm = surface::polyhedron_measures(eval.tris, Xs);
      volume = pm.volume;
      for (int d = 0; d < 3; ++d) c[d] = pm.centroid[d];
      if (eval.axis_site >= 0)  // the material point (0, 0) on the piecewise-linear surface
        x_axis = Xs[eval.axis_site];
      else
        for (int v = 0; v < 3; ++v) x_axis += eval.axis_weights[v] * Xs[eval.axis_triangle[v]];
    }
    if (k == 0) series["start"] = run::Series{{"axis0"}, {{x_axis - c[0]}}};
    const Sample s = sample(k * spec.dt, Xs, x_axis, c, volume, series.at("start").rows.at(0).at(0));
    series["samples"].columns = {"t", "d_axis", "r_max", "r_min", "volume"};
    series["samples"].rows.push_back({s.t, s.d_axis, s.r_max, s.r_min, s.volume});
  }
};

Relaxation::Relaxation(const RelaxationSpec& spec, const EvaluationSet& eval, const std::string& checkpoint,
                       const std::string& label, double sitting)
    : impl_(std::make_unique<Impl>(spec, eval, checkpoint, label, sitting)) {}
Relaxation::~Relaxation() = default;

bool Relaxation::advance() { return !impl_->loop->evolve(1).ended(); }

bool Relaxation::advance_all() { return impl_->loop->evolve().ended(); }

void Relaxation::mark_block() {
  // phases.total(): the wall time of the steps so far, summed from the series "phases".
  run::SeriesSet& s = impl_->loop->series();
  PhaseTimes p;
  for (const std::vector<double>& q : s["phases"].rows) {  // q[1], the products, is part of q[0]
    p.forces += q[0];
    p.spread += q[2];
    p.solve += q[3];
    p.interpolate += q[4];
    p.update += q[5];
  }
  s["blocks"].rows.push_back({p.total()});
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
    r.failure = std::string(to_string(impl_->spec.method)) + " at step " + to_text(p.clock.step) + " (t = " + to_text(p.clock.t) + "): " +
                p.stop_message;
  r.label = loop.label();
  r.seconds = p.wall_seconds;
  const run::SeriesSet& s = loop.series();
  if (auto it = s.find("samples"); it != s.end())
    for (const std::vector<double>& q : it->second.rows) r.series.push_back(Sample{q[0], q[1], q[2], q[3], q[4]});
  r.force_integral0 = r.max_force0 = NAN;
  if (auto it = s.find("start"); it != s.end() && it->second.rows.at(0).size() == 3) {
    r.force_integral0 = it->second.rows[0][1];
    r.max_force0 = it->second.rows[0][2];
  }
  PhaseLog per_step;
  if (auto it = s.find("phases"); it != s.end())
    for (const std::vector<double>& q : it->second.rows) {
      r.phases.forces += q[0];
      r.phases.force_products += q[1];
      r.phases.spread += q[2];
      r.phases.solve += q[3];
      r.phases.interpolate += q[4];
      r.phases.update += q[5];
      per_step.forces.push_back(q[0]);
      per_step.products.push_back(q[1]);
      per_step.spread.push_back(q[2]);
      per_step.solve.push_back(q[3]);
      per_step.interpolate.push_back(q[4]);
      per_step.update.push_back(q[5]);
    }
  r.median = per_step.medians();
  if (auto it = s.find("blocks"); it != s.end())
    for (const std::vector<double>& q : it->second.rows) r.block_ends.push_back(q.at(0));
  return r;
}

RelaxationResult relax(const RelaxationSpec& spec, const EvaluationSet& eval, const std::string& checkpoint,
                       const std::string& label, double sitting) {
  Relaxation run(spec, eval, checkpoint, label, sitting);
  run.advance_all();
  return run.result();
}

std::vector<RelaxationResult> relax_lockstep(const std::vector<std::pair<RelaxationSpec, const EvaluationSet*>>& runs) {
  std::vector<std::unique_ptr<Relaxation>> rs;
  for (const auto& [spec, eval] : runs) rs.push_back(std::make_unique<Relaxation>(spec, *eval));
  for (bool any = true; any;) {
    any = false;
    for (auto& r : rs) any = r->advance() || any;
  }
  std::vector<RelaxationResult> out;
  for (auto& r : rs) out.push_back(r->result());
  return out;
}

}  // namespace rbfib::chapter3
