#pragma once
// What every study driver shares: the command line (--scale quick|full, --out DIR), the echo of
// parameters, provenance (compiler, backend, machine, threads), timing as the median of repeats,
// and the one machine-readable results file DIR/results.json (format: harness/FORMAT.md).
#include "rbfib/core/series.hpp"
#include "rbfib/io/json.hpp"

#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace rbfib::study {

using io::Json, io::row, io::number;  // results.json (harness/FORMAT.md)
using rbfib::median, rbfib::slope, rbfib::power_law_order;  // series statistics (core/series.hpp)

enum class Scale { quick, full };

struct Options {
  std::string name;
  Scale scale = Scale::quick;
  std::string out_dir = ".";
  double sitting = INFINITY;    ///< --sitting: wall seconds of this sitting for runs kept over sittings
  bool resumable = false;       ///< --resumable: keep checkpoints at quick scale too (full scale always does)
  std::string commit = "unknown";  ///< --commit: the commit that built this driver (the harness passes it)
  std::string source_dir;       ///< --source: the source tree (stored inputs); default: the configured one
  bool keeps_runs() const { return scale == Scale::full || resumable; }
};

/// Parses argv (--scale quick|full, --out DIR, --sitting SECONDS, --resumable, --commit HASH,
/// --source DIR); prints usage and exits 0 on --help; prints one line and exits 2 on bad input.
Options parse_command_line(int argc, char** argv, const std::string& name, const std::string& description);

const char* to_string(Scale s);

/// An empty results table {"columns": ..., "units": ..., "rows": []} (format: harness/FORMAT.md).
Json table(const std::vector<std::string>& columns, const std::vector<std::string>& units);

/// A results document pre-filled with the study name, scale and provenance.
Json make_results(const Options& opt);

/// Writes results to <out_dir>/results.json and says where.
void write_results(const Options& opt, const Json& results);

/// The commit the harness says built this driver (--commit), or "unknown": kept with saved
/// full-scale runs so that a result is traced to the code that computed it.
std::string source_commit(const Options& opt);

/// A sitting: wall seconds from now that a full-scale run continued over several sittings may take
/// before it saves its checkpoint and reports what it has (--sitting; unset: no limit).
class Sitting {
 public:
  explicit Sitting(const Options& opt);
  double remaining() const;  ///< s (infinite without a limit)
  double elapsed() const;    ///< s since the sitting began
 private:
  double limit_;
  std::chrono::steady_clock::time_point start_;
};

/// How far one resumable run has come, recorded as results["runs"][id] (harness/FORMAT.md): a
/// check that measures the run (`run: id` in the reference) is NOT RUN until it has finished.
struct RunProgress {
  bool finished = false;          ///< reached its end, or stopped by a numerical check (the stop is its result)
  double t = 0;                   ///< simulated time reached (s)
  double t_end = 0;               ///< the run's end (s)
  long steps = 0;                 ///< steps from t = 0
  double seconds_per_step = NAN;  ///< wall time per step over the run's sittings (s)
  std::string stopped;            ///< the numerical stop's message, if one ended the run
  /// This sitting's wall time per step when it took steps (s): the hours to go follow it, the
  /// rate of the machine and load the run is on now. NaN: seconds_per_step.
  double seconds_per_step_here = NAN;
};

/// results["runs"][id]: finished, progress (t / t_end), the simulated time as text, steps, s per
/// step, the mean step (ns) and the hours to go here at this sitting's rate (0 when finished).
void record_run(Json& results, const std::string& id, const RunProgress& p);

/// Prints "[name] message" to stdout, flushed (progress on long runs).
void log(const Options& opt, const std::string& message);

/// Median wall time in seconds of `repeats` calls of fn.
double median_seconds(int repeats, const std::function<void()>& fn);

/// Shortest wall time in seconds of `repeats` calls of fn (the STREAM convention for bandwidths).
double best_seconds(int repeats, const std::function<void()>& fn);

/// Seconds of one triad a = b + 3 c over n doubles per array on the execution device (best of
/// 10, after a touch); the bandwidth is 3 x 8 n bytes over it. n = 2^24 (384 MiB in all) is out of
/// every cache.
double triad_seconds(long long n);

/// The path of a file in the source tree (stored inputs such as reference/point_sets/...): under
/// --source when given, else under the configured source tree.
std::string source_path(const Options& opt, const std::string& relative);

/// Runs body, turning any exception into one line on stderr and exit status 1.
int run_main(const std::string& name, const std::function<int()>& body);

}  // namespace rbfib::study
