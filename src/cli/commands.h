// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: the subcommands, each given its
// arguments (after the command name) and the two output streams.
#ifndef SPRING_MOTION_SRC_CLI_COMMANDS_H
#define SPRING_MOTION_SRC_CLI_COMMANDS_H

#include <spring_motion/Error.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace spring_motion {
namespace cli {

/// Exit statuses of spring-motion (documented in docs/cli.md and --help).
enum Exit_status : int
{
  exit_success = 0,        ///< done; `check`: the mesh is valid
  exit_input_error = 1,    ///< bad input file, label, or output path: nothing written
  exit_usage_error = 2,    ///< bad command line: nothing read or written
  exit_invalid = 3,        ///< `deform`: a step inverted an element, outputs hold the last valid state;
                           ///< `check`: the mesh has degenerate or inverted elements
  exit_internal_error = 4, ///< a bug or out of memory: please report it
  exit_interrupted = 130   ///< SIGINT / SIGTERM: the run stopped, its outputs removed
};

/// Set by the SIGINT / SIGTERM handler of main(); `deform` checks it after
/// every step and stops, removing what it wrote.
bool interrupted();
void install_interrupt_handlers();

/// Thrown when interrupted() is seen (a spring_motion::Error like every
/// exception of the command, with exit status 130).
class Interrupted : public Error
{
public:
  Interrupted() : Error("interrupted: the run stopped and its outputs were removed") {}
};

/// What main() prints for the exception in flight (call inside a catch
/// block) and the exit status it returns: one function, so that another MPI
/// rank can print the very same line.
struct Failure
{
  int status = 0;
  std::string line;
};
Failure describe_failure(const std::string& command);

/// An error that another MPI rank met and described (describe_failure): the
/// rank 0 of a partitioned run before it scattered the mesh. Printed as it
/// is, with its exit status.
class Relayed_error : public Error
{
public:
  Relayed_error(const Failure& f) : Error(f.line), status_(f.status) {}
  int status() const noexcept { return status_; }

private:
  int status_;
};

/// An error every rank of an MPI run has already printed (before they
/// finished together, so that mpiexec killed none before it had printed):
/// main() prints nothing more and exits with its status.
class Reported_error : public Error
{
public:
  explicit Reported_error(int status) : Error(""), status_(status) {}
  int status() const noexcept { return status_; }

private:
  int status_;
};

int deform_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err,
                   bool err_is_terminal);
int check_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);
int convert_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

/// The --help texts.
std::string main_help();
std::string deform_help();
std::string check_help();
std::string convert_help();

/// The message of a library `Error` without its " [source.h:123]" suffix,
/// which means nothing to a user of the command.
std::string without_source_location(const std::string& message);

} // namespace cli
} // namespace spring_motion

#endif
