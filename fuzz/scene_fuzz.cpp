// Fuzz target `scene`: the `ellipsect` program's scene readers and its check and render
// commands on arbitrary files. The first byte picks the file's kind (JSON, or CSV: its
// header says bodies or pairs), the output format, the queries and a time window; the rest
// is the file. Scenes are read with read_mesh_files off, so a mesh "file" key reads nothing
// (it is bad input here); with bit 128 of the first byte set, the rest is instead a mesh file
// given to the in-memory readers, parse_obj or (bit 1) parse_stl. What docs/cli.md promises
// for every input:
//   - the command succeeds, or fails with BadInput (exit status 2) whose message starts with
//     the file's name; any other exception (exit status 3 or 4), a crash, a hang or a stack
//     overflow is a failure;
//   - on success the output is valid UTF-8; JSON output parses as JSON with one record per
//     pair; CSV output has the header's number of fields on every line; an SVG picture is
//     valid UTF-8;
//   - a mesh file parses to arrays TriangleMesh::from_arrays accepts, or fails with BadInput
//     whose message starts with the file's name.
#include "fuzz_support.hpp"

#include "commands.hpp"
#include "common.hpp"
#include "csv.hpp"
#include "mesh_file.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

using namespace ellipsect;
using namespace ellipsect::cli;

namespace fs = std::filesystem;

// A directory of this process's files, removed at exit.
const fs::path& work_dir() {
  static const fs::path dir = [] {
    char name[] = "/tmp/ellipsect_fuzz_XXXXXX";
    FUZZ_CHECK(mkdtemp(name) != nullptr, << "cannot create a temporary directory");
    std::atexit([] { fs::remove_all(work_dir()); });
    return fs::path(name);
  }();
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs a command; true when it succeeded, false for bad input (the message checked).
template <class Command>
bool run_command(const char* name, const std::string& scene, Command&& command) {
  try {
    const int rc = command();
    FUZZ_CHECK(rc == exit_ok, << name << " returned " << rc);
    return true;
  } catch (const BadInput& e) {
    const std::string what = e.what();
    FUZZ_CHECK(what.rfind(scene, 0) == 0, << name << ": the message does not start with the file: " << what);
    return false;
  } catch (const std::exception& e) {
    FUZZ_CHECK(false, << name << ": unexpected exception (exit status 3 or 4): " << e.what());
  }
  return false;
}

void check_csv(const std::string& text) {
  std::istringstream lines(text);
  std::string line, scratch;
  std::vector<std::string_view> fields;
  std::size_t columns = 0;
  for (std::size_t k = 0; std::getline(lines, line); ++k) {
    const std::string err = split_csv(line, fields, scratch);
    FUZZ_CHECK(err.empty(), << "CSV output line " << k + 1 << ": " << err << ": " << line);
    if (k == 0) columns = fields.size();
    FUZZ_CHECK(fields.size() == columns, << "CSV output line " << k + 1 << " has " << fields.size()
                                         << " fields, the header " << columns);
  }
}

void check_mesh_file(const std::string& content, bool stl) {
  const std::string name = stl ? "mesh.stl" : "mesh.obj";
  MeshArrays m;
  try {
    m = stl ? parse_stl(content, name) : parse_obj(content, name);
  } catch (const BadInput& e) {
    const std::string what = e.what();
    FUZZ_CHECK(what.rfind(name, 0) == 0, << "the message does not start with the file: " << what);
    return;
  }
  try {
    (void)TriangleMesh<double, 3>::from_arrays(m.vertices, m.triangles);
  } catch (const InputError& e) {
    FUZZ_CHECK(false, << "parsed, but from_arrays rejects it: " << e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string content(reinterpret_cast<const char*>(data + 1), size - 1);
  if (mode & 128) {
    fuzz::trace() = "mode " + std::to_string(mode) + ", mesh file (" + std::to_string(content.size()) + " bytes)";
    check_mesh_file(content, (mode & 1) != 0);
    return 0;
  }
  fuzz::trace() = "mode " + std::to_string(mode) + ", file (" + std::to_string(content.size()) + " bytes) as given";
  const fs::path scene = work_dir() / ((mode & 1) ? "scene.csv" : "scene.json");
  std::ofstream(scene, std::ios::binary) << content;

  CheckOptions check;
  check.common.scene = scene.string();
  check.common.threads = 1;
  check.common.progress = Progress::Mode::never;
  check.common.read_mesh_files = false;
  check.format = (mode & 2) ? "csv" : "json";
  check.output = (work_dir() / "out").string();
  static const std::vector<std::vector<std::string>> queries = {
      {}, {"relation", "contact"}, {"distance"}, {"relation", "contact", "distance"}};
  check.queries = queries[(mode >> 2) % 4];
  if (mode & 16) check.common.window = Window{0.5, 4};
  if (mode & 32) check.report = "candidates";
  if (!run_command("check", scene.string(), [&] { return run_check(check); })) return 0;

  const std::string out = slurp(check.output);
  FUZZ_CHECK(invalid_utf8_at(out) == std::string::npos, << "output is not UTF-8 at byte " << invalid_utf8_at(out));
  if (check.format == "json") {
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(out);
    } catch (const nlohmann::json::exception& e) {
      FUZZ_CHECK(false, << "JSON output does not parse: " << e.what());
    }
    FUZZ_CHECK(j.contains("results") && j["results"].is_array() && j["summary"]["listed"] == j["results"].size(),
               << "JSON output: results and summary.listed disagree");
  } else {
    check_csv(out);
  }

  if (mode & 64) {
    RenderOptions render;
    render.common = check.common;
    render.output = (work_dir() / "picture.svg").string();
    if (run_command("render", scene.string(), [&] { return run_render(render); })) {
      const std::string svg = slurp(render.output);
      FUZZ_CHECK(invalid_utf8_at(svg) == std::string::npos, << "SVG is not UTF-8 at byte " << invalid_utf8_at(svg));
    }
  }
  return 0;
}
