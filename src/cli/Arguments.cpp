// Copyright (c) 2026 SpringMotion developers.
#include "Arguments.h"

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
  bool options_ended = false;
  for(std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string& a = arguments[i];
    if(options_ended || a.size() < 2 || a.compare(0, 2, "--") != 0) {
      if(!options_ended && a.size() >= 2 && a[0] == '-' && !std::isdigit(static_cast<unsigned char>(a[1])) &&
         a[1] != '.')
        throw Usage_error("unknown option '" + a + "': options are written --name");
      operands_.push_back(a);
      continue;
    }
    if(a == "--") {
      options_ended = true;
      continue;
    }
    std::string name = a.substr(2);
    std::optional<std::string> inline_value;
    if(const auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name.erase(eq);
    }
    const Option_spec* spec = nullptr;
    for(const Option_spec& s : specs)
      if(s.name == name)
        spec = &s;
    if(spec == nullptr)
      throw Usage_error("unknown option '--" + name + "'");
    if(!spec->repeatable && values_.count(name) != 0)
      throw Usage_error("option --" + name + " is given twice: expected it once");
    std::string value;
    if(spec->takes_value) {
      if(inline_value)
        value = *inline_value;
      else if(i + 1 < arguments.size())
        value = arguments[++i];
      else
        throw Usage_error("option --" + name + " needs a value");
    } else if(inline_value)
      throw Usage_error("option --" + name + " takes no value");
    values_[name].push_back(value);
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
