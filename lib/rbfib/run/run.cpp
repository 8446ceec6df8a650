#include "rbfib/run/run.hpp"

#include "rbfib/core/units.hpp"

#include <cstdio>
#include <filesystem>

namespace rbfib::run {

namespace {

using clock_type = std::chrono::steady_clock;

double seconds_between(clock_type::time_point a, clock_type::time_point b) { return std::chrono::duration<double>(b - a).count(); }

/// Whether a cadence is due: by steps and simulated time counted from t = 0 (so that a continued
/// run samples where an uninterrupted one does), by wall time from the last firing. On a split
/// fluid a cadence by wall time fires on every process when it fires on any (one reduction), so
/// that all go on to the same collective calls.
class Due {
 public:
  Due(const Cadence& c, double t, clock_type::time_point now, const FluidDecomposition* parts)
      : c_(c), last_wall_(now), parts_(parts) {
    next_t_ = c.time > 0 ? (std::floor(t / c.time * (1 + 1e-12)) + 1) * c.time : INFINITY;
  }
  bool operator()(long step, double t, clock_type::time_point now) {
    bool by_wall = c_.wall > 0 && seconds_between(last_wall_, now) >= c_.wall;
    if (parts_ && c_.wall > 0) by_wall = !parts_->all(!by_wall);
    bool due = (c_.steps > 0 && step % c_.steps == 0) || by_wall;
    if (c_.time > 0 && t >= next_t_ * (1 - 1e-12)) {
      due = true;
      while (next_t_ <= t * (1 + 1e-12)) next_t_ += c_.time;
    }
    if (due) last_wall_ = now;
    return due;
  }

