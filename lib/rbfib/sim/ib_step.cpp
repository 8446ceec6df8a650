#include "rbfib/sim/ib_step.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/sim/membrane_stability.hpp"

#include <thrust/copy.h>
#include <thrust/device_ptr.h>
#include <thrust/find.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace rbfib::sim {

namespace {
using clock_type = std::chrono::steady_clock;
double seconds_since(clock_type::time_point& t0) {
  synchronize();
  const auto t1 = clock_type::now();
  const double s = std::chrono::duration<double>(t1 - t0).count();
  t0 = t1;
  return s;
}
/// The boxes the Lagrangian sets interpolate from and spread into: the fluid's, or on a split fluid
/// those of the wider grid its cells reach (FluidDecomposition::lagrangian_grid).
std::array<Box, 3> lagrangian_boxes(const FluidStep& fluid) {
  if (const FluidDecomposition* parts = fluid.parts()) {
    const MacGrid& g = parts->lagrangian_grid();
    return {g.component(0), g.component(1), g.component(2)};
  }
  const MacOperators& ops = fluid.operators();
  return {ops.component_box(0), ops.component_box(1), ops.component_box(2)};
}
}  // namespace

const char* to_string(Coupling c) {
  switch (c) {
    case Coupling::seed: return "seed (a)-(g), first order";
    case Coupling::midpoint: return "midpoint, second order";
    case Coupling::forward_euler: return "forward Euler (Chapter 3, eq. 87)";
  }
  return "?";
}

const char* to_string(StepCriterion c) {
  switch (c) {
    case StepCriterion::inertial: return "inertial (eq. 5.4)";
    case StepCriterion::stability: return "stability (the sets' bounds and a growth guard; eq. 5.4 stops the run)";
  }
  return "?";
}

ImmersedBoundary::ImmersedBoundary(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options,
                                   BoundaryVelocity boundary, IbOptions ib)
    : ImmersedBoundary(std::make_unique<NavierStokesStep>(grid, fluid, std::move(options), std::move(boundary)), std::move(ib)) {}

ImmersedBoundary::ImmersedBoundary(std::unique_ptr<FluidStep> fluid, IbOptions ib)
    : fluid_(std::move(fluid)),
      ib_(lagrangian_boxes(*fluid_), ib.kernel),
      options_(std::move(ib)) {
  require(fluid_->grid().dims == 3, "grid.dims", fluid_->grid().dims, "the immersed-boundary step needs a 3D grid");
  // On one part of a split fluid, the Lagrangian grid is a window of the split axis: each point at
  // its image nearest this process's part.
  if (const FluidDecomposition* parts = fluid_->parts()) ib_.set_window(parts->split_axis(), parts->split_cells());
  require(options_.coupling != Coupling::midpoint || fluid_->has_midpoint_velocity(), "ib.coupling", to_string(options_.coupling),
          "needs Peskin's two-stage fluid scheme (its midpoint velocity), not " + fluid_->name());
  if (!options_.body_force_density[0].empty())
    for (int a = 0; a < 3; ++a)
      require(index_t(options_.body_force_density[a].size()) == fluid_->operators().component_box(a).size(),
              "ib.body_force_density[" + to_text(a) + "].size", options_.body_force_density[a].size(),
              "must be the number of faces of velocity component " + to_text(a) + " (" +
                  to_text(fluid_->operators().component_box(a).size()) + ")");
  const AdaptiveStep& a = options_.adaptive;
  if (a.enabled) {
    require(std::isfinite(a.dt_min) && a.dt_min > 0, "ib.adaptive.dt_min", a.dt_min, "must be positive and finite (s)");
    require(a.max_level >= 0 && a.max_level <= 30, "ib.adaptive.max_level", a.max_level, "must lie in [0, 30]");
    require(a.grow_after >= 1, "ib.adaptive.grow_after", a.grow_after, "must be at least 1 step");
    require(a.ratio > 1 && a.ratio <= 2, "ib.adaptive.ratio", a.ratio, "must lie in (1, 2]");
    require(a.guard_growth >= 1, "ib.adaptive.guard_growth", a.guard_growth, "must be at least 1");
    require(a.guard_steps >= 1, "ib.adaptive.guard_steps", a.guard_steps, "must be at least 1 step");
    const double k = std::log(fluid_->dt() / a.dt_min) / std::log(a.ratio);
    level_ = int(std::lround(k));
    require(std::abs(k - level_) < 1e-9 && level_ >= 0 && level_ <= a.max_level, "fluid.dt", fluid_->dt(),
            "must be " + to_text(a.ratio) + "^k dt_min (dt_min = " + to_text(a.dt_min) + " s) with k in [0, " + to_text(a.max_level) + "]");
    require(fluid_->dt() <= a.dt_max * (1 + 1e-12), "fluid.dt", fluid_->dt(),
            "exceeds the adaptive step's guard dt_max = " + to_text(a.dt_max) + " s (a wall's own stability bound)");
  }
}

