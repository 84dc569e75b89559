// Copyright (c) 2026 SpringMotion developers.
// spring-motion: the command-line tool. This file only dispatches to the
// subcommands (commands.h) and turns exceptions into one-line messages and
// exit statuses.
#include "Arguments.h"
#include "commands.h"

#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>

#include <csignal>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include <unistd.h>

#ifndef SPRING_MOTION_VERSION
#define SPRING_MOTION_VERSION "unknown"
#endif

namespace spring_motion {
namespace cli {
namespace {
volatile std::sig_atomic_t interrupt_flag = 0;
extern "C" void on_interrupt(int) { interrupt_flag = 1; }
} // namespace
bool interrupted() { return interrupt_flag != 0; }
void install_interrupt_handlers()
{
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

Failure describe_failure(const std::string& command)
{
  try {
    throw;
  } catch(const Reported_error& e) {
    return {e.status(), ""};
  } catch(const Relayed_error& e) {
    return {e.status(), e.what()};
  } catch(const Interrupted& e) {
    return {exit_interrupted, std::string("spring-motion: ") + e.what()};
  } catch(const Usage_error& e) {
    return {exit_usage_error, "spring-motion " + command + ": " + e.what() + " (see 'spring-motion " + command +
                                  " --help')"};
  } catch(const spring_motion::Input_error& e) {
    return {exit_input_error, std::string("spring-motion: ") + e.what()};
  } catch(const spring_motion::Error& e) {
    return {exit_input_error, "spring-motion: " + without_source_location(e.what())};
  } catch(const std::bad_alloc&) {
    return {exit_internal_error, "spring-motion: out of memory"};
  } catch(const std::exception& e) {
    return {exit_internal_error, std::string("spring-motion: internal error: ") + e.what()};
  }
}
} // namespace cli
} // namespace spring_motion

int main(int argc, char** argv)
{
  using namespace spring_motion::cli;
  std::ios::sync_with_stdio(false);
  const std::vector<std::string> all(argv + 1, argv + argc);
  const std::string command = all.empty() ? std::string() : all.front();
  const std::vector<std::string> rest(all.empty() ? all.end() : all.begin() + 1, all.end());
  try {
    if(command.empty() || command == "--help" || command == "-h" || command == "help") {
      std::cout << main_help();
      return command.empty() ? exit_usage_error : exit_success;
    }
    if(command == "--version") {
      std::cout << "spring-motion " << SPRING_MOTION_VERSION << "\n";
      return exit_success;
    }
    if(command == "deform")
      return deform_command(rest, std::cout, std::cerr, isatty(STDERR_FILENO) != 0);
    if(command == "check")
      return check_command(rest, std::cout, std::cerr);
    if(command == "convert")
      return convert_command(rest, std::cout, std::cerr);
    std::cerr << "spring-motion: unknown command '" << command
              << "': expected deform, check or convert (see 'spring-motion --help')\n";
    return exit_usage_error;
  } catch(...) {
    const Failure f = describe_failure(command);
    if(!f.line.empty()) // one write: the ranks of an MPI run print to one stream at once
      std::cerr << f.line + "\n";
    return f.status;
  }
}
