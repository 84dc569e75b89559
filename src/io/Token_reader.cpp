// Copyright (c) 2026 SpringMotion developers.
#include "Token_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <system_error>

namespace spring_motion {
namespace io_internal {

Token_reader::Token_reader(std::istream& in, std::string file_name)
  : Error_reporter(std::move(file_name), false), in_(in)
{
  // '\r' too: files written on Windows must read the same.
  for(const char c : {' ', '\t', '\r', '\n', '\v', '\f'})
    kind_[static_cast<unsigned char>(c)] = blank;
  // The size of what is left bounds every reserve(); streams that cannot seek
  // (pipes) simply get a fixed bound.
  const std::istream::pos_type start = in_.tellg();
  if(start != std::istream::pos_type(-1) && in_.seekg(0, std::ios::end)) {
    const std::istream::pos_type end = in_.tellg();
    if(end != std::istream::pos_type(-1) && end >= start) {
      bytes_available_ = static_cast<std::size_t>(end - start);
      size_known_ = true;
    }
  }
  in_.clear();
  if(start != std::istream::pos_type(-1))
    in_.seekg(start);
  in_.clear();
}

bool Token_reader::read_line()
{
  if(!std::getline(in_, current_line_)) {
    if(in_.bad())
      fail("read error");
    current_line_.clear();
    position_ = 0;
    return false;
  }
  ++line_number_;
  bytes_consumed_ += current_line_.size() + (in_.eof() ? 0 : 1);
  position_ = 0;
  // Editors on Windows may start a text file with a UTF-8 byte order mark.
  if(line_number_ == 1 && current_line_.compare(0, 3, "\xEF\xBB\xBF") == 0)
    position_ = 3;
  return true;
}

void Token_reader::set_comment_character(char c)
{
  if(comment_ != '\0' && kind(comment_) == comment)
    kind_[static_cast<unsigned char>(comment_)] = part_of_token;
  comment_ = c;
  // a blank stays a blank: comments start at a character tokens can hold
  if(c != '\0' && kind(c) != blank)
    kind_[static_cast<unsigned char>(c)] = comment;
}

bool Token_reader::next(std::string_view& token)
{
  const char* line = current_line_.data();
  std::size_t size = current_line_.size(), p = position_;
  for(;;) {
    while(p < size && kind(line[p]) == blank)
      ++p;
    if(p < size && kind(line[p]) == comment) {
      if(comment_handler_)
        comment_handler_(std::string_view(current_line_).substr(p + 1), line_number_);
      p = size;
    }
    if(p < size)
      break;
    if(!read_line())
      return false;
    line = current_line_.data();
    size = current_line_.size();
    p = position_;
  }
  token_start_ = p;
  while(p < size && kind(line[p]) == part_of_token)
    ++p;
  position_ = p;
  token = std::string_view(line + token_start_, p - token_start_);
  return true;
}

void Token_reader::put_back()
{
  position_ = token_start_;
}

void Token_reader::skip_rest_of_line()
{
  position_ = current_line_.size();
}

std::string_view Token_reader::rest_of_line()
{
  std::string_view rest = std::string_view(current_line_).substr(position_);
  position_ = current_line_.size();
  return rest;
}

std::string Token_reader::progress_suffix() const
{
  if(progress_ == nullptr)
    return {};
  return " (section " + progress_->section + ": expected " + std::to_string(progress_->expected)
         + " " + progress_->entries + ", read " + std::to_string(progress_->read) + ")";
}

std::string Token_reader::quote(std::string_view token)
{
  constexpr std::size_t max_length = 40;
  std::string text = "'";
  for(std::size_t i = 0; i < token.size() && i < max_length; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    text += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if(token.size() > max_length)
    text += "...";
  text += "'";
  return text;
}

std::string_view Token_reader::expect_token(const char* what)
{
  std::string_view token;
  if(next(token))
    return token;
  if(progress_ != nullptr)
    fail("unexpected end of file in section " + progress_->section + ": expected "
         + std::to_string(progress_->expected) + " " + progress_->entries + ", read "
         + std::to_string(progress_->read));
  fail(std::string("unexpected end of file: expected ") + what);
}

void Token_reader::fail_unexpected(std::string_view token, const char* what,
                                   const std::string& problem) const
{
  // The progress suffix turns a section that ended early (the next keyword
  // where a number should be) into "expected 8 vertices, read 5".
  std::string message = std::string("expected ") + what + ", found " + quote(token);
  if(!problem.empty())
    message += ": " + problem;
  fail(message + progress_suffix());
}

double Token_reader::expect_double(const char* what)
{
  const std::string_view token = expect_token(what);
  double value = 0;
  if(!parse_double(token, value))
    fail_unexpected(token, what);
  if(!std::isfinite(value))
    fail_unexpected(token, what, "not a finite number");
  return value;
}

std::int64_t Token_reader::expect_integer(const char* what)
{
  const std::string_view token = expect_token(what);
  std::int64_t value = 0;
  if(!parse_integer(token, value))
    fail_unexpected(token, what);
  return value;
}

std::size_t Token_reader::expect_count(const char* what, std::size_t max)
{
  const std::string_view token = expect_token(what);
  std::int64_t value = 0;
  if(!parse_integer(token, value))
    fail_unexpected(token, what);
  if(value < 0)
    fail_unexpected(token, what, "a count cannot be negative");
  if(static_cast<std::uint64_t>(value) > max)
    fail_unexpected(token, what, "more than the supported " + std::to_string(max));
  return static_cast<std::size_t>(value);
}

std::size_t Token_reader::reserve_limit(std::size_t count, std::size_t min_bytes_per_entry) const
{
  const std::size_t limit = size_known_ ? bytes_available_ / std::max<std::size_t>(1, min_bytes_per_entry) + 1
                                        : std::size_t(1) << 16;
  return std::min(count, limit);
}

bool parse_double(std::string_view token, double& value)
{
  if(token.size() > 1 && token.front() == '+' && token[1] != '-' && token[1] != '+')
    token.remove_prefix(1);
  if(token.empty())
    return false;
  const char* first = token.data();
  const char* last = first + token.size();
  const std::from_chars_result result = std::from_chars(first, last, value, std::chars_format::general);
  if(result.ptr != last)
    return false;
  if(result.ec == std::errc())
    return true;
  if(result.ec == std::errc::result_out_of_range) {
    // from_chars leaves the value alone out of range; strtod gives the
    // rounded result: 0 or a subnormal on underflow (fine), inf on overflow
    // (rejected by the caller as not finite).
    const std::string copy(token);
    value = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return false;
}

bool parse_integer(std::string_view token, std::int64_t& value)
{
  if(token.size() > 1 && token.front() == '+' && token[1] != '-' && token[1] != '+')
    token.remove_prefix(1);
  if(token.empty())
    return false;
  const char* first = token.data();
  const char* last = first + token.size();
  const std::from_chars_result result = std::from_chars(first, last, value, 10);
  return result.ec == std::errc() && result.ptr == last;
}

bool parse_label_comment(std::string_view comment, int& label, std::string& name)
{
  std::size_t i = 0;
  while(i < comment.size() && (comment[i] == ' ' || comment[i] == '\t'))
    ++i;
  if(comment.compare(i, 6, "label ") != 0)
    return false;
  i += 6;
  const std::size_t colon = comment.find(": ", i);
  if(colon == std::string_view::npos)
    return false;
  std::int64_t value = 0;
  if(!parse_integer(comment.substr(i, colon - i), value) || value < std::numeric_limits<int>::min()
     || value > std::numeric_limits<int>::max())
    return false;
  std::string_view text = comment.substr(colon + 2);
  while(!text.empty() && (text.back() == '\r' || text.back() == ' ' || text.back() == '\t'))
    text.remove_suffix(1);
  if(text.empty())
    return false;
  label = static_cast<int>(value);
  name = std::string(text);
  return true;
}

bool equal_ignoring_case(std::string_view a, std::string_view b)
{
  if(a.size() != b.size())
    return false;
  for(std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if(x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if(y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if(x != y)
      return false;
  }
  return true;
}

} // namespace io_internal
} // namespace spring_motion
