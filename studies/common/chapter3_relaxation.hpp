#pragma once
// The Chapter 3 relaxation studies' bookkeeping (chapter3_dynamics, chapter3_table1): the runs of
// the model of rbfib/models/shell_relaxation.hpp, computed once per invocation, kept over sittings
// and recorded in the results.
#include "common/study.hpp"
#include "rbfib/models/shell_relaxation.hpp"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace rbfib::chapter3 {

/// The parameters both Sec. 4.2 studies share (units, box, forces, kernel, time update, sites).
void describe_dynamic_test(study::Json& P);

/// The runs of a study, each computed once per invocation; with --resumable or at full scale also
/// kept in DIR/run_<label>.h5, the run loop's checkpoint, so that a run the sitting (--sitting)
/// leaves unfinished continues next time and a finished one is read back. Runs are counted in
/// groups, recorded as results["runs"][group]: a group is finished when every run asked of it has
/// finished; an unfinished run gives no values (its checks are not run).
class Relaxations {
 public:
  explicit Relaxations(const study::Options& opt);
  /// The group the next runs belong to.
  void group(const std::string& g) { group_ = g; }
  const EvaluationSet& sites(index_t n);
  /// The stored maximal-determinant-like set of degree N with the weights of eq. (45).
  const EvaluationSet& md_sites(int N);
  std::string md_file(int N) const;
  /// The finished run of spec (or one with no samples when the sitting left it unfinished).
  const RelaxationResult& get(const RelaxationSpec& spec);
  /// Runs of one evaluation set in lockstep, one step of each in turn, so that a change of load
  /// on the shared machine falls on all alike; all again unless all are kept finished. The wall
  /// time of each run's steps is marked at the ends of `blocks` blocks of steps (block_ends).
  std::vector<const RelaxationResult*> lockstep(const std::vector<RelaxationSpec>& specs, int blocks);
  /// results["runs"][group] for every group.
  void record(study::Json& results) const;

 private:
  struct Group {
    double t = 0, t_end = 0, seconds = 0;
    long steps = 0;
    bool finished = true;
    std::string stopped;  ///< the first numerical stop among them
  };
  std::string path(const std::string& label) const;
  const EvaluationSet& sites_of(const RelaxationSpec& s);
  void count(const std::string& key, const RelaxationSpec& s, const RelaxationResult* r);
  void finished(const std::string& label, const RelaxationResult& r) const;

  const study::Options& opt_;
  bool keep_;
  const study::Sitting sitting_;
  RelaxationResult skipped_;  ///< what a run not started in this sitting gives (no samples)
  std::string group_ = "runs";
  std::map<std::string, Group> groups_;
  std::set<std::string> counted_;
  std::map<index_t, EvaluationSet> sets_;
  std::map<int, EvaluationSet> md_sets_;
  std::map<std::string, RelaxationResult> done_;
};

}  // namespace rbfib::chapter3
