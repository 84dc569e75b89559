// The thread chooser behind Solver_options::threads = 0: it must settle on
// the cheaper of the team and one thread, keep probing the other rarely,
// follow a change of load, and not run the team while one thread cannot get
// a core of its own or other processes hold the cores the team needs.
#include <spring_motion/internal/solver/thread_chooser.h>
#include <spring_motion/internal/solver/threads.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cfenv>
#include <stdexcept>
#include <thread>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef __linux__
#include <sched.h>
#endif

using spring_motion::internal::Thread_chooser;

namespace {

double full_core(int) { return 1.0; }

// The free-core count not known: the choice rests on measurements alone (and
// a test run beside other tests does not see their load).
int unknown_cores() { return -1; }

// Runs `steps` steps whose cost per unit of work is team_cost(step) with the
// team and one_cost(step) with one thread, a one-thread step's thread running
// share(step) of its wall time; returns how many used the team.
template <class Team_cost, class One_cost, class Share = double (*)(int)>
int team_steps(Thread_chooser& c, int first, int steps, Team_cost team_cost, One_cost one_cost,
               Share share = full_core)
{
  int team = 0;
  for(int i = first; i < first + steps; ++i) {
    const int t = c.next(0);
    const bool is_team = t > 1;
    team += is_team;
    const std::size_t iterations = 20;
    const double seconds = (is_team ? team_cost(i) : one_cost(i)) * (iterations + 4);
    // a team's calling thread spins at its barriers: its CPU time is its wall
    // time whether or not the team had its cores
    c.record(seconds, iterations, is_team ? seconds : share(i) * seconds);
  }
  return team;
}

// Two other CPU-bound processes on 2 cores: a thread gets 2/3 of a core on
// average, and anything from 1/2 to all of it in a single step.
double crowded_core(int step)
{
  const double shares[] = {0.71, 0.56, 1.0, 0.58, 0.65, 0.87, 0.5, 0.7, 0.8};
  return shares[step % 9];
}

} // namespace

TEST_CASE("thread chooser: a positive request is obeyed and nothing is measured", "[threads]")
{
  Thread_chooser c{unknown_cores};
  for(int i = 0; i < 5; ++i) {
    CHECK(c.next(3) == 3);
    c.record(1.0, 10);
  }
}

#ifdef _OPENMP
TEST_CASE("thread chooser: its costs not yet measured raise no floating-point exception", "[threads][errors]")
{
  // a cost not yet measured is a NaN; an ordered comparison with it raises
  // FE_INVALID (SIGFPE under feenableexcept, as in tests/test_fp_traps.cpp
  // run alone on an idle machine): every choice of the first steps, with
  // the team dearer, then cheaper, then a probe of one thread
  omp_set_num_threads(2);
  for(double one_thread : {0.5, 2.0, 8.0}) {
    INFO("one thread's cost " << one_thread);
    Thread_chooser c{[] { return 2; }};
    std::feclearexcept(FE_ALL_EXCEPT);
    const int team = team_steps(c, 0, 40, [](int) { return 1.0; }, [&](int) { return one_thread; });
    CHECK(std::fetestexcept(FE_INVALID) == 0);
    CHECK(team > 0); // the team was tried: the comparisons above ran
    CHECK(team < 40); // and one thread
  }
}

