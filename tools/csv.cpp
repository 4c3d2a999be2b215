#include "csv.hpp"

#include "common.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace ellipsect::cli {

LineReader::LineReader(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) throw IoError(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (fstat(fileno(file_), &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      std::fclose(file_);
      file_ = nullptr;
      throw IoError(path + ": is a directory");
    }
    if (S_ISREG(st.st_mode)) size_ = static_cast<std::uint64_t>(st.st_size);
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
}

LineReader::~LineReader() {
  if (file_ != nullptr) std::fclose(file_);
  std::free(buffer_);
}

bool LineReader::next(std::string& line, std::uint64_t& line_number) {
  for (;;) {
    errno = 0;
    const ssize_t n = getline(&buffer_, &capacity_, file_);
    if (n < 0) {
      if (std::ferror(file_)) throw IoError(path_ + ": read error: " + std::strerror(errno));
      return false;
    }
    ++line_;
    bytes_ += static_cast<std::uint64_t>(n);
    std::size_t len = static_cast<std::size_t>(n);
    while (len > 0 && (buffer_[len - 1] == '\n' || buffer_[len - 1] == '\r')) --len;
    std::size_t first = 0;
    while (first < len && (buffer_[first] == ' ' || buffer_[first] == '\t')) ++first;
    if (first == len || buffer_[first] == '#') continue;
    if (line_ == 1 && len >= 3 && static_cast<unsigned char>(buffer_[0]) == 0xEF &&
        static_cast<unsigned char>(buffer_[1]) == 0xBB && static_cast<unsigned char>(buffer_[2]) == 0xBF) {
      line.assign(buffer_ + 3, len - 3);  // UTF-8 byte order mark
    } else {
      line.assign(buffer_, len);
    }
    line_number = line_;
    return true;
  }
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string split_csv(std::string_view line, std::vector<std::string_view>& fields, std::string& scratch) {
  fields.clear();
  scratch.clear();
  scratch.reserve(line.size());
  std::size_t i = 0;
  for (;;) {
    // Skip blanks before a quoted field.
    std::size_t j = i;
    while (j < line.size() && (line[j] == ' ' || line[j] == '\t')) ++j;
    if (j < line.size() && line[j] == '"') {
      const std::size_t start = scratch.size();
      std::size_t k = j + 1;
      bool closed = false;
      while (k < line.size()) {
        if (line[k] == '"') {
          if (k + 1 < line.size() && line[k + 1] == '"') {
            scratch += '"';
            k += 2;
            continue;
          }
          closed = true;
          ++k;
          break;
        }
        scratch += line[k++];
      }
      if (!closed) return "unterminated quoted field (field " + std::to_string(fields.size() + 1) + ")";
      while (k < line.size() && (line[k] == ' ' || line[k] == '\t')) ++k;
      fields.emplace_back(scratch.data() + start, scratch.size() - start);
      if (k == line.size()) return {};
      if (line[k] != ',')
        return "unexpected character after a quoted field (field " + std::to_string(fields.size()) + ")";
      i = k + 1;
      continue;
    }
    const std::size_t comma = line.find(',', i);
    const std::string_view field = line.substr(i, comma == std::string_view::npos ? std::string_view::npos : comma - i);
    if (field.find('"') != std::string_view::npos)
      return "a quote inside an unquoted field (field " + std::to_string(fields.size() + 1) + ")";
    fields.push_back(field);
    if (comma == std::string_view::npos) return {};
    i = comma + 1;
  }
}

}  // namespace ellipsect::cli