namespace {
bool by_id(const CellRecord& a, const CellRecord& b) { return a.id < b.id; }
}  // namespace

ImmersedBoundary::Carried ImmersedBoundary::carried() const {
  Carried c;
  c.fluid = fluid_->state();
  const FluidDecomposition* parts = fluid_->parts();
  if (parts) {
    // The whole run's state on every process: the fluid gathered, every cell sent to every process.
    const MacOperators& ops = fluid_->operators();
    for (int a = 0; a < 3; ++a) c.fluid.u[a] = parts->gather(ops.component_box(a), c.fluid.u[a]);
    c.fluid.p = parts->gather(ops.scalar_box(), c.fluid.p);
    for (dvec& phi : c.fluid.phi)
      if (!phi.empty()) phi = parts->gather(ops.scalar_box(), phi);
    std::vector<double> mine;
    std::vector<index_t> nd;
    for (std::size_t b = 0; b < batches_.size(); ++b) {
      nd.push_back(batch(index_t(b)).type().n_data());
      for (const CellRecord& r : cell_records(batch(index_t(b)), ids_[b])) pack(r, index_t(b), mine);
    }
    std::vector<std::vector<CellRecord>> whole(batches_.size());
    for (const std::vector<double>& m : parts->exchange(std::vector<std::vector<double>>(std::size_t(parts->processes()), mine)))
      unpack(m, nd, [&](index_t b, CellRecord r) { whole[std::size_t(b)].push_back(std::move(r)); });
    for (std::size_t b = 0; b < batches_.size(); ++b) {
      std::sort(whole[b].begin(), whole[b].end(), by_id);
      const std::vector<double> state = state_of(whole[b], nd[b]);
      c.batches.push_back(dvec(state.begin(), state.end()));
    }
  } else {
    for (const auto* b : batches_) c.batches.push_back(b->batch().state().storage());
  }
  for (std::size_t p = 0; p < points_.size(); ++p)
    c.points.push_back(parts ? whole_points(*parts, points_[p]->points().X, point_ids_[p], point_counts_[p]) : points_[p]->points().X);
  for (const auto* q : shells_) c.shells.push_back(q->shell().X);
  for (const auto* q : cortices_) c.cortices.push_back(q->cortex().X);
  c.clock = clock();
  return c;
}