TEST_CASE("thread chooser: settles on the cheaper option and follows a change of load", "[threads]")
{
  omp_set_num_threads(2);
  SECTION("idle machine: the team is twice as fast, one thread is only probed")
  {
    Thread_chooser c{unknown_cores};
    const int team = team_steps(c, 0, 100, [](int) { return 1.0; }, [](int) { return 2.0; });
    CHECK(team >= 94);
    CHECK(team < 100); // it did try one thread
    CHECK(c.chosen() == 2);
  }
  SECTION("busy machine: the team is three times slower, it is only probed")
  {
    Thread_chooser c{unknown_cores};
    const int team = team_steps(c, 0, 100, [](int) { return 3.0; }, [](int) { return 1.0; });
    CHECK(team <= 4);
    CHECK(c.chosen() == 1);
    // the cost of the probes: under 1.25x one thread all along
    const double cost = (team * 3.0 + (100 - team) * 1.0) / 100;
    CHECK(cost < 1.25);
  }
  SECTION("busy machine, a short run: the team is tried once in 20 steps")
  {
    // the first step on one thread, the team once, then a clear loss (3x)
    // puts the next probe 32 steps away
    Thread_chooser c{unknown_cores};
    CHECK(c.next(0) == 1);
    c.record(1.0, 20);
    CHECK(team_steps(c, 1, 19, [](int) { return 3.0; }, [](int) { return 1.0; }) == 1);
  }
  SECTION("the first step: its start on one thread, the rest on the team when that thread had a core")
  {
    Thread_chooser idle{unknown_cores};
    CHECK(idle.next(0) == 1);
    CHECK(idle.after_setup(0.05, 0.049) == 2);
    CHECK(idle.chosen() == 2);
    idle.record(0.2, 20, 0.2);
    CHECK_FALSE(idle.crowded());
    // later steps as before: the team measured, then one thread
    CHECK(idle.next(0) == 2);
    CHECK(idle.after_setup(0.05, 0.05) == 2);
    idle.record(1.0, 20, 1.0);
    CHECK(idle.next(0) == 1);
    CHECK(idle.after_setup(0.05, 0.05) == 1);

    // two thirds of a core: the whole first step on one thread, and its
    // share says crowded
    Thread_chooser busy{unknown_cores};
    CHECK(busy.next(0) == 1);
    CHECK(busy.after_setup(0.05, 0.034) == 1);
    busy.record(0.3, 20, 0.2);
    CHECK(busy.crowded());
    CHECK(busy.next(0) == 1); // no team probe while crowded

    // a start too short to tell, an unknown CPU time, a requested count
    Thread_chooser short_start{unknown_cores}, unknown{unknown_cores}, fixed{unknown_cores};
    CHECK(short_start.next(0) == 1);
    CHECK(short_start.after_setup(0.005, 0.005) == 1);
    CHECK(unknown.next(0) == 1);
    CHECK(unknown.after_setup(0.05, -1) == 1);
    CHECK(fixed.next(3) == 3);
    CHECK(fixed.after_setup(0.05, 0.05) == 3);
  }
  SECTION("crowded cores, seen by one thread's CPU share: the team is not tried")
  {
    // the one-thread steps get 2/3 of a core: a team, which needs two free
    // cores, is not probed at all, though one step had a core to itself
    Thread_chooser c{unknown_cores};
    CHECK(team_steps(c, 0, 100, [](int) { return 3.0; }, [](int) { return 1.0; }, crowded_core) == 0);
    CHECK(c.chosen() == 1);
    CHECK(c.crowded());
  }
  SECTION("a core frees up: the team is tried within a few steps and kept")
  {
    Thread_chooser c{unknown_cores};
    CHECK(team_steps(c, 0, 20, [](int) { return 3.0; }, [](int) { return 1.0; }, crowded_core) == 0);
    // idle from step 20: the team is twice as fast
    const int team = team_steps(c, 20, 20, [](int) { return 1.0; }, [](int) { return 2.0; });
    CHECK(team >= 15);
    CHECK(c.chosen() == 2);
    CHECK_FALSE(c.crowded());
  }
  SECTION("a full core for one thread: the team is probed as before")
  {
    // one other busy process: one thread runs freely, the team stalls
    Thread_chooser c{unknown_cores};
    CHECK(team_steps(c, 0, 20, [](int) { return 3.0; }, [](int) { return 1.0; }) == 1);
    CHECK(c.chosen() == 1);
  }
  SECTION("a close call (the team 1.5x slower) is checked again after 8 steps")
  {
    Thread_chooser c{unknown_cores};
    CHECK(team_steps(c, 0, 12, [](int) { return 1.5; }, [](int) { return 1.0; }) == 2);
  }
  SECTION("the load comes and goes: the choice follows within the probe interval")
  {
    Thread_chooser c{unknown_cores};
    const auto busy = [](int i) { return i >= 30 && i < 130; };
    team_steps(c, 0, 30, [](int) { return 1.0; }, [](int) { return 2.0; });
    CHECK(c.chosen() == 2);
    // at most 64 steps (the longest interval) plus one to notice the load
    // busy: the team costs 3, one thread 1; idle: 1 and 2
    const auto team_cost = [&](int i) { return busy(i) ? 3.0 : 1.0; };
    const auto one_cost = [&](int i) { return busy(i) ? 1.0 : 2.0; };
    const int team_busy = team_steps(c, 30, 100, team_cost, one_cost);
    CHECK(c.chosen() == 1);
    CHECK(team_busy <= 66);
    team_steps(c, 130, 80, team_cost, one_cost);
    CHECK(c.chosen() == 2);
  }
  SECTION("other processes hold the cores: no team step, and the team comes back when they go")
  {
    // the case the CPU share cannot see: one thread alone on a core, two
    // other processes sharing the other; every one-thread step had its core
    int free = 0, reads = 0;
    Thread_chooser c{[&] {
      ++reads;
      return free;
    }};
    CHECK(c.next(0) == 1);
    CHECK(c.after_setup(0.05, 0.05) == 1); // its start had a core, the team would not
    CHECK(reads == 2);                     // at the step's start and after its set-up
    c.record(0.3, 20, 0.3);
    CHECK_FALSE(c.crowded());
    CHECK(team_steps(c, 1, 99, [](int) { return 3.0; }, [](int) { return 1.0; }) == 0);
    CHECK(c.chosen() == 1);
    // one core free is not enough for a team of two either
    free = 1;
    CHECK(team_steps(c, 100, 20, [](int) { return 3.0; }, [](int) { return 1.0; }) == 0);
    // both cores free: the team is tried at once and kept where it is faster
    free = 2;
    const int team = team_steps(c, 120, 20, [](int) { return 1.0; }, [](int) { return 2.0; });
    CHECK(team >= 18);
    CHECK(c.chosen() == 2);
    // the load comes back while the team is the choice: one step more on
    // the team (its read is outvoted by the one before), then one thread
    // while the cores are held
    free = 0;
    CHECK(team_steps(c, 140, 20, [](int) { return 3.0; }, [](int) { return 1.0; }) == 1);
    // read only when a team step was about to start (twice in the first
    // step), never more often
    CHECK(reads <= 2 + 99 + 20 + 20 + 20);
    CHECK(reads >= 40);
  }
  SECTION("a process that runs for a moment: one read is outvoted, two in a row are not")
  {
    std::vector<int> free = {0, 2};
    std::size_t read = 0;
    Thread_chooser first{[&] { return free[read++ % free.size()]; }};
    CHECK(first.next(0) == 1);
    CHECK(first.after_setup(0.05, 0.05) == 2); // crowded at the start only
    read = 0;
    free = {2, 0, 2, 2, 0, 0, 0, 2};
    Thread_chooser c{[&] { return free[std::min(read++, free.size() - 1)]; }};
    CHECK(c.next(0) == 1);
    CHECK(c.after_setup(0.05, 0.05) == 2); // crowded after the set-up only
    c.record(0.2, 20, 0.2);
    CHECK(c.next(0) == 2); // the team's first probe: free
    c.record(0.2, 20, 0.2);
    CHECK(c.next(0) == 1); // the one-thread probe: not read
    c.record(0.4, 20, 0.4);
    CHECK(c.next(0) == 2); // free
    c.record(0.2, 20, 0.2);
    CHECK(c.next(0) == 2); // crowded, but the read a step before found two cores
    c.record(0.2, 20, 0.2);
    CHECK(c.next(0) == 1); // crowded twice in a row
    c.record(0.4, 20, 0.4);
    CHECK(c.next(0) == 1);
    c.record(0.4, 20, 0.4);
    CHECK(c.next(0) == 2); // free again
    CHECK(read == 8);
  }
  SECTION("a read that says crowded after steps without reads is not outvoted")
  {
    // the team is probed after one-thread steps that read nothing: the load
    // may have come since the last read
    const std::vector<int> free = {2, 2, 2, 0};
    std::size_t read = 0;
    Thread_chooser c{[&] { return free[std::min(read++, free.size() - 1)]; }};
    CHECK(c.next(0) == 1);
    CHECK(c.after_setup(0.05, 0.05) == 2);
    c.record(0.2, 20, 0.2);
    CHECK(c.next(0) == 2);
    c.record(0.6, 20, 0.6); // the team probe: three times one thread
    int team = 0;
    for(int i = 0; i < 40; ++i) {
      team += c.next(0) > 1;
      c.record(0.2, 20, 0.2);
    }
    // the probe fell due 32 steps after the team lost clearly (at the 34th
    // step of the loop) and waits, reading at each step, while crowded
    CHECK(read == 3 + 7);
    CHECK(team == 0);
  }
  SECTION("free cores: the first step's solve goes to the team as before")
  {
    Thread_chooser c{[] { return 2; }};
    CHECK(c.next(0) == 1);
    CHECK(c.after_setup(0.05, 0.049) == 2);
  }
  SECTION("short steps: a read that found the cores free holds for read_holds of steps")
  {
    // steps of a millisecond on the team, two on one thread (the 2D paper
    // mesh's size): a read every step would cost several per cent
    int free = 2, reads = 0;
    Thread_chooser c{[&] {
      ++reads;
      return free;
    }};
    CHECK(c.next(0) == 1);
    c.record(0.004, 20, 0.004);
    const double ms = 0.001 / 24; // team_steps' seconds per unit of work
    CHECK(team_steps(c, 1, 100, [&](int) { return ms; }, [&](int) { return 2 * ms; }) >= 90);
    // one read at the first step, then one per read_holds / 1 ms team steps
    // (one-thread probes read nothing)
    const int per_hold = int(Thread_chooser::read_holds / 0.001 + 0.5);
    CHECK(reads >= 1 + 90 / per_hold - 1);
    CHECK(reads <= 1 + 100 / per_hold + 1);
    // the load comes: the held read runs out within read_holds of steps and
    // the team stops (one step more on the team: the held read outvotes the
    // first crowded one)
    free = 0;
    const int busy_team = team_steps(c, 101, 30, [&](int) { return 3 * ms; }, [&](int) { return ms; });
    CHECK(busy_team <= int(Thread_chooser::read_holds / 0.003) + 2);
    CHECK(c.chosen() == 1);
  }
}
#endif

