#include "common/chapter3_relaxation.hpp"

#include "rbfib/core/error.hpp"

#include <filesystem>

namespace rbfib::chapter3 {

namespace st = rbfib::study;

void describe_dynamic_test(st::Json& P) {
  P["units"] = "dimensionless (mu = 1, moduli 1, reference the unit sphere), as the paper's Sec. 4";
  P["box"] = "[-2, 2]^3, periodic; steady Stokes (alpha = 0), exact inverse of the MAC operators (Sec. 3.2)";
  P["mu"] = 1.0;
  P["moduli"] =
      "neo-Hookean (eq. 68) Gs = 1, A = 1; surface tension (eq. 72) sigma = 1; total force their sum (Sec. 4.2)";
  P["kernel"] = "peskin4 (Peskin's 4-point function, the paper's [25])";
  P["time_update"] =
      "Sec. 3.3: forces at X^k, spread, Stokes solve, interpolate, X^{k+1} = X^k + dt U^{k+1} (eq. 87)";
  P["ellipsoid"] = "eq. (88), a = 1.2, b = c = 1/sqrt(1.2)";
  P["evaluation_sites"] =
      "Bauer spiral (diss. eq. 5.1), n = 2 eta^2 + 1 (Fig. 4 full: 8281), weights diss. eq. (2.22) with "
      "phi = r^3; for comparison the stored MD sets with eq. (45) weights (table sites)";
  P["interpolation_sites"] = "(M+1)^2 maximal-determinant-like sites, M = 7 (m = 64) or 14 (m = 225)";
}

Relaxations::Relaxations(const st::Options& opt) : opt_(opt), keep_(opt.keeps_runs()), sitting_(opt) {}

const EvaluationSet& Relaxations::sites(index_t n) {
  auto it = sets_.find(n);
  if (it == sets_.end()) {
    it = sets_.emplace(n, make_evaluation_set(n)).first;
    st::log(opt_, "evaluation set n = " + to_text(n) + ": weights and triangulation in " +
                      to_text(it->second.seconds) + " s");
  }
  return it->second;
}

std::string Relaxations::md_file(int N) const {
  return st::source_path(opt_, "reference/point_sets/max_determinant_N" + to_text(N) + ".txt");
}

const EvaluationSet& Relaxations::md_sites(int N) {
  auto it = md_sets_.find(N);
  if (it == md_sets_.end()) {
    it = md_sets_.emplace(N, make_md_evaluation_set(md_file(N), N)).first;
    st::log(opt_, "MD evaluation set N = " + to_text(N) + ": eq. (45) weights and triangulation in " +
                      to_text(it->second.seconds) + " s");
  }
  return it->second;
}

const EvaluationSet& Relaxations::sites_of(const RelaxationSpec& s) {
  return s.md_degree < 0 ? sites(s.n) : md_sites(s.md_degree);
}

std::string Relaxations::path(const std::string& label) const {
  return keep_ ? opt_.out_dir + "/run_" + label + ".h5" : std::string();
}

const RelaxationResult& Relaxations::get(const RelaxationSpec& s) {
  const std::string key = s.label();
  auto it = done_.find(key);
  if (it == done_.end()) {
    Relaxation run(s, sites_of(s), path(key), st::source_commit(opt_), sitting_.remaining());
    run.advance_all();
    RelaxationResult r = run.result();
    if (r.continued && r.finished && r.steps == s.steps)
      st::log(opt_, key + ": taken from " + path(key) + " (begun by " + r.label + ")");
    else if (r.finished)
      finished(key, r);
    it = done_.emplace(key, std::move(r)).first;
  }
  count(key, s, &it->second);
  return it->second.finished ? it->second : skipped_;
}

std::vector<const RelaxationResult*> Relaxations::lockstep(const std::vector<RelaxationSpec>& specs, int blocks) {
  std::vector<std::string> keys;
  std::vector<RelaxationResult> rs(specs.size());
  bool all = true;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    keys.push_back(specs[i].label("_lockstep"));
    if (done_.count(keys[i])) continue;
    if (keep_ && std::filesystem::exists(path(keys[i])))
      rs[i] = Relaxation(specs[i], sites_of(specs[i]), path(keys[i])).result();
    all = all && rs[i].finished;
  }
  if (!all && sitting_.remaining() <= 0) {
    for (std::size_t i = 0; i < specs.size(); ++i) count(keys[i], specs[i], nullptr);
    return std::vector<const RelaxationResult*>(specs.size(), &skipped_);
  }
  if (!all) {
    std::vector<std::unique_ptr<Relaxation>> runs;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      if (keep_) std::filesystem::remove(path(keys[i]));  // all again, together
      runs.push_back(std::make_unique<Relaxation>(specs[i], sites_of(specs[i]), path(keys[i]), st::source_commit(opt_)));
    }
    const int steps = specs.front().steps, every = std::max(1, steps / blocks);
    int last = 0;
    for (bool any = true; any;) {
      any = false;
      for (auto& r : runs) any = r->advance() || any;
      const int k = runs.front()->step();
      if (k != last && (k % every == 0 || k == steps)) {
        for (auto& r : runs) r->mark_block();
        last = k;
      }
    }
    for (std::size_t i = 0; i < specs.size(); ++i) {
      rs[i] = runs[i]->result();
      done_.erase(keys[i]);
      finished(keys[i], rs[i]);
    }
  }
  std::vector<const RelaxationResult*> out;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    auto it = done_.find(keys[i]);
    if (it == done_.end()) it = done_.emplace(keys[i], std::move(rs[i])).first;
    count(keys[i], specs[i], &it->second);
    out.push_back(&it->second);
  }
  return out;
}

void Relaxations::count(const std::string& key, const RelaxationSpec& s, const RelaxationResult* r) {
  if (!counted_.insert(group_ + " " + key).second) return;
  Group& g = groups_[group_];
  g.t_end += s.steps * s.dt;
  if (!r || !r->finished) g.finished = false;
  if (!r) return;
  g.t += r->steps * s.dt;
  g.steps += r->steps;
  g.seconds += r->seconds;
  if (r->failed && g.stopped.empty()) g.stopped = r->failure;
}

void Relaxations::finished(const std::string& label, const RelaxationResult& r) const {
  st::log(opt_, label + ": " + to_text(r.steps) + " steps in " + to_text(r.seconds) + " s, d_axis " +
                    to_text(r.d_axis()) + (r.failed ? " FAILED: " + r.failure : std::string()));
}

void Relaxations::record(st::Json& results) const {
  for (const auto& [id, g] : groups_) {
    st::RunProgress p;
    p.finished = g.finished;
    p.t = g.t;
    p.t_end = g.t_end;
    p.steps = g.steps;
    p.seconds_per_step = g.steps > 0 ? g.seconds / double(g.steps) : NAN;
    p.stopped = g.stopped;
    st::record_run(results, id, p);
  }
}

}  // namespace rbfib::chapter3