void ImmersedBoundary::restore(const Carried& whole) {
  require(whole.batches.size() == batches_.size(), "checkpoint: cell batches", whole.batches.size(),
          "must equal this setup's " + to_text(batches_.size()));
  // On a split fluid: this process's part of the whole run's state.
  const FluidDecomposition* parts = fluid_->parts();
  const bool split = parts != nullptr;
  Carried part;                             // the fluid's part and the Lagrangian sets (no cells)
  std::vector<std::vector<CellRecord>> cells;  // each batch's cells in the whole run, owned after the checks
  if (split) {
    const MacOperators& ops = fluid_->operators();
    for (int a = 0; a < 3; ++a) part.fluid.u[a] = parts->extend(ops.component_box(a), whole.fluid.u[a]);
    part.fluid.p = parts->extend(ops.scalar_box(), whole.fluid.p);
    for (int k = 0; k < 2; ++k)
      if (!whole.fluid.phi[k].empty()) part.fluid.phi[k] = parts->extend(ops.scalar_box(), whole.fluid.phi[k]);
    part.fluid.t = whole.fluid.t;
    require(whole.points.size() == points_.size(), "checkpoint: point sets", whole.points.size(),
            "must equal this setup's " + to_text(points_.size()));
    for (std::size_t p = 0; p < points_.size(); ++p) {
      require(index_t(whole.points[p].size()) == 3 * point_counts_[p], "checkpoint: point set " + to_text(p) + " size",
              whole.points[p].size(), "must equal this setup's " + to_text(3 * point_counts_[p]));
      part.points.push_back(points_at(whole.points[p], point_ids_[p]));
    }
    part.shells = whole.shells;
    part.cortices = whole.cortices;
    part.clock = whole.clock;
    for (std::size_t b = 0; b < batches_.size(); ++b) {
      const index_t nd = batch(index_t(b)).type().n_data(), N = index_t(whole_body_[b].size()) / 3;
      require(index_t(whole.batches[b].size()) == 6 * nd * N, "checkpoint: batch " + to_text(b) + " size", whole.batches[b].size(),
              "must equal this setup's " + to_text(6 * nd * N));
      cells.push_back(records_of(std::vector<double>(whole.batches[b].begin(), whole.batches[b].end()), whole_body_[b], nd));
    }
  }
  const Carried& c = split ? part : whole;
  require(c.points.size() == points_.size(), "checkpoint: point sets", c.points.size(),
          "must equal this setup's " + to_text(points_.size()));
  require(c.shells.size() == shells_.size(), "checkpoint: LDSM shells", c.shells.size(),
          "must equal this setup's " + to_text(shells_.size()));
  const FluidState& now = fluid_->state();
  for (int a = 0; a < 3; ++a)
    require(c.fluid.u[a].size() == now.u[a].size(), "checkpoint: velocity component " + to_text(a) + " size",
            c.fluid.u[a].size(), "must equal this grid's " + to_text(now.u[a].size()));
  require(c.fluid.p.size() == now.p.size(), "checkpoint: pressure size", c.fluid.p.size(),
          "must equal this grid's " + to_text(now.p.size()));
  for (std::size_t b = 0; b < batches_.size() && !split; ++b)
    require(c.batches[b].size() == batch(index_t(b)).state().storage().size(), "checkpoint: batch " + to_text(b) + " size",
            c.batches[b].size(), "must equal this setup's " + to_text(batch(index_t(b)).state().storage().size()));
  for (std::size_t p = 0; p < points_.size(); ++p)
    require(c.points[p].size() == points(index_t(p)).X.size(), "checkpoint: point set " + to_text(p) + " size",
            c.points[p].size(), "must equal this setup's " + to_text(points(index_t(p)).X.size()));
  for (std::size_t q = 0; q < shells_.size(); ++q)
    require(c.shells[q].size() == shells_[q]->shell().X.size(), "checkpoint: LDSM shell " + to_text(q) + " size",
            c.shells[q].size(), "must equal this setup's " + to_text(shells_[q]->shell().X.size()));
  require(c.cortices.size() == cortices_.size(), "checkpoint: cortices", c.cortices.size(),
          "must equal this setup's " + to_text(cortices_.size()));
  for (std::size_t q = 0; q < cortices_.size(); ++q)
    require(c.cortices[q].size() == cortices_[q]->cortex().X.size(), "checkpoint: cortex " + to_text(q) + " size",
            c.cortices[q].size(), "must equal this setup's " + to_text(cortices_[q]->cortex().X.size()));
  require(std::isfinite(c.clock.dt) && c.clock.dt > 0, "checkpoint: dt", c.clock.dt, "must be positive");
  fluid_->state() = c.fluid;
  for (std::size_t q = 0; q < shells_.size(); ++q) shells_[q]->shell().X = c.shells[q];
  for (std::size_t q = 0; q < cortices_.size(); ++q) cortices_[q]->cortex().X = c.cortices[q];
  for (std::size_t b = 0; b < batches_.size(); ++b)
    if (split) own(index_t(b), cells[b]);
    else batch(index_t(b)).state().storage() = c.batches[b];
  for (std::size_t p = 0; p < points_.size(); ++p) points_[p]->points().X = c.points[p];
  steps_ = c.clock.step;
  level_ = c.clock.level;
  allowing_ = c.clock.allowing;
  cap_ = c.clock.cap;
  past_.clear();  // the growth guard starts afresh (its memory is not carried)
  flipping_ = quiet_ = 0;
  fluid_->set_dt(c.clock.dt);
}

double ImmersedBoundary::rung(int level) const {
  const AdaptiveStep& a = options_.adaptive;
  return a.ratio == 2 ? std::ldexp(a.dt_min, level) : a.dt_min * std::pow(a.ratio, level);
}

void ImmersedBoundary::set_level(int level) {
  level_ = level;
  allowing_ = 0;
  past_.clear();  // D is a difference at one step size
  flipping_ = quiet_ = 0;
  fluid_->set_dt(rung(level));
}

int ImmersedBoundary::level_within(double dt) const {
  const AdaptiveStep& a = options_.adaptive;
  if (!(dt >= a.dt_min)) return -1;
  int k = int(std::floor(std::log(dt / a.dt_min) / std::log(a.ratio) + 1e-9));
  while (k > 0 && a.dt_min * std::pow(a.ratio, k) > dt * (1 + 1e-12)) --k;
  return std::min(k, a.max_level);
}

namespace {
/// d = F - 2 f1 + f2 (entrywise).
void second_difference(const dvec& F, const dvec& f1, const dvec& f2, dvec& d) {
  d.resize(F.size());
  const double *pF = ptr(F), *p1 = ptr(f1), *p2 = ptr(f2);
  double* pd = ptr(d);
  for_each_index(index_t(F.size()), [=] RBFIB_HD (index_t k) { pd[k] = pF[k] - 2 * p1[k] + p2[k]; });
}
}  // namespace

bool ImmersedBoundary::guarded() const {
  return options_.adaptive.enabled && options_.adaptive.criterion == StepCriterion::stability;
}

bool ImmersedBoundary::watched() const { return guarded() || options_.watch_stability; }