#ifdef _OPENMP
// A step's loops run on the count the chooser (or the caller) gives from
// chosen_parallel_threshold items; loops at OpenMP's default (0: the set-up,
// the output) stay serial up to parallel_threshold.
TEST_CASE("thread counts: an explicit count shares out smaller loops than the default", "[threads]")
{
  using namespace spring_motion::internal;
  omp_set_num_threads(2);
  constexpr std::size_t chosen = chosen_parallel_threshold, fallback = parallel_threshold;
  REQUIRE(chosen < fallback);
  CHECK(thread_count(2, chosen) == 2);
  CHECK(thread_count(2, chosen - 1) == 1);
  CHECK(thread_count(1, fallback) == 1);
  CHECK(thread_count(0, chosen) == 1);
  CHECK(thread_count(0, fallback - 1) == 1);
  CHECK(thread_count(0, fallback) == 2);
  // stiffness loops: a sixteenth of the items
  CHECK(heavy_thread_count(2, chosen / 16) == 2);
  CHECK(heavy_thread_count(2, chosen / 16 - 1) == 1);
  CHECK(heavy_thread_count(0, chosen / 16) == 1);
  CHECK(heavy_thread_count(0, fallback / 16) == 2);
}
#endif

#ifdef _OPENMP
// The team is started (a region the compiler cannot drop: an empty one was
// dropped, and with it the start) while the caller's own work runs on the
// caller's thread; an exception from that work leaves the region and the
// team usable.
TEST_CASE("team start: the caller's work on the caller's thread while the team's threads run", "[threads]")
{
  using namespace spring_motion::internal;
  omp_set_num_threads(2);
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id ran_on;
  CHECK(run_while_team_starts(2, [&] { ran_on = std::this_thread::get_id(); }) == 2);
  CHECK(ran_on == caller);
  CHECK(start_team(2) == 2);
  CHECK(start_team(1) == 1);
  CHECK(start_team(0) == 2); // OpenMP's default, 2 here
  CHECK_THROWS_AS(run_while_team_starts(2, [] { throw std::runtime_error("unreadable"); }), std::runtime_error);
  CHECK(start_team(2) == 2);
}

