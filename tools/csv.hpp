// Line-oriented CSV reading (RFC 4180 fields; a quoted field may not span lines).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace ellipsect::cli {

class LineReader {
public:
  // Opens `path` for reading; throws IoError naming it when it cannot.
  explicit LineReader(const std::string& path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line that is not blank and not a comment (first non-blank character '#'),
  // without its line break; false at the end of the file. Throws IoError on a read error.
  bool next(std::string& line, std::uint64_t& line_number);

  const std::string& path() const noexcept { return path_; }
  std::uint64_t bytes_read() const noexcept { return bytes_; }
  // Size of the file in bytes, 0 when unknown (a pipe).
  std::uint64_t size() const noexcept { return size_; }

private:
  std::string path_;
  std::FILE* file_ = nullptr;
  char* buffer_ = nullptr;
  std::size_t capacity_ = 0;
  std::uint64_t line_ = 0;
  std::uint64_t bytes_ = 0;
  std::uint64_t size_ = 0;
};

// Splits one CSV record into fields. Unquoted fields are views into `line`; quoted fields
// are unescaped into `scratch` (reserved up front, so views stay valid). Returns an empty
// string on success, else a description of what is malformed.
std::string split_csv(std::string_view line, std::vector<std::string_view>& fields, std::string& scratch);

// Removes surrounding blanks.
std::string_view trim(std::string_view s);

}  // namespace ellipsect::cli
