#include "rbfib/core/threads.hpp"

#include <omp.h>
#include <sched.h>
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

/// Busy time (s) of the CPUs this process may run on (its affinity mask), from /proc/stat's
/// per-CPU lines without idle and iowait; -1 where /proc/stat is not readable (the team is then
/// left as it is). A container shown the host's CPUs sees only its own in the mask.
double machine_busy_seconds() {
  cpu_set_t mask;
  CPU_ZERO(&mask);
  const bool masked = sched_getaffinity(0, sizeof mask, &mask) == 0;
  std::ifstream f("/proc/stat");
  std::string line;
  double ticks = 0;
  bool any = false;
  while (std::getline(f, line)) {
    if (line.rfind("cpu", 0) != 0) break;  // the cpu lines come first
    if (line.size() < 4 || line[3] == ' ') continue;  // the all-CPU line
    std::istringstream in(line.substr(3));
    int cpu = -1;
    double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
    if (!(in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq)) continue;
    in >> steal;  // absent on old kernels; time the hypervisor gave to other machines
    if (masked && (cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &mask))) continue;
    ticks += user + nice + system + irq + softirq + steal;
    any = true;
  }
  return any ? ticks / 100 : -1;  // USER_HZ = 100 on every Linux ABI
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
  if (omp_in_parallel()) return;  // only the thread that starts the parallel regions sizes them
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