 private:
  Cadence c_;
  double next_t_;
  clock_type::time_point last_wall_;
  const FluidDecomposition* parts_;
};

}  // namespace

double Progress::hours_to_go() const {
  if (ended()) return 0;
  const double t = clock.t, mean_dt = clock.step > 0 ? t / double(clock.step) : clock.dt;
  const double h = (t_end - t) / mean_dt * seconds_per_step_here() / 3600;
  return std::isfinite(h) ? std::max(0.0, h) : NAN;
}

std::string Progress::describe() const {
  // The time units that suit the run's end and its step.
  const double unit = t_end >= 1e-3 ? units::ms : units::us;
  const char* name = t_end >= 1e-3 ? "ms" : "us";
  char line[320];
  // The rate of this sitting's steps; none yet (a run resumed already finished): not printed.
  char rate[48] = "no steps this sitting";
  if (sitting_steps > 0 && sitting_seconds > 0) std::snprintf(rate, sizeof rate, "%.3g steps/s", double(sitting_steps) / sitting_seconds);
  const double t = clock.t, mean_dt = clock.step > 0 ? t / double(clock.step) : clock.dt;
  const bool long_step = mean_dt >= 1e-5;  // 10 us and above in us, below in ns
  std::snprintf(line, sizeof line, "t = %.4g of %.4g %s (%.1f%%), step %ld, %s, mean dt %.4g %s", t / unit, t_end / unit, name,
                t_end > 0 ? 100 * t / t_end : 0.0, clock.step, rate, mean_dt / (long_step ? units::us : units::ns),
                long_step ? "us" : "ns");
  std::string s = line;
  if (status == RunStatus::stopped) return s + ", stopped (" + to_string(*stop_cause) + "): " + stop_message;
  if (status == RunStatus::finished) return s + ", finished";
  const double h = hours_to_go();
  if (std::isfinite(h)) {
    std::snprintf(line, sizeof line, ", %.3g h to go", h);
    s += line;
  }
  return s;
}

Run::Run(const std::string& text, const std::string& origin, Options options, Hooks hooks)
    : Run(scene::parse_scene(text, origin), std::move(options), std::move(hooks)) {}

Run::Run(scene::Scene scene, Options options, Hooks hooks)
    : scene_(std::move(scene)),
      source_(scene_->source),
      options_(std::move(options)),
      hooks_(std::move(hooks)),
      ib_(io::build_scene(*scene_, options_.parts)) {
  start();
}

Run::Run(std::string source, sim::ImmersedBoundary ib, Options options, Hooks hooks)
    : source_(std::move(source)), options_(std::move(options)), hooks_(std::move(hooks)), ib_(std::move(ib)) {
  start();
}

const scene::Scene& Run::scene() const {
  if (!scene_) throw InputError("run scene", "none", "this run was built from a coupled step, not a scene");
  return *scene_;
}

void Run::start() {
  require(options_.t_end > 0 && std::isfinite(options_.t_end), "run end t_end (s)", options_.t_end, "must be positive and finite");
  require(options_.sitting >= 0, "sitting (s)", options_.sitting, "must be >= 0");
  if (hooks_.built) hooks_.built(ib_);
  if (!options_.checkpoint.empty() && std::filesystem::exists(options_.checkpoint)) {
    io::Checkpoint k = io::read_checkpoint(options_.checkpoint);
    if (k.scene_yaml == source_) {
      if (!k.fluid_kept) {  // an ended run (the reader allows no other): NaN of the grid's sizes in the fluid's place
        const FluidState built = ib_.carried().fluid;
        for (int a = 0; a < 3; ++a) k.state.fluid.u[a] = dvec(built.u[a].size(), NAN);
        k.state.fluid.p = dvec(built.p.size(), NAN);
        for (int j = 0; j < 2; ++j) k.state.fluid.phi[j] = dvec(built.phi[j].size(), NAN);
        fluid_kept_ = false;
      }
      ib_.restore(k.state);
      record_ = std::move(k.record);
      continued_ = true;
    }
  }
  if (!continued_) {
    record_.label = options_.label;
    sample(nullptr);
    if (hooks_.after_step) hooks_.after_step(ib_, nullptr, record_.series);
    if (hooks_.snapshot) hooks_.snapshot(ib_);
  }
}

const Series& Run::series(const std::string& name) const {
  const auto it = record_.series.find(name);
  if (it == record_.series.end()) throw InputError("series", name, "is not one of this run's");
  return it->second;
}

void Run::sample(const sim::IbStepReport* report) {
  if (hooks_.sample) hooks_.sample(ib_, report, record_.series);
}

void Run::checkpoint() {
  if (options_.checkpoint.empty()) return;
  const bool keep_fluid = fluid_kept_ && (record_.status == RunStatus::running || options_.ended_keeps_fluid);
  io::write_checkpoint(options_.checkpoint, source_, ib_, record_, keep_fluid);
  if (hooks_.checkpointed) hooks_.checkpointed(record_.series);
}

Progress Run::progress() const {
  Progress p;
  p.status = record_.status;
  p.clock = ib_.clock();
  p.t_end = options_.t_end;
  p.wall_seconds = record_.wall_seconds;
  p.steps_timed = record_.steps_timed;
  p.sitting_seconds = sitting_seconds_;
  p.sitting_steps = sitting_steps_;
  if (record_.status == RunStatus::stopped) {
    p.stop_message = record_.stop_message;
    p.stop_cause = record_.stop_cause;
  }
  return p;
}

Progress Run::evolve(long max_steps) {
  if (record_.status != RunStatus::running) {
    if (hooks_.progress) hooks_.progress(progress());
    return progress();
  }
  const auto start = clock_type::now();
  // On a split fluid a wall-clock decision (the sitting's end, a cadence by wall time) is taken
  // when any process takes it, so that all go on to the same collective calls; the progress lines
  // (no collective) need no agreement.
  const FluidDecomposition* parts = ib_.fluid().parts();
  Due checkpoint_due(options_.checkpoint_every, ib_.time(), start, parts), sample_due(options_.sample_every, ib_.time(), start, parts),
      snapshot_due(options_.snapshot_every, ib_.time(), start, parts), progress_due(options_.progress_every, ib_.time(), start, nullptr);
  const double end = std::min(options_.t_end, options_.until);
  long taken = 0;
  auto sitting_over = [&] {
    if (!std::isfinite(options_.sitting)) return false;
    const bool over = seconds_between(start, clock_type::now()) >= options_.sitting;
    return parts ? !parts->all(!over) : over;
  };
  try {
    while (ib_.time() < end * (1 - 1e-12) && !sitting_over()) {
      if (max_steps >= 0 && taken == max_steps) return progress();  // the caller steps again soon
      ++taken;
      const auto t0 = clock_type::now();
      const sim::IbStepReport report = ib_.step(options_.land_on_end ? options_.t_end - ib_.time() : INFINITY);
      const auto t1 = clock_type::now();
      sitting_seconds_ += seconds_between(t0, t1);
      record_.wall_seconds += seconds_between(t0, t1);
      ++sitting_steps_;
      ++record_.steps_timed;
      const long step = ib_.step_count();
      const double t = ib_.time();
      const bool last = t >= options_.t_end * (1 - 1e-12);
      try {  // a hook that measures the new state may find it broken (an inverted cell): say where
        if (sample_due(step, t, t1) || last) sample(&report);
        if (hooks_.after_step) hooks_.after_step(ib_, &report, record_.series);
        if (hooks_.snapshot && snapshot_due(step, t, t1)) hooks_.snapshot(ib_);
      } catch (const NumericalError& e) {
        throw NumericalError(e.cause(), "after step " + to_text(step) + " at t = " + to_text(t) + " s: " + e.what());
      }
      if (last) record_.status = RunStatus::finished;
      else if (checkpoint_due(step, t, t1)) checkpoint();
      if (hooks_.progress && progress_due(step, t, t1)) hooks_.progress(progress());
    }
  } catch (const NumericalError& e) {
    // The step left the last good state in place: it is what the checkpoint keeps.
    record_.status = RunStatus::stopped;
    record_.stop_message = e.what();
    record_.stop_cause = e.cause();
  }
  checkpoint();
  if (hooks_.progress) hooks_.progress(progress());
  return progress();
}

}  // namespace rbfib::run