void ImmersedBoundary::guard(IbStepReport& r) {
  const AdaptiveStep& a = options_.adaptive;
  const FluidDecomposition* parts = fluid_->parts();
  past_.resize(sets_.size());
  // Per set: D^n . D^n, D^n . D^{n-1}, D^{n-1} . D^{n-1}; a set without a full memory counts as missing.
  std::vector<double> sums(3 * sets_.size() + 1, 0.0);
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    const dvec* F = sets_[i]->force_values();
    PastForces& p = past_[i];
    if (!F || F->empty()) continue;
    if (p.f1.size() != F->size() || p.f2.size() != F->size() || p.v.size() != F->size()) {
      sums.back() += 1;
      continue;
    }
    second_difference(*F, p.f1, p.f2, p.now);
    sums[3 * i] = blas::dot(p.now, p.now), sums[3 * i + 1] = blas::dot(p.now, p.v), sums[3 * i + 2] = blas::dot(p.v, p.v);
  }
  if (parts)
    for (double& x : sums) x = parts->sum(x);
  if (sums.back() > 0) return;  // some set's memory is not full: nothing measured
  attempt_measured_ = true;
  bool flipping = false;
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    const double vv = sums[3 * i], vw = sums[3 * i + 1], ww = sums[3 * i + 2];
    if (!(vv > 0 && ww > 0)) continue;
    const double cosine = vw / std::sqrt(vv * ww), growth = std::sqrt(vv / ww);
    r.oscillation_cosine = std::isnan(r.oscillation_cosine) ? cosine : std::min(r.oscillation_cosine, cosine);
    if (cosine < -0.5) {
      r.oscillation_growth = std::isnan(r.oscillation_growth) ? growth : std::max(r.oscillation_growth, growth);
      if (growth > a.guard_growth) flipping = true;
    }
  }
  attempt_flipping_ = flipping;
  if (!guarded() || !flipping || flipping_ + 1 < a.guard_steps || level_ == 0) return;
  // A growing sign-flipping mode: two rungs down, and no rung above the one under this one again.
  cap_ = level_ - 1;
  throw Refused{std::max(level_ - 2, 0), "the growth guard (a sign-flipping part of the forces grew by " +
                                             to_text(r.oscillation_growth) + " per step over " + to_text(a.guard_steps) + " steps)"};
}

void ImmersedBoundary::remember_forces() {
  past_.resize(sets_.size());
  flipping_ = attempt_flipping_ ? flipping_ + 1 : 0;
  quiet_ = attempt_measured_ && !attempt_flipping_ ? quiet_ + 1 : 0;
  attempt_flipping_ = attempt_measured_ = false;
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    const dvec* F = sets_[i]->force_values();
    PastForces& p = past_[i];
    if (!F) continue;
    if (p.f1.size() == F->size() && p.f2.size() == F->size()) {
      if (p.now.size() != F->size()) second_difference(*F, p.f1, p.f2, p.now);
      std::swap(p.v, p.now);
    } else {
      p.v.clear();
    }
    p.now.clear();
    std::swap(p.f2, p.f1);
    p.f1 = *F;
  }
}

index_t ImmersedBoundary::cells_in_run(index_t b) const {
  const FluidDecomposition* parts = fluid_->parts();
  return parts ? index_t(whole_body_.at(std::size_t(b)).size()) / 3 : batch(b).size();
}

std::vector<double> ImmersedBoundary::run_cell_values(index_t b, const std::vector<double>& mine) const {
  const FluidDecomposition* parts = fluid_->parts();
  if (!parts) return mine;
  const std::vector<index_t>& ids = ids_.at(std::size_t(b));
  require(mine.size() == ids.size(), "run_cell_values: values", mine.size(), "must be one per cell of this process, " + to_text(ids.size()));
  std::vector<double> message;  // (id, value) pairs
  for (std::size_t c = 0; c < ids.size(); ++c) message.insert(message.end(), {double(ids[c]), mine[c]});
  std::vector<double> all(static_cast<std::size_t>(cells_in_run(b)), NAN);
  for (const std::vector<double>& m : parts->exchange(std::vector<std::vector<double>>(std::size_t(parts->processes()), message)))
    for (std::size_t k = 0; k + 1 < m.size(); k += 2) all.at(static_cast<std::size_t>(m[k])) = m[k + 1];
  return all;
}

void ImmersedBoundary::own(index_t b, const std::vector<CellRecord>& whole) {
  const FluidDecomposition& parts = *fluid_->parts();
  const std::shared_ptr<const cells::CellType> type = batch(b).type_ptr();
  std::vector<CellRecord> mine;
  ids_[std::size_t(b)].clear();
  for (const CellRecord& r : whole) {
    const double x = site_mean(r, parts.split_axis(), type->n_data());
    // A cell with a non-finite site stays with process 0, whose step names it (locate()).
    if (std::isfinite(x) ? parts.owner(x) == parts.process() : parts.process() == 0) {
      mine.push_back(r);
      ids_[std::size_t(b)].push_back(r.id);
    }
  }
  batches_[std::size_t(b)]->replace(batch_of(type, mine));
}