// A loop of in_team: every index once; one thread enters no region, a
// team's threads share the loop, and inside a caller's own region each
// caller thread's team of one runs its whole loop (an orphaned loop there
// would have split it between the caller's threads).
TEST_CASE("in_team: a team of one outside any region, its loops whole inside a caller's region", "[threads]")
{
  using namespace spring_motion::internal;
  constexpr long n = 1000;
  auto run = [&](int threads, std::vector<int>& hits, int& level, int& team) {
    in_team(threads, [&] {
#pragma omp for schedule(static)
      for(long i = 0; i < n; ++i)
        ++hits[std::size_t(i)];
#pragma omp master
      {
        level = omp_get_level();
        team = omp_get_num_threads();
      }
    });
  };
  for(const int threads : {1, 2}) {
    std::vector<int> hits(n, 0);
    int level = -1, team = -1;
    run(threads, hits, level, team);
    CHECK(std::count(hits.begin(), hits.end(), 1) == n);
    CHECK(level == (threads == 1 ? 0 : 1));
    CHECK(team == threads);
  }
  std::vector<std::vector<int>> hits(2, std::vector<int>(n, 0));
  std::vector<int> level(2, -1), team(2, -1);
#pragma omp parallel num_threads(2)
  {
    const int me = omp_get_thread_num();
    run(1, hits[std::size_t(me)], level[std::size_t(me)], team[std::size_t(me)]);
  }
  for(std::size_t t = 0; t < 2; ++t) {
    CHECK(std::count(hits[t].begin(), hits[t].end(), 1) == n);
    CHECK(team[t] == 1);
  }
}
#endif

