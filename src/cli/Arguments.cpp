// Copyright (c) 2026 SpringMotion developers.
#include "Arguments.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <iterator>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace spring_motion {
namespace cli {

bool parse_number(const std::string& text, double& value)
{
  if(text.empty() || std::isspace(static_cast<unsigned char>(text.front())))
    return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE && std::isfinite(value);
}

std::vector<std::string> split_list(const std::string& text)
{
  std::vector<std::string> items;
  std::string::size_type start = 0;
  for(;;) {
    const auto comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if(comma == std::string::npos)
      return items;
    start = comma + 1;
  }
}

Arguments::Arguments(const std::vector<std::string>& arguments, const std::vector<Option_spec>& specs)
{
  // CLI11 reads the command line; the values stay text here, each checked
  // when the command reads it, so that every message names its option.
  CLI::App app;
  app.set_help_flag(); // --help is an option of ours, answered by the command
  app.allow_extras();  // unknown options are named below, in our words
  app.add_option("operands", operands_);
  std::map<std::string, int> flag_counts;
  for(const Option_spec& spec : specs) {
    if(spec.takes_value)
      app.add_option("--" + spec.name, values_[spec.name])
          ->expected(1)
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    else
      app.add_flag("--" + spec.name, flag_counts[spec.name])->disable_flag_override();
  }
  // "--name=" gives an empty value, which CLI11 would take from the next
  // argument: a value of one NUL stands for it (no shell passes a NUL).
  const std::string empty_marker(1, '\0');
  std::vector<std::string> args;
  for(const std::string& a : arguments)
    if(a.size() > 3 && a.compare(0, 2, "--") == 0 && a.back() == '=' && a.find('=') == a.size() - 1) {
      args.push_back(a.substr(0, a.size() - 1));
      args.push_back(empty_marker);
    } else
      args.push_back(a);
  std::reverse(args.begin(), args.end()); // CLI11 takes them last first
  try {
    app.parse(args);
  } catch(const CLI::ArgumentMismatch& e) {
    // CLI11's message starts with the option's name, with or without dashes
    const std::string what = e.what();
    std::string name = what.substr(0, what.find_first_of(": "));
    if(const auto first = name.find_first_not_of('-'); first != std::string::npos)
      name = "--" + name.substr(first);
    if(what.find("disallowed flag override") != std::string::npos)
      throw Usage_error("option " + name + " takes no value");
    throw Usage_error("option " + name + " needs a value");
  } catch(const CLI::ParseError& e) {
    throw Usage_error(e.what());
  }
  for(const std::string& extra : app.remaining()) {
    if(extra.size() >= 2 && extra[0] == '-' && (std::isdigit(static_cast<unsigned char>(extra[1])) || extra[1] == '.')) {
      operands_.push_back(extra); // a negative number is an operand
      continue;
    }
    const std::string name = extra.substr(0, extra.find('='));
    if(name.size() >= 2 && name.compare(0, 2, "--") == 0)
      throw Usage_error("unknown option '" + name + "'");
    throw Usage_error("unknown option '" + name + "': options are written --name");
  }
  for(const auto& [name, count] : flag_counts)
    values_[name].assign(std::size_t(std::max(count, 0)), std::string());
  for(auto it = values_.begin(); it != values_.end();) {
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const Option_spec& s) { return s.name == it->first; });
    if(it->second.size() > 1 && !spec->repeatable)
      throw Usage_error("option --" + it->first + " is given twice: expected it once");
    for(std::string& v : it->second)
      if(v == empty_marker)
        v.clear();
    it = it->second.empty() ? values_.erase(it) : std::next(it);
  }
}

std::optional<std::string> Arguments::value(const std::string& name) const
{
  const auto it = values_.find(name);
  if(it == values_.end())
    return std::nullopt;
  return it->second.back();
}

std::vector<std::string> Arguments::values(const std::string& name) const
{
  const auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

double Arguments::number(const std::string& name, double fallback) const
{
  const auto text = value(name);
  if(!text)
    return fallback;
  double v = 0;
  if(!parse_number(*text, v))
    throw Usage_error("--" + name + ": expected a finite number, found '" + *text + "'");
  return v;
}

long long Arguments::integer(const std::string& name, long long fallback, long long min, long long max) const
{
  const auto text = value(name);
  if(!text)
    return fallback;
  char* end = nullptr;
  errno = 0;
  const long long v = text->empty() ? 0 : std::strtoll(text->c_str(), &end, 10);
  if(text->empty() || end != text->c_str() + text->size() || errno == ERANGE || v < min || v > max)
    throw Usage_error("--" + name + ": expected an integer from " + std::to_string(min) + " to " +
                      std::to_string(max) + ", found '" + *text + "'");
  return v;
}

std::vector<double> Arguments::numbers(const std::string& name, std::size_t min_count, std::size_t max_count) const
{
  const auto text = value(name);
  if(!text)
    return {};
  const auto items = split_list(*text);
  const std::string expected = min_count == max_count ? std::to_string(min_count)
                                                      : std::to_string(min_count) + " or " + std::to_string(max_count);
  if(items.size() < min_count || items.size() > max_count)
    throw Usage_error("--" + name + ": expected " + expected + " comma-separated numbers, found '" + *text + "'");
  std::vector<double> out;
  for(const auto& item : items) {
    double v = 0;
    if(!parse_number(item, v))
      throw Usage_error("--" + name + ": expected " + expected + " comma-separated finite numbers, found '" + *text +
                        "'");
    out.push_back(v);
  }
  return out;
}

} // namespace cli
} // namespace spring_motion