void ImmersedBoundary::migrate() {
  const FluidDecomposition* parts = fluid_->parts();
  if (!parts || parts->processes() == 1) return;
  const int me = parts->process(), axis = parts->split_axis();
  const std::size_t B = batches_.size();
  std::vector<std::vector<double>> to(std::size_t(parts->processes()));
  std::vector<std::vector<CellRecord>> kept(B);
  std::vector<char> left(B, 0);
  std::vector<index_t> nd(B);
  for (std::size_t b = 0; b < B; ++b) {
    nd[b] = batch(index_t(b)).type().n_data();
    // Owners from the centroids alone; the cells' whole state is read only when one leaves.
    const std::vector<double> x = site_means(batch(index_t(b)), axis);
    std::vector<int> owner(x.size());
    for (std::size_t c = 0; c < x.size(); ++c) {
      owner[c] = std::isfinite(x[c]) ? parts->owner(x[c]) : me;  // a non-finite cell stays, for locate() to name it
      left[b] |= owner[c] != me;
    }
    if (!left[b]) continue;
    std::vector<CellRecord> all = cell_records(batch(index_t(b)), ids_[b]);
    for (std::size_t c = 0; c < all.size(); ++c)
      if (owner[c] == me) kept[b].push_back(std::move(all[c]));
      else pack(all[c], index_t(b), to[std::size_t(owner[c])]);
  }
  std::vector<std::vector<CellRecord>> incoming(B);
  for (const std::vector<double>& m : parts->exchange(to))
    unpack(m, nd, [&](index_t b, CellRecord r) { incoming[std::size_t(b)].push_back(std::move(r)); });
  for (std::size_t b = 0; b < B; ++b) {
    if (!left[b] && incoming[b].empty()) continue;
    if (!left[b]) kept[b] = cell_records(batch(index_t(b)), ids_[b]);
    for (CellRecord& r : incoming[b]) kept[b].push_back(std::move(r));
    std::sort(kept[b].begin(), kept[b].end(), by_id);
    ids_[b].clear();
    for (const CellRecord& r : kept[b]) ids_[b].push_back(r.id);
    batches_[b]->replace(batch_of(batch(index_t(b)).type_ptr(), kept[b]));
  }
}

IbStepReport ImmersedBoundary::step(double at_most) {
  migrate();
  const AdaptiveStep& a = options_.adaptive;
  // The run's end: a rung that passes it is shortened for this step alone (the level is kept).
  const bool shortened = a.enabled && at_most > 0 && at_most < dt() * (1 - 1e-9);
  auto land = [&] {
    if (shortened) fluid_->set_dt(std::min(rung(level_), at_most));
  };
  land();
  int refused = 0;
  int by_guard = 0;
  for (;;) {
    try {
      IbStepReport r = attempt();
      r.refused = refused;
      r.refused_by_guard = by_guard;
      if (shortened) {  // the rung again for any step after this one; the guard's memory is of one step size
        fluid_->set_dt(rung(level_));
        past_.clear();
        flipping_ = quiet_ = 0;
      }
      if (a.enabled) {
        // Grow by one level only after grow_after consecutive steps that allowed the next rung: by
        // eq. 5.4 (inertial criterion) and by the sets' bounds and the guard's cap.
        const double next = a.ratio * rung(level_);
        // With the stability criterion the guard must first have watched this rung quietly for
        // guard_steps steps (its memory starts empty at each rung): a ladder that climbed faster
        // would outrun the guard.
        const bool open = level_ < a.max_level && next <= a.dt_max * (1 + 1e-12) &&
                          (a.criterion == StepCriterion::stability ? (cap_ < 0 || level_ < cap_) && quiet_ >= a.guard_steps
                                                                    : next <= r.dt_bound);
        allowing_ = open ? allowing_ + 1 : 0;
        if (allowing_ >= a.grow_after) set_level(level_ + 1);
      }
      return r;
    } catch (const Refused& no) {
      // Take the step again at once at the level the refusal names.
      if (no.level < 0)
        throw NumericalError(Cause::stopping_condition, "immersed-boundary step " + to_text(steps_) + " at t = " + to_text(time()) +
                             " s: " + no.why + " (the state before this step is kept)");
      if (a.criterion == StepCriterion::stability) ++by_guard;
      set_level(std::min(no.level, level_ - 1));
      land();
      ++refused;
    }
  }
}

