// Copyright (c) 2026 SpringMotion developers.
#include "Byte_reader.h"

#include <algorithm>

namespace spring_motion {
namespace io_internal {

namespace {

bool is_blank(int c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

constexpr std::size_t max_word_length = 256;
constexpr std::size_t max_name_length = 4096;
// Without a known file size, blocks are read in chunks of this many bytes, so
// that memory grows only with data actually present.
constexpr std::size_t chunk_bytes = std::size_t(1) << 24;

} // namespace

Byte_reader::Byte_reader(std::istream& in, std::string file_name, std::size_t offset)
  : Error_reporter(std::move(file_name), true), in_(in), offset_(offset)
{
  const std::istream::pos_type start = in_.tellg();
  if(start != std::istream::pos_type(-1) && in_.seekg(0, std::ios::end)) {
    const std::istream::pos_type end = in_.tellg();
    if(end != std::istream::pos_type(-1) && end >= start) {
      end_ = offset_ + static_cast<std::size_t>(end - start);
      size_known_ = true;
    }
  }
  in_.clear();
  if(start != std::istream::pos_type(-1))
    in_.seekg(start);
  in_.clear();
}

int Byte_reader::get()
{
  const int c = in_.get();
  if(c == std::char_traits<char>::eof()) {
    if(in_.bad())
      fail("read error");
    return c;
  }
  ++offset_;
  return c;
}

int Byte_reader::peek()
{
  return in_.peek();
}

bool Byte_reader::next_word(std::string& word, std::size_t& word_offset)
{
  word.clear();
  int c = peek();
  while(c != std::char_traits<char>::eof() && is_blank(c)) {
    get();
    c = peek();
  }
  if(c == std::char_traits<char>::eof()) {
    word_offset = offset_;
    return false;
  }
  word_offset = offset_;
  while(c != std::char_traits<char>::eof() && !is_blank(c)) {
    if(word.size() == max_word_length)
      fail_at(word_offset, "expected a keyword or a number, found " + Token_reader::quote(word)
                               + " and more without a blank (binary data where text should be?)");
    word.push_back(static_cast<char>(get()));
    c = peek();
  }
  return true;
}

std::string Byte_reader::expect_word(const char* what, std::size_t& word_offset)
{
  std::string word;
  if(!next_word(word, word_offset))
    fail(std::string("unexpected end of file: expected ") + what);
  return word;
}

std::int64_t Byte_reader::expect_text_integer(const char* what)
{
  std::size_t at = 0;
  const std::string word = expect_word(what, at);
  std::int64_t value = 0;
  if(!parse_integer(word, value))
    fail_at(at, std::string("expected ") + what + ", found " + Token_reader::quote(word));
  return value;
}

std::size_t Byte_reader::expect_text_count(const char* what, std::size_t max)
{
  std::size_t at = 0;
  const std::string word = expect_word(what, at);
  std::int64_t value = 0;
  if(!parse_integer(word, value))
    fail_at(at, std::string("expected ") + what + ", found " + Token_reader::quote(word));
  if(value < 0)
    fail_at(at, std::string("expected ") + what + ", found " + Token_reader::quote(word)
                  + ": a count cannot be negative");
  if(static_cast<std::uint64_t>(value) > max)
    fail_at(at, std::string("expected ") + what + ", found " + Token_reader::quote(word)
                  + ": more than the supported " + std::to_string(max));
  return static_cast<std::size_t>(value);
}

void Byte_reader::end_line(const char* before)
{
  for(;;) {
    const int c = peek();
    if(c == '\n') {
      get();
      return;
    }
    if(c == ' ' || c == '\t' || c == '\r') {
      get();
      continue;
    }
    fail(std::string("expected the end of the line before ") + before
         + (c == std::char_traits<char>::eof() ? ", found the end of the file" : ""));
  }
}

std::string Byte_reader::expect_quoted(const char* what)
{
  int c = peek();
  while(c == ' ' || c == '\t')
    c = (get(), peek());
  const std::size_t start = offset_;
  if(c != '"')
    fail(std::string("expected ") + what + " in double quotes");
  get();
  std::string name;
  for(;;) {
    c = get();
    if(c == std::char_traits<char>::eof())
      fail_at(start, std::string("unexpected end of file in ") + what + ": expected a closing quote");
    if(c == '"')
      return name;
    if(c == '\n')
      fail_at(start, std::string("expected ") + what + " in double quotes on one line");
    if(name.size() == max_name_length)
      fail_at(start, std::string(what) + " longer than " + std::to_string(max_name_length) + " bytes");
    name.push_back(static_cast<char>(c));
  }
}

bool Byte_reader::skip_past(const std::string& marker)
{
  // The marker ("$EndNodeData") has its first character nowhere else, so a
  // mismatch can restart the comparison at the current character.
  std::size_t matched = 0;
  for(;;) {
    const int c = get();
    if(c == std::char_traits<char>::eof())
      return false;
    if(static_cast<char>(c) == marker[matched]) {
      if(++matched == marker.size())
        return true;
    } else
      matched = static_cast<char>(c) == marker[0] ? 1 : 0;
  }
}

void Byte_reader::read_exactly(void* target, std::size_t bytes, const char* what)
{
  in_.read(static_cast<char*>(target), static_cast<std::streamsize>(bytes));
  const std::size_t got = static_cast<std::size_t>(in_.gcount());
  if(in_.bad())
    fail("read error");
  if(got != bytes) {
    offset_ += got;
    fail(std::string("unexpected end of file: expected ") + what);
  }
  offset_ += bytes;
}

void Byte_reader::read_block(std::vector<unsigned char>& buffer, std::size_t count, std::size_t entry_bytes,
                             const char* what)
{
  buffer.clear();
  if(count == 0 || entry_bytes == 0)
    return;
  const std::size_t remaining = size_known_ && end_ > offset_ ? end_ - offset_ : 0;
  if(size_known_ && count > remaining / entry_bytes)
    fail(std::to_string(count) + " " + what + " of " + std::to_string(entry_bytes) + " bytes each, but only "
         + std::to_string(remaining) + " bytes remain in the file");
  if(count > static_cast<std::size_t>(-1) / entry_bytes)
    fail(std::to_string(count) + " " + what + ": more than the memory can address");
  const std::size_t total = count * entry_bytes;
  std::size_t done = 0;
  while(done < total) {
    const std::size_t step = std::min(total - done, size_known_ ? total : chunk_bytes);
    buffer.resize(done + step);
    read_exactly(buffer.data() + done, step, what);
    done += step;
  }
}

std::int32_t Byte_reader::read_int32(const char* what)
{
  unsigned char bytes[4];
  read_exactly(bytes, sizeof bytes, what);
  return int32_at(bytes);
}

std::uint64_t Byte_reader::read_uint64(const char* what)
{
  unsigned char bytes[8];
  read_exactly(bytes, sizeof bytes, what);
  return uint64_at(bytes);
}

double Byte_reader::read_double(const char* what)
{
  unsigned char bytes[8];
  read_exactly(bytes, sizeof bytes, what);
  return double_at(bytes);
}

} // namespace io_internal
} // namespace spring_motion
