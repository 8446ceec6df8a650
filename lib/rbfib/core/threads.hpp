#pragma once
// The OpenMP team size on a machine shared with other programs.
//
// A team of as many threads as cores collapses when another program keeps one core busy: every
// barrier waits for the thread that shares its core, and a team that spins at barriers (the
// fastest choice on a quiet machine) holds its cores while it waits. Measured on 2 cores with a
// busy loop beside a 48^3 capsule scene: 9 steps/s against 38 alone (24%); with one thread, 19
// (50%, the fair share). So before each parallel launch the team is sized to the cores the other
// programs leave free, measured over the last half second from /proc/stat (the busy time of the
// CPUs this process may use) less this process's own CPU time (getrusage): the team shrinks when
// another program takes a core and grows back when it leaves. On a quiet machine nothing changes.
//
// A team size set by the user (OMP_NUM_THREADS) is kept as it is: that is how to ask for the
// fixed, fastest setting on a dedicated machine.
namespace rbfib {

/// Called before each parallel launch (for_each_index, exec.hpp) and between steps; does nothing
/// inside a parallel region. Costs a clock read except every half second, when it measures the
/// other programs' load and may resize the team for the parallel regions that follow.
void share_cores();

/// The team size share_cores() has chosen (omp_get_max_threads() until it has run).
int shared_team_size();

}  // namespace rbfib