index_t ImmersedBoundary::add(cells::Batch batch) {
  AdaptiveStep& a = options_.adaptive;
  if (a.enabled && a.criterion == StepCriterion::stability && std::isfinite(a.membrane_gain)) {
    // No rung above the membranes' explicit stability bound at gain 1/2 (sim/membrane_stability.hpp).
    const MacGrid& g = fluid_->grid();
    const double h = std::min({g.h(0), g.h(1), g.h(2)});
    const MembraneStiffness m = membrane_stiffness(batch.type());
    const double bound = membrane_dt_limit(m, h, fluid_->density(), fluid_->viscosity(), options_.kernel, a.membrane_gain);
    a.dt_max = std::min(a.dt_max, bound);
    require(fluid_->dt() <= a.dt_max * (1 + 1e-12), "fluid.dt", fluid_->dt(),
            "exceeds the membranes' stability bound for cell type '" + batch.type().name() + "': " + to_text(bound) + " s (" +
                membrane_limiting_family(m, h, fluid_->density(), fluid_->viscosity(), options_.kernel, a.membrane_gain) +
                " modes at gain " + to_text(a.membrane_gain) + "; docs/derivations/membrane_stability)");
  }
  std::vector<index_t> ids(static_cast<std::size_t>(batch.size()));
  std::iota(ids.begin(), ids.end(), index_t(0));
  const FluidDecomposition* parts = fluid_->parts();
  if (!parts) {
    ids_.push_back(ids);
    whole_body_.emplace_back();
    return keep(std::make_unique<CellBatchSet>(std::move(batch)), batches_);
  }
  const std::vector<CellRecord> whole = cell_records(batch, ids);
  whole_body_.push_back(batch.body_force());
  ids_.emplace_back();
  const index_t b = keep(std::make_unique<CellBatchSet>(std::move(batch)), batches_);
  own(b, whole);
  return b;
}

index_t ImmersedBoundary::add(TetheredPoints p) {
  const FluidDecomposition* parts = fluid_->parts();
  require(!p.frame || !parts, "tethered points '" + p.name + "': frame", "true", "a frame (Chapter 3's capillary) runs on one process only");
  if (p.frame)
    for (const TetheredPointSet* q : points_)
      require(!q->points().frame, "tethered points '" + p.name + "': frame", "true",
              "only one point set may hold the frame ('" + q->points().name + "' does)");
  const bool midpoint = options_.coupling == Coupling::midpoint;
  const index_t n = index_t(p.X.size()) / 3;
  std::vector<index_t> ids;
  if (parts) {  // the whole set checked as one process would, then this process's points by anchor
    TetheredPointSet whole(p, midpoint);
    const std::vector<double> anchors(p.anchors.begin(), p.anchors.end());
    const int axis = parts->split_axis();
    for (index_t k = 0; k < n; ++k)
      if (parts->owner(anchors[std::size_t(axis * n + k)]) == parts->process()) ids.push_back(k);
    p.X = points_at(p.X, ids);
    p.anchors = points_at(p.anchors, ids);
  }
  point_ids_.push_back(std::move(ids));
  point_counts_.push_back(n);
  // The seed's coupling holds the springs at X^n; the midpoint coupling at X^{n+1/2}.
  return keep(std::make_unique<TetheredPointSet>(std::move(p), midpoint, parts != nullptr), points_);
}

index_t ImmersedBoundary::add(LdsmShell shell) {
  require(!fluid_->parts() || fluid_->parts()->processes() == 1, "LDSM shell: processes",
          fluid_->parts() ? fluid_->parts()->processes() : 1, "LDSM shells run on one process only");
  return keep(std::make_unique<LdsmShellSet>(std::move(shell)), shells_);
}

index_t ImmersedBoundary::add(HeldWall wall) {
  const std::string field = "held wall '" + wall.name + "'";
  require(held_.empty(), field + ": held walls", held_.size() + 1, "must be at most one");
  require(!fluid_->has_midpoint_velocity(), field + ": fluid", fluid_->name(),
          "must be affine in its force (not Peskin's two-stage scheme, whose advection uses the half step's velocity)");
  return keep(std::make_unique<HeldWallSet>(std::move(wall), fluid_->parts()), held_);
}

index_t ImmersedBoundary::add(Cortex cortex, const LagrangianSet& membrane) {
  const std::string field = "cortex '" + cortex.name + "'";
  require(!fluid_->parts(), field + ": processes", "several", "a cortex runs on one process only");
  require(options_.coupling == Coupling::forward_euler, field + ": coupling", to_string(options_.coupling),
          "must be forward_euler (Chapter 3's update, Sec. 3.3: the cortex's forces act at X^n)");
  bool ours = false;
  for (const auto& s : sets_) ours = ours || s.get() == &membrane;
  require(ours, field + ": membrane", membrane.name(), "must be a set of this step, added before the cortex");
  for (const CellBatchSet* b : batches_)
    if (b == &membrane)
      require(b->batch().size() == 1, field + ": membrane cells", b->batch().size(), "must be one cell");
  return keep(std::make_unique<CortexSet>(std::move(cortex), membrane), cortices_);
}

