#include "output.hpp"

#include "common.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>

namespace ellipsect::cli {

namespace {

// The temporary file to remove if the program is interrupted (one output at a time).
char pending_temp[4096] = {};
volatile std::sig_atomic_t pending_set = 0;

extern "C" void remove_pending_and_exit(int sig) {
  if (pending_set != 0) ::unlink(pending_temp);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_handlers() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  std::signal(SIGINT, remove_pending_and_exit);
  std::signal(SIGTERM, remove_pending_and_exit);
  std::signal(SIGHUP, remove_pending_and_exit);
}

}  // namespace

Output::Output(const std::string& path) : path_(path) {
  if (path.empty() || path == "-") {
    to_stdout_ = true;
    file_ = stdout;
    return;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw IoError(path + ": is a directory");
    file_ = std::fopen(path.c_str(), "wb");
    if (file_ == nullptr) throw IoError(path + ": cannot open for writing: " + std::strerror(errno));
    return;
  }
  std::string tmpl = path + ".tmp-XXXXXX";
  if (tmpl.size() >= sizeof pending_temp) throw IoError(path + ": path too long");
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw IoError(path + ": cannot create the output file: " + std::strerror(errno));
  ::fchmod(fd, 0644 & ~[] {
    const mode_t m = ::umask(0);
    ::umask(m);
    return m;
  }());
  temp_ = tmpl;
  install_handlers();
  pending_set = 0;
  std::memcpy(pending_temp, temp_.c_str(), temp_.size() + 1);
  pending_set = 1;
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    ::close(fd);
    ::unlink(temp_.c_str());
    pending_set = 0;
    throw IoError(path + ": cannot open for writing: " + std::strerror(errno));
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
}

Output::~Output() {
  if (committed_) return;
  if (file_ != nullptr && !to_stdout_) std::fclose(file_);
  if (to_stdout_ && file_ != nullptr) std::fflush(file_);
  if (!temp_.empty()) {
    ::unlink(temp_.c_str());
    pending_set = 0;
  }
}

void Output::fail_write() {
  const std::string why = std::strerror(errno);
  throw IoError((to_stdout_ ? std::string("stdout") : path_) + ": write error: " + why);
}

void Output::write(std::string_view text) {
  if (file_ == nullptr) throw IoError(path_ + ": write after close");
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail_write();
}

void Output::close_stream() {
  if (file_ == nullptr || to_stdout_) return;
  const bool bad = std::ferror(file_) != 0;
  const int rc = std::fclose(file_);
  file_ = nullptr;
  if (bad || rc != 0) fail_write();
}

void Output::commit() {
  if (to_stdout_) {
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) fail_write();
    committed_ = true;
    return;
  }
  close_stream();
  if (!temp_.empty()) {
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      ::unlink(temp_.c_str());
      pending_set = 0;
      throw IoError(path_ + ": cannot rename the finished output into place: " + why);
    }
    pending_set = 0;
  }
  committed_ = true;
}

Progress::Progress(Mode mode, std::string unit) : unit_(std::move(unit)) {
  enabled_ = mode == Mode::always || (mode == Mode::automatic && ::isatty(STDERR_FILENO) == 1);
  start_ = last_ = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

void Progress::update(double fraction, std::uint64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < 1.0) return;
  if (shown_ && std::chrono::duration<double>(now - last_).count() < 0.1) return;
  last_ = now;
  shown_ = true;
  char line[160];
  const double rate = static_cast<double>(done) / elapsed;
  if (fraction >= 0) {
    if (fraction > 1) fraction = 1;
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    char bar[width + 1];
    for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '.';
    bar[width] = 0;
    std::snprintf(line, sizeof line, "\rellipsect: [%s] %3d%%  %llu %s  %.3g %s/s ", bar,
                  static_cast<int>(fraction * 100), static_cast<unsigned long long>(done), unit_.c_str(), rate,
                  unit_.c_str());
  } else {
    std::snprintf(line, sizeof line, "\rellipsect: %llu %s  %.3g %s/s ", static_cast<unsigned long long>(done),
                  unit_.c_str(), rate, unit_.c_str());
  }
  std::fputs(line, stderr);
  std::fflush(stderr);
}

void Progress::finish() {
  if (shown_) {
    std::fputs("\n", stderr);
    std::fflush(stderr);
    shown_ = false;
  }
  enabled_ = false;
}

Progress::Mode parse_progress_mode(const std::string& s) {
  if (s == "always") return Progress::Mode::always;
  if (s == "never") return Progress::Mode::never;
  return Progress::Mode::automatic;
}

}  // namespace ellipsect::cli
