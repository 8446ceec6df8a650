#include "common/scene_run.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/scene/scene.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rbfib::study {

namespace {

void save_rows(const std::string& path, const std::vector<std::vector<double>>& rows) {
  {
    std::ofstream f(path + ".tmp");
    f.precision(17);
    for (const std::vector<double>& r : rows) {
      for (std::size_t k = 0; k < r.size(); ++k) f << (k ? " " : "") << r[k];
      f << '\n';
    }
  }
  std::filesystem::rename(path + ".tmp", path);
}

/// The rows of a samples file; the first number of a row is its time, and rows after t_max
/// (written after the checkpoint being continued from) are dropped.
std::vector<std::vector<double>> load_rows(const std::string& path, double t_max) {
  std::vector<std::vector<double>> rows;
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::vector<double> r;
    bool ok = true;
    for (std::string word; in >> word;) {  // strtod, not >>, so that nan and inf read back
      char* end = nullptr;
      r.push_back(std::strtod(word.c_str(), &end));
      ok = ok && end == word.c_str() + word.size();
    }
    if (r.empty() || !ok) throw InputError("samples file " + path, "'" + line + "'", "a malformed line");
    if (r[0] <= t_max * (1 + 1e-12)) rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace

RunProgress SceneRun::progress(double t_end) const {
  return {finished, samples.empty() ? 0.0 : samples.back().at(0), t_end, steps, seconds_per_step(), stopped};
}

SceneRun run_scene(const std::string& text, const std::string& tag, int every, bool resumable, const Options& opt,
                   const SceneRunHooks& hooks, double max_seconds) {
  using clock = std::chrono::steady_clock;
  std::ofstream(opt.out_dir + "/scene_" + tag + ".yaml") << text;
  const scene::Scene scene = scene::parse_scene(text, "scene_" + tag + ".yaml");
  // A run whose starting state the prepare hook sets: the placements in the text are not where the
  // cells start, and the hook's caller checks the state it sets.
  sim::ImmersedBoundary ib = scene::build(scene, !hooks.prepare);
  if (hooks.at_start) hooks.at_start(ib);
  SceneRun r;
  const std::string ckpt = opt.out_dir + "/checkpoint_" + tag + ".h5", samples = opt.out_dir + "/samples_" + tag + ".txt",
                    stopped = opt.out_dir + "/stopped_" + tag + ".txt";
  if (resumable && std::filesystem::exists(ckpt)) {
    io::Checkpoint c = io::read_checkpoint(ckpt);
    if (c.scene_yaml == text) {
      ib.restore(c.state);
      r.samples = load_rows(samples, ib.time());
      if (std::ifstream f(stopped); f) {  // stopped in an earlier sitting: the same failure would recur
        std::getline(f, r.stopped);
        log(opt, tag + ": stopped in an earlier sitting at t = " + to_text(ib.time() / units::ms) + " ms: " + r.stopped);
      } else {
        log(opt, tag + ": continuing from " + ckpt + " at t = " + to_text(ib.time() / units::ms) + " ms");
      }
    }
  }
  if (r.samples.empty()) {
    if (hooks.prepare) hooks.prepare(ib);
    r.samples.push_back(hooks.sample(ib, nullptr));
    if (hooks.after_step) hooks.after_step(ib);
  }
  const long total = std::lround(scene.t_end / scene.fluid_options.dt);
  const auto t0 = clock::now();
  auto last_log = t0, last_save = t0;
  try {
    while (r.stopped.empty() && ib.step_count() < total &&
           !(resumable && std::chrono::duration<double>(clock::now() - t0).count() > max_seconds)) {
      const sim::IbStepReport rep = ib.step();
      ++r.steps_timed;
      r.min_bound = std::min(r.min_bound, rep.dt_bound);
      if (ib.step_count() % every == 0 || ib.step_count() == total) r.samples.push_back(hooks.sample(ib, &rep));
      if (hooks.after_step) hooks.after_step(ib);
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_log).count() > 30) {
        const double el = std::chrono::duration<double>(now - t0).count();
        log(opt, tag + ": t = " + to_text(ib.time() / units::ms) + " of " + to_text(scene.t_end / units::ms) + " ms, " +
                     to_text(double(r.steps_timed) / el) + " steps/s, ETA " + to_text(double(total - ib.step_count()) * el / double(r.steps_timed)) +
                     " s");
        last_log = now;
      }
      if (resumable && std::chrono::duration<double>(now - last_save).count() > 300) {
        io::write_checkpoint(ckpt, text, ib);
        save_rows(samples, r.samples);
        last_save = now;
      }
    }
  } catch (const NumericalError& e) {
    r.stopped = e.what();
    log(opt, tag + ": stopped at t = " + to_text(ib.time() / units::ms) + " ms: " + r.stopped);
  }
  r.seconds = std::chrono::duration<double>(clock::now() - t0).count();
  r.steps = ib.step_count();
  r.finished = !r.stopped.empty() || r.steps >= total;
  if (resumable) {  // the end, or the last good state before a failure
    io::write_checkpoint(ckpt, text, ib);
    save_rows(samples, r.samples);
    if (!r.stopped.empty()) std::ofstream(stopped) << r.stopped << "\n";
  }
  for (index_t b = 0; b < ib.batches(); ++b) r.final_positions.push_back(ib.batch(b).positions_host());
  for (index_t p = 0; p < ib.point_sets(); ++p) r.final_points.push_back(ib.points(p).X);
  return r;
}

}  // namespace rbfib::study