IbStepReport ImmersedBoundary::attempt() {
  IbStepReport r;
  const double dt = fluid_->dt();
  r.dt = dt;
  const double t = time();
  const Coupling coupling = options_.coupling;
  for (TetheredPointSet* p : points_)  // constants that follow the step: set from this step's dt
    if (const auto& rule = p->points().follow) {
      const TetherConstants c = tether_constants_for_step(rule->sheet, dt, rule->gain);
      p->points().k = c.k, p->points().eta = c.eta;
    }
  // Keep X^n (and U): the whole Lagrangian state is restored on failure; the fluid's next state
  // goes into its other buffer and is accepted only at the end.
  for_each_set([](LagrangianSet& s) { s.save(); });
  const FluidDecomposition* parts = fluid_->parts();
  // On a split fluid, a failure of this process's sets becomes every process's failure before the
  // next exchange (agreed(): every process then restores and reports the same error).
  // The velocity the Lagrangian sets interpolate: the fluid's, or on a split fluid the fluid's
  // widened to the Lagrangian grid (collective: before the phase that may fail on one process).
  auto lagrangian = [&](const VectorField& u) -> const VectorField& {
    if (!parts) return u;
    for (int a = 0; a < 3; ++a) parts->widen(u[a], u_wide_[a]);
    return u_wide_;
  };
  try {
    auto t0 = clock_type::now();
    // (a) U^n = I u^n at X^n; (b) X* = X^n + dt U^n (midpoint: X^{n+1/2} = X^n + dt/2 U^n;
    // forward Euler: neither, the forces act at X^n).
    const VectorField& u_start = coupling == Coupling::forward_euler ? fluid_->state().u : lagrangian(fluid_->state().u);
    agreed(parts, [&] {
      for_each_set([&](LagrangianSet& s) {
        s.locate(ib_);
        if (coupling == Coupling::forward_euler) return;
        s.interpolate_start(ib_, u_start);
        s.predict(coupling == Coupling::midpoint ? 0.5 * dt : dt);
      });
      r.seconds_interpolation += seconds_since(t0);
      // (c) F^{n+1} at X* (sample sites), with U^n for dissipation.
      for_each_set([&](LagrangianSet& s) {
        r.elastic_energy += s.compute_force();
        r.seconds_force_products += s.seconds_force_products();
      });
    });
    if (parts) r.elastic_energy = parts->sum(r.elastic_energy);
    if (watched()) guard(r);
    r.seconds_forces = seconds_since(t0);
    // (d) f^{n+1} = S F^{n+1} from where the forces act, summed over the sets, plus the body force.
    // A split fluid: spread on the Lagrangian grid, its ghost planes summed into their owners and
    // the owned planes brought to the fluid's grid before the body force is added.
    const std::array<Box, 3> boxes = lagrangian_boxes(*fluid_);
    VectorField& spread_to = parts ? f_wide_ : f_;
    for (int a = 0; a < 3; ++a)
      spread_to[a].assign(static_cast<std::size_t>(boxes[a].size()), parts ? 0.0 : options_.body_force[a]);
    agreed(parts, [&] { for_each_set([&](LagrangianSet& s) { s.spread(ib_, options_.spreading, spread_to, scratch_); }); });
    if (parts)
      for (int a = 0; a < 3; ++a) {
        parts->narrow_sum(f_wide_[a], f_[a]);
        if (options_.body_force[a] != 0.0) blas::shift(options_.body_force[a], f_[a]);
      }
    for (int a = 0; a < 3; ++a)
      if (!options_.body_force_density[a].empty()) blas::axpy(1.0, options_.body_force_density[a], f_[a]);
    r.seconds_spreading = seconds_since(t0);
    // Eq. 5.4: dt <= (1/4) sqrt(h rho / ||f||_inf).
    r.max_force_density = max_abs(parts, f_);
    const MacGrid& g = fluid_->grid();
    const double h = std::min({g.h(0), g.h(1), g.h(2)});
    r.dt_bound = r.max_force_density > 0 ? 0.25 * std::sqrt(h * fluid_->density() / r.max_force_density)
                                         : std::numeric_limits<double>::infinity();
    if (!std::isfinite(r.max_force_density)) throw NumericalError(Cause::non_finite, "non-finite spread force density");
    if (options_.watch_stability) r.peak_set = peak_set(f_);
    const AdaptiveStep& a = options_.adaptive;
    if (a.enabled && a.criterion == StepCriterion::inertial && dt > r.dt_bound)
      throw Refused{std::min(level_within(r.dt_bound), level_ - 1),
                    "stopping condition (eq. 5.4) violated even at dt_min = " + to_text(a.dt_min) +
                        " s: (1/4) sqrt(h rho / ||f||_inf) = " + to_text(r.dt_bound) + " s"};
    // The stability criterion: eq. 5.4 stops the run where the seed's step (dt_min) violates it.
    const double stop_dt = a.enabled && a.criterion == StepCriterion::stability ? a.dt_min : dt;
    if (options_.stopping_condition && stop_dt > r.dt_bound)
      throw NumericalError(Cause::stopping_condition, "stopping condition (eq. 5.4) violated: ||f||_inf = " + to_text(r.max_force_density) +
                                                          " dyn/cm^3, dt = " + to_text(stop_dt) + " s > (1/4) sqrt(h rho / ||f||_inf) = " +
                                                          to_text(r.dt_bound) + " s");
    // (e) the fluid step, into the fluid's other buffer; with a held wall, its force solved from
    // that step and the step taken again with it (sim/held_wall.hpp).
    r.fluid = fluid_->step(&f_);
    if (!held_.empty()) {
      auto th = clock_type::now();
      held_.front()->hold(ib_, *fluid_, options_.spreading, f_, scratch_);
      r.fluid = fluid_->step(&f_);
      r.seconds_held = seconds_since(th);
    }
    const FluidState& next = fluid_->next();
    for (int a = 0; a < 3; ++a)
      if (!blas::all_finite(next.u[a]))
        throw NumericalError(Cause::non_finite, "non-finite fluid velocity (component " + to_text(a) + ")");
    const double cell_volume = g.h(0) * g.h(1) * g.h(2);
    r.max_velocity = max_abs(parts, next.u);
    r.kinetic_energy = 0.5 * fluid_->density() * dot(parts, next.u, next.u) * cell_volume;
    r.seconds_fluid = seconds_since(t0);  // with its checks and diagnostics
    // (f) U^{n+1} = I u^{n+1} at X^n (midpoint: U^{n+1/2} = I u^{n+1/2} at X^{n+1/2}, sorted once more);
    const bool midpoint = coupling == Coupling::midpoint;
    const VectorField& u_final = lagrangian(midpoint ? fluid_->midpoint_velocity() : next.u);
    agreed(parts, [&] {
      for_each_set([&](LagrangianSet& s) { s.interpolate_end(ib_, u_final, midpoint); });
      r.seconds_interpolation += seconds_since(t0);
      // (g) X^{n+1} = X^n + dt (U + u_c), u_c the frame's velocity (eq. 95) or zero.
      for (const TetheredPointSet* p : points_)
        if (p->points().frame) r.frame_velocity = p->frame_velocity(dt);
      for_each_set([&](LagrangianSet& s) { s.update(dt, r.frame_velocity); });
    });
    r.seconds_update = seconds_since(t0);
  } catch (...) {
    for_each_set([](LagrangianSet& s) { s.restore(); });
    try {
      throw;
    } catch (const Refused&) {
      throw;
    } catch (const NumericalError& ex) {
      throw NumericalError(ex.cause(), "immersed-boundary step " + to_text(steps_) + " at t = " + to_text(t) + " s: " + ex.what() +
                                           " (the state before this step is kept)");
    } catch (const std::exception& ex) {
      throw NumericalError(Cause::solver, "immersed-boundary step " + to_text(steps_) + " at t = " + to_text(t) + " s: " + ex.what() +
                                              " (the state before this step is kept)");
    }
  }
  fluid_->accept();
  ++steps_;
  if (watched()) remember_forces();
  return r;
}

