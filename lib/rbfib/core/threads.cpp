#include "rbfib/core/threads.hpp"

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace rbfib {

namespace {

using clock = std::chrono::steady_clock;

/// Busy CPU time of all CPUs (s): /proc/stat's first line without idle and iowait; -1 where
/// /proc/stat is not readable (then the team is left as it is).
double machine_busy_seconds() {
  std::ifstream f("/proc/stat");
  std::string cpu;
  double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(f >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq) || cpu != "cpu") return -1;
  f >> steal;  // absent on old kernels; time the hypervisor gave to other machines
  static const double tick = 100;  // USER_HZ, 100 on every Linux ABI
  return (user + nice + system + irq + softirq + steal) / tick;
}

double own_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Share {
  bool fixed = std::getenv("OMP_NUM_THREADS") != nullptr;  // the user's choice is kept
  int cores = omp_get_num_procs();
  int max_team = omp_get_max_threads();
  int team = max_team;
  clock::time_point last = clock::now();
  double last_busy = machine_busy_seconds(), last_own = own_cpu_seconds();
};

Share& share() {
  static Share s;
  return s;
}

}  // namespace

void share_cores() {
  Share& s = share();
  if (s.fixed || s.max_team < 2 || s.last_busy < 0) return;
  const clock::time_point now = clock::now();
  const double wall = std::chrono::duration<double>(now - s.last).count();
  if (wall < 0.5) return;
  const double busy = machine_busy_seconds(), own = own_cpu_seconds();
  // Cores the other programs kept busy over the interval (CPU-seconds per second).
  const double others = std::max(0.0, (busy - s.last_busy) - (own - s.last_own)) / wall;
  s.last = now, s.last_busy = busy, s.last_own = own;
  const int team = std::clamp(int(std::floor(double(s.cores) - others + 0.5)), 1, s.max_team);
  if (team != s.team) {
    s.team = team;
    omp_set_num_threads(team);
  }
}

int shared_team_size() { return share().team; }

}  // namespace rbfib
