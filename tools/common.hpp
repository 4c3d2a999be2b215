// Shared pieces of the `ellipsect` command-line program: errors and exit codes, number
// and string formatting, the thread count (parallel work runs on the library's pool,
// ellipsect/parallel.hpp).
#pragma once

#include <ellipsect/parallel.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ellipsect::cli {

// Exit codes (documented in docs/cli.md).
enum ExitCode : int {
  exit_ok = 0,
  exit_usage = 1,      // bad command line
  exit_bad_input = 2,  // the scene (or pairs file) is malformed or invalid
  exit_io = 3,         // a file cannot be read or written, rsvg-convert missing or failed
  exit_internal = 4,   // an unexpected internal error
};

// A problem with the input's content. The message names the file, the line (CSV) or the
// JSON path, and the field.
struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file that cannot be opened, read or written.
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A bad option value found after parsing (e.g. --plane for a 2D scene).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Shortest decimal that reads back as the same double ("nan"/"inf" are never written:
// callers write null or an empty field for non-finite values).
inline void append_number(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

inline std::string number_string(double x) {
  std::string s;
  append_number(s, x);
  return s;
}

// Length (1 to 4) of the well-formed UTF-8 sequence starting at s[i] (RFC 3629: no overlong
// forms, no surrogates, nothing above U+10FFFF), or 0 when the bytes there are not one.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i);

// Offset of the first byte of `s` that does not begin a well-formed UTF-8 sequence, or npos
// when all of `s` is UTF-8.
std::size_t invalid_utf8_at(std::string_view s);

// The UTF-8 replacement character U+FFFD, written for every byte that does not begin a
// well-formed sequence when text of unknown encoding (a file name) is written as JSON or SVG.
inline constexpr std::string_view utf8_replacement = "\xEF\xBF\xBD";

// Appends the well-formed UTF-8 sequence starting at s[i], or U+FFFD when the byte there does
// not begin one; returns the bytes of `s` consumed (>= 1).
std::size_t append_utf8_sequence(std::string& out, std::string_view s, std::size_t i);

// A JSON string literal (quotes included); always valid JSON: bytes that are not UTF-8 are
// written as U+FFFD (ids never contain them: the scene readers reject them).
void append_json_string(std::string& out, std::string_view s);

// A CSV field, quoted when it holds a comma, a quote, a line break or leading/trailing
// blanks.
void append_csv_field(std::string& out, std::string_view s);

// Parses a whole field as a double (leading '+' and surrounding blanks accepted; "nan" and
// "inf" are parsed, callers reject them). False when the field is not a number.
bool parse_double(std::string_view s, double& out);

// The whole file; IoError naming it when it cannot be opened or read.
std::string read_file(const std::string& path);

// Number of threads for --threads N (0: all hardware threads).
int resolve_threads(int requested);

}  // namespace ellipsect::cli
