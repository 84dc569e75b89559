// Copyright (c) 2026 SpringMotion developers.
// Private to src/io: the cursor of the binary Gmsh reader. Not installed.
#ifndef SPRING_MOTION_SRC_IO_BYTE_READER_H
#define SPRING_MOTION_SRC_IO_BYTE_READER_H

#include "Token_reader.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <istream>
#include <string>
#include <utility>
#include <vector>

namespace spring_motion {
namespace io_internal {

/// Reads a file that mixes short text (keywords, counts, names) with binary
/// blocks, keeping the byte offset of everything it reads: errors read
/// "FILE: byte N: message" (an Input_error without a line). Multi-byte values
/// are swapped when the file's byte order is not the machine's.
class Byte_reader : public Error_reporter
{
public:
  /// `offset`: the position of the stream's current byte in the file.
  Byte_reader(std::istream& in, std::string file_name, std::size_t offset);

  std::size_t offset() const { return offset_; }

  /// Whether multi-byte values must be reversed (set from the file's marker).
  void set_swap(bool swap) { swap_ = swap; }


  /// The next word of text (blanks skipped first), and the offset of its
  /// first byte; false at the end of the file. Words longer than 256 bytes
  /// are an error: binary garbage where a keyword or a count should be.
  bool next_word(std::string& word, std::size_t& word_offset);
  std::string expect_word(const char* what, std::size_t& word_offset);
  /// A text count in [0, max], as the MSH 2.2 sections start with.
  std::size_t expect_text_count(const char* what, std::size_t max);
  std::int64_t expect_text_integer(const char* what);
  /// Consumes blanks up to and including the end of the line: binary data
  /// starts right after it.
  void end_line(const char* before);
  /// A double-quoted name (at most 4096 bytes), without its quotes.
  std::string expect_quoted(const char* what);
  /// Skips everything up to and including `marker`; false if the file ends first.
  bool skip_past(const std::string& marker);

  /// `count` entries of `entry_bytes` bytes each into `buffer`, after
  /// checking that the rest of the file can hold them: a hostile count never
  /// makes the reader allocate more than the file's size.
  void read_block(std::vector<unsigned char>& buffer, std::size_t count, std::size_t entry_bytes,
                  const char* what);
  std::int32_t read_int32(const char* what);
  std::uint64_t read_uint64(const char* what);
  double read_double(const char* what);

  std::int32_t int32_at(const unsigned char* p) const
  {
    std::uint32_t u = load<std::uint32_t>(p);
    std::int32_t value;
    std::memcpy(&value, &u, sizeof value);
    return value;
  }
  std::uint64_t uint64_at(const unsigned char* p) const { return load<std::uint64_t>(p); }
  double double_at(const unsigned char* p) const
  {
    const std::uint64_t u = load<std::uint64_t>(p);
    double value;
    std::memcpy(&value, &u, sizeof value);
    return value;
  }

private:
  template <class Unsigned>
  Unsigned load(const unsigned char* p) const
  {
    unsigned char bytes[sizeof(Unsigned)];
    std::memcpy(bytes, p, sizeof bytes);
    if(swap_)
      for(std::size_t i = 0; i < sizeof bytes / 2; ++i)
        std::swap(bytes[i], bytes[sizeof bytes - 1 - i]);
    Unsigned value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
  }
  int get();
  int peek();
  void read_exactly(void* target, std::size_t bytes, const char* what);

  std::size_t current_position() const override { return offset_; }

  std::istream& in_;
  std::size_t offset_;
  std::size_t end_ = 0; // the file's size when known
  bool size_known_ = false;
  bool swap_ = false;
};

} // namespace io_internal
} // namespace spring_motion

#endif
