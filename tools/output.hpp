// Output files written atomically, and the progress bar.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace ellipsect::cli {

// Writes to stdout (path "" or "-"), or to a temporary file next to `path` that is renamed
// onto `path` by commit(). Destroyed without commit (an error, an exception, SIGINT or
// SIGTERM), the temporary file is removed: no partial output file is ever left behind.
// A path that exists and is not a regular file (/dev/null, a pipe) is written directly.
class Output {
public:
  explicit Output(const std::string& path);
  ~Output();
  Output(const Output&) = delete;
  Output& operator=(const Output&) = delete;

  void write(std::string_view text);
  // Flushes, closes and renames into place. Throws IoError on failure.
  void commit();
  bool is_stdout() const noexcept { return to_stdout_; }
  // The file being written (the temporary one until commit).
  const std::string& writing_path() const noexcept { return temp_.empty() ? path_ : temp_; }
  const std::string& path() const noexcept { return path_; }
  // Closes the stream without renaming (to let another program write the temporary file).
  void close_stream();

private:
  void fail_write();
  std::string path_, temp_;
  std::FILE* file_ = nullptr;
  bool to_stdout_ = false;
  bool committed_ = false;
};

// A progress bar on stderr, shown only when enabled (stderr a terminal, or forced) and the
// work has lasted over a second; redrawn at most ten times a second.
class Progress {
public:
  enum class Mode { automatic, always, never };
  Progress(Mode mode, std::string unit);
  ~Progress();
  // fraction in [0, 1], or negative when the total is unknown.
  void update(double fraction, std::uint64_t done);
  void finish();

private:
  bool enabled_ = false;
  bool shown_ = false;
  std::string unit_;
  std::chrono::steady_clock::time_point start_, last_;
};

Progress::Mode parse_progress_mode(const std::string& s);

}  // namespace ellipsect::cli
