// Copyright (c) 2026 SpringMotion developers.
// Private to src/io: the tokenizer and the number parsing shared by the
// Medit and Gmsh readers. Not installed.
#ifndef SPRING_MOTION_SRC_IO_TOKEN_READER_H
#define SPRING_MOTION_SRC_IO_TOKEN_READER_H

#include <spring_motion/Input_error.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <istream>
#include <string>
#include <string_view>
#include <utility>

namespace spring_motion {
namespace io_internal {

/// Where a reader reports an error: at a line of a text file, at a byte
/// offset of a binary one ("file.msh: byte 1234: ..."). What the code shared
/// by the readers (finish_mesh) needs to point into the file.
class Error_reporter
{
public:
  /// At the current position.
  [[noreturn]] void fail(const std::string& message) const { fail_at(current_position(), message); }
  /// At `position`: a 1-based line (0: none), or a byte offset for a binary reader.
  [[noreturn]] void fail_at(std::size_t position, const std::string& message) const
  {
    if(byte_offsets_)
      throw Input_error(file_name_, 0, "byte " + std::to_string(position) + ": " + message);
    throw Input_error(file_name_, position, message);
  }
  const std::string& file_name() const { return file_name_; }

protected:
  Error_reporter(std::string file_name, bool byte_offsets)
    : file_name_(std::move(file_name)), byte_offsets_(byte_offsets)
  {}
  Error_reporter(const Error_reporter&) = default;
  Error_reporter& operator=(const Error_reporter&) = default;
  ~Error_reporter() = default;
  virtual std::size_t current_position() const = 0;

private:
  std::string file_name_;
  bool byte_offsets_;
};

/// Where a reader is inside a counted section, so that a truncated file or a
/// wrong count is reported as "section X: expected N entries, read M".
struct Section_progress
{
  std::string section;     // as written in the file: "Vertices", "$Nodes"
  std::string entries;     // plural noun: "vertices", "nodes"
  std::size_t expected = 0;
  std::size_t read = 0;
};

/// Splits a text stream into whitespace-separated tokens while keeping the
/// line number of each one, which every error message needs. Lines are read
/// one at a time, so memory stays bounded by the longest line.
class Token_reader : public Error_reporter
{
public:
  Token_reader(std::istream& in, std::string file_name);

  /// Characters from `c` to the end of the line are ignored (Medit's '#').
  void set_comment_character(char c);
  /// Called with the text after the comment character (and the line) for
  /// every comment skipped; a comment may be seen twice after put_back().
  void set_comment_handler(std::function<void(std::string_view, std::size_t)> handler)
  {
    comment_handler_ = std::move(handler);
  }

  /// The next token, or false at the end of the input. The view stays valid
  /// until the next call that moves the reader.
  bool next(std::string_view& token);
  /// Makes the token just returned by `next()` the next one again.
  void put_back();
  /// Drops what is left of the current line (for entries whose length the
  /// reader cannot know, such as elements of an unknown Gmsh type).
  void skip_rest_of_line();
  /// What is left of the current line, consumed (Gmsh's quoted names).
  std::string_view rest_of_line();

  /// The line of the token last returned; at the end of input, the last line.
  std::size_t line() const { return line_number_; }


  /// Bytes taken from the stream so far (whole lines, with their newline):
  /// where a binary part of the file starts after a text header.
  std::size_t bytes_consumed() const { return bytes_consumed_; }

  /// Counted section being read, for the messages of `expect_*()`; null when
  /// none. The object must outlive its use (see `Progress_scope`).
  void set_progress(Section_progress* progress) { progress_ = progress; }

  /// The next token, or an "unexpected end of file" error naming `what`.
  std::string_view expect_token(const char* what);
  double expect_double(const char* what);
  std::int64_t expect_integer(const char* what);
  /// A count of entries: an integer in [0, max].
  std::size_t expect_count(const char* what, std::size_t max);

  /// How many entries of at least `min_bytes_per_entry` bytes the rest of the
  /// input can hold, at most `count`: what a reader may reserve() without
  /// letting an absurd count in a hostile file allocate gigabytes.
  std::size_t reserve_limit(std::size_t count, std::size_t min_bytes_per_entry) const;

  /// A token made safe to quote in a one-line message.
  static std::string quote(std::string_view token);

private:
  bool read_line();
  [[noreturn]] void fail_unexpected(std::string_view token, const char* what,
                                    const std::string& problem = std::string()) const;
  std::string progress_suffix() const;

  std::size_t current_position() const override { return line_number_; }

  std::istream& in_;
  std::string current_line_;
  std::size_t position_ = 0;
  std::size_t token_start_ = 0;
  std::size_t line_number_ = 0;
  std::size_t bytes_consumed_ = 0;
  std::size_t bytes_available_ = 0; // 0 when the stream cannot tell its size
  bool size_known_ = false;
  // What each byte is to the tokenizer: a table read once a character
  // instead of a comparison with each blank and the comment character
  // (splitting the lines took half the instructions of reading a large mesh).
  enum Char_kind : unsigned char { part_of_token, blank, comment };
  Char_kind kind(char c) const { return kind_[static_cast<unsigned char>(c)]; }
  std::array<Char_kind, 256> kind_{};
  char comment_ = '\0';
  std::function<void(std::string_view, std::size_t)> comment_handler_;
  Section_progress* progress_ = nullptr;
};

/// Sets a reader's progress for the lifetime of the scope.
class Progress_scope
{
public:
  Progress_scope(Token_reader& reader, Section_progress& progress) : reader_(reader)
  {
    reader_.set_progress(&progress);
  }
  ~Progress_scope() { reader_.set_progress(nullptr); }
  Progress_scope(const Progress_scope&) = delete;
  Progress_scope& operator=(const Progress_scope&) = delete;

private:
  Token_reader& reader_;
};

/// Parses a whole token as a double; false if it is not one. Non-finite
/// values ("nan", "inf", overflow) parse, the caller rejects them.
bool parse_double(std::string_view token, double& value);
/// Parses a whole token as a base-10 integer; false if not one or too large.
bool parse_integer(std::string_view token, std::int64_t& value);

/// Reads a comment "label N: NAME" (leading blanks allowed, trailing blanks
/// and CR dropped), as the Medit and SU2 writers keep label names: true with
/// N and NAME when the comment is one, false otherwise.
bool parse_label_comment(std::string_view comment, int& label, std::string& name);

/// ASCII case-insensitive equality, for Medit keywords and file extensions.
bool equal_ignoring_case(std::string_view a, std::string_view b);

} // namespace io_internal
} // namespace spring_motion

#endif
