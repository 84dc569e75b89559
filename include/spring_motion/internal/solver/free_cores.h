// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_FREE_CORES_H
#define SPRING_MOTION_INTERNAL_SOLVER_FREE_CORES_H

#include <algorithm>
#include <cstddef>
#include <cstdio>

#ifdef __linux__
#include <dirent.h>
#include <unistd.h>
#endif

namespace spring_motion {
namespace internal {

/// Whether a line of /proc/PID/stat says the thread is running or ready to
/// run (state R). The state follows the command name in parentheses, and the
/// name may itself hold ") R": the last parenthesis ends it.
inline bool stat_line_running(const char* line)
{
  const char* close = nullptr;
  for(const char* c = line; *c; ++c)
    if(*c == ')')
      close = c;
  return close && close[1] == ' ' && close[2] == 'R';
}

/// The threads of this process that are running or ready to run, or -1
/// where the platform does not tell.
inline int running_threads_here()
{
#ifdef __linux__
  DIR* dir = opendir("/proc/self/task");
  if(!dir)
    return -1;
  int running = 0;
  while(const dirent* e = readdir(dir)) {
    if(e->d_name[0] == '.')
      continue;
    char path[64], line[512];
    std::snprintf(path, sizeof path, "/proc/self/task/%.20s/stat", e->d_name);
    std::FILE* f = std::fopen(path, "r");
    if(!f)
      continue; // the thread ended
    const std::size_t got = std::fread(line, 1, sizeof line - 1, f);
    std::fclose(f);
    line[got] = 0;
    running += stat_line_running(line);
  }
  closedir(dir);
  return running;
#else
  return -1;
#endif
}

/// The threads of every process that are running or ready to run, or -1
/// where the platform does not tell.
inline int running_threads_everywhere()
{
#ifdef __linux__
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if(!f)
    return -1;
  double a, b, c;
  int running = -1, total = 0;
  if(std::fscanf(f, "%lf %lf %lf %d/%d", &a, &b, &c, &running, &total) != 5)
    running = -1;
  std::fclose(f);
  return running;
#else
  return -1;
#endif
}

/// The cores that other processes leave to this one right now: the online
/// cores less the other processes' threads that are running or ready to run,
/// or -1 where the platform does not tell (Linux does, in tens of
/// microseconds: the benchmark prints what a call costs).
///
/// Why: a thread that runs alone on a core sees nothing of the other cores
/// (the scheduler often leaves it alone on one, and two other processes
/// sharing the other), and a team needs a core per thread.
inline int free_cores()
{
#ifdef __linux__
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  if(online < 1)
    return -1;
  // this process's threads change state between the reads (a team thread
  // going to sleep): read until they hold still, or count them at their
  // most, which errs towards free cores (the measured choice then decides)
  int others = 0;
  for(int attempt = 0; attempt < 3; ++attempt) {
    const int before = running_threads_here(), all = running_threads_everywhere(), after = running_threads_here();
    if(before < 0 || all < 0 || after < 0)
      return -1;
    others = std::max(0, all - std::max(before, after));
    if(before == after)
      break;
  }
  return int(std::max(0L, online - long(others)));
#else
  return -1;
#endif
}

} // namespace internal
} // namespace spring_motion

#endif
