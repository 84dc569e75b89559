// The count of cores that other processes leave free, read from the system:
// a thread of this process that runs must count as this process's, and a
// process that runs beside it as another's.
#include <spring_motion/internal/solver/free_cores.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <thread>

#ifdef __linux__
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

using namespace spring_motion::internal;

TEST_CASE("free cores: a stat line's state follows the last parenthesis", "[threads]")
{
  CHECK(stat_line_running("4242 (spring-motion) R 1 4242 4242 0 -1"));
  CHECK_FALSE(stat_line_running("4242 (spring-motion) S 1 4242 4242 0 -1"));
  // a command name may hold parentheses and a state letter
  CHECK_FALSE(stat_line_running("4242 (a) R (b) S 1 4242"));
  CHECK(stat_line_running("4242 (x) S) R 1 4242"));
  CHECK_FALSE(stat_line_running("4242 (no end"));
  CHECK_FALSE(stat_line_running(""));
}

#ifdef __linux__
TEST_CASE("free cores: this process's running threads are its own", "[threads]")
{
  // a second thread that spins is running or ready to run all along, as
  // the reading thread is
  std::atomic<bool> stop{false};
  std::thread spinner([&] {
    while(!stop.load(std::memory_order_relaxed)) {
    }
  });
  int here = 0;
  for(int i = 0; i < 5; ++i)
    here = std::max(here, running_threads_here());
  const int everywhere = running_threads_everywhere();
  stop = true;
  spinner.join();
  CHECK(here >= 2);
  CHECK(everywhere >= 1);
}

TEST_CASE("free cores: another process's running thread holds a core", "[threads]")
{
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  const int before = free_cores();
  CHECK(before >= 0);
  CHECK(before <= online);
  // a child that spins is runnable all along: whatever else runs, at most
  // all cores but one are free (other tests may hold more)
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if(child == 0)
    for(volatile unsigned long spin = 0;; spin = spin + 1) {
    }
  usleep(50000);
  int most = -1;
  for(int i = 0; i < 5; ++i)
    most = std::max(most, free_cores());
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  CHECK(most >= 0);
  CHECK(most <= online - 1);
}
#else
TEST_CASE("free cores: not known here", "[threads]")
{
  CHECK(free_cores() == -1);
}
#endif
