#include "common/study.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/core/exec.hpp"
#include "rbfib/core/units.hpp"

#include <CLI/CLI.hpp>
#if defined(RBFIB_BACKEND_CUDA)
#include <cuda_runtime.h>
#endif
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>
#include <vector>

namespace rbfib::study {

const char* to_string(Scale s) { return s == Scale::quick ? "quick" : "full"; }

Options parse_command_line(int argc, char** argv, const std::string& name, const std::string& description) {
  Options opt;
  opt.name = name;
  auto fail = [&](const std::string& msg) {
    std::cerr << name << ": " << msg << " (try --help)\n";
    std::exit(2);
  };
  CLI::App app{description, "study_" + name};
  std::string scale = "quick", sitting;
  app.add_option("--scale", scale, "quick (CI sizes, default) or full (the paper's sizes)");
  app.add_option("--out", opt.out_dir, "the directory for results.json and the runs' files (default .)");
  app.add_option("--sitting", sitting,
                 "wall seconds this sitting may take: runs kept over sittings then save their checkpoints and report how far "
                 "they came (default: no limit)");
  app.add_flag("--resumable", opt.resumable, "keep checkpoints at quick scale too (full scale always keeps them)");
  app.add_option("--commit", opt.commit, "the commit that built this driver, kept with saved runs");
  app.add_option("--source", opt.source_dir, "the source tree for stored inputs (default: the configured one)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    std::exit(app.exit(e));
  } catch (const CLI::ParseError& e) {
    fail(e.what());
  }
  if (scale == "quick") opt.scale = Scale::quick;
  else if (scale == "full") opt.scale = Scale::full;
  else fail("--scale = '" + scale + "' is not one of: quick, full");
  if (!sitting.empty()) {
    char* end = nullptr;
    opt.sitting = std::strtod(sitting.c_str(), &end);
    if (end == sitting.c_str() || *end != '\0' || !(opt.sitting > 0)) fail("--sitting = '" + sitting + "' must be a positive number of seconds");
  }
  std::error_code ec;
  std::filesystem::create_directories(opt.out_dir, ec);
  if (ec) fail("--out = '" + opt.out_dir + "' cannot be created: " + ec.message());
  std::cout << "[" << name << "] scale = " << to_string(opt.scale) << ", out = " << opt.out_dir
            << ", backend = " << backend_name() << ", threads = " << omp_get_max_threads() << std::endl;
  return opt;
}

static std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

Json table(const std::vector<std::string>& columns, const std::vector<std::string>& units) {
  Json t = Json::object();
  t["columns"] = Json(columns);
  t["units"] = Json(units);
  t["rows"] = Json::array();
  return t;
}

/// The GPU the CUDA backend runs on ("" on the CPU backend).
static std::string gpu_name() {
#if defined(RBFIB_BACKEND_CUDA)
  int device = 0;
  cudaDeviceProp props;
  if (cudaGetDevice(&device) == cudaSuccess && cudaGetDeviceProperties(&props, device) == cudaSuccess) return props.name;
  return "unknown (cudaGetDeviceProperties failed)";
#else
  return "";
#endif
}

Json make_results(const Options& opt) {
  Json r = Json::object();
  r["study"] = opt.name;
  r["scale"] = to_string(opt.scale);
  Json& p = r["provenance"];
#if defined(__clang__)
  p["compiler"] = std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  p["compiler"] = std::string("gcc ") + __VERSION__;
#endif
  p["backend"] = backend_name();
  p["threads"] = omp_get_max_threads();
  p["cpu"] = cpu_model();
  if (const std::string gpu = gpu_name(); !gpu.empty()) p["gpu"] = gpu;
  p["hardware_threads"] = int(std::thread::hardware_concurrency());
  return r;
}

void write_results(const Options& opt, const Json& results) {
  const auto path = std::filesystem::path(opt.out_dir) / "results.json";
  std::ofstream out(path);
  results.write(out);
  out << "\n";
  if (!out) throw std::runtime_error("cannot write " + path.string());
  std::cout << "[" << opt.name << "] results written to " << path.string() << std::endl;
}

void record_run(Json& results, const std::string& id, const RunProgress& p) {
  Json& r = results["runs"][id];
  r["finished"] = p.finished;
  r["progress"] = p.t_end > 0 ? std::min(1.0, p.t / p.t_end) : (p.finished ? 1.0 : 0.0);
  char simulated[64];
  const bool in_ms = p.t_end >= units::ms;  // the unit that suits the run's end
  const double unit = in_ms ? units::ms : units::us;
  std::snprintf(simulated, sizeof simulated, "%.4g of %.4g %s", p.t / unit, p.t_end / unit, in_ms ? "ms" : "us");
  r["simulated"] = simulated;
  r["steps"] = p.steps;
  r["seconds_per_step"] = std::isfinite(p.seconds_per_step) ? Json(p.seconds_per_step) : Json();
  const double mean_dt = p.steps > 0 ? p.t / double(p.steps) : NAN;
  r["mean_dt_ns"] = std::isfinite(mean_dt) ? Json(mean_dt / units::ns) : Json();
  const double here = std::isfinite(p.seconds_per_step_here) ? p.seconds_per_step_here : p.seconds_per_step;
  const double hours = p.finished ? 0.0 : (p.t_end - p.t) / mean_dt * here / 3600;
  r["hours_to_go"] = std::isfinite(hours) ? Json(hours) : Json();
  if (!p.stopped.empty()) r["stopped"] = p.stopped;
}

void log(const Options& opt, const std::string& message) { std::cout << "[" << opt.name << "] " << message << std::endl; }

Sitting::Sitting(const Options& opt) : limit_(opt.sitting), start_(std::chrono::steady_clock::now()) {}

double Sitting::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

double Sitting::remaining() const { return limit_ - elapsed(); }

std::string source_commit(const Options& opt) { return opt.commit; }

double median_seconds(int repeats, const std::function<void()>& fn) {
  std::vector<double> t;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return median(t);
}

double best_seconds(int repeats, const std::function<void()>& fn) {
  double best = 1e300;
  for (int r = 0; r < std::max(1, repeats); ++r) best = std::min(best, median_seconds(1, fn));
  return best;
}

namespace {
struct Triad {
  const double *b, *c;
  double s;
  double* a;
  RBFIB_HD void operator()(index_t i) const { a[i] = b[i] + s * c[i]; }
};
}  // namespace

double triad_seconds(long long n) {
  dvec a(n, 0.0), b(n, 1.0), c(n, 2.0);
  for_each_index(n, Triad{ptr(b), ptr(c), 3.0, ptr(a)});  // touch
  return best_seconds(10, [&] {
    for_each_index(n, Triad{ptr(b), ptr(c), 3.0, ptr(a)});
    synchronize();
  });
}

int run_main(const std::string& name, const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << name << ": error: " << e.what() << std::endl;
    return 1;
  }
}

std::string source_path(const Options& opt, const std::string& relative) {
  return (opt.source_dir.empty() ? std::string(RBFIB_SOURCE_DIR) : opt.source_dir) + "/" + relative;
}

}  // namespace rbfib::study