#if defined(_OPENMP) && defined(__linux__)
// A team thread woken on its caller's core moves off it: the thread leaves
// the core at once and keeps every core it was allowed.
TEST_CASE("team start: a thread moved off a core leaves it and keeps its allowed cores", "[threads]")
{
  using namespace spring_motion::internal;
  cpu_set_t before;
  REQUIRE(sched_getaffinity(0, sizeof before, &before) == 0);
  if(CPU_COUNT(&before) < 2)
    return; // nowhere to move to
  // The scheduler may move the thread back at any time: one of three tries
  // must find it elsewhere right after the move (it is never elsewhere
  // without it on an idle machine).
  int moved = 0;
  for(int attempt = 0; attempt < 3 && moved == 0; ++attempt) {
    const int cpu = sched_getcpu();
    move_off_cpu(cpu);
    moved += sched_getcpu() != cpu;
    cpu_set_t after;
    REQUIRE(sched_getaffinity(0, sizeof after, &after) == 0);
    CHECK(CPU_EQUAL(&before, &after));
  }
  CHECK(moved == 1);
}
#endif

#ifdef _OPENMP
// One slow step of the choice (another process's moment on a core) must not
// send a run to the other option for a probe interval; two in a row must.
TEST_CASE("thread chooser: one dearer step of the choice does not change it, two in a row do", "[threads]")
{
  omp_set_num_threads(2);
  SECTION("one slow team step among fast ones: the team stays the choice")
  {
    Thread_chooser c{unknown_cores};
    // the team twice as fast, but step 40 takes four times a team step
    const int team = team_steps(c, 0, 100, [](int i) { return i == 40 ? 4.0 : 1.0; }, [](int) { return 2.0; });
    CHECK(team >= 94);
    CHECK(c.chosen() == 2);
  }
  SECTION("two slow team steps in a row: one thread from the second")
  {
    Thread_chooser c{unknown_cores};
    CHECK(team_steps(c, 0, 40, [](int) { return 1.0; }, [](int) { return 2.0; }) >= 36);
    CHECK(c.chosen() == 2);
    // the load comes for good: the team costs 8 (a clear loss), one thread 2
    int team = 0;
    for(int i = 0; i < 4; ++i) {
      const bool is_team = c.next(0) > 1;
      team += is_team;
      c.record((is_team ? 8.0 : 2.0) * 24, 20, is_team ? 8.0 * 24 : 2.0 * 24);
    }
    CHECK(team == 2);
    CHECK(c.chosen() == 1);
  }
}
#endif
