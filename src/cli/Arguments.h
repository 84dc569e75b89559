// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: the command line of one subcommand.
#ifndef SPRING_MOTION_SRC_CLI_ARGUMENTS_H
#define SPRING_MOTION_SRC_CLI_ARGUMENTS_H

#include <spring_motion/Error.h>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace spring_motion {
namespace cli {

/// A command line that does not make sense (unknown option, missing or
/// malformed value): exit status 2, with a pointer to the command's --help.
class Usage_error : public Error
{
public:
  explicit Usage_error(const std::string& message) : Error(message) {}
};

/// An option a command accepts: `--name VALUE` (or `--name=VALUE`) when it
/// takes a value, else a flag. A repeatable option may be given several times.
struct Option_spec
{
  std::string name; // without the leading "--"
  bool takes_value = true;
  bool repeatable = false;
};

/// The options and operands of one subcommand, read by CLI11. Values are
/// checked when they are read, so that each message names the option.
class Arguments
{
public:
  /// Throws Usage_error for an option not in `specs`, a missing value or a
  /// non-repeatable option given twice. "--" ends the options.
  Arguments(const std::vector<std::string>& arguments, const std::vector<Option_spec>& specs);

  const std::vector<std::string>& operands() const { return operands_; }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  /// The (last) value of an option, if given.
  std::optional<std::string> value(const std::string& name) const;
  /// Every value of a repeatable option, in order.
  std::vector<std::string> values(const std::string& name) const;

  /// The value as a finite number; `fallback` when the option is absent.
  double number(const std::string& name, double fallback) const;
  /// The value as an integer in [min, max]; `fallback` when absent.
  long long integer(const std::string& name, long long fallback, long long min, long long max) const;
  /// A comma-separated list of `min_count` to `max_count` finite numbers.
  std::vector<double> numbers(const std::string& name, std::size_t min_count, std::size_t max_count) const;

private:
  std::vector<std::string> operands_;
  std::map<std::string, std::vector<std::string>> values_;
};

/// Parses a whole string as a finite double (no trailing characters).
bool parse_number(const std::string& text, double& value);
/// Splits at commas; "a,,b" gives an empty item (callers reject it).
std::vector<std::string> split_list(const std::string& text);

} // namespace cli
} // namespace spring_motion

#endif