int ImmersedBoundary::peak_set(const VectorField& f) const {
  if (fluid_->parts()) return -1;  // one process's part of the grid: not attributed
  int comp = -1;
  index_t at = 0;
  double peak = 0;
  for (int a = 0; a < 3; ++a) {
    if (f[a].empty()) continue;
    const host_vector<double> h(f[a]);
    for (std::size_t k = 0; k < h.size(); ++k)
      if (std::abs(h[k]) > peak) peak = std::abs(h[k]), comp = a, at = index_t(k);
  }
  if (comp < 0) return -1;
  const Box box = fluid_->operators().component_box(comp);
  const index_t nx = box.n(0), ny = box.n(1);
  const std::array<double, 3> x{box.x(0, int(at % nx)), box.x(1, int((at / nx) % ny)), box.x(2, int(at / (nx * ny)))};
  return nearest_set(x);
}

int ImmersedBoundary::nearest_set(const std::array<double, 3>& x) const {
  const MacGrid& g = fluid_->grid();
  int best = -1;
  double closest = INFINITY;
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    if (!sets_[i]->force_values()) continue;
    const std::vector<double> X = sets_[i]->force_sites();  // n x 3
    const std::size_t n = X.size() / 3;
    for (std::size_t k = 0; k < n; ++k) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) {
        double d = X[a * n + k] - x[std::size_t(a)];
        if (g.periodic(a)) d -= g.length[std::size_t(a)] * std::round(d / g.length[std::size_t(a)]);
        d2 += d * d;
      }
      if (d2 < closest) closest = d2, best = int(i);
    }
  }
  return best;
}

}  // namespace rbfib::sim
