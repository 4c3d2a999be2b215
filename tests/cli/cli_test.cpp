// End-to-end tests of the `ellipsect` program: each test runs the built binary, captures
// its exit code, stdout and stderr, and checks them.
//
// Expected answers come from outside the program: closed forms for circles and spheres
// (and, for distances, for ellipses facing each other along an axis), and the 50-digit
// reference (tests/reference/reference.hpp) for the bundled scenes, with the bodies built
// here from the scene files by the test's own code.
//
// The million-pair test streams a generated pairs CSV and measures the child's peak
// resident set size with wait4(); the pair count is scaled by ELLIPSECT_CASE_SCALE (the
// sanitizer pass uses 0.05).
#include "tests/reference/reference.hpp"

#include <ellipsect/geometry.hpp>
#include <ellipsect/version.hpp>

#include <Eigen/Geometry>

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;
namespace ref = ellipsect::reference;
using json = nlohmann::json;

const std::string cli = ELLIPSECT_CLI;
const std::string make_scene = ELLIPSECT_MAKE_SCENE;
const fs::path source_dir = ELLIPSECT_SOURCE_DIR;
const fs::path scenes = source_dir / "examples" / "scenes";

double case_scale() {
  const char* s = std::getenv("ELLIPSECT_CASE_SCALE");
  return s != nullptr ? std::atof(s) : 1.0;
}

struct Outcome {
  int code = -1;
  std::string out, err;
  long max_rss_kb = 0;  // peak resident set size of the child
  double seconds = 0;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

// A fresh directory for the running test.
fs::path work_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d = fs::path(ELLIPSECT_CLI_WORK) / (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Runs a program with stdout and stderr captured in files of `dir`.
Outcome run_program(const std::string& program, const std::vector<std::string>& args, const fs::path& dir) {
  const fs::path out_path = dir / "stdout.txt", err_path = dir / "stderr.txt";
  std::vector<std::string> storage;
  storage.push_back(program);
  for (const auto& a : args) storage.push_back(a);
  std::vector<char*> argv;
  for (auto& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int rc = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  Outcome r;
  if (rc != 0) {
    r.err = "cannot start " + program;
    return r;
  }
  int status = 0;
  struct rusage usage {};
  while (::wait4(pid, &status, 0, &usage) < 0) {
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.max_rss_kb = usage.ru_maxrss;
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  return r;
}

Outcome run_cli(const std::vector<std::string>& args, const fs::path& dir) { return run_program(cli, args, dir); }

std::string describe(const Outcome& r) {
  return "exit " + std::to_string(r.code) + "\n--- stderr:\n" + r.err + "\n--- stdout (first 2000 chars):\n" +
         r.out.substr(0, 2000);
}

json parse_json(const std::string& text) {
  try {
    return json::parse(text);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "output is not JSON: " << e.what() << "\n" << text.substr(0, 2000);
    return json();
  }
}

// No output file and no temporary file next to it.
void expect_no_output(const fs::path& dir, const std::string& name) {
  EXPECT_FALSE(fs::exists(dir / name)) << name << " was left behind";
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().rfind(name + ".tmp", 0), std::string::npos)
        << "temporary file left behind: " << e.path();
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> f;
  std::string cur;
  for (const char c : line) {
    if (c == ',') {
      f.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  f.push_back(cur);
  return f;
}

// ------------------------------------------------------------------------------------------
// Reference bodies built from a scene file (the test's own reading of the format).
// ------------------------------------------------------------------------------------------

template <int N>
struct RefBody {
  std::string id;
  ref::Body<N> body;
  Eigen::Matrix<double, N, 1> velocity;
};

template <int N>
std::vector<RefBody<N>> reference_bodies(const json& scene) {
  std::vector<RefBody<N>> out;
  for (const auto& b : scene["bodies"]) {
    RefBody<N> r;
    r.id = b["id"].get<std::string>();
    for (int i = 0; i < N; ++i) r.body.center[i] = b["center"][static_cast<std::size_t>(i)].get<double>();
    if (b.contains("radius")) {
      r.body.radii.setConstant(b["radius"].get<double>());
    } else {
      for (int i = 0; i < N; ++i) r.body.radii[i] = b["radii"][static_cast<std::size_t>(i)].get<double>();
    }
    r.body.axes.setIdentity();
    if constexpr (N == 2) {
      double angle = 0;
      if (b.contains("angle")) angle = b["angle"].get<double>();
      if (b.contains("direction")) angle = std::atan2(b["direction"][1].get<double>(), b["direction"][0].get<double>());
      r.body.axes << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    } else {
      if (b.contains("quaternion")) {
        const auto& q = b["quaternion"];
        r.body.axes = Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>())
                          .normalized()
                          .toRotationMatrix();
      }
    }
    r.velocity.setZero();
    if (b.contains("velocity"))
      for (int i = 0; i < N; ++i) r.velocity[i] = b["velocity"][static_cast<std::size_t>(i)].get<double>();
    out.push_back(r);
  }
  return out;
}

std::string ref_contact_name(ref::ContactKind k) {
  switch (k) {
    case ref::ContactKind::hit: return "hit";
    case ref::ContactKind::touching_at_start: return "touching_at_start";
    case ref::ContactKind::overlapping_at_start: return "overlapping_at_start";
    case ref::ContactKind::none: return "no_contact_in_window";
  }
  return "?";
}

// Checks every record of `check` output for a scene against the reference.
template <int N>
void expect_matches_reference(const fs::path& scene_path, const json& out, double time_rel_tol, double point_tol) {
  const json scene = json::parse(slurp(scene_path));
  const auto bodies = reference_bodies<N>(scene);
  auto find = [&](const std::string& id) -> const RefBody<N>& {
    for (const auto& b : bodies)
      if (b.id == id) return b;
    throw std::runtime_error("no body " + id);
  };
  double t_max = std::numeric_limits<double>::infinity();
  if (scene.contains("time_window") && !scene["time_window"][1].is_null()) t_max = scene["time_window"][1].get<double>();
  ASSERT_FALSE(out["results"].empty());
  for (const auto& rec : out["results"]) {
    SCOPED_TRACE(scene_path.filename().string() + " pair " + rec.dump());
    const auto& a = find(rec["a"].get<std::string>());
    const auto& b = find(rec["b"].get<std::string>());
    const auto cls = ref::classify<N>(a.body, b.body, 1e-30);
    EXPECT_EQ(rec["relation"].get<std::string>(), ref::name(cls.relation));
    if (!rec.contains("contact")) continue;
    const auto c = ref::first_contact<N>(a.body, a.velocity, b.body, b.velocity, t_max, 1e-30);
    const json& rc = rec["contact"];
    EXPECT_EQ(rc["status"].get<std::string>(), ref_contact_name(c.kind));
    if (c.kind == ref::ContactKind::hit) {
      const double t = ref::to_double(c.time);
      EXPECT_NEAR(rc["time"].get<double>(), t, time_rel_tol * std::abs(t));
      for (int i = 0; i < N; ++i) {
        EXPECT_NEAR(rc["point"][static_cast<std::size_t>(i)].get<double>(), ref::to_double(c.point[i]), point_tol);
        EXPECT_NEAR(rc["normal"][static_cast<std::size_t>(i)].get<double>(), ref::to_double(c.normal[i]), point_tol);
      }
    }
  }
}

// ------------------------------------------------------------------------------------------
// Basics
// ------------------------------------------------------------------------------------------

TEST(Cli, VersionPrintsTheLibraryVersion) {
  const auto dir = work_dir();
  const Outcome r = run_cli({"--version"}, dir);
  EXPECT_EQ(r.code, 0) << describe(r);
  EXPECT_EQ(r.out, std::string("ellipsect ") + ellipsect::version + "\n");
}

TEST(Cli, EveryCommandHasHelpWithAnExample) {
  const auto dir = work_dir();
  for (const std::string cmd : {"check", "render", "bench", "enclose", "fit"}) {
    const Outcome r = run_cli({cmd, "--help"}, dir);
    EXPECT_EQ(r.code, 0) << describe(r);
    EXPECT_NE(r.out.find("Examples:"), std::string::npos) << cmd;
    EXPECT_NE(r.out.find("ellipsect " + cmd + " examples/scenes/"), std::string::npos) << cmd;
  }
  const Outcome top = run_cli({"--help"}, dir);
  EXPECT_EQ(top.code, 0);
  EXPECT_NE(top.out.find("Exit codes"), std::string::npos);
}

TEST(Cli, UsageErrorsExitWithOne) {
  const auto dir = work_dir();
  const std::string scene = (scenes / "swept_2d.json").string();
  const std::vector<std::vector<std::string>> cases = {
      {},                                                      // no command
      {"frobnicate"},                                          // unknown command
      {"check"},                                               // no scene
      {"check", scene, "--bogus"},                             // unknown option
      {"check", scene, "--format", "xml"},                     // bad value
      {"check", scene, "--query", "volume"},                   // unknown query
      {"check", scene, "--window", "5", "1"},                  // end before start
      {"render", scene},                                       // no -o
      {"render", scene, "-o", (dir / "x.txt").string()},       // unknown picture type
      {"render", scene, "--plane", "xz", "-o", (dir / "x.svg").string()},  // 2D scene
  };
  for (const auto& args : cases) {
    const Outcome r = run_cli(args, dir);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(r.code, 1) << joined << "\n" << describe(r);
    EXPECT_FALSE(r.err.empty()) << joined;
  }
  expect_no_output(dir, "x.svg");
}

// ------------------------------------------------------------------------------------------
// Answers
// ------------------------------------------------------------------------------------------

// Circles, so every answer has a closed form. A (r 2) at the origin; B (r 3) at (10, 3)
// moving (-2, 0): |c_B(t)|^2 = (10 - 2t)^2 + 9 = 25 at t = 3, where the centers are
// (0, 0) and (4, 3): contact point 2 (4, 3) / 5 = (1.6, 1.2), normal (0.8, 0.6).
// C (r 1) at (0, 10): B's top is at y = 6, C's bottom at 9: no contact.
// D (r 1) at (0.5, 0) lies inside A (1.5 < 2); E (r 1) at (2.5, 0) overlaps A;
// F (r 3) at (5, 0) touches A at (2, 0) exactly.
const char* circles_scene = R"({
  "time_window": [0, 10],
  "bodies": [
    {"id": "A", "center": [0, 0], "radius": 2},
    {"id": "B", "center": [10, 3], "radius": 3, "velocity": [-2, 0]},
    {"id": "C", "center": [0, 10], "radius": 1},
    {"id": "D", "center": [0.5, 0], "radius": 1},
    {"id": "E", "center": [2.5, 0], "radius": 1},
    {"id": "F", "center": [5, 0], "radius": 3}
  ],
  "pairs": [["A", "B"], ["B", "C"], ["A", "D"], ["D", "A"], ["A", "E"], ["A", "F"]]
})";

TEST(CliAnswers, CirclesMatchClosedForms) {
  const auto dir = work_dir();
  write_file(dir / "circles.json", circles_scene);
  const Outcome r = run_cli({"check", (dir / "circles.json").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 6u);
  const char* relations[] = {"separated", "separated", "a_contains_b", "b_contains_a", "overlapping", "touching"};
  const char* statuses[] = {"hit", "no_contact_in_window", "overlapping_at_start", "overlapping_at_start",
                            "overlapping_at_start", "touching_at_start"};
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(res[k]["index"].get<int>(), static_cast<int>(k));
    EXPECT_EQ(res[k]["relation"], relations[k]) << k;
    EXPECT_EQ(res[k]["contact"]["status"], statuses[k]) << k;
  }
  const json& hit = res[0]["contact"];
  EXPECT_NEAR(hit["time"].get<double>(), 3.0, 1e-13);
  EXPECT_NEAR(hit["point"][0].get<double>(), 1.6, 1e-12);
  EXPECT_NEAR(hit["point"][1].get<double>(), 1.2, 1e-12);
  EXPECT_NEAR(hit["normal"][0].get<double>(), 0.8, 1e-12);
  EXPECT_NEAR(hit["normal"][1].get<double>(), 0.6, 1e-12);
  EXPECT_TRUE(res[1]["contact"]["time"].is_null());
  EXPECT_TRUE(res[1]["contact"]["point"].is_null());
  const json& touch = res[5]["contact"];
  EXPECT_EQ(touch["time"].get<double>(), 0.0);
  EXPECT_NEAR(touch["point"][0].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(touch["point"][1].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(touch["normal"][0].get<double>(), 1.0, 1e-12);
  // Summary.
  EXPECT_EQ(out["summary"]["pairs"], 6);
  EXPECT_EQ(out["summary"]["relation"]["separated"], 2);
  EXPECT_EQ(out["summary"]["contact"]["overlapping_at_start"], 3);
  EXPECT_EQ(out["dimension"], 2);
  EXPECT_EQ(out["time_window"], json::parse("[0, 10]"));
}

// Spheres: A (r 1) at the origin, B (r 2) at (7, 2, 2) moving (-1, 0, 0):
// (7 - t)^2 + 8 = 9 at t = 6; contact point (1, 2, 2) / 3, normal the same.
const char* spheres_scene = R"({
  "bodies": [
    {"id": "A", "center": [0, 0, 0], "radius": 1},
    {"id": "B", "center": [7, 2, 2], "radius": 2, "velocity": [-1, 0, 0]}
  ]
})";

TEST(CliAnswers, SpheresMatchClosedFormsInEveryWindow) {
  const auto dir = work_dir();
  write_file(dir / "spheres.json", spheres_scene);
  const std::string scene = (dir / "spheres.json").string();
  struct Case {
    std::vector<std::string> window;
    const char* relation;
    const char* status;
  };
  const std::vector<Case> cases = {
      {{}, "separated", "hit"},                              // [0, inf)
      {{"--window", "2", "10"}, "separated", "hit"},         // time stays absolute
      {{"--window", "0", "5"}, "separated", "no_contact_in_window"},
      {{"--window", "0", "inf"}, "separated", "hit"},
      {{"--window", "7", "10"}, "overlapping", "overlapping_at_start"},  // at t0 = 7 |c| = sqrt(8) < 3
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"check", scene};
    args.insert(args.end(), c.window.begin(), c.window.end());
    const Outcome r = run_cli(args, dir);
    ASSERT_EQ(r.code, 0) << describe(r);
    const json out = parse_json(r.out);
    ASSERT_EQ(out["results"].size(), 1u);
    const json& rec = out["results"][0];
    EXPECT_EQ(rec["relation"], c.relation) << r.out;
    EXPECT_EQ(rec["contact"]["status"], c.status) << r.out;
    if (std::string(c.status) == "hit") {
      EXPECT_NEAR(rec["contact"]["time"].get<double>(), 6.0, 6e-13);
      for (int i = 0; i < 3; ++i) {
        const double expected = i == 0 ? 1.0 / 3 : 2.0 / 3;
        EXPECT_NEAR(rec["contact"]["point"][i].get<double>(), expected, 1e-12);
        EXPECT_NEAR(rec["contact"]["normal"][i].get<double>(), expected, 1e-12);
      }
    }
    if (std::string(c.status) == "overlapping_at_start") {
      EXPECT_EQ(rec["contact"]["time"].get<double>(), 7.0);  // the window start
    }
  }
}

TEST(CliAnswers, BundledScenesMatchTheReference) {
  const auto dir = work_dir();
  struct Case {
    const char* file;
    int dim;
    double time_tol, point_tol;
  };
  // Grazing contact times are conditioned like sqrt(rounding) (docs/method.md).
  const std::vector<Case> cases = {{"niemitalo_ellipse_circle.json", 2, 0, 0},
                                   {"niemitalo_two_ellipses.json", 2, 0, 0},
                                   {"swept_2d.json", 2, 1e-10, 1e-9},
                                   {"swept_3d.json", 3, 1e-10, 1e-9},
                                   {"grazing_2d.json", 2, 1e-5, 1e-3}};
  for (const auto& c : cases) {
    const fs::path scene = scenes / c.file;
    const Outcome r = run_cli({"check", scene.string()}, dir);
    ASSERT_EQ(r.code, 0) << c.file << describe(r);
    const json out = parse_json(r.out);
    if (c.dim == 2) {
      expect_matches_reference<2>(scene, out, c.time_tol, c.point_tol);
    } else {
      expect_matches_reference<3>(scene, out, c.time_tol, c.point_tol);
    }
  }
}

TEST(CliAnswers, NiemitaloWorkedExamples) {
  const auto dir = work_dir();
  // Example 1: the ellipse lies in x <= 9 and the circle in x >= 10.
  const Outcome r1 = run_cli({"check", (scenes / "niemitalo_ellipse_circle.json").string()}, dir);
  ASSERT_EQ(r1.code, 0) << describe(r1);
  EXPECT_EQ(parse_json(r1.out)["results"][0]["relation"], "separated");
  // Example 2: the small ellipse (radii 6.4, 4.8 at (3, 4)) lies inside the big one.
  const Outcome r2 = run_cli({"check", (scenes / "niemitalo_two_ellipses.json").string()}, dir);
  ASSERT_EQ(r2.code, 0) << describe(r2);
  EXPECT_EQ(parse_json(r2.out)["results"][0]["relation"], "a_contains_b");
}

TEST(CliAnswers, CsvOutputCarriesTheSameNumbersAsJson) {
  const auto dir = work_dir();
  const std::string scene = (scenes / "swept_3d.json").string();
  const Outcome rj = run_cli({"check", scene}, dir);
  const Outcome rc = run_cli({"check", scene, "--format", "csv"}, dir);
  ASSERT_EQ(rj.code, 0) << describe(rj);
  ASSERT_EQ(rc.code, 0) << describe(rc);
  const json out = parse_json(rj.out);
  const auto lines = split_lines(rc.out);
  ASSERT_EQ(lines.size(), 2u) << rc.out;
  EXPECT_EQ(lines[0],
            "index,a,b,relation,contact_status,contact_time,contact_x,contact_y,contact_z,normal_x,normal_y,normal_z,"
            "contact_iterations");
  const auto f = split_csv_line(lines[1]);
  ASSERT_EQ(f.size(), 13u);
  const json& rec = out["results"][0];
  EXPECT_EQ(f[1], "A");
  EXPECT_EQ(f[2], "B");
  EXPECT_EQ(f[3], rec["relation"]);
  EXPECT_EQ(f[4], rec["contact"]["status"]);
  EXPECT_EQ(std::stod(f[5]), rec["contact"]["time"].get<double>());  // shortest round-trip decimals
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(std::stod(f[6 + static_cast<std::size_t>(i)]), rec["contact"]["point"][i].get<double>());
    EXPECT_EQ(std::stod(f[9 + static_cast<std::size_t>(i)]), rec["contact"]["normal"][i].get<double>());
  }
}

TEST(CliAnswers, AllThreeInputFormsGiveTheSameAnswers) {
  const auto dir = work_dir();
  // swept_2d.json as a bodies CSV with a pairs file, and as a pairs CSV.
  write_file(dir / "bodies.csv",
             "id,x,y,rx,ry,angle,vx,vy\n"
             "A,0,0,3,1,0.5,0,0\n"
             "B,8,1.5,1.5,0.5,-0.3,-2,-0.25\n"
             "C,-6,-3,1,1,,,\n");
  write_file(dir / "pairs.csv", "a,b\nA,B\nA,C\nB,C\n");
  write_file(dir / "inline.csv",
             "a_id,a_x,a_y,a_rx,a_ry,a_angle,a_vx,a_vy,b_id,b_x,b_y,b_rx,b_ry,b_angle,b_vx,b_vy\n"
             "A,0,0,3,1,0.5,0,0,B,8,1.5,1.5,0.5,-0.3,-2,-0.25\n"
             "A,0,0,3,1,0.5,0,0,C,-6,-3,1,1,0,0,0\n"
             "B,8,1.5,1.5,0.5,-0.3,-2,-0.25,C,-6,-3,1,1,0,0,0\n");
  const Outcome rj = run_cli({"check", (scenes / "swept_2d.json").string()}, dir);
  const Outcome rb = run_cli({"check", (dir / "bodies.csv").string(), "--pairs", (dir / "pairs.csv").string(),
                            "--window", "0", "10"}, dir);
  const Outcome rp = run_cli({"check", (dir / "inline.csv").string(), "--window", "0", "10"}, dir);
  ASSERT_EQ(rj.code, 0) << describe(rj);
  ASSERT_EQ(rb.code, 0) << describe(rb);
  ASSERT_EQ(rp.code, 0) << describe(rp);
  const json oj = parse_json(rj.out), ob = parse_json(rb.out), op = parse_json(rp.out);
  ASSERT_EQ(oj["results"].size(), 3u);
  ASSERT_EQ(ob["results"].size(), 3u);
  ASSERT_EQ(op["results"].size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    for (const json* o : {&ob, &op}) {
      const json& x = (*o)["results"][k];
      EXPECT_EQ(x["a"], oj["results"][k]["a"]);
      EXPECT_EQ(x["b"], oj["results"][k]["b"]);
      EXPECT_EQ(x["relation"], oj["results"][k]["relation"]);
      EXPECT_EQ(x["contact"], oj["results"][k]["contact"]);  // bit for bit
    }
    EXPECT_EQ(op["results"][k]["line"], k + 2);  // the pairs CSV records its source line
  }
}

TEST(CliAnswers, OutputIsTheSameForEveryThreadCount) {
  const auto dir = work_dir();
  const std::string bodies = (scenes / "bodies_10k.csv").string();
  const Outcome r1 = run_cli({"check", bodies, "-j", "1"}, dir);
  const Outcome r2 = run_cli({"check", bodies, "-j", "2"}, dir);
  const Outcome r5 = run_cli({"check", bodies, "-j", "5"}, dir);
  ASSERT_EQ(r1.code, 0) << describe(r1);
  EXPECT_EQ(r1.out, r2.out);
  EXPECT_EQ(r1.out, r5.out);
  // A streamed pairs CSV (several chunks) with velocities.
  const long rows = std::max(20000L, static_cast<long>(60000 * case_scale()));
  const Outcome gen = run_program(make_scene, {"pairs", "--count", std::to_string(rows), "--seed", "3", "--velocity",
                                           "-o", (dir / "pairs.csv").string()}, dir);
  ASSERT_EQ(gen.code, 0) << describe(gen);
  const Outcome p1 = run_cli({"check", (dir / "pairs.csv").string(), "--format", "csv", "-j", "1", "--window", "0",
                            "50"}, dir);
  const Outcome p3 = run_cli({"check", (dir / "pairs.csv").string(), "--format", "csv", "-j", "3", "--window", "0",
                            "50"}, dir);
  ASSERT_EQ(p1.code, 0) << describe(p1);
  EXPECT_EQ(split_lines(p1.out).size(), static_cast<std::size_t>(rows + 1));
  EXPECT_TRUE(p1.out == p3.out) << "outputs differ between -j 1 and -j 3";
}

TEST(CliAnswers, BroadPhaseAgreesWithCheckingEveryPair) {
  const auto dir = work_dir();
  // 300 moving bodies packed so that many boxes meet: 44,850 pairs.
  const Outcome gen = run_program(make_scene, {"bodies", "--count", "300", "--seed", "5", "--extent", "120", "--velocity",
                                           "-o", (dir / "bodies.csv").string()}, dir);
  ASSERT_EQ(gen.code, 0) << describe(gen);
  const std::string scene = (dir / "bodies.csv").string();
  const Outcome with = run_cli({"check", scene, "--window", "0", "4", "--format", "csv"}, dir);
  const Outcome without = run_cli({"check", scene, "--window", "0", "4", "--format", "csv", "--no-broad-phase"}, dir);
  ASSERT_EQ(with.code, 0) << describe(with);
  ASSERT_EQ(without.code, 0) << describe(without);
  const auto a = split_lines(with.out), b = split_lines(without.out);
  ASSERT_EQ(a.size(), 300u * 299u / 2u + 1u);
  ASSERT_EQ(a.size(), b.size());
  std::size_t hits = 0, overlaps = 0;
  for (std::size_t k = 1; k < a.size(); ++k) {
    const auto fa = split_csv_line(a[k]), fb = split_csv_line(b[k]);
    // index, a, b, relation, status, time: the same; iterations may differ for pairs the
    // broad phase decided without iterating.
    for (std::size_t i = 0; i <= 5; ++i) ASSERT_EQ(fa[i], fb[i]) << "line " << k + 1 << ": " << a[k] << " vs " << b[k];
    hits += fa[4] == "hit";
    overlaps += fa[3] != "separated";
  }
  EXPECT_GT(hits, 10u);  // the sample exercises the swept boxes
  EXPECT_GT(overlaps, 5u);
}

TEST(CliAnswers, LargeBodyFilesReportBroadPhaseCandidates) {
  const auto dir = work_dir();
  const Outcome r = run_cli({"check", (scenes / "bodies_10k.csv").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  EXPECT_EQ(out["bodies"], 10000);
  EXPECT_EQ(out["pair_source"], "broad-phase candidates");
  const json& s = out["summary"];
  EXPECT_EQ(s["pairs"], 10000LL * 9999 / 2);
  EXPECT_EQ(s["listed"].get<std::size_t>(), out["results"].size());
  long long total = 0;
  for (const auto& [k, v] : s["relation"].items()) total += v.get<long long>();
  EXPECT_EQ(total, 10000LL * 9999 / 2);
  // Every listed candidate is a distinct pair in increasing order.
  std::string prev_a, prev_b;
  for (const auto& rec : out["results"]) {
    const std::string a = rec["a"], b = rec["b"];
    EXPECT_LT(a, b);
    EXPECT_TRUE(prev_a < a || (prev_a == a && prev_b < b));
    prev_a = a;
    prev_b = b;
  }
  EXPECT_GT(s["relation"]["overlapping"].get<int>(), 100);
}

TEST(CliAnswers, BundledTenThousandBodyFileIsReproducible) {
  const auto dir = work_dir();
  const Outcome gen = run_program(make_scene, {"bodies", "--count", "10000", "--seed", "1", "-o",
                                               (dir / "bodies.csv").string()}, dir);
  ASSERT_EQ(gen.code, 0) << describe(gen);
  EXPECT_TRUE(slurp(dir / "bodies.csv") == slurp(scenes / "bodies_10k.csv"))
      << "examples/scenes/bodies_10k.csv differs from `ellipsect_make_scene bodies --count 10000 --seed 1`";
}

// ------------------------------------------------------------------------------------------
// Distance (--query distance): closed forms for circles, spheres and ellipses on an axis
// ------------------------------------------------------------------------------------------

template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

// The expected signed distance of a pair, with its accuracy scale (the library's: largest
// radius of a + largest radius of b + |distance|).
template <int N>
struct ExpectedDistance {
  const char* status;
  double distance;
  Vector<N> point_a, point_b, normal;
  double scale;
};

// Two balls: with u = (c_b - c_a) / |c_b - c_a| (distinct centers), the signed distance is
// |c_b - c_a| - r_a - r_b (minus the penetration depth when negative), the witness points
// c_a + r_a u and c_b - r_b u, the normal u.
template <int N>
ExpectedDistance<N> balls(const char* status, const Vector<N>& ca, double ra, const Vector<N>& cb, double rb) {
  const Vector<N> u = (cb - ca).normalized();
  const double d = (cb - ca).norm() - ra - rb;
  return {status, d, ca + ra * u, cb - rb * u, u, ra + rb + std::abs(d)};
}

// A "distance" record against the expected answer, to the library's stated accuracy
// (include/ellipsect/distance.hpp): the distance to 1e-12 * scale, the witness points to
// 1e-10 * scale (unique optima), the unit normal to 1e-10.
template <int N>
void expect_distance(const json& d, const ExpectedDistance<N>& e) {
  SCOPED_TRACE(d.dump());
  ASSERT_TRUE(d.is_object());
  EXPECT_EQ(d.at("status"), e.status);
  EXPECT_NEAR(d.at("distance").get<double>(), e.distance, 1e-12 * e.scale);
  for (const char* key : {"point_a", "point_b", "normal"}) ASSERT_EQ(d.at(key).size(), static_cast<std::size_t>(N)) << key;
  for (int i = 0; i < N; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(d.at("point_a")[k].get<double>(), e.point_a[i], 1e-10 * e.scale) << i;
    EXPECT_NEAR(d.at("point_b")[k].get<double>(), e.point_b[i], 1e-10 * e.scale) << i;
    EXPECT_NEAR(d.at("normal")[k].get<double>(), e.normal[i], 1e-10) << i;
  }
  EXPECT_GE(d.at("iterations").get<int>(), 0);
}

// The distance columns of a CSV row, looked up by header name, as the JSON record's
// "distance" object (empty fields as null).
json distance_from_csv(const std::vector<std::string>& header, const std::vector<std::string>& row, int dim) {
  auto text = [&](const std::string& name) {
    const auto i = static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    EXPECT_LT(i, row.size()) << "no column " << name;
    return i < row.size() ? row[i] : std::string();
  };
  auto number = [&](const std::string& name) {
    const std::string t = text(name);
    return t.empty() ? json() : json(std::stod(t));
  };
  auto vec = [&](const std::string& prefix) {
    json v = json::array();
    for (int i = 0; i < dim; ++i) v.push_back(number(prefix + "xyz"[i]));
    return v;
  };
  return {{"status", text("distance_status")},
          {"distance", number("distance")},
          {"point_a", vec("point_a_")},
          {"point_b", vec("point_b_")},
          {"normal", vec("distance_normal_")},
          {"iterations", std::stoi(text("distance_iterations"))}};
}

TEST(CliDistance, CirclesMatchClosedForms) {
  const auto dir = work_dir();
  write_file(dir / "circles.json", circles_scene);
  const std::string scene = (dir / "circles.json").string();
  const Outcome r = run_cli({"check", scene, "--query", "relation,contact,distance"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  EXPECT_EQ(out["queries"], json::parse(R"(["relation", "contact", "distance"])"));
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 6u);
  // The circles of circles_scene at t = 0: A-D is a containment (depth 2.5), A-E overlaps
  // by 0.5, A-F touches.
  using V = Vector<2>;
  const V a(0, 0), b(10, 3), c(0, 10), d(0.5, 0), e(2.5, 0), f(5, 0);
  const ExpectedDistance<2> expected[] = {balls<2>("separated", a, 2, b, 3),   balls<2>("separated", b, 3, c, 1),
                                          balls<2>("overlapping", a, 2, d, 1), balls<2>("overlapping", d, 1, a, 2),
                                          balls<2>("overlapping", a, 2, e, 1), balls<2>("touching", a, 2, f, 3)};
  for (std::size_t k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    expect_distance(res[k]["distance"], expected[k]);
  }
  EXPECT_NEAR(res[2]["distance"]["distance"].get<double>(), -2.5, 1e-12 * 5.5);
  EXPECT_EQ(out["summary"]["distance"],
            json::parse(R"({"separated": 2, "touching": 1, "overlapping": 3, "did_not_converge": 0})"));
  // Off by default; asking for it changes no other answer.
  const Outcome plain = run_cli({"check", scene}, dir);
  ASSERT_EQ(plain.code, 0) << describe(plain);
  const json p = parse_json(plain.out);
  EXPECT_EQ(p["queries"], json::parse(R"(["relation", "contact"])"));
  EXPECT_FALSE(p["summary"].contains("distance"));
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_FALSE(p["results"][k].contains("distance")) << k;
    json rec = res[k];
    rec.erase("distance");
    EXPECT_EQ(rec, p["results"][k]) << k;
  }
}

TEST(CliDistance, SpheresAtTheWindowStart) {
  const auto dir = work_dir();
  write_file(dir / "spheres.json", spheres_scene);
  const std::string scene = (dir / "spheres.json").string();
  // B's center at t0 is (7 - t0, 2, 2) (spheres_scene); A is the unit sphere at the origin.
  struct Case {
    std::vector<std::string> window;
    double t0;
    const char* status;
  };
  const std::vector<Case> cases = {{{}, 0, "separated"},
                                   {{"--window", "2", "10"}, 2, "separated"},
                                   {{"--window", "7", "10"}, 7, "overlapping"}};  // |c| = sqrt(8) < 3
  for (const auto& c : cases) {
    SCOPED_TRACE(c.t0);
    std::vector<std::string> args = {"check", scene, "--query", "distance"};
    args.insert(args.end(), c.window.begin(), c.window.end());
    const Outcome r = run_cli(args, dir);
    ASSERT_EQ(r.code, 0) << describe(r);
    const json out = parse_json(r.out);
    EXPECT_EQ(out["queries"], json::parse(R"(["distance"])"));
    ASSERT_EQ(out["results"].size(), 1u);
    const json& rec = out["results"][0];
    EXPECT_FALSE(rec.contains("relation"));
    EXPECT_FALSE(rec.contains("contact"));
    expect_distance(rec["distance"], balls<3>(c.status, Vector<3>(0, 0, 0), 1, Vector<3>(7 - c.t0, 2, 2), 2));
  }
}

// Ellipses facing each other along a common axis. Separated: the facing vertices are the
// closest points (the segment joining them is normal to both boundaries, and a critical
// pair of a convex problem is its minimum), so the distance is the center distance minus
// the two semi-axes along it. Overlapping: the depth is the least over unit n of
// h(n) = rho_a(n) + rho_b(n) - n . (c_b - c_a) (rho: support radius about the center);
// for A (radii 4, 1) and C (radii 3, 2, 6 along x) h(theta) = sqrt(16 cos^2 + sin^2) +
// sqrt(9 cos^2 + 4 sin^2) - 6 cos = 1 + 0.29 sin^2 + O(sin^4) near theta = 0, and a grid of
// 10^6 directions finds no other minimum: depth 1 along x, witness points the vertices.
// The same in 3D for the ellipsoid pairs along z (h = 0.5 + 1.33 y^2 + 2.33 x^2 + ... near
// the z axis, no other minimum on a 600 x 1200 grid).
TEST(CliDistance, EllipsesAlongAPrincipalAxis) {
  const auto dir = work_dir();
  write_file(dir / "axis2.json", R"({
    "bodies": [
      {"id": "A", "center": [0, 0], "radii": [4, 1]},
      {"id": "B", "center": [10, 0], "radii": [3, 2]},
      {"id": "C", "center": [6, 0], "radii": [3, 2]},
      {"id": "V", "center": [0, 0], "radii": [4, 1], "angle": 1.5707963267948966},
      {"id": "W", "center": [0, -9], "radius": 2}
    ],
    "pairs": [["A", "B"], ["B", "A"], ["A", "C"], ["V", "W"]]
  })");
  write_file(dir / "axis3.json", R"({
    "bodies": [
      {"id": "A", "center": [0, 0, 0], "radii": [3, 1, 2]},
      {"id": "B", "center": [0, 0, 5], "radii": [1, 2, 1]},
      {"id": "C", "center": [0, 0, 3], "radii": [1, 2, 1.5]}
    ],
    "pairs": [["A", "B"], ["A", "C"]]
  })");
  using V2 = Vector<2>;
  using V3 = Vector<3>;
  const Outcome r2 = run_cli({"check", (dir / "axis2.json").string(), "--query", "relation,distance"}, dir);
  ASSERT_EQ(r2.code, 0) << describe(r2);
  const json o2 = parse_json(r2.out);
  ASSERT_EQ(o2["results"].size(), 4u);
  const ExpectedDistance<2> e2[] = {{"separated", 3, V2(4, 0), V2(7, 0), V2(1, 0), 10},
                                    {"separated", 3, V2(7, 0), V2(4, 0), V2(-1, 0), 10},
                                    {"overlapping", -1, V2(4, 0), V2(3, 0), V2(1, 0), 8},
                                    {"separated", 3, V2(0, -4), V2(0, -7), V2(0, -1), 9}};
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    expect_distance(o2["results"][k]["distance"], e2[k]);
  }
  EXPECT_EQ(o2["results"][2]["relation"], "overlapping");
  const Outcome r3 = run_cli({"check", (dir / "axis3.json").string(), "--query", "distance"}, dir);
  ASSERT_EQ(r3.code, 0) << describe(r3);
  const json o3 = parse_json(r3.out);
  ASSERT_EQ(o3["results"].size(), 2u);
  expect_distance(o3["results"][0]["distance"],
                  ExpectedDistance<3>{"separated", 2, V3(0, 0, 2), V3(0, 0, 4), V3(0, 0, 1), 6});
  expect_distance(o3["results"][1]["distance"],
                  ExpectedDistance<3>{"overlapping", -0.5, V3(0, 0, 2), V3(0, 0, 1.5), V3(0, 0, 1), 5.5});
}

TEST(CliDistance, CsvColumnsComeAfterTheExistingOnes) {
  const auto dir = work_dir();
  const std::string scene = (scenes / "swept_2d.json").string();
  const Outcome plain = run_cli({"check", scene, "--format", "csv"}, dir);
  const Outcome with = run_cli({"check", scene, "--format", "csv", "--query", "relation,contact,distance"}, dir);
  const Outcome js = run_cli({"check", scene, "--query", "relation,contact,distance"}, dir);
  ASSERT_EQ(plain.code, 0) << describe(plain);
  ASSERT_EQ(with.code, 0) << describe(with);
  ASSERT_EQ(js.code, 0) << describe(js);
  const auto p = split_lines(plain.out), w = split_lines(with.out);
  ASSERT_EQ(p.size(), 4u) << plain.out;
  ASSERT_EQ(w.size(), p.size()) << with.out;
  EXPECT_EQ(w[0], p[0] + ",distance_status,distance,point_a_x,point_a_y,point_b_x,point_b_y,distance_normal_x,"
                         "distance_normal_y,distance_iterations");
  EXPECT_EQ(p[0], "index,a,b,relation,contact_status,contact_time,contact_x,contact_y,normal_x,normal_y,"
                  "contact_iterations");
  const auto header = split_csv_line(w[0]);
  const json out = parse_json(js.out);
  for (std::size_t k = 1; k < w.size(); ++k) {
    SCOPED_TRACE(w[k]);
    EXPECT_EQ(w[k].rfind(p[k] + ",", 0), 0u) << "the existing columns moved or changed: " << p[k];
    const auto f = split_csv_line(w[k]);
    ASSERT_EQ(f.size(), header.size());
    EXPECT_EQ(distance_from_csv(header, f, 2), out["results"][k - 1]["distance"]);  // the same numbers
  }
  // A 3D pairs CSV (with its line column) of spheres, against the closed form.
  write_file(dir / "spheres.csv",
             "a_id,a_x,a_y,a_z,a_rx,a_ry,a_rz,b_id,b_x,b_y,b_z,b_rx,b_ry,b_rz\n"
             "A,0,0,0,1,1,1,B,2,3,6,2,2,2\n"
             "A,0,0,0,1,1,1,C,1,2,2,3,3,3\n"
             "D,1,-2,3,0.5,0.5,0.5,E,3,-3,5,1,1,1\n");
  const Outcome s = run_cli({"check", (dir / "spheres.csv").string(), "--format", "csv", "--query", "relation,distance"},
                            dir);
  ASSERT_EQ(s.code, 0) << describe(s);
  const auto lines = split_lines(s.out);
  ASSERT_EQ(lines.size(), 4u) << s.out;
  EXPECT_EQ(lines[0], "index,line,a,b,relation,distance_status,distance,point_a_x,point_a_y,point_a_z,point_b_x,"
                      "point_b_y,point_b_z,distance_normal_x,distance_normal_y,distance_normal_z,distance_iterations");
  using V = Vector<3>;
  const ExpectedDistance<3> expected[] = {balls<3>("separated", V(0, 0, 0), 1, V(2, 3, 6), 2),      // 7 - 3 = 4
                                          balls<3>("overlapping", V(0, 0, 0), 1, V(1, 2, 2), 3),    // 3 - 4 = -1
                                          balls<3>("separated", V(1, -2, 3), 0.5, V(3, -3, 5), 1)};  // 3 - 1.5
  const char* relations[] = {"separated", "overlapping", "separated"};
  const auto sh = split_csv_line(lines[0]);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(lines[k + 1]);
    const auto f = split_csv_line(lines[k + 1]);
    ASSERT_EQ(f.size(), sh.size());
    EXPECT_EQ(f[1], std::to_string(k + 2));
    EXPECT_EQ(f[4], relations[k]);
    expect_distance(distance_from_csv(sh, f, 3), expected[k]);
  }
}

TEST(CliDistance, PairsLeftOutByTheBroadPhaseGetTheirDistance) {
  const auto dir = work_dir();
  // Only P-R's boxes meet; the other five pairs are decided by the broad phase.
  write_file(dir / "bodies.csv", "id,x,y,rx,ry\nP,0,0,1,1\nQ,3,4,1,1\nR,0.5,0,1,1\nS,100,0,2,2\n");
  const std::string scene = (dir / "bodies.csv").string();
  const Outcome r = run_cli({"check", scene, "--query", "relation,distance"}, dir);
  const Outcome exact = run_cli({"check", scene, "--query", "relation,distance", "--no-broad-phase"}, dir);
  const Outcome cand = run_cli({"check", scene, "--query", "relation,distance", "--report", "candidates"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  ASSERT_EQ(exact.code, 0) << describe(exact);
  ASSERT_EQ(cand.code, 0) << describe(cand);
  const json out = parse_json(r.out), oe = parse_json(exact.out), oc = parse_json(cand.out);
  using V = Vector<2>;
  const V p(0, 0), q(3, 4), rr(0.5, 0), s(100, 0);
  const ExpectedDistance<2> expected[] = {balls<2>("separated", p, 1, q, 1),   balls<2>("overlapping", p, 1, rr, 1),
                                          balls<2>("separated", p, 1, s, 2),   balls<2>("separated", q, 1, rr, 1),
                                          balls<2>("separated", q, 1, s, 2),   balls<2>("separated", rr, 1, s, 2)};
  ASSERT_EQ(out["results"].size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    expect_distance(out["results"][k]["distance"], expected[k]);
  }
  EXPECT_EQ(out["results"], oe["results"]);  // bit for bit
  const json counts = json::parse(R"({"separated": 5, "touching": 0, "overlapping": 1, "did_not_converge": 0})");
  EXPECT_EQ(out["summary"]["distance"], counts);
  // Only the candidate is listed; the summary counts the others as separated.
  EXPECT_EQ(oc["pair_source"], "broad-phase candidates");
  ASSERT_EQ(oc["results"].size(), 1u);
  EXPECT_EQ(oc["results"][0]["a"], "P");
  EXPECT_EQ(oc["results"][0]["b"], "R");
  EXPECT_EQ(oc["results"][0]["distance"], out["results"][1]["distance"]);
  EXPECT_EQ(oc["summary"]["distance"], counts);
}

TEST(CliDistance, UnknownQueryNamesListTheAvailableOnes) {
  const auto dir = work_dir();
  const std::string scene = (scenes / "swept_2d.json").string();
  const Outcome c = run_cli({"check", scene, "--query", "relation,penetration"}, dir);
  EXPECT_EQ(c.code, 1) << describe(c);
  EXPECT_NE(c.err.find("unknown query \"penetration\" (available: relation, contact, distance)"), std::string::npos)
      << c.err;
  const Outcome b = run_cli({"bench", scene, "--query", "signed_distance"}, dir);
  EXPECT_EQ(b.code, 1) << describe(b);
  EXPECT_NE(b.err.find("unknown query \"signed_distance\" (available: overlap, classify, contact, distance)"),
            std::string::npos)
      << b.err;
}

// ------------------------------------------------------------------------------------------
// Query options: --tolerance, the caps (--max-contact-iterations, ..., --max-motion-steps)
// ------------------------------------------------------------------------------------------

// Each invalid value is a usage error (exit 1) naming the option and the accepted range,
// with no output written.
TEST(CliOptions, InvalidValuesNameTheOption) {
  const auto dir = work_dir();
  const std::string scene = (scenes / "swept_2d.json").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--tolerance", "nan"}, "--tolerance: must be 0 or in [1e-14, 1e-09] (got nan)"},
      {{"--tolerance", "-1e-12"}, "--tolerance: must be 0 or in [1e-14, 1e-09] (got -1e-12)"},
      {{"--tolerance", "inf"}, "--tolerance: must be 0 or in [1e-14, 1e-09] (got inf)"},
      {{"--tolerance", "1e-3"}, "--tolerance: must be 0 or in [1e-14, 1e-09] (got 0.001)"},
      {{"--tolerance", "1e-15"}, "--tolerance: must be 0 or in [1e-14, 1e-09] (got 1e-15)"},
      {{"--tolerance", "tiny"}, "--tolerance"},
      {{"--max-contact-iterations", "0"}, "--max-contact-iterations: must be in [1, 100000] (got 0)"},
      {{"--max-contact-iterations", "-3"}, "--max-contact-iterations: must be in [1, 100000] (got -3)"},
      {{"--max-contact-iterations", "100001"}, "--max-contact-iterations: must be in [1, 100000] (got 100001)"},
      {{"--max-contact-iterations", "4294967360"}, "--max-contact-iterations: must be in [1, 100000] (got 4294967360)"},
      {{"--max-contact-iterations", "2.5"}, "--max-contact-iterations"},
      {{"--max-motion-steps", "0"}, "--max-motion-steps: must be in [1, 1000000] (got 0)"},
      {{"--max-motion-steps", "1000001"}, "--max-motion-steps: must be in [1, 1000000] (got 1000001)"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"check", scene, "-o", (dir / "out.json").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome r = run_cli(args, dir);
    EXPECT_EQ(r.code, 1) << extra[0] << " " << extra[1] << "\n" << describe(r);
    EXPECT_NE(r.err.find(message), std::string::npos) << "expected \"" << message << "\" in: " << r.err;
    expect_no_output(dir, "out.json");
  }
}

// The options reach every query. Unit circles with centres 2 + 5e-10 apart have the relative
// gap 5e-10: separated in the default band (1e-12), touching in a band of 1e-9, for the
// relation, the first contact and the signed distance alike. B of the circles scene meets A at
// t = 3 after Newton steps on a curved path: one step is not enough (did_not_converge).
TEST(CliOptions, OptionsReachTheQueries) {
  const auto dir = work_dir();
  write_file(dir / "near.json", R"({
  "bodies": [
    {"id": "A", "center": [0, 0], "radius": 1},
    {"id": "B", "center": [2.0000000005, 0], "radius": 1}
  ]
})");
  const std::string near = (dir / "near.json").string();
  const Outcome plain = run_cli({"check", near, "--query", "relation,contact,distance"}, dir);
  ASSERT_EQ(plain.code, 0) << describe(plain);
  const json p = parse_json(plain.out)["results"][0];
  EXPECT_EQ(p["relation"], "separated");
  EXPECT_EQ(p["contact"]["status"], "no_contact_in_window");
  EXPECT_EQ(p["distance"]["status"], "separated");
  const Outcome wide = run_cli({"check", near, "--query", "relation,contact,distance", "--tolerance", "1e-9"}, dir);
  ASSERT_EQ(wide.code, 0) << describe(wide);
  const json w = parse_json(wide.out)["results"][0];
  EXPECT_EQ(w["relation"], "touching");
  EXPECT_EQ(w["contact"]["status"], "touching_at_start");
  EXPECT_EQ(w["distance"]["status"], "touching");

  write_file(dir / "circles.json", circles_scene);
  const std::string circles = (dir / "circles.json").string();
  const Outcome capped = run_cli({"check", circles, "--max-contact-iterations", "1"}, dir);
  ASSERT_EQ(capped.code, 0) << describe(capped);
  EXPECT_EQ(parse_json(capped.out)["results"][0]["contact"]["status"], "did_not_converge");
  const Outcome enough = run_cli({"check", circles, "--max-contact-iterations", "100000", "--max-motion-steps", "1000000"}, dir);
  ASSERT_EQ(enough.code, 0) << describe(enough);
  EXPECT_EQ(parse_json(enough.out)["results"][0]["contact"]["status"], "hit");
}

// A turning body's first contact advances in steps, each a signed distance: one step does
// not reach the contact of the bundled tipping rod.
TEST(CliOptions, MotionStepsCapTheRigidMotionSearch) {
  const auto dir = work_dir();
  const std::string rod = (scenes / "turning_rod.json").string();
  const Outcome plain = run_cli({"check", rod}, dir);
  ASSERT_EQ(plain.code, 0) << describe(plain);
  const Outcome capped = run_cli({"check", rod, "--max-motion-steps", "1"}, dir);
  ASSERT_EQ(capped.code, 0) << describe(capped);
  const json p = parse_json(plain.out)["summary"]["contact"], c = parse_json(capped.out)["summary"]["contact"];
  EXPECT_EQ(p.value("did_not_converge", 0), 0) << p;
  EXPECT_GT(c.value("did_not_converge", 0), 0) << c;
}

// ------------------------------------------------------------------------------------------
// Bad input: message (file, line or JSON path, field), exit code 2, no output file.
// ------------------------------------------------------------------------------------------

struct BadCase {
  std::string name;     // file name (its extension picks the format)
  std::string content;
  std::vector<std::string> expected;  // substrings of the message
  std::vector<std::string> extra_args = {};
  std::string named_file = {};  // the file the message must name (default: this one)
};

void expect_bad_input(const BadCase& c, const fs::path& dir, int expected_code = 2) {
  SCOPED_TRACE(c.name);
  write_file(dir / c.name, c.content);
  std::vector<std::string> args = {"check", (dir / c.name).string(), "-o", (dir / "out.json").string()};
  args.insert(args.end(), c.extra_args.begin(), c.extra_args.end());
  const Outcome r = run_cli(args, dir);
  EXPECT_EQ(r.code, expected_code) << describe(r);
  const std::string named = (dir / (c.named_file.empty() ? c.name : c.named_file)).string();
  EXPECT_NE(r.err.find(named + ":"), std::string::npos) << "message does not name " << named << ": " << r.err;
  for (const auto& s : c.expected) EXPECT_NE(r.err.find(s), std::string::npos) << "expected \"" << s << "\" in: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  expect_no_output(dir, "out.json");
}

TEST(CliBadInput, MalformedFiles) {
  const auto dir = work_dir();
  expect_bad_input({"malformed.json", "{\n  \"bodies\": [\n    {\"id\": \"a\", \"center\": [0, 0], \"radius\": 1},\n  ]\n}\n",
                    {"malformed.json:4:3: malformed JSON"}}, dir);
  expect_bad_input({"not_object.json", "[1, 2]", {"$: expected a JSON object"}}, dir);
  expect_bad_input({"short.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,1,2,1\n", {"short.csv:3: malformed CSV: 4 fields, the header has 5"}}, dir);
  expect_bad_input({"quote.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,1,\"2,1,1\n", {"quote.csv:3: malformed CSV: unterminated quoted field"}}, dir);
  expect_bad_input({"header.csv", "id,x,y,rx,ry,colour\na,0,0,1,1,red\n", {"header.csv:1: header: unknown column \"colour\""}}, dir);
  expect_bad_input({"neither.csv", "p,q\n1,2\n", {"neither.csv:1: header: neither a bodies CSV"}}, dir);
}

TEST(CliBadInput, MissingFields) {
  const auto dir = work_dir();
  expect_bad_input({"noradii.json", R"({"bodies": [{"id": "a", "center": [0, 0]}]})", {"$.bodies[0].radii: missing"}}, dir);
  expect_bad_input({"noid.json", R"({"bodies": [{"center": [0, 0], "radius": 1}]})", {"$.bodies[0].id: missing"}}, dir);
  expect_bad_input({"nobodies.json", R"({"pairs": []})", {"$.bodies: missing"}}, dir);
  expect_bad_input({"nocol.csv", "id,x,y,rx\na,0,0,1\n", {"nocol.csv:1: header: missing column ry"}}, dir);
  expect_bad_input({"novalue.csv", "id,x,y,rx,ry\na,0,,1,1\n", {"novalue.csv:2: column y: missing value"}}, dir);
  expect_bad_input({"typo.json", R"({"bodies": [{"id": "a", "center": [0, 0], "radii": [1, 1], "velocty": [1, 0]}]})",
                    {"$.bodies[0].velocty: unknown key"}}, dir);
}

TEST(CliBadInput, WrongTypes) {
  const auto dir = work_dir();
  expect_bad_input({"type.json", R"({"bodies": [{"id": "a", "center": [0, "zero"], "radius": 1}]})",
                    {"$.bodies[0].center[1]: expected a number, got a string"}}, dir);
  expect_bad_input({"type2.json", R"({"bodies": [{"id": "a", "center": [0, 0], "radii": 1}]})",
                    {"$.bodies[0].radii: expected an array of 2 numbers, got a number"}}, dir);
  expect_bad_input({"type3.json", R"({"bodies": [{"id": true, "center": [0, 0], "radius": 1}]})",
                    {"$.bodies[0].id: expected a string"}}, dir);
  expect_bad_input({"type.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,1,2,1,x1\n", {"type.csv:3: column ry: not a number: \"x1\""}}, dir);
}

TEST(CliBadInput, NonFiniteNumbers) {
  const auto dir = work_dir();
  expect_bad_input({"nan.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,1,nan,1,1\n", {"nan.csv:3: column y: must be finite, got nan"}}, dir);
  expect_bad_input({"inf.csv", "id,x,y,rx,ry,vx,vy\na,0,0,1,1,inf,0\n", {"inf.csv:2: column vx: must be finite, got inf"}}, dir);
  expect_bad_input({"big.csv", "id,x,y,rx,ry\na,1e999,0,1,1\n", {"big.csv:2: column x: must be finite"}}, dir);
  expect_bad_input({"inf.json", R"({"bodies": [{"id": "a", "center": [0, 1e999], "radius": 1}]})",
                    {"inf.json:1:39: number 1e999 is out of range"}}, dir);
  expect_bad_input({"nan.json", R"({"bodies": [{"id": "a", "center": [0, NaN], "radius": 1}]})",
                    {"nan.json:1:", "malformed JSON"}}, dir);
}

TEST(CliBadInput, NonPositiveRadii) {
  const auto dir = work_dir();
  expect_bad_input({"neg.json", R"({"bodies": [{"id": "a", "center": [0, 0], "radii": [1, -2]}]})",
                    {"$.bodies[0].radii[1]: must be > 0, got -2"}}, dir);
  expect_bad_input({"zero.json", R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radius": 0}]})",
                    {"$.bodies[0].radius: must be > 0, got 0"}}, dir);
  expect_bad_input({"zero.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,1,2,1,0\n", {"zero.csv:3: column ry: must be > 0, got 0"}}, dir);
  expect_bad_input({"pairs.csv", "a_x,a_y,a_rx,a_ry,b_x,b_y,b_rx,b_ry\n0,0,1,1,3,0,1,1\n0,0,1,1,3,0,-1,1\n",
                    {"pairs.csv:3: column b_rx: must be > 0, got -1"}}, dir);
}

TEST(CliBadInput, NonUnitQuaternionsAreRejected) {
  const auto dir = work_dir();
  expect_bad_input({"quat.json",
                    R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radii": [1, 2, 3], "quaternion": [1, 0.1, 0, 0]}]})",
                    {"$.bodies[0].quaternion: not a unit quaternion: |q| = 1.00498"}}, dir);
  // 0.7071 written with four digits is 1e-5 off: rejected, not silently normalized.
  expect_bad_input({"quat.csv", "id,x,y,z,rx,ry,rz,qw,qx,qy,qz\na,0,0,0,1,1,1,0.7071,0.7071,0,0\n",
                    {"quat.csv:2: columns qw,qx,qy,qz: not a unit quaternion"}}, dir);
  expect_bad_input({"rot.json",
                    R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radius": 1, "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, -1]]}]})",
                    {"$.bodies[0].rotation: is a reflection"}}, dir);
  // Within 1e-6 of unit length: accepted (and normalized).
  const auto ok = dir / "ok.json";
  write_file(ok, R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radii": [1, 2, 3], "quaternion": [0.70710678, 0.70710678, 0, 0]},
                                {"id": "b", "center": [5, 0, 0], "radius": 1}]})");
  const Outcome r = run_cli({"check", ok.string()}, dir);
  EXPECT_EQ(r.code, 0) << describe(r);
}

TEST(CliBadInput, MixedDimensions) {
  const auto dir = work_dir();
  expect_bad_input({"mixed.json",
                    R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1}, {"id": "b", "center": [0, 0, 1], "radius": 1}]})",
                    {"$.bodies[1].center: has 3 components, but the scene is 2D", "cannot be mixed"}}, dir);
  expect_bad_input({"mixed2.json",
                    R"({"dimension": 3, "bodies": [{"id": "a", "center": [0, 0, 0], "radius": 1, "angle": 0.5}]})",
                    {"$.bodies[0].angle: an angle orients a 2D body"}}, dir);
  expect_bad_input({"mixed.csv", "a_x,a_y,a_z,a_rx,a_ry,a_rz,b_x,b_y,b_rx,b_ry\n0,0,0,1,1,1,2,2,1,1\n",
                    {"mixed.csv:1: header: column a_z", "cannot be mixed"}}, dir);
}

TEST(CliBadInput, UnknownPairIds) {
  const auto dir = work_dir();
  expect_bad_input({"unknown.json",
                    R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1}, {"id": "b", "center": [3, 0], "radius": 1}],
                        "pairs": [["a", "b"], ["a", "c"]]})",
                    {"$.pairs[1][1]: unknown id \"c\" (no body or obstacle has it)"}}, dir);
  expect_bad_input({"dup.json",
                    R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1}, {"id": "a", "center": [3, 0], "radius": 1}]})",
                    {"$.bodies[1].id: duplicate id \"a\""}}, dir);
  write_file(dir / "pairs.csv", "a,b\na,b\nb,zz\n");
  expect_bad_input({"bodies.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,3,0,1,1\n",
                    {"pairs.csv:3: column b: unknown id \"zz\""},
                    {"--pairs", (dir / "pairs.csv").string()},
                    "pairs.csv"}, dir);
}

TEST(CliBadInput, EmptyFiles) {
  const auto dir = work_dir();
  expect_bad_input({"empty.json", "", {"empty.json: empty file"}}, dir);
  expect_bad_input({"blank.json", "  \n\n", {"blank.json: empty file"}}, dir);
  expect_bad_input({"empty.csv", "", {"empty.csv: empty file"}}, dir);
  expect_bad_input({"header_only.csv", "id,x,y,rx,ry\n", {"header_only.csv: no bodies"}}, dir);
  expect_bad_input({"pairs_header_only.csv", "a_x,a_y,a_rx,a_ry,b_x,b_y,b_rx,b_ry\n", {"pairs_header_only.csv: no pairs"}}, dir);
  expect_bad_input({"no_bodies.json", R"({"bodies": []})", {"$.bodies: empty"}}, dir);
}

TEST(CliBadInput, AnErrorDeepInAStreamLeavesNoOutputFile) {
  const auto dir = work_dir();
  const long rows = 50000;
  const Outcome gen = run_program(make_scene, {"pairs", "--count", std::to_string(rows), "--seed", "9", "-o",
                                           (dir / "pairs.csv").string()}, dir);
  ASSERT_EQ(gen.code, 0) << describe(gen);
  // Break the radius of row 40,000 (line 40,001): several chunks have been written by then.
  std::string text = slurp(dir / "pairs.csv");
  std::size_t pos = 0;
  for (int line = 1; line < 40001; ++line) pos = text.find('\n', pos) + 1;
  const std::size_t comma = text.find(',', text.find(',', pos) + 1);  // after a_x, a_y
  ASSERT_NE(comma, std::string::npos);
  text = text.substr(0, comma + 1) + "-" + text.substr(comma + 1);
  write_file(dir / "pairs.csv", text);
  for (const std::string format : {"json", "csv"}) {
    const Outcome r = run_cli({"check", (dir / "pairs.csv").string(), "--format", format, "-o",
                             (dir / "out.json").string()}, dir);
    EXPECT_EQ(r.code, 2) << describe(r);
    EXPECT_NE(r.err.find("pairs.csv:40001: column a_rx: must be > 0"), std::string::npos) << r.err;
    expect_no_output(dir, "out.json");
  }
}

// A velocity of 1e308 carries a shape beyond the range of double by the window start t0 = 2:
// bad input naming the scene and the body (in a pair of bodies or with an obstacle) or the
// obstacle.
TEST(CliBadInput, ShapesMovedBeyondTheRangeOfDoubleNameTheScene) {
  const auto dir = work_dir();
  const std::string bodies = R"("time_window": [2, 3],
    "bodies": [{"id": "a", "center": [0, 0], "radius": 1, "velocity": [1e308, 0]}, {"id": "b", "center": [5, 0], "radius": 1}])";
  const std::string floor = R"({"id": "floor", "type": "half_space", "point": [0, -5], "normal": [0, 1]})";
  expect_bad_input({"body_pair.json", "{" + bodies + R"(, "pairs": [["a", "b"]]})",
                    {"body_pair.json: body a at t = 2: ", "must be finite"}}, dir);
  expect_bad_input({"body_obstacle.json", "{" + bodies + R"(, "obstacles": [)" + floor + R"(], "pairs": [["a", "floor"]]})",
                    {"body_obstacle.json: body a at t = 2: ", "must be finite"}}, dir);
  expect_bad_input({"obstacle.json", R"({"time_window": [2, 3], "bodies": [{"id": "b", "center": [5, 0], "radius": 1}],
                      "obstacles": [{"id": "rod", "type": "capsule", "p0": [0, 0], "p1": [1, 0], "radius": 1,
                                     "velocity": [1e308, 0]}]})",
                    {"obstacle.json: obstacle rod at t = 2: ", "offset"}}, dir);
}

TEST(CliBadInput, IoErrorsExitWithThree) {
  const auto dir = work_dir();
  const Outcome missing = run_cli({"check", (dir / "nowhere.json").string()}, dir);
  EXPECT_EQ(missing.code, 3) << describe(missing);
  EXPECT_NE(missing.err.find("nowhere.json: cannot open"), std::string::npos);
  const Outcome unwritable = run_cli({"check", (scenes / "swept_2d.json").string(), "-o",
                                    (dir / "no" / "such" / "dir.json").string()}, dir);
  EXPECT_EQ(unwritable.code, 3) << describe(unwritable);
  EXPECT_NE(unwritable.err.find("dir.json"), std::string::npos);
}

// A value nested 75,000 levels deep (a 160 KB file) in time_window, pairs or dimension made
// `check` overflow its stack: parsing and destroying were iterative, but the error message
// printed the value with nlohmann::json::dump(), which recurses once per level. Scenes are now
// rejected before parsing when arrays and objects nest deeper than 64 levels (a scene needs 5),
// and values quoted in messages are cut to 60 characters.
TEST(CliBadInput, DeeplyNestedJsonValueIsRejectedNotACrash) {
  const auto dir = work_dir();
  const int depth = 75000;
  const std::string deep = std::string(depth, '[') + std::string(depth, ']');
  const std::string body = R"({"id": "a", "center": [0, 0], "radius": 1})";
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"deep_time_window.json", "{\"bodies\": [" + body + "],\n \"time_window\": " + deep + "}"},
           {"deep_pairs.json", "{\"bodies\": [" + body + "],\n \"pairs\": [" + deep + "]}"},
           {"deep_dimension.json", "{\"dimension\": " + deep + ",\n \"bodies\": [" + body + "]}"},
           {"deep_object.json", "{\"bodies\": [" + body + "], \"comment\": " +
                                    [] {
                                      std::string o;
                                      for (int i = 0; i < depth; ++i) o += "{\"k\": ";
                                      return o + "1" + std::string(depth, '}');
                                    }() + "}"}}) {
    const int line = name == "deep_time_window.json" || name == "deep_pairs.json" ? 2 : 1;
    expect_bad_input({name, text, {name + ":" + std::to_string(line) + ":", "nested deeper than 64 levels"}}, dir);
  }
  // Brackets inside strings do not count.
  const auto ok = dir / "brackets.json";
  write_file(ok, "{\"title\": \"" + std::string(100, '[') + "\", \"bodies\": [" + body + "]}");
  const Outcome r = run_cli({"check", ok.string()}, dir);
  EXPECT_EQ(r.code, 0) << describe(r);
  // Within the limit, the message quotes the value cut short.
  const std::string nested = std::string(60, '[') + std::string(60, ']');
  expect_bad_input({"nested_window.json", "{\"bodies\": [" + body + "], \"time_window\": " + nested + "}",
                    {"$.time_window: expected [start, end]", "got " + std::string(57, '[') + "...\n"}}, dir);
}

// A bodies CSV with the id caf\xE9 (Latin-1) made `check` exit 0 with output that is not JSON:
// ids were copied byte for byte. CSV ids (bodies, pairs CSV, pairs files) must now be UTF-8,
// checked when read (JSON's parser already rejected such bytes); and text of unknown encoding
// that reaches the output (the scene's file name) is written with U+FFFD in place of bytes that
// are not UTF-8.
TEST(CliBadInput, NonUtf8IdIsRejectedInEveryInputForm) {
  const auto dir = work_dir();
  const std::string cafe = "caf\xE9";
  for (const std::string format : {"json", "csv"}) {
    SCOPED_TRACE(format);
    const std::vector<std::string> args = {"--format", format};
    expect_bad_input({"bodies.csv", "id,x,y,rx,ry\n" + cafe + ",0,0,1,1\nb,1,0,1,1\n",
                      {"bodies.csv:2: column id: not valid UTF-8 (byte 0xE9 at offset 3"}, args}, dir);
    expect_bad_input({"pairs3.csv", "a_id,a_x,a_y,a_z,a_rx,a_ry,a_rz,b_id,b_x,b_y,b_z,b_rx,b_ry,b_rz\n"
                                    "a,0,0,0,1,1,1,b,3,0,0,1,1,1\na,0,0,0,1,1,1,x\xC3\x28,3,0,0,1,1,1\n",
                      {"pairs3.csv:3: column b_id: not valid UTF-8 (byte 0xC3 at offset 1"}, args}, dir);
    expect_bad_input({"scene.json", "{\"bodies\": [{\"id\": \"" + cafe + "\", \"center\": [0, 0], \"radius\": 1}]}",
                      {"scene.json:1:", "malformed JSON", "UTF-8"}, args}, dir);
    write_file(dir / "pairs.csv", "a,b\na,b\n" + cafe + ",b\n");
    std::vector<std::string> with_pairs = {"--pairs", (dir / "pairs.csv").string()};
    with_pairs.insert(with_pairs.end(), args.begin(), args.end());
    expect_bad_input({"bodies_ok.csv", "id,x,y,rx,ry\na,0,0,1,1\nb,1,0,1,1\n",
                      {"pairs.csv:3: column a: not valid UTF-8"}, with_pairs, "pairs.csv"}, dir);
  }
  // Overlong forms, surrogates and code points above U+10FFFF are not UTF-8 either.
  for (const std::string bad : {"\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xE2\x82"})
    expect_bad_input({"bad.csv", "id,x,y,rx,ry\nz" + bad + ",0,0,1,1\n", {"bad.csv:2: column id: not valid UTF-8"}},
                     dir);
}

// UTF-8 ids (2- and 4-byte sequences) come back unchanged in JSON and CSV output; a scene
// whose file name is not UTF-8 still gives valid JSON, the name's bad byte replaced by U+FFFD.
TEST(CliAnswers, Utf8IdsAndNonUtf8FileNamesGiveValidOutput) {
  const auto dir = work_dir();
  const std::string cafe = "caf\xC3\xA9", rocket = "\xF0\x9F\x9A\x80";
  const fs::path scene = dir / "sc\xE9ne.csv";
  write_file(scene, "id,x,y,rx,ry\n" + cafe + ",0,0,1,1\n" + rocket + ",1,0,1,1\n");
  const Outcome j = run_cli({"check", scene.string()}, dir);
  ASSERT_EQ(j.code, 0) << describe(j);
  const json out = parse_json(j.out);
  ASSERT_EQ(out["results"].size(), 1u);
  EXPECT_EQ(out["results"][0]["a"].get<std::string>(), cafe);
  EXPECT_EQ(out["results"][0]["b"].get<std::string>(), rocket);
  EXPECT_EQ(out["results"][0]["relation"].get<std::string>(), "overlapping");
  EXPECT_EQ(out["scene"].get<std::string>(), (dir / "sc\xEF\xBF\xBDne.csv").string());
  const Outcome c = run_cli({"check", scene.string(), "--format", "csv"}, dir);
  ASSERT_EQ(c.code, 0) << describe(c);
  const auto lines = split_lines(c.out);
  ASSERT_EQ(lines.size(), 2u) << c.out;
  EXPECT_EQ(lines[1], "0," + cafe + "," + rocket + ",overlapping");
}

// ------------------------------------------------------------------------------------------
// Render
// ------------------------------------------------------------------------------------------

namespace pt = boost::property_tree;

struct SvgSummary {
  pt::ptree root;
  int bodies = 0, overlapping = 0, contacts = 0, contact_points = 0, normals = 0, starts = 0, paths = 0;
  int obstacles = 0, obstacles_overlapping = 0;
  bool legend = false;
  std::string attr(const char* name) const { return root.get<std::string>(std::string("svg.<xmlattr>.") + name, ""); }
};

void walk(const pt::ptree& node, const std::string& tag, SvgSummary& s) {
  const std::string cls = node.get<std::string>("<xmlattr>.class", "");
  const std::string id = node.get<std::string>("<xmlattr>.id", "");
  if (tag == "ellipse" && (cls == "body" || cls == "body overlapping")) ++s.bodies;
  if (tag == "ellipse" && cls == "body overlapping") ++s.overlapping;
  if (tag == "ellipse" && cls == "start") ++s.starts;
  if (tag == "line" && cls == "path") ++s.paths;
  if (tag == "path" && (cls == "obstacle" || cls == "obstacle overlapping")) ++s.obstacles;
  if (tag == "path" && cls == "obstacle overlapping") ++s.obstacles_overlapping;
  if (tag == "g" && cls == "contact") ++s.contacts;
  if (tag == "circle" && cls == "contact-point") ++s.contact_points;
  if (tag == "line" && cls == "contact-normal") ++s.normals;
  if (tag == "g" && id == "legend") s.legend = true;
  for (const auto& [child_tag, child] : node) walk(child, child_tag, s);
}

SvgSummary read_svg(const fs::path& p) {
  SvgSummary s;
  std::ifstream f(p);
  pt::read_xml(f, s.root);  // throws on malformed XML
  for (const auto& [tag, child] : s.root) walk(child, tag, s);
  return s;
}

TEST(CliRender, SweptSceneAtFirstContact) {
  const auto dir = work_dir();
  const std::string scene = (scenes / "swept_2d.json").string();
  const Outcome r = run_cli({"render", scene, "-o", (dir / "swept.svg").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const SvgSummary s = read_svg(dir / "swept.svg");
  EXPECT_EQ(s.bodies, 3);  // A, B, C
  EXPECT_EQ(s.contacts, 1);
  EXPECT_EQ(s.contact_points, 1);
  EXPECT_EQ(s.normals, 1);
  EXPECT_EQ(s.overlapping, 0);  // touching at the contact time is not overlap
  EXPECT_EQ(s.starts, 1);       // B moves: its start position is drawn
  EXPECT_EQ(s.paths, 1);
  EXPECT_TRUE(s.legend);
  // The default time is the first contact reported by `check`.
  const Outcome c = run_cli({"check", scene}, dir);
  const json out = parse_json(c.out);
  EXPECT_EQ(std::stod(s.attr("data-time")), out["results"][0]["contact"]["time"].get<double>());
  EXPECT_EQ(s.attr("data-bodies"), "3");
}

TEST(CliRender, OverlappingBodiesAreRedAtTheChosenTime) {
  const auto dir = work_dir();
  // Niemitalo example 2: one ellipse inside the other (containment counts as overlap).
  const Outcome r = run_cli({"render", (scenes / "niemitalo_two_ellipses.json").string(), "-o", (dir / "n.svg").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const SvgSummary s = read_svg(dir / "n.svg");
  EXPECT_EQ(s.bodies, 2);
  EXPECT_EQ(s.overlapping, 2);
  EXPECT_EQ(s.contacts, 0);
  // Circles scene at t = 4: B (center (2, 3), r 3) overlaps A; D, E, F overlap or touch A.
  write_file(dir / "circles.json", circles_scene);
  const Outcome r4 = run_cli({"render", (dir / "circles.json").string(), "--time", "4", "-o", (dir / "c.svg").string()}, dir);
  ASSERT_EQ(r4.code, 0) << describe(r4);
  const SvgSummary s4 = read_svg(dir / "c.svg");
  EXPECT_EQ(s4.bodies, 6);
  EXPECT_EQ(s4.attr("data-time"), "4");
  EXPECT_EQ(s4.overlapping, 4);  // A, B, D, E (F only touches A; C is apart)
}

TEST(CliRender, ThreeDimensionalSceneProjectedOntoEachPlane) {
  const auto dir = work_dir();
  for (const std::string plane : {"xy", "yz", "xz"}) {
    const fs::path out = dir / ("swept3d_" + plane + ".svg");
    const Outcome r = run_cli({"render", (scenes / "swept_3d.json").string(), "--plane", plane, "-o", out.string()}, dir);
    ASSERT_EQ(r.code, 0) << describe(r);
    const SvgSummary s = read_svg(out);
    EXPECT_EQ(s.bodies, 2) << plane;
    EXPECT_EQ(s.contact_points, 1) << plane;
    EXPECT_EQ(s.attr("data-plane"), plane);
    EXPECT_EQ(s.attr("data-dimension"), "3");
  }
}

TEST(CliRender, OneRowOfAPairsCsv) {
  const auto dir = work_dir();
  write_file(dir / "inline.csv",
             "a_id,a_x,a_y,a_rx,a_ry,a_angle,a_vx,a_vy,b_id,b_x,b_y,b_rx,b_ry,b_angle,b_vx,b_vy\n"
             "A,0,0,3,1,0.5,0,0,C,-6,-3,1,1,0,0,0\n"
             "A,0,0,3,1,0.5,0,0,B,8,1.5,1.5,0.5,-0.3,-2,-0.25\n");
  const Outcome r = run_cli({"render", (dir / "inline.csv").string(), "--row", "2", "--window", "0", "10", "-o",
                             (dir / "row2.svg").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const SvgSummary s = read_svg(dir / "row2.svg");
  EXPECT_EQ(s.bodies, 2);
  EXPECT_EQ(s.contact_points, 1);
  const Outcome bad = run_cli({"render", (dir / "inline.csv").string(), "--row", "3", "-o", (dir / "row3.svg").string()}, dir);
  EXPECT_EQ(bad.code, 2) << describe(bad);
  EXPECT_NE(bad.err.find("row 3 does not exist"), std::string::npos) << bad.err;
  expect_no_output(dir, "row3.svg");
}

TEST(CliRender, TenThousandBodies) {
  const auto dir = work_dir();
  const Outcome r = run_cli({"render", (scenes / "bodies_10k.csv").string(), "-o", (dir / "b.svg").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const SvgSummary s = read_svg(dir / "b.svg");
  EXPECT_EQ(s.bodies, 10000);
  EXPECT_GT(s.overlapping, 100);
  // The same overlapping bodies as `check` finds.
  const Outcome c = run_cli({"check", (scenes / "bodies_10k.csv").string()}, dir);
  ASSERT_EQ(c.code, 0) << describe(c);
  const json out = parse_json(c.out);
  std::set<std::string> red;
  for (const auto& rec : out["results"])
    if (rec["relation"] != "separated" && rec["relation"] != "touching") {
      red.insert(rec["a"].get<std::string>());
      red.insert(rec["b"].get<std::string>());
    }
  EXPECT_EQ(static_cast<std::size_t>(s.overlapping), red.size());
}

TEST(CliRender, PngThroughRsvgConvert) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) GTEST_SKIP() << "rsvg-convert not installed";
  const auto dir = work_dir();
  const Outcome r = run_cli({"render", (scenes / "swept_2d.json").string(), "-o", (dir / "swept.png").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const std::string png = slurp(dir / "swept.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // No temporary file is left.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// ------------------------------------------------------------------------------------------
// Obstacles: half-spaces, triangles, boxes and meshes (inline, OBJ, STL)
// ------------------------------------------------------------------------------------------

void expect_hit(const json& contact, double time, const std::vector<double>& point, const std::vector<double>& normal) {
  SCOPED_TRACE(contact.dump());
  EXPECT_EQ(contact["status"], "hit");
  EXPECT_NEAR(contact["time"].get<double>(), time, 1e-12 * std::max(1.0, time));
  for (std::size_t i = 0; i < point.size(); ++i) {
    EXPECT_NEAR(contact["point"][i].get<double>(), point[i], 1e-12);
    EXPECT_NEAR(contact["normal"][i].get<double>(), normal[i], 1e-12);
  }
}

// A unit circle falling at speed 2 from (0, 5), and obstacles with closed-form contacts:
// - tilted: the half-plane 0.6 x + 0.8 y <= 0: the center's height above its line is 4 - 1.6 t,
//   1 at t = 1.875, the contact point c(t) - n = (-0.6, 0.45), the normal -n;
// - floor: a triangle with its top edge on y = 0: center height 1 at t = 2, point (0, 0);
// - diamond: a square of half side 1 turned by pi/4 with its top corner at (0, 0): t = 2 (not
//   the 2.207 of an unturned square, whose top is at y = 1 - sqrt(2));
// - mesh: two triangles, the second with its top edge on y = 0: t = 2 on triangle 1; the
//   circle "sitter" at (-15, -1.5) overlaps triangle 0 at the start;
// - wedge: the triangle (0, 0), (3, 2), (3, -2) that the circle "side", moving right along
//   y = 0.5, meets at its vertex (0, 0): center at (-sqrt(3)/2, 0.5), t = 5 - sqrt(3)/2,
//   normal (sqrt(3)/2, -0.5).
const char* obstacles_2d_scene = R"({
  "time_window": [0, 10],
  "bodies": [
    {"id": "ball", "center": [0, 5], "radius": 1, "velocity": [0, -2]},
    {"id": "sitter", "center": [-15, -1.5], "radius": 1},
    {"id": "side", "center": [-5, 0.5], "radius": 1, "velocity": [1, 0]}
  ],
  "obstacles": [
    {"id": "tilted", "type": "half_space", "point": [0, 0], "normal": [3, 4]},
    {"id": "floor", "type": "triangle", "vertices": [[-10, 0], [10, 0], [0, -5]]},
    {"id": "diamond", "type": "box", "center": [0, -1.4142135623730951], "half_extents": [1, 1], "angle": 0.7853981633974483},
    {"id": "mesh", "type": "mesh", "vertices": [[-20, -1], [-10, -1], [-15, -3], [-4, 0], [4, 0], [0, -2]],
     "triangles": [[0, 1, 2], [3, 4, 5]]},
    {"id": "wedge", "type": "triangle", "vertices": [[0, 0], [3, 2], [3, -2]]}
  ],
  "pairs": [["ball", "tilted"], ["ball", "floor"], ["ball", "diamond"], ["ball", "mesh"], ["sitter", "mesh"],
            ["side", "wedge"], ["ball", "sitter"]]
})";

TEST(CliObstacles, FallingCircleMatchesClosedFormsForEveryObstacleType) {
  const auto dir = work_dir();
  write_file(dir / "obstacles.json", obstacles_2d_scene);
  const Outcome r = run_cli({"check", (dir / "obstacles.json").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  EXPECT_EQ(out["obstacles"], 5);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 7u);
  for (std::size_t k = 0; k < 7; ++k)
    if (k != 4) {
      EXPECT_EQ(res[k]["relation"], "separated") << k;
    }
  expect_hit(res[0]["contact"], 1.875, {-0.6, 0.45}, {-0.6, -0.8});
  expect_hit(res[1]["contact"], 2.0, {0, 0}, {0, -1});
  expect_hit(res[2]["contact"], 2.0, {0, 0}, {0, -1});
  expect_hit(res[3]["contact"], 2.0, {0, 0}, {0, -1});
  EXPECT_EQ(res[3]["contact"]["triangle"], 1);
  EXPECT_TRUE(res[3]["relation_triangle"].is_null());
  EXPECT_EQ(res[4]["relation"], "overlapping");
  EXPECT_EQ(res[4]["relation_triangle"], 0);
  EXPECT_EQ(res[4]["contact"]["status"], "overlapping_at_start");
  EXPECT_EQ(res[4]["contact"]["triangle"], 0);
  expect_hit(res[5]["contact"], 5 - std::sqrt(3.0) / 2, {0, 0}, {std::sqrt(3.0) / 2, -0.5});
  // Only mesh records carry triangles.
  EXPECT_FALSE(res[1].contains("relation_triangle"));
  EXPECT_FALSE(res[1]["contact"].contains("triangle"));
  EXPECT_FALSE(res[6].contains("relation_triangle"));
  EXPECT_EQ(out["summary"]["contact"]["hit"], 5);

  // CSV: the same numbers, the triangles in the last columns.
  const Outcome c = run_cli({"check", (dir / "obstacles.json").string(), "-f", "csv"}, dir);
  ASSERT_EQ(c.code, 0) << describe(c);
  const auto lines = split_lines(c.out);
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[0], "index,a,b,relation,contact_status,contact_time,contact_x,contact_y,normal_x,normal_y,"
                      "contact_iterations,relation_triangle,contact_triangle");
  const auto mesh_row = split_csv_line(lines[4]);
  EXPECT_EQ(mesh_row[2], "mesh");
  EXPECT_EQ(std::stod(mesh_row[5]), res[3]["contact"]["time"].get<double>());
  EXPECT_EQ(mesh_row[11], "");
  EXPECT_EQ(mesh_row[12], "1");
  const auto sitter_row = split_csv_line(lines[5]);
  EXPECT_EQ(sitter_row[11], "0");
  EXPECT_EQ(sitter_row[12], "0");
  const auto floor_row = split_csv_line(lines[2]);
  EXPECT_EQ(floor_row.size(), 13u);
  EXPECT_EQ(floor_row[11], "");
  EXPECT_EQ(floor_row[12], "");
}

TEST(CliObstacles, EveryBodyAgainstEveryObstacleWithoutListedPairs) {
  const auto dir = work_dir();
  json scene = json::parse(obstacles_2d_scene);
  scene.erase("pairs");
  write_file(dir / "all.json", scene.dump());
  const Outcome r = run_cli({"check", (dir / "all.json").string(), "--query", "relation,distance"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  // 3 body pairs, then each of the 3 bodies against each of the 5 obstacles.
  ASSERT_EQ(res.size(), 3u + 15u);
  EXPECT_EQ(out["summary"]["pairs"], 18);
  EXPECT_EQ(res[3]["a"], "ball");
  EXPECT_EQ(res[3]["b"], "tilted");
  EXPECT_EQ(res[17]["a"], "side");
  EXPECT_EQ(res[17]["b"], "wedge");
  // Signed distance against every obstacle: the ball's center is 4 above the tilted line and
  // 5 above the floor triangle's top edge.
  EXPECT_EQ(res[3]["distance"]["status"], "separated");
  EXPECT_NEAR(res[3]["distance"]["distance"].get<double>(), 3.0, 1e-14);
  EXPECT_EQ(res[4]["b"], "floor");
  EXPECT_EQ(res[4]["distance"]["status"], "separated");
  EXPECT_NEAR(res[4]["distance"]["distance"].get<double>(), 4.0, 1e-14);
  EXPECT_NEAR(res[4]["distance"]["normal"][1].get<double>(), -1.0, 1e-14);
  EXPECT_FALSE(res[4]["distance"].contains("triangle"));
  // The sitter's center lies inside the mesh's triangle 0 (its deepest); the side circle
  // overlaps the floor's top edge by 0.5.
  EXPECT_EQ(res[11]["a"], "sitter");
  EXPECT_EQ(res[11]["b"], "mesh");
  EXPECT_EQ(res[11]["distance"]["status"], "overlapping");
  EXPECT_EQ(res[11]["distance"]["triangle"], 0);
  EXPECT_EQ(res[14]["b"], "floor");
  EXPECT_NEAR(res[14]["distance"]["distance"].get<double>(), -0.5, 1e-14);
  // Overlapping: the sitter and the side circle below the tilted line, the side circle across
  // the floor, the sitter in the mesh; everything else apart (the body pairs too).
  EXPECT_EQ(out["summary"]["distance"]["separated"], 14);
  EXPECT_EQ(out["summary"]["distance"]["overlapping"], 4);
}

// The floor y <= 0 rising at speed 1 and the ball falling at 2 from height 5 close their gap of
// 4 at t = 4/3; the same with the window starting at t0 = 1 (the obstacle moved there first),
// for the floor as a half-plane and as a moving mesh.
TEST(CliObstacles, MovingObstaclesAndWindowsThatStartLater) {
  const auto dir = work_dir();
  write_file(dir / "rising.json", R"({
    "bodies": [{"id": "ball", "center": [0, 5], "radius": 1, "velocity": [0, -2]}],
    "obstacles": [
      {"id": "plane", "type": "half_space", "point": [0, 0], "normal": [0, 1], "velocity": [0, 1]},
      {"id": "mesh", "type": "mesh", "vertices": [[-5, 0], [5, 0], [0, -3]], "triangles": [[0, 1, 2]], "velocity": [0, 1]}
    ]})");
  for (const std::vector<std::string>& window : {std::vector<std::string>{}, {"--window", "1", "10"}}) {
    std::vector<std::string> args = {"check", (dir / "rising.json").string()};
    args.insert(args.end(), window.begin(), window.end());
    const Outcome r = run_cli(args, dir);
    ASSERT_EQ(r.code, 0) << describe(r);
    const json out = parse_json(r.out);
    ASSERT_EQ(out["results"].size(), 2u);
    for (const auto& rec : out["results"]) expect_hit(rec["contact"], 4.0 / 3, {0, 4.0 / 3}, {0, -1});
  }
}

// The contact normal of the ball on the floor y <= 0 is minus the half-plane's normal (0, 1):
// written (0, -1), not (-0, -1), in JSON and CSV, for the contact and the distance.
TEST(CliObstacles, NormalsAreWrittenWithoutTheSignOfZero) {
  const auto dir = work_dir();
  write_file(dir / "floor.json", R"({
    "bodies": [{"id": "ball", "center": [0, 5], "radius": 1, "velocity": [0, -2]}],
    "obstacles": [{"id": "floor", "type": "half_space", "point": [0, 0], "normal": [0, 1]}]})");
  const Outcome r = run_cli({"check", (dir / "floor.json").string(), "--query", "relation,contact,distance"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  EXPECT_NE(r.out.find(R"("time": 2, "point": [0, 0], "normal": [0, -1])"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(R"("point_b": [0, 0], "normal": [0, -1])"), std::string::npos) << r.out;
  const Outcome c = run_cli({"check", (dir / "floor.json").string(), "--query", "relation,contact,distance", "-f", "csv"},
                            dir);
  ASSERT_EQ(c.code, 0) << describe(c);
  const auto lines = split_lines(c.out);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "0,ball,floor,separated,hit,2,0,0,0,-1,0,separated,4,0,4,0,0,0,-1,0");
}

// The cube [-1, 1]^3 as a box, as an OBJ (quads, every index form, negative indices, lines
// to ignore, CRLF) and as ASCII and binary STL, all with the same 12 triangles in the same
// order: two per face, the faces -x, +x, -y, +y, -z, +z.
const int cube_quads[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

Eigen::Vector3f cube_corner(int k) {
  return Eigen::Vector3f(k & 1 ? 1.f : -1.f, k & 2 ? 1.f : -1.f, k & 4 ? 1.f : -1.f);
}

// The triangles (0, 1, 2) and (0, 2, 3) of each quad.
std::vector<std::array<Eigen::Vector3f, 3>> cube_triangles() {
  std::vector<std::array<Eigen::Vector3f, 3>> t;
  for (const auto& q : cube_quads)
    for (int j = 1; j <= 2; ++j) t.push_back({cube_corner(q[0]), cube_corner(q[j]), cube_corner(q[j + 1])});
  return t;
}

const char* cube_obj =
    "# the cube [-1, 1]^3\r\nmtllib cube.mtl\no cube\n"
    "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1 1.0\n"
    "vt 0 0\nvn 1 0 0\ng faces\nusemtl grey\ns off\n\n"
    "f 1 3 7 5\n"
    "f 2/1 4/1 8/1 6/1\n"
    "f 1//1 2//1 6//1 5//1  # a comment\n"
    "f 3/1/1 4/1/1 8/1/1 7/1/1\r\n"
    "f -8 -7 -5 -6\n"
    "f 5 6 8 7\n";

std::string cube_ascii_stl() {
  std::string s = "solid cube\n";
  for (const auto& t : cube_triangles()) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (const auto& v : t)
      s += "      vertex " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid cube\n";
}

// Binary STL: an 80-byte header, the triangle count, then per triangle a normal, three
// vertices (little-endian floats) and two attribute bytes. This machine is little-endian
// (checked by the test).
std::string stl_binary(const std::vector<std::array<Eigen::Vector3f, 3>>& triangles) {
  std::string s = "binary cube";
  s.resize(80, ' ');
  const auto count = static_cast<std::uint32_t>(triangles.size());
  s.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : triangles) {
    const float normal[3] = {0, 0, 0};
    s.append(reinterpret_cast<const char*>(normal), 12);
    for (const auto& v : t) s.append(reinterpret_cast<const char*>(v.data()), 12);
    s.append(2, '\0');
  }
  return s;
}

// Spheres against the cube, closed forms:
//   s1 (r 0.5) from (5, 0.2, 0.3) at (-1, 0, 0): meets the face x = 1 at t = 3.5 at
//      (1, 0.2, 0.3), inside the face's second triangle (z > y): triangle 3;
//   s2 (r 1) from (3, 3, 0) at (-1, -1, 0): meets the edge x = y = 1 when sqrt(2) (2 - t) = 1,
//      at (1, 1, 0), normal (-1, -1, 0) / sqrt(2);
//   s3 (r 0.2) at the center: inside the solid box, apart from the surface meshes;
//   s4 (r 0.5) at (1.2, 0, 0): overlaps the face x = 1, first on triangle 2 (the point (1, 0, 0)
//      lies on the face's diagonal, shared by triangles 2 and 3).
TEST(CliObstacles, SphereAgainstObjAndStlCubesAnswersAsTheBox) {
  const std::uint32_t one = 1;
  ASSERT_EQ(*reinterpret_cast<const unsigned char*>(&one), 1) << "the binary STL writer assumes little-endian";
  const auto dir = work_dir();
  fs::create_directories(dir / "meshes");
  write_file(dir / "meshes" / "cube.obj", cube_obj);
  write_file(dir / "meshes" / "cube.stl", cube_ascii_stl());
  write_file(dir / "meshes" / "cube_binary.STL", stl_binary(cube_triangles()));
  write_file(dir / "cubes.json", R"({
    "time_window": [0, 10],
    "bodies": [
      {"id": "s1", "center": [5, 0.2, 0.3], "radius": 0.5, "velocity": [-1, 0, 0]},
      {"id": "s2", "center": [3, 3, 0], "radius": 1, "velocity": [-1, -1, 0]},
      {"id": "s3", "center": [0, 0, 0], "radius": 0.2},
      {"id": "s4", "center": [1.2, 0, 0], "radius": 0.5}
    ],
    "obstacles": [
      {"id": "box", "type": "box", "center": [0, 0, 0], "half_extents": [1, 1, 1]},
      {"id": "obj", "type": "mesh", "file": "meshes/cube.obj"},
      {"id": "ascii", "type": "mesh", "file": "meshes/cube.stl"},
      {"id": "binary", "type": "mesh", "file": "meshes/cube_binary.STL"}
    ]})");
  const Outcome r = run_cli({"check", (dir / "cubes.json").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 6u + 16u);
  const double h = 1 / std::sqrt(2.0);
  for (int body = 0; body < 4; ++body)
    for (int o = 0; o < 4; ++o) {
      const json& rec = res[static_cast<std::size_t>(6 + 4 * body + o)];
      SCOPED_TRACE(rec.dump());
      static const char* const ids[] = {"s1", "s2", "s3", "s4"};
      EXPECT_EQ(rec["a"], ids[body]);
      const bool mesh = o > 0;
      EXPECT_EQ(rec.contains("relation_triangle"), mesh);
      if (body == 0) {
        EXPECT_EQ(rec["relation"], "separated");
        expect_hit(rec["contact"], 3.5, {1, 0.2, 0.3}, {-1, 0, 0});
        if (mesh) {
          EXPECT_EQ(rec["contact"]["triangle"], 3);
        }
      } else if (body == 1) {
        EXPECT_EQ(rec["relation"], "separated");
        expect_hit(rec["contact"], 2 - h, {1, 1, 0}, {-h, -h, 0});
        // The edge's triangles: 2 (+x face) and 6 (+y face).
        if (mesh) {
          EXPECT_TRUE(rec["contact"]["triangle"] == 2 || rec["contact"]["triangle"] == 6);
        }
      } else if (body == 2) {
        EXPECT_EQ(rec["relation"], mesh ? "separated" : "b_contains_a");
        EXPECT_EQ(rec["contact"]["status"], mesh ? "no_contact_in_window" : "overlapping_at_start");
      } else {
        EXPECT_EQ(rec["relation"], "overlapping");
        EXPECT_EQ(rec["contact"]["status"], "overlapping_at_start");
        if (mesh) {
          EXPECT_EQ(rec["relation_triangle"], 2);
        }
      }
    }
  // The pictures: every obstacle drawn, the box and the meshes red where s4 overlaps them.
  for (const std::string plane : {"xy", "xz"}) {
    const fs::path svg = dir / ("cubes_" + plane + ".svg");
    const Outcome rr = run_cli({"render", (dir / "cubes.json").string(), "--time", "0", "--plane", plane, "-o",
                               svg.string()}, dir);
    ASSERT_EQ(rr.code, 0) << describe(rr);
    const SvgSummary s = read_svg(svg);
    EXPECT_EQ(s.obstacles, 4);
    EXPECT_EQ(s.obstacles_overlapping, 4);
    EXPECT_EQ(s.attr("data-obstacles"), "4");
  }
}

// The bundled scenes: B (r 0.5) falls at 1.5 from (6, 0, 4) onto the apex of the binary STL
// tetrahedron, (6, 0, 1.6) rounded to float: t = (3.5 - float(1.6)) / 1.5.
TEST(CliObstacles, BundledObstacleScenes) {
  const auto dir = work_dir();
  const Outcome r2 = run_cli({"check", (scenes / "obstacles_2d.json").string()}, dir);
  ASSERT_EQ(r2.code, 0) << describe(r2);
  EXPECT_EQ(parse_json(r2.out)["results"].size(), 3u + 3u * 4u);
  const Outcome r3 = run_cli({"check", (scenes / "obstacles_3d.json").string()}, dir);
  ASSERT_EQ(r3.code, 0) << describe(r3);
  const json out = parse_json(r3.out);
  ASSERT_EQ(out["results"].size(), 3u + 3u * 4u);
  const json& tetrahedron = out["results"][9];
  ASSERT_EQ(tetrahedron["a"], "B");
  ASSERT_EQ(tetrahedron["b"], "tetrahedron");
  const double apex = static_cast<double>(1.6f);
  expect_hit(tetrahedron["contact"], (3.5 - apex) / 1.5, {6, 0, apex}, {0, 0, -1});
  for (const std::string scene : {"obstacles_2d.json", "obstacles_3d.json"}) {
    const Outcome p = run_cli({"render", (scenes / scene).string(), "-o", (dir / (scene + ".svg")).string()}, dir);
    ASSERT_EQ(p.code, 0) << describe(p);
    EXPECT_EQ(read_svg(dir / (scene + ".svg")).obstacles, 4);
  }
}

TEST(CliObstacles, RenderDrawsObstaclesRedWhenABodyOverlapsThem) {
  const auto dir = work_dir();
  write_file(dir / "obstacles.json", obstacles_2d_scene);
  // At the first contact (the tilted half-plane, t = 1.875) only the sitter overlaps: the mesh.
  const Outcome r = run_cli({"render", (dir / "obstacles.json").string(), "-o", (dir / "first.svg").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const SvgSummary s = read_svg(dir / "first.svg");
  EXPECT_NEAR(std::stod(s.attr("data-time")), 1.875, 1e-14);
  EXPECT_EQ(s.obstacles, 5);
  EXPECT_EQ(s.obstacles_overlapping, 1);
  EXPECT_EQ(s.overlapping, 1);  // the sitter
  EXPECT_EQ(s.contact_points, 5);
  // At t = 3 the ball is below y = 0: inside the tilted half-plane, the floor, the diamond
  // and the mesh; the side circle (center (-2, 0.5)) is still apart from the wedge.
  const Outcome r3 = run_cli({"render", (dir / "obstacles.json").string(), "--time", "3", "-o", (dir / "t3.svg").string()}, dir);
  ASSERT_EQ(r3.code, 0) << describe(r3);
  const SvgSummary s3 = read_svg(dir / "t3.svg");
  EXPECT_EQ(s3.obstacles_overlapping, 4);
  EXPECT_EQ(s3.attr("data-obstacles-overlapping"), "4");
  EXPECT_EQ(s3.overlapping, 2);  // the ball and the sitter
}

TEST(CliObstacles, PairsFilesNameObstaclesInColumnB) {
  const auto dir = work_dir();
  json scene = json::parse(obstacles_2d_scene);
  scene.erase("pairs");
  write_file(dir / "scene.json", scene.dump());
  write_file(dir / "pairs.csv", "a,b\nball,floor\nside,wedge\n");
  const Outcome r = run_cli({"check", (dir / "scene.json").string(), "--pairs", (dir / "pairs.csv").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  ASSERT_EQ(out["results"].size(), 2u);
  expect_hit(out["results"][0]["contact"], 2.0, {0, 0}, {0, -1});
  write_file(dir / "bad_pairs.csv", "a,b\nball,floor\nfloor,ball\n");
  expect_bad_input({"scene2.json", scene.dump(), {"bad_pairs.csv:3: \"floor\" is an obstacle"},
                    {"--pairs", (dir / "bad_pairs.csv").string()}, "bad_pairs.csv"}, dir);
}

TEST(CliObstacles, MalformedObstaclesNameTheField) {
  const auto dir = work_dir();
  const std::string head2 = R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1}], "obstacles": [)";
  const std::string head3 = R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radius": 1}], "obstacles": [)";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {head2 + R"({"id": "o", "type": "sphere"}]})", "$.obstacles[0].type: unknown obstacle type \"sphere\""},
      {head2 + R"({"type": "triangle"}]})", "$.obstacles[0].id: missing"},
      {head2 + R"({"id": "o", "type": "triangle", "vertices": [[0, 0], [1, 0]]}]})",
       "$.obstacles[0].vertices: expected 3 vertices, got 2"},
      {head2 + R"({"id": "o", "type": "triangle", "vertices": [[0, 0], [1, 0], [0, 1, 2]]}]})",
       "$.obstacles[0].vertices[2]: has 3 components, but the scene is 2D"},
      {head2 + R"({"id": "o", "type": "half_space", "point": [0, 0], "normal": [0, 0]}]})", "$.obstacles[0].normal: "},
      {head2 + R"({"id": "o", "type": "half_space", "normal": [0, 1]}]})", "$.obstacles[0].point: missing"},
      {head2 + R"({"id": "o", "type": "box", "center": [0, 0], "half_extents": [1, -1]}]})",
       "$.obstacles[0].half_extents[1]: "},
      {head3 + R"({"id": "o", "type": "box", "center": [0, 0, 0], "half_extents": [1, 1, 1], "quaternion": [1, 0.1, 0, 0]}]})",
       "$.obstacles[0].quaternion: not a unit quaternion"},
      {head2 + R"({"id": "o", "type": "mesh", "vertices": [[0, 0], [1, 0], [0, 1], [1, 1]], "triangles": [[0, 1, 2], [1, 3, 7]]}]})",
       "$.obstacles[0].triangles[1][2]: vertex index 7 is not in [0, 4)"},
      {head2 + R"({"id": "o", "type": "mesh", "vertices": [[0, 0], [1, 0], [0, 1]], "triangles": [[0, 1]]}]})",
       "$.obstacles[0].triangles[0]: expected 3 vertex indices"},
      {head2 + R"({"id": "o", "type": "mesh", "vertices": [[0, 0], [1, 0], [0, 1]], "triangles": [[0, 1, 1.5]]}]})",
       "$.obstacles[0].triangles[0][2]: expected a vertex index (an integer), got a number"},
      {head2 + R"({"id": "o", "type": "mesh", "file": "cube.obj"}]})", "$.obstacles[0].file: mesh files (OBJ, STL) are 3D"},
      {head3 + R"({"id": "o", "type": "mesh", "file": "cube.obj", "vertices": []}]})",
       "$.obstacles[0].file: give either a file or vertices and triangles"},
      {head2 + R"({"id": "a", "type": "half_space", "point": [0, 0], "normal": [0, 1]}]})",
       "$.obstacles[0].id: duplicate id \"a\" (also $.bodies[0])"},
      {head2 + R"({"id": "o", "type": "half_space", "point": [0, 0], "normal": [0, 1], "colour": "red"}]})",
       "$.obstacles[0].colour: unknown key"},
      {head2 + R"({"id": "o", "type": "half_space", "point": [0, 0], "normal": [0, 1]}], "pairs": [["o", "a"]]})",
       "$.pairs[0]: \"o\" is an obstacle"},
      {R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1}], "obstacles": {}})",
       "$.obstacles: expected an array of obstacles"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k)
    expect_bad_input({"bad" + std::to_string(k) + ".json", cases[k].first, {cases[k].second}}, dir);
}

TEST(CliObstacles, MalformedMeshFilesNameTheFileAndLine) {
  const auto dir = work_dir();
  const auto scene_with = [](const std::string& file) {
    return R"({"bodies": [{"id": "a", "center": [0, 0, 5], "radius": 1}], "obstacles": [{"id": "m", "type": "mesh", "file": ")" +
           file + R"("}]})";
  };
  const auto stl_triangle = cube_triangles()[0];
  std::string nan_stl = stl_binary({stl_triangle});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan_stl[84 + 12 + 12 + 8], &nan, 4);  // vertex 1, z
  std::string short_stl = stl_binary(cube_triangles());
  short_stl.resize(short_stl.size() - 7);
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "index.obj:4: f: vertex 3 of the face: index 9 refers to no vertex"},
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero.obj:4: f: vertex 1 of the face: index 0"},
      {"negative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n", "negative.obj:3: f: vertex 3 of the face: index -3 refers to no vertex"},
      {"nan.obj", "v 0 0 0\nv 1 nan 0\n", "nan.obj:2: v: y: must be finite, got \"nan\""},
      {"short_v.obj", "v 0 0\n", "short_v.obj:1: v: expected x y z, got 2 numbers"},
      {"two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "two.obj:4: f: a face needs at least 3 vertices, got 2"},
      {"word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/1\n", "word.obj:4: f: vertex 3 of the face: not a vertex index: \"x/1\""},
      {"faceless.obj", "v 0 0 0\n", "faceless.obj: no faces"},
      {"short.stl", short_stl, "short.stl: truncated binary STL: its header counts 12 triangles (84 + 50 * 12 = 684 bytes), the file has 677 bytes"},
      {"tiny.stl", std::string("\x01\x02\x03", 3), "tiny.stl: truncated binary STL: 3 bytes"},
      {"nan.stl", nan_stl, "nan.stl: triangle 0, vertex 1, coordinate 2: must be finite, got nan"},
      {"loop.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid x\n",
       "loop.stl:6: endloop: a facet has 3 vertices, this one 2"},
      {"open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "open.stl:4: the file ends inside a facet"},
      {"word.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n", "word.stl:4: vertex: z: not a number: \"zero\""},
      {"cube.ply", "ply\n", "cube.ply: unknown mesh file type"},
  };
  for (const auto& [file, content, message] : cases) {
    write_file(dir / file, content);
    expect_bad_input({"scene_" + file + ".json", scene_with(file),
                      {"$.obstacles[0].file: " + (dir / file).string(), message}}, dir);
  }
  // A missing mesh file is an I/O error (exit status 3) naming the scene, the field and the file.
  expect_bad_input({"missing.json", scene_with("nowhere.stl"), {"$.obstacles[0].file: ", "nowhere.stl: cannot open"}},
                   dir, 3);
  // So is a path that is not a regular file.
  fs::create_directories(dir / "dir.obj");
  expect_bad_input({"directory.json", scene_with("dir.obj"), {"dir.obj: not a regular file"}}, dir, 3);
}

// ------------------------------------------------------------------------------------------
// Capsules (stadiums in 2D)
// ------------------------------------------------------------------------------------------

void expect_distance(const json& distance, const char* status, double value, const std::vector<double>& point_a,
                     const std::vector<double>& point_b, const std::vector<double>& normal) {
  SCOPED_TRACE(distance.dump());
  EXPECT_EQ(distance["status"], status);
  EXPECT_NEAR(distance["distance"].get<double>(), value, 1e-12 * std::max(1.0, std::abs(value)));
  for (std::size_t i = 0; i < normal.size(); ++i) {
    EXPECT_NEAR(distance["point_a"][i].get<double>(), point_a[i], 1e-12);
    EXPECT_NEAR(distance["point_b"][i].get<double>(), point_b[i], 1e-12);
    EXPECT_NEAR(distance["normal"][i].get<double>(), normal[i], 1e-12);
  }
}

// The bar: the points within 0.5 of the segment (-3, 0)..(3, 0): its top edge y = 0.5 for
// |x| <= 3, half discs of radius 0.5 round (-3, 0) and (3, 0). Closed forms:
// - ball (r 1) falls at 2 from (0, 5): its center's height above the segment, 5 - 2t, is
//   1 + 0.5 at t = 1.75, touching the top edge at (0, 0.5), normal (0, -1); at t = 0 the gap
//   is 5 - 1.5 = 3.5 between (0, 4) and (0, 0.5);
// - side (r 1) moves at -2 along y = 1.2 from x = 10 towards the end disc round (3, 0): its
//   center is 1.5 from (3, 0) when (x - 3)^2 + 1.2^2 = 1.5^2, x = 3.9, t = (10 - 3.9) / 2 =
//   3.05; normal (3 - 3.9, -1.2) / 1.5 = (-0.6, -0.8), point (3, 0) + 0.5 (0.6, 0.8) =
//   (3.3, 0.4); at t = 0 the gap is |(7, 1.2)| - 1.5 = sqrt(50.44) - 1.5;
// - away (r 1) rises at 1 from (0, 5): never meets the bar;
// - sunk (r 1) at (0, 1) reaches down to y = 0, 0.5 into the bar: overlapping, distance -0.5
//   from its lowest point (0, 0) to the top edge's (0, 0.5), normal (0, -1);
// - small (r 0.2) at (1, 0), on the segment: inside the bar (b_contains_a), the bar to be
//   moved 0.5 + 0.2 across it to clear it: distance -0.7;
// - big (r 10) at the origin: the bar's farthest point is 3.5 away: the bar is inside it
//   (a_contains_b), the bar to be moved 10 + 0.5 across the segment to clear it: -10.5.
const char* capsule_2d_scene = R"({
  "time_window": [0, 10],
  "bodies": [
    {"id": "ball", "center": [0, 5], "radius": 1, "velocity": [0, -2]},
    {"id": "side", "center": [10, 1.2], "radius": 1, "velocity": [-2, 0]},
    {"id": "away", "center": [0, 5], "radius": 1, "velocity": [0, 1]},
    {"id": "sunk", "center": [0, 1], "radius": 1},
    {"id": "small", "center": [1, 0], "radius": 0.2},
    {"id": "big", "center": [0, 0], "radius": 10}
  ],
  "obstacles": [{"id": "bar", "type": "capsule", "p0": [-3, 0], "p1": [3, 0], "radius": 0.5}],
  "pairs": [["ball", "bar"], ["side", "bar"], ["away", "bar"], ["sunk", "bar"], ["small", "bar"], ["big", "bar"]]
})";

TEST(CliCapsules, CirclesAgainstAHorizontalCapsuleMatchClosedForms) {
  const auto dir = work_dir();
  write_file(dir / "bar.json", capsule_2d_scene);
  const Outcome r = run_cli({"check", (dir / "bar.json").string(), "--query", "relation,contact,distance"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  EXPECT_EQ(out["obstacles"], 1);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 6u);
  const char* const relations[] = {"separated", "separated", "separated", "overlapping", "b_contains_a", "a_contains_b"};
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(res[k]["relation"], relations[k]) << k;
  expect_hit(res[0]["contact"], 1.75, {0, 0.5}, {0, -1});
  expect_distance(res[0]["distance"], "separated", 3.5, {0, 4}, {0, 0.5}, {0, -1});
  expect_hit(res[1]["contact"], 3.05, {3.3, 0.4}, {-0.6, -0.8});
  EXPECT_NEAR(res[1]["distance"]["distance"].get<double>(), std::sqrt(50.44) - 1.5, 1e-12);
  EXPECT_EQ(res[2]["contact"]["status"], "no_contact_in_window");
  EXPECT_TRUE(res[2]["contact"]["time"].is_null());
  expect_distance(res[3]["distance"], "overlapping", -0.5, {0, 0}, {0, 0.5}, {0, -1});
  for (std::size_t k = 3; k < 6; ++k) EXPECT_EQ(res[k]["contact"]["status"], "overlapping_at_start") << k;
  EXPECT_EQ(res[4]["distance"]["status"], "overlapping");
  EXPECT_NEAR(res[4]["distance"]["distance"].get<double>(), -0.7, 1e-12);
  EXPECT_NEAR(res[5]["distance"]["distance"].get<double>(), -10.5, 1e-12);
  // Capsule records carry no triangles.
  EXPECT_FALSE(res[0].contains("relation_triangle"));
  EXPECT_FALSE(res[0]["contact"].contains("triangle"));
  EXPECT_FALSE(res[0]["distance"].contains("triangle"));

  // CSV: the same numbers, no triangle columns.
  const Outcome c = run_cli({"check", (dir / "bar.json").string(), "--query", "relation,contact,distance", "-f", "csv"},
                            dir);
  ASSERT_EQ(c.code, 0) << describe(c);
  const auto lines = split_lines(c.out);
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0], "index,a,b,relation,contact_status,contact_time,contact_x,contact_y,normal_x,normal_y,"
                      "contact_iterations,distance_status,distance,point_a_x,point_a_y,point_b_x,point_b_y,"
                      "distance_normal_x,distance_normal_y,distance_iterations");
  for (std::size_t k = 0; k < 2; ++k) {
    const auto row = split_csv_line(lines[k + 1]);
    ASSERT_EQ(row.size(), 20u);
    const json& rec = res[k];
    EXPECT_EQ(row[2], "bar");
    EXPECT_EQ(row[4], "hit");
    EXPECT_EQ(std::stod(row[5]), rec["contact"]["time"].get<double>());
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(std::stod(row[6 + i]), rec["contact"]["point"][i].get<double>());
      EXPECT_EQ(std::stod(row[8 + i]), rec["contact"]["normal"][i].get<double>());
      EXPECT_EQ(std::stod(row[17 + i]), rec["distance"]["normal"][i].get<double>());
    }
    EXPECT_EQ(row[11], "separated");
    EXPECT_EQ(std::stod(row[12]), rec["distance"]["distance"].get<double>());
  }
}

// The bar rising at 1 and the ball falling at 2 close their gap of 3.5 at t = 7/6, the bar's
// top edge then at 7/6 + 0.5 = 5/3 (the ball's center at 5 - 7/3 = 8/3, 1 above); with the
// window starting at t0 = 1 (the bar moved there first) the gap at t0 is 3 - 1.5 = 0.5.
TEST(CliCapsules, MovingCapsuleAndWindowsThatStartLater) {
  const auto dir = work_dir();
  write_file(dir / "rising.json", R"({
    "bodies": [{"id": "ball", "center": [0, 5], "radius": 1, "velocity": [0, -2]}],
    "obstacles": [{"id": "bar", "type": "capsule", "p0": [-3, 0], "p1": [3, 0], "radius": 0.5, "velocity": [0, 1]}]})");
  for (const auto& [start, t0, gap] : {std::tuple{"0", 0.0, 3.5}, std::tuple{"1", 1.0, 0.5}}) {
    const Outcome r = run_cli({"check", (dir / "rising.json").string(), "--window", start, "10", "--query",
                               "relation,contact,distance"}, dir);
    ASSERT_EQ(r.code, 0) << describe(r);
    const json out = parse_json(r.out);
    ASSERT_EQ(out["results"].size(), 1u);
    const json& rec = out["results"][0];
    EXPECT_EQ(rec["relation"], "separated");
    expect_hit(rec["contact"], 7.0 / 6, {0, 5.0 / 3}, {0, -1});
    expect_distance(rec["distance"], "separated", gap, {0, 4 - 2 * t0}, {0, 0.5 + t0}, {0, -1});
  }
}

// 3D, closed forms:
// - E (radii 2, 1, 0.5 along x, y, z) falls at 1 from (0, 0, 3) onto the rod (radius 0.5 round
//   the y axis from y = -2 to 2): across the rod (along x) E's underside rises as x^2 / 16 and
//   the rod's top falls as x^2, so they first meet at E's lowest point (0, 0, 2.5 - t) and
//   the rod's top (0, 0, 0.5): t = 2, normal (0, 0, -1); the gap at t = 0 is 2;
// - S (r 1) falls at 2 from (1, 1, 4) onto diag (radius 0.5 round (-2, -2, 0)..(2, 2, 0),
//   which passes under S's center at (1, 1, 0)): 4 - 2t = 1.5 at t = 1.25, at (1, 1, 0.5).
// Seen along y (plane xz) the rod is the disc of radius 0.5 round the origin.
TEST(CliCapsules, EllipsoidsAgainstCapsulesIn3D) {
  const auto dir = work_dir();
  write_file(dir / "rods.json", R"({
    "time_window": [0, 10],
    "bodies": [
      {"id": "E", "center": [0, 0, 3], "radii": [2, 1, 0.5], "velocity": [0, 0, -1]},
      {"id": "S", "center": [1, 1, 4], "radius": 1, "velocity": [0, 0, -2]}
    ],
    "obstacles": [
      {"id": "rod", "type": "capsule", "p0": [0, -2, 0], "p1": [0, 2, 0], "radius": 0.5},
      {"id": "diag", "type": "capsule", "p0": [-2, -2, 0], "p1": [2, 2, 0], "radius": 0.5}
    ],
    "pairs": [["E", "rod"], ["S", "diag"]]})");
  const Outcome r = run_cli({"check", (dir / "rods.json").string(), "--query", "relation,contact,distance"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 2u);
  EXPECT_EQ(res[0]["relation"], "separated");
  expect_hit(res[0]["contact"], 2.0, {0, 0, 0.5}, {0, 0, -1});
  expect_distance(res[0]["distance"], "separated", 2.0, {0, 0, 2.5}, {0, 0, 0.5}, {0, 0, -1});
  EXPECT_EQ(res[1]["relation"], "separated");
  expect_hit(res[1]["contact"], 1.25, {1, 1, 0.5}, {0, 0, -1});
  expect_distance(res[1]["distance"], "separated", 2.5, {1, 1, 3}, {1, 1, 0.5}, {0, 0, -1});
  // Drawn as stadiums: two sides and two half circles each (for the rod seen along its axis,
  // sides of length 0: its disc). Red at t = 2.5, E's lowest point (0, 0, 0) and S's center
  // (1, 1, -1) then inside the rod and diag.
  for (const std::string plane : {"xy", "xz"}) {
    const fs::path svg = dir / ("rods_" + plane + ".svg");
    const Outcome p = run_cli({"render", (dir / "rods.json").string(), "--plane", plane, "--time", "2.5", "-o",
                               svg.string()}, dir);
    ASSERT_EQ(p.code, 0) << describe(p);
    const SvgSummary s = read_svg(svg);
    EXPECT_EQ(s.obstacles, 2);
    EXPECT_EQ(s.obstacles_overlapping, 2);
    const std::string text = slurp(svg);
    const std::string key = "data-type=\"capsule\" d=\"";
    std::size_t capsules = 0;
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
      ++capsules;
      const std::size_t begin = at + key.size();
      const std::string d = text.substr(begin, text.find('"', begin) - begin);
      EXPECT_EQ(std::count(d.begin(), d.end(), 'L'), 2) << d;
      EXPECT_EQ(std::count(d.begin(), d.end(), 'A'), 2) << d;
    }
    EXPECT_EQ(capsules, 2u);
  }
}

TEST(CliCapsules, MalformedCapsulesNameTheField) {
  const auto dir = work_dir();
  const std::string head2 = R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1}], "obstacles": [)";
  const std::string head3 = R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radius": 1}], "obstacles": [)";
  const std::string capsule = R"({"id": "o", "type": "capsule", )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {head2 + capsule + R"("p0": [0, 0], "radius": 1}]})", "$.obstacles[0].p1: missing"},
      {head2 + capsule + R"("p1": [0, 0], "radius": 1}]})", "$.obstacles[0].p0: missing"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0]}]})", "$.obstacles[0].radius: missing"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0], "radius": 0}]})", "$.obstacles[0].radius: must be > 0 (got 0)"},
      {head3 + capsule + R"("p0": [0, 0, 0], "p1": [1, 0, 0], "radius": -0.5}]})",
       "$.obstacles[0].radius: must be > 0 (got -0.5)"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0], "radius": "NaN"}]})",
       "$.obstacles[0].radius: expected a number, got a string"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0], "radius": null}]})",
       "$.obstacles[0].radius: expected a number, got null"},
      {head2 + capsule + R"("p0": [0, "Infinity"], "p1": [1, 0], "radius": 1}]})",
       "$.obstacles[0].p0[1]: expected a number, got a string"},
      {head2 + capsule + R"("p0": 0, "p1": [1, 0], "radius": 1}]})",
       "$.obstacles[0].p0: expected an array of 2 numbers, got a number"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0, 0], "radius": 1}]})",
       "$.obstacles[0].p1: has 3 components, but the scene is 2D"},
      {head3 + capsule + R"("p0": [0, 0, 0], "p1": [1, 0], "radius": 1}]})",
       "$.obstacles[0].p1: has 2 components, but the scene is 3D"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0], "radius": 1, "velocity": [1, 0, 0]}]})",
       "$.obstacles[0].velocity: has 3 components, but the scene is 2D"},
      {head2 + capsule + R"("p0": [0, 0], "p1": [1, 0], "radius": 1, "center": [0, 0]}]})",
       "$.obstacles[0].center: unknown key (allowed here: id, type, p0, p1, radius, velocity, comment)"},
      {head2 + R"({"id": "o", "type": "stadium"}]})", "(half_space, triangle, box, capsule or mesh)"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k)
    expect_bad_input({"bad" + std::to_string(k) + ".json", cases[k].first, {cases[k].second}}, dir);
  // A radius beyond the range of double never reaches the scene: the JSON number is rejected.
  expect_bad_input({"huge.json", head2 + capsule + R"("p0": [0, 0], "p1": [1, 0], "radius": 1e999}]})",
                    {"huge.json:1:", "number 1e999 is out of range"}}, dir);
}

// The bundled scene, closed forms:
// - E (radii 1.5, 0.6 along x, y) falls at 1 from (0, 5): its lowest point (0, 4.4 - t)
//   meets the bar's flat top y = 0.5 (|x| <= 4) at t = 3.9, normal (0, -1);
// - C (r 0.8) rolls at 2 along y = 7 from x = -2 to the peg, the disc of radius 0.7 round
//   (6, 7): centers 1.5 apart at x = 4.5, t = 3.25, point (5.3, 7), normal (1, 0);
// - B (r 1) falls at 2 from (-6, 9); the arm (radius 0.4) slides at 1 along x, its segment
//   (-9 + t, 2)..(-6 + t, 5) on the line y = x + 11 - t, from which B's center (-6, 9 - 2t)
//   is (9 - 2t + 6 - 11 + t) / sqrt(2) = (4 - t) / sqrt(2) away: 1.4 at t = 4 - 1.4 sqrt(2)
//   (about 2.02; the center's foot on the line is then (10 - 3t) / sqrt(2), about 2.79, along
//   the segment of length 3 sqrt(2) from its first end), at the center moved 1 along the
//   normal (1, -1) / sqrt(2): (-6 + sqrt(2) / 2, 1 + 2.8 sqrt(2) - sqrt(2) / 2).
TEST(CliCapsules, BundledCapsuleScene) {
  const auto dir = work_dir();
  const fs::path scene = scenes / "obstacles_capsule.json";
  const Outcome r = run_cli({"check", scene.string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 3u + 3u * 3u);
  EXPECT_EQ(res[3]["a"], "E");
  EXPECT_EQ(res[3]["b"], "bar");
  expect_hit(res[3]["contact"], 3.9, {0, 0.5}, {0, -1});
  EXPECT_EQ(res[7]["a"], "C");
  EXPECT_EQ(res[7]["b"], "peg");
  expect_hit(res[7]["contact"], 3.25, {5.3, 7}, {1, 0});
  EXPECT_EQ(res[11]["a"], "B");
  EXPECT_EQ(res[11]["b"], "arm");
  const double h = std::sqrt(2.0) / 2;
  expect_hit(res[11]["contact"], 4 - 1.4 * std::sqrt(2.0), {-6 + h, 1 + 2.3 * std::sqrt(2.0)}, {h, -h});
  EXPECT_EQ(out["summary"]["contact"]["hit"], 3);
  // Drawn at the first contact (B and the arm), nothing overlapping.
  const Outcome p = run_cli({"render", scene.string(), "-o", (dir / "capsules.svg").string()}, dir);
  ASSERT_EQ(p.code, 0) << describe(p);
  const SvgSummary s = read_svg(dir / "capsules.svg");
  EXPECT_NEAR(std::stod(s.attr("data-time")), 4 - 1.4 * std::sqrt(2.0), 1e-12);
  EXPECT_EQ(s.obstacles, 3);
  EXPECT_EQ(s.obstacles_overlapping, 0);
}

// ------------------------------------------------------------------------------------------
// Turning bodies (angular_velocity): rigid motion
// ------------------------------------------------------------------------------------------

// A hit under rigid motion, to the accuracy the library states for it (contact.hpp: time
// within 1e-12 relative, point within 1e-10 of the bodies' size, normal within 1e-9 rad),
// with room to spare; `iterations` counts its advancement steps (at least one).
void expect_rigid_hit(const json& contact, double time, const std::vector<double>& point,
                      const std::vector<double>& normal) {
  SCOPED_TRACE(contact.dump());
  EXPECT_EQ(contact["status"], "hit");
  EXPECT_NEAR(contact["time"].get<double>(), time, 1e-9 * std::max(1.0, time));
  for (std::size_t i = 0; i < point.size(); ++i) {
    EXPECT_NEAR(contact["point"][i].get<double>(), point[i], 1e-9);
    EXPECT_NEAR(contact["normal"][i].get<double>(), normal[i], 1e-9);
  }
  EXPECT_GT(contact["iterations"].get<int>(), 0);
}

// The rotation, in degrees, of the drawn ellipse of class `cls` and id `id` in an SVG (the
// outline's angle from the plane's first axis, negated: SVG's y axis points down).
double drawn_rotation(const std::string& svg, const std::string& cls, const std::string& id) {
  const std::string key = "<ellipse class=\"" + cls + "\" data-id=\"" + id + "\"";
  const std::size_t at = svg.find(key);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no " << key;
    return std::numeric_limits<double>::quiet_NaN();
  }
  return std::stod(svg.substr(svg.find("rotate(", at) + 7));
}

// An ellipse's outline drawn at `degrees` (a half turn maps it onto itself), to the two
// decimals the SVG is written with.
void expect_drawn_at(double drawn, double degrees) { EXPECT_NEAR(std::remainder(drawn - degrees, 180.0), 0.0, 0.006); }

// The turning rod: an ellipse of radii (2, 0.1) centered at (0, 1), at angle 0 at t = 0,
// turning counterclockwise at 1 rad per unit time (no velocity: it turns in place) above the
// floor y <= 0. At time t its axes are u = (cos t, sin t) and v = (-sin t, cos t); its support
// along n = (0, -1), how far its lowest point lies below the center, is
//     rho(t) = sqrt((2 u.n)^2 + (0.1 v.n)^2) = sqrt(4 sin^2 t + 0.01 cos^2 t),
// which grows from 0.1 on [0, pi/2]. The rod touches the floor when rho = 1: with s = sin t,
// 4 s^2 + 0.01 (1 - s^2) = 1, s^2 = 0.99 / 3.99, at t* = asin(sqrt(0.99 / 3.99)) (0.5214).
// The lowest point is the center plus the support offset (4 (u.n) u + 0.01 (v.n) v) / rho =
// -(4 s u + 0.01 c v) (c = cos t, rho = 1): x = -4 s c + 0.01 s c = -3.99 s c = -sqrt(2.97)
// (s c = sqrt(0.99 * 3) / 3.99), y = 1 - rho = 0; the normal from the rod to the floor is
// (0, -1). rho has period pi (a half turn maps the ellipse onto itself): after t = pi the rod
// touches again at pi + t*, at the same point.
// - slab: the floor as a box, [-5, 5] x [-1, 0], whose top edge holds that point: the same;
// - mirror: the rod's mirror image in the line y = 0 at every time (center (0, -1), turning
//   clockwise at -1): while the rod lies above the line its image lies below, and both reach
//   it at t*, at the rod's lowest point: the same contact, normal (0, -1) from rod to mirror.
const double rod_t = std::asin(std::sqrt(0.99 / 3.99));
const double rod_x = -std::sqrt(2.97);
const double pi = 3.14159265358979323846;

const char* turning_rod_2d_scene = R"({
  "time_window": [0, 10],
  "bodies": [
    {"id": "rod", "center": [0, 1], "radii": [2, 0.1], "angular_velocity": 1},
    {"id": "mirror", "center": [0, -1], "radii": [2, 0.1], "angular_velocity": -1}
  ],
  "obstacles": [
    {"id": "floor", "type": "half_space", "point": [0, 0], "normal": [0, 1]},
    {"id": "slab", "type": "box", "center": [0, -0.5], "half_extents": [5, 0.5]}
  ],
  "pairs": [["rod", "floor"], ["rod", "slab"], ["rod", "mirror"]]
})";

TEST(CliTurning, RodTippingOntoAHalfPlaneABoxAndItsMirrorImage) {
  const auto dir = work_dir();
  write_file(dir / "rod.json", turning_rod_2d_scene);
  // No body has a velocity: the angular velocities alone make the contact a default query.
  const Outcome r = run_cli({"check", (dir / "rod.json").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  EXPECT_EQ(out["queries"], json::parse(R"(["relation", "contact"])"));
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 3u);
  for (const auto& rec : res) {
    EXPECT_EQ(rec["relation"], "separated") << rec.dump();
    expect_rigid_hit(rec["contact"], rod_t, {rod_x, 0}, {0, -1});
  }
  // At t = 0 the rod lies flat, its lowest point 0.9 above the floor and 1.8 above the mirror's
  // highest.
  const Outcome d = run_cli({"check", (dir / "rod.json").string(), "--query", "distance"}, dir);
  ASSERT_EQ(d.code, 0) << describe(d);
  const json dout = parse_json(d.out);
  expect_distance(dout["results"][0]["distance"], "separated", 0.9, {0, 0.9}, {0, 0}, {0, -1});
  expect_distance(dout["results"][2]["distance"], "separated", 1.8, {0, 0.9}, {0, -0.9}, {0, -1});
  // CSV: the same contact.
  const Outcome c = run_cli({"check", (dir / "rod.json").string(), "-f", "csv"}, dir);
  ASSERT_EQ(c.code, 0) << describe(c);
  const auto lines = split_lines(c.out);
  ASSERT_EQ(lines.size(), 4u);
  const auto row = split_csv_line(lines[1]);
  EXPECT_EQ(row[4], "hit");
  EXPECT_EQ(std::stod(row[5]), res[0]["contact"]["time"].get<double>());
  EXPECT_EQ(row[10], std::to_string(res[0]["contact"]["iterations"].get<int>()));
}

// The rod of the 2D test in 3D: radii (2, 0.1, 0.1), centered at (0, 0, 1), angular velocity
// (0, -1, 0): the turn by -t about y takes the first axis to (cos t, 0, sin t) and the third to
// (-sin t, 0, cos t), and leaves the second along y, so the support along (0, 0, -1) is the
// 2D rho(t): it touches the floor z <= 0 at t*, at (-sqrt(2.97), 0, 0), normal (0, 0, -1).
// The floor as a box (its top face z = 0 over [-5, 5]^2) and as a mesh of two triangles over
// the same square, split along its diagonal y = x: the point (y = 0 > x) lies in triangle 1.
TEST(CliTurning, RodTippingOntoABoxAndAMeshIn3D) {
  const auto dir = work_dir();
  write_file(dir / "rod3.json", R"({
    "bodies": [{"id": "rod", "center": [0, 0, 1], "radii": [2, 0.1, 0.1], "angular_velocity": [0, -1, 0]}],
    "obstacles": [
      {"id": "slab", "type": "box", "center": [0, 0, -0.5], "half_extents": [5, 5, 0.5]},
      {"id": "floor", "type": "mesh", "vertices": [[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]],
       "triangles": [[0, 1, 2], [0, 2, 3]]}
    ]})");
  const Outcome r = run_cli({"check", (dir / "rod3.json").string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 2u);
  for (const auto& rec : res) {
    EXPECT_EQ(rec["relation"], "separated") << rec.dump();
    expect_rigid_hit(rec["contact"], rod_t, {rod_x, 0, 0}, {0, 0, -1});
  }
  EXPECT_EQ(res[1]["contact"]["triangle"], 1);
  EXPECT_TRUE(res[1]["relation_triangle"].is_null());
}

// Bodies that turn into themselves answer as their translational twins:
// - 2D: a circle (r 1) at the origin spinning at 3 rad per unit time, and a circle (r 1)
//   from (5, 0) at (-1, 0): centers 2 apart at t = 3, point (1, 0), normal (1, 0);
// - 3D: an ellipsoid of radii (2, 0.5, 0.5) spinning about its first axis (angular velocity
//   (5, 0, 0)), its two equal radii turning into each other, and a ball (r 1) from (6, 0, 0) at
//   (-1, 0, 0): 6 - t = 2 + 1 at t = 3, point (2, 0, 0), normal (1, 0, 0).
// And two turning rods: the 2D test's rod and mirror, listed without the obstacles.
TEST(CliTurning, BodyPairsInRigidMotion) {
  const auto dir = work_dir();
  write_file(dir / "spin2.json", R"({"bodies": [
    {"id": "spinning", "center": [0, 0], "radius": 1, "angular_velocity": 3},
    {"id": "moving", "center": [5, 0], "radius": 1, "velocity": [-1, 0]}]})");
  write_file(dir / "spin3.json", R"({"bodies": [
    {"id": "spinner", "center": [0, 0, 0], "radii": [2, 0.5, 0.5], "angular_velocity": [5, 0, 0]},
    {"id": "ball", "center": [6, 0, 0], "radius": 1, "velocity": [-1, 0, 0]}]})");
  json rods = json::parse(turning_rod_2d_scene);
  rods.erase("obstacles");
  rods.erase("pairs");
  write_file(dir / "rods.json", rods.dump());
  const std::vector<std::tuple<std::string, double, std::vector<double>, std::vector<double>>> cases = {
      {"spin2.json", 3.0, {1, 0}, {1, 0}},
      {"spin3.json", 3.0, {2, 0, 0}, {1, 0, 0}},
      {"rods.json", rod_t, {rod_x, 0}, {0, -1}}};
  for (const auto& [file, time, point, normal] : cases) {
    SCOPED_TRACE(file);
    const Outcome r = run_cli({"check", (dir / file).string()}, dir);
    ASSERT_EQ(r.code, 0) << describe(r);
    const json out = parse_json(r.out);
    ASSERT_EQ(out["results"].size(), 1u);
    EXPECT_EQ(out["results"][0]["relation"], "separated");
    expect_rigid_hit(out["results"][0]["contact"], time, point, normal);
  }
}

// Windows that start later turn the bodies to their start (the 2D rod, closed forms above):
// - t0 = 1: rho(1) = sqrt(4 sin^2 1 + 0.01 cos^2 1) (about 1.684) > 1: the rod reaches into
//   the floor, the slab and its mirror image: overlapping at the start, signed distance to
//   the floor 1 - rho(1), normal (0, -1);
// - t0 = 0.25 < t*: apart, the gap 1 - rho(0.25), the contact still at t*;
// - t0 = pi: the rod is flat again, 0.9 above the floor; the next contact at pi + t*.
// Drawn at t = 1 the rod is red and turned by 1 rad; at its first contact by t* from its
// start outline, drawn flat.
TEST(CliTurning, LaterWindowStartsTurnTheBodies) {
  const auto dir = work_dir();
  write_file(dir / "rod.json", turning_rod_2d_scene);
  const auto rho = [](double t) {
    return std::sqrt(4 * std::sin(t) * std::sin(t) + 0.01 * std::cos(t) * std::cos(t));
  };
  const std::string scene = (dir / "rod.json").string();
  const auto check = [&](const std::string& t0) {
    const Outcome r = run_cli({"check", scene, "--window", t0, "10", "--query", "relation,contact,distance"}, dir);
    EXPECT_EQ(r.code, 0) << describe(r);
    return parse_json(r.out)["results"];
  };
  const json at1 = check("1");
  ASSERT_EQ(at1.size(), 3u);
  for (const auto& rec : at1) {
    EXPECT_EQ(rec["relation"], "overlapping") << rec.dump();
    EXPECT_EQ(rec["contact"]["status"], "overlapping_at_start") << rec.dump();
    EXPECT_EQ(rec["contact"]["time"], 1) << rec.dump();
    EXPECT_EQ(rec["distance"]["status"], "overlapping") << rec.dump();
  }
  EXPECT_NEAR(at1[0]["distance"]["distance"].get<double>(), 1 - rho(1), 1e-12);
  EXPECT_NEAR(at1[0]["distance"]["normal"][1].get<double>(), -1, 1e-12);
  const json early = check("0.25");
  ASSERT_EQ(early.size(), 3u);
  EXPECT_EQ(early[0]["relation"], "separated");
  EXPECT_NEAR(early[0]["distance"]["distance"].get<double>(), 1 - rho(0.25), 1e-12);
  for (const auto& rec : early) expect_rigid_hit(rec["contact"], rod_t, {rod_x, 0}, {0, -1});
  const json later = check("3.141592653589793");
  ASSERT_EQ(later.size(), 3u);
  EXPECT_NEAR(later[0]["distance"]["distance"].get<double>(), 0.9, 1e-12);
  for (const auto& rec : later) {
    EXPECT_EQ(rec["relation"], "separated") << rec.dump();
    expect_rigid_hit(rec["contact"], pi + rod_t, {rod_x, 0}, {0, -1});
  }

  const Outcome p1 = run_cli({"render", scene, "--time", "1", "-o", (dir / "t1.svg").string()}, dir);
  ASSERT_EQ(p1.code, 0) << describe(p1);
  const SvgSummary s1 = read_svg(dir / "t1.svg");
  EXPECT_EQ(s1.overlapping, 2);  // the rod and its mirror image
  EXPECT_EQ(s1.obstacles_overlapping, 2);
  expect_drawn_at(drawn_rotation(slurp(dir / "t1.svg"), "body overlapping", "rod"), -180 / pi);
  const Outcome p = run_cli({"render", scene, "-o", (dir / "first.svg").string()}, dir);
  ASSERT_EQ(p.code, 0) << describe(p);
  const SvgSummary s = read_svg(dir / "first.svg");
  EXPECT_NEAR(std::stod(s.attr("data-time")), rod_t, 1e-9);
  EXPECT_EQ(s.starts, 2);  // turning in place: start outlines, no paths
  EXPECT_EQ(s.paths, 0);
  const std::string svg = slurp(dir / "first.svg");
  expect_drawn_at(drawn_rotation(svg, "body", "rod"), -rod_t * 180 / pi);
  expect_drawn_at(drawn_rotation(svg, "body", "mirror"), rod_t * 180 / pi);
  expect_drawn_at(drawn_rotation(svg, "start", "rod"), 0);
}

// Adding a zero angular velocity to every body of the bundled moving scenes changes no
// answer: the translational answers, bit for bit.
TEST(CliTurning, ZeroAngularVelocitiesChangeNothing) {
  const auto dir = work_dir();
  for (const std::string file : {"swept_2d.json", "swept_3d.json", "grazing_2d.json", "obstacles_2d.json",
                                 "obstacles_capsule.json"}) {
    SCOPED_TRACE(file);
    json scene = json::parse(slurp(scenes / file));
    for (auto& b : scene["bodies"])
      b["angular_velocity"] = b["center"].size() == 2 ? json(0) : json::parse("[0, 0, 0]");
    write_file(dir / file, scene.dump());
    for (const std::vector<std::string>& window : {std::vector<std::string>{}, {"--window", "0.5", "10"}}) {
      std::vector<std::string> given = {"check", (scenes / file).string(), "--query", "relation,contact,distance"};
      std::vector<std::string> zero = {"check", (dir / file).string(), "--query", "relation,contact,distance"};
      given.insert(given.end(), window.begin(), window.end());
      zero.insert(zero.end(), window.begin(), window.end());
      const Outcome a = run_cli(given, dir), b = run_cli(zero, dir);
      ASSERT_EQ(a.code, 0) << describe(a);
      ASSERT_EQ(b.code, 0) << describe(b);
      const json ja = parse_json(a.out), jb = parse_json(b.out);
      EXPECT_EQ(ja["results"].dump(), jb["results"].dump());
      EXPECT_EQ(ja["summary"], jb["summary"]);
    }
  }
}

TEST(CliTurning, MalformedAngularVelocitiesNameTheField) {
  const auto dir = work_dir();
  const std::string head2 = R"({"bodies": [{"id": "a", "center": [0, 0], "radius": 1, )";
  const std::string head3 = R"({"bodies": [{"id": "a", "center": [0, 0, 0], "radius": 1, )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {head2 + R"("angular_velocity": [0, 1]}]})",
       "$.bodies[0].angular_velocity: expected a number (a 2D body turns in its plane"},
      {head2 + R"("angular_velocity": "fast"}]})", "$.bodies[0].angular_velocity: expected a number, got a string"},
      {head2 + R"("angular_velocity": null}]})", "$.bodies[0].angular_velocity: expected a number, got null"},
      {head3 + R"("angular_velocity": 1}]})",
       "$.bodies[0].angular_velocity: expected an array of 3 numbers (a 3D body turns about an axis"},
      {head3 + R"("angular_velocity": [0, 1]}]})",
       "$.bodies[0].angular_velocity: has 2 components, but the scene is 3D"},
      {head3 + R"("angular_velocity": [0, 1, 0, 0]}]})",
       "$.bodies[0].angular_velocity: has 4 components, but the scene is 3D"},
      {head3 + R"("angular_velocity": [0, "1", 0]}]})",
       "$.bodies[0].angular_velocity[1]: expected a number, got a string"},
      {head3 + R"("angular_velocity": {"x": 1}}]})",
       "$.bodies[0].angular_velocity: expected an array of 3 numbers, got an object"},
      {head2 + R"("angular_velocty": 1}]})", "$.bodies[0].angular_velocty: unknown key"},
      // Obstacles never turn.
      {head2 + R"("velocity": [0, -1]}], "obstacles": [{"id": "o", "type": "half_space", "point": [0, -5],
                   "normal": [0, 1], "angular_velocity": 1}]})",
       "$.obstacles[0].angular_velocity: unknown key"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k)
    expect_bad_input({"bad" + std::to_string(k) + ".json", cases[k].first, {cases[k].second}}, dir);
  // Non-finite: JSON has no NaN, and 1e999 is rejected where it is read.
  expect_bad_input({"huge.json", head3 + R"("angular_velocity": [0, 1e999, 0]}]})",
                    {"huge.json:1:", "number 1e999 is out of range"}}, dir);
  // Turned by an angle beyond the range of double at the window start t0 = 2 (1e308 rad per
  // unit time): bad input naming the scene, the body and t0, with a body or an obstacle.
  const std::string turning = R"({"time_window": [2, 3],
    "bodies": [{"id": "a", "center": [0, 0], "radius": 1, "angular_velocity": 1e308}, {"id": "b", "center": [5, 0], "radius": 1}],
    "obstacles": [{"id": "floor", "type": "half_space", "point": [0, -5], "normal": [0, 1]}], )";
  expect_bad_input({"body_pair.json", turning + R"("pairs": [["a", "b"]]})",
                    {"body_pair.json: body a at t = 2: ", "turns the body by an angle beyond the range"}}, dir);
  expect_bad_input({"body_obstacle.json", turning + R"("pairs": [["a", "floor"]]})",
                    {"body_obstacle.json: body a at t = 2: ", "turns the body by an angle beyond the range"}}, dir);
}

// The bundled scene (all pairs: 6 body pairs, then each of the 4 bodies against the ground and
// the crate), closed forms:
// - rod: the 3D rod above, tipping onto the ground at t*;
// - plank (radii 1.5, 0.2, 0.2) falls at 1 from (6, 0, 2) spinning about the vertical (angular
//   velocity (0, 0, 2)), which turns its first two axes in the horizontal plane and leaves its
//   third: its lowest point stays below its center, at (6, 0, 1.8 - t); it meets the crate's
//   top z = 0.5 (over [5, 7] x [-1, 1]) at t = 1.3 and the ground at t = 1.8 (each pair on its
//   own), normal (0, 0, -1);
// - spinner (radii 2, 0.5, 0.5) at (0, 6, 3) spins about its first axis, keeping its shape;
//   the ball (r 0.5) from (6, 6, 3) at (-1, 0, 0) meets its tip (2, 6, 3) when 6 - t = 2.5, at
//   t = 3.5, normal (1, 0, 0);
// - nothing else meets: the bodies' bounding balls (radius 2 about the rod and the spinner, 1.5
//   about the plank, 0.5 about the ball) stay further apart than their radii, the spinner and
//   the ball 2.5 above the ground, the rod 5 from the crate.
// Drawn onto the xz plane at the first contact (t*), the rod's outline is turned by t*.
TEST(CliTurning, BundledTurningScene) {
  const auto dir = work_dir();
  const fs::path scene = scenes / "turning_rod.json";
  const Outcome r = run_cli({"check", scene.string()}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  const json& res = out["results"];
  ASSERT_EQ(res.size(), 6u + 4u * 2u);
  for (const auto& rec : res) EXPECT_EQ(rec["relation"], "separated") << rec.dump();
  EXPECT_EQ(res[5]["a"], "spinner");
  EXPECT_EQ(res[5]["b"], "ball");
  expect_rigid_hit(res[5]["contact"], 3.5, {2, 6, 3}, {1, 0, 0});
  EXPECT_EQ(res[6]["a"], "rod");
  EXPECT_EQ(res[6]["b"], "ground");
  expect_rigid_hit(res[6]["contact"], rod_t, {rod_x, 0, 0}, {0, 0, -1});
  EXPECT_EQ(res[8]["a"], "plank");
  EXPECT_EQ(res[8]["b"], "ground");
  expect_rigid_hit(res[8]["contact"], 1.8, {6, 0, 0}, {0, 0, -1});
  EXPECT_EQ(res[9]["b"], "crate");
  expect_rigid_hit(res[9]["contact"], 1.3, {6, 0, 0.5}, {0, 0, -1});
  EXPECT_EQ(out["summary"]["contact"]["hit"], 4);
  EXPECT_EQ(out["summary"]["contact"]["no_contact_in_window"], 10);
  const Outcome p = run_cli({"render", scene.string(), "--plane", "xz", "-o", (dir / "turning.svg").string()}, dir);
  ASSERT_EQ(p.code, 0) << describe(p);
  const SvgSummary s = read_svg(dir / "turning.svg");
  EXPECT_NEAR(std::stod(s.attr("data-time")), rod_t, 1e-9);
  EXPECT_EQ(s.bodies, 4);
  EXPECT_EQ(s.overlapping, 0);
  expect_drawn_at(drawn_rotation(slurp(dir / "turning.svg"), "body", "rod"), -rod_t * 180 / pi);
}

// ------------------------------------------------------------------------------------------
// Bench
// ------------------------------------------------------------------------------------------

TEST(CliBench, PrintsQueriesPerSecond) {
  const auto dir = work_dir();
  const Outcome r = run_cli({"bench", (scenes / "swept_3d.json").string(), "--min-time", "0.02"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  EXPECT_NE(r.out.find("queries/s"), std::string::npos) << r.out;
  for (const char* q : {"overlap", "classify", "contact"}) EXPECT_NE(r.out.find(q), std::string::npos) << q;
  const Outcome j = run_cli({"bench", (scenes / "bodies_10k.csv").string(), "--min-time", "0.02", "--query", "overlap",
                           "--format", "json", "-j", "1"}, dir);
  ASSERT_EQ(j.code, 0) << describe(j);
  const json out = parse_json(j.out);
  ASSERT_EQ(out["results"].size(), 1u);
  EXPECT_EQ(out["results"][0]["query"], "overlap");
  EXPECT_GT(out["results"][0]["queries_per_second"].get<double>(), 0);
  EXPECT_EQ(out["bodies"], 10000);
}

TEST(CliBench, TimesTheDistanceQuery) {
  const auto dir = work_dir();
  const Outcome r = run_cli({"bench", (scenes / "swept_3d.json").string(), "--min-time", "0.02", "--query",
                             "classify,distance", "--format", "json", "-j", "1"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  const json out = parse_json(r.out);
  ASSERT_EQ(out["results"].size(), 2u);
  EXPECT_EQ(out["results"][1]["query"], "distance");
  EXPECT_GT(out["results"][1]["queries_per_second"].get<double>(), 0);
}

// ------------------------------------------------------------------------------------------
// A million pairs in bounded memory
// ------------------------------------------------------------------------------------------

// Peak RSS measured on the development machine (Release build, 2 threads): about 20 MB for
// 1,000,000 pairs with velocities (118 MB of CSV in, 109 MB out) and 18 MB for 100,000:
// memory holds two chunks of 16,384 pairs, not the file. The bound leaves room for
// allocator and thread-stack slack; AddressSanitizer's quarantine and shadow memory need
// more (56 MB measured for 1,000,000 pairs).
#if defined(__SANITIZE_ADDRESS__)
constexpr long rss_bound_kb = 256 * 1024;
#else
constexpr long rss_bound_kb = 64 * 1024;
#endif

TEST(CliLarge, MillionPairsStreamInBoundedMemory) {
  const auto dir = work_dir();
  const long rows = std::max(20000L, static_cast<long>(1000000 * case_scale()));
  const fs::path in = dir / "pairs.csv", out = dir / "results.csv";
  const Outcome gen = run_program(make_scene, {"pairs", "--count", std::to_string(rows), "--seed", "11", "--velocity",
                                           "-o", in.string()}, dir);
  ASSERT_EQ(gen.code, 0) << describe(gen);
  const Outcome r = run_cli({"check", in.string(), "--format", "csv", "--window", "0", "20", "-o", out.string(),
                           "--progress", "always", "--stats"}, dir);
  ASSERT_EQ(r.code, 0) << describe(r);
  std::printf("[ measured ] %ld pairs: peak RSS %.1f MB, %.2f s wall, %.3g pairs/s (input %.0f MB)\n", rows,
              static_cast<double>(r.max_rss_kb) / 1024.0, r.seconds, static_cast<double>(rows) / r.seconds,
              static_cast<double>(fs::file_size(in)) / 1e6);
  ::testing::Test::RecordProperty("peak_rss_kb", std::to_string(r.max_rss_kb));
  EXPECT_LT(r.max_rss_kb, rss_bound_kb) << "peak RSS " << r.max_rss_kb << " kB";
  // Every pair answered, in input order.
  std::ifstream f(out);
  std::string line;
  long n = 0, last_index = -1;
  bool ordered = true;
  std::getline(f, line);  // header
  while (std::getline(f, line)) {
    const long index = std::stol(line.substr(0, line.find(',')));
    ordered = ordered && index == last_index + 1;
    last_index = index;
    ++n;
  }
  EXPECT_EQ(n, rows);
  EXPECT_TRUE(ordered);
  EXPECT_NE(r.err.find("pairs in"), std::string::npos) << r.err;  // --stats
  if (r.seconds > 1.5) {
    EXPECT_NE(r.err.find("ellipsect: ["), std::string::npos) << "no progress bar: " << r.err;
  }
  fs::remove(in);
  fs::remove(out);
}

// ------------------------------------------------------------------------------------------
// enclose and fit
// ------------------------------------------------------------------------------------------

// The bundled edge points: enclose writes the library's body bit for bit, every point inside it
// as read back from the scene (its form in 50 digits), and check reads the scene; fit's
// ellipse is the library's too, near the generating one; a mesh gives a 3D body.
TEST(CliGeometry, EncloseAndFitWriteTheLibrarysBodyAsAScene) {
  const auto dir = work_dir();
  const fs::path points_file = scenes / "edge_points.csv";
  std::vector<ellipsect::Vec<double, 2>> points;
  {
    std::ifstream f(points_file);
    std::string line;
    while (std::getline(f, line))
      if (!line.empty() && line[0] != '#' && line[0] != 'x')
        points.push_back({std::stod(line.substr(0, line.find(','))), std::stod(line.substr(line.find(',') + 1))});
  }
  ASSERT_EQ(points.size(), 240u);
  const auto read_body = [](const std::string& text) {
    const auto j = nlohmann::json::parse(text);
    const auto& b = j.at("bodies").at(0);
    ellipsect::Mat<double, 2> r;
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 2; ++k) r(i, k) = b.at("rotation").at(i).at(k).get<double>();
    return ellipsect::Ellipsoid<double, 2>::from_axes({b.at("center")[0].get<double>(), b.at("center")[1].get<double>()}, r,
                                                      {b.at("radii")[0].get<double>(), b.at("radii")[1].get<double>()});
  };
  const Outcome e = run_cli({"enclose", points_file.string(), "-o", (dir / "hull.json").string()}, dir);
  ASSERT_EQ(e.code, 0) << describe(e);
  EXPECT_NE(e.err.find("enclose: optimal"), std::string::npos) << e.err;
  const auto hull = read_body(slurp(dir / "hull.json"));
  const auto expected = ellipsect::enclosing_ellipsoid<double, 2>(points).body;
  EXPECT_EQ(hull.center(), expected.center());
  EXPECT_EQ(hull.radii(), expected.radii());
  EXPECT_EQ(hull.axes().cwiseAbs(), expected.axes().cwiseAbs());
  using R = ellipsect::reference::Real;
  for (const auto& p : points) {
    R q = 0;
    for (int k = 0; k < 2; ++k) {
      R y = 0;
      for (int i = 0; i < 2; ++i) y += R(hull.axes()(i, k)) * (R(p[i]) - R(hull.center()[i]));
      q += y * y / (R(hull.radii()[k]) * R(hull.radii()[k]));
    }
    EXPECT_LE(q, 1);
  }
  const Outcome c = run_cli({"check", (dir / "hull.json").string()}, dir);
  EXPECT_EQ(c.code, 0) << describe(c);

  const Outcome f = run_cli({"fit", points_file.string()}, dir);
  ASSERT_EQ(f.code, 0) << describe(f);
  const auto fit = read_body(f.out);
  EXPECT_EQ(fit.center(), (ellipsect::fit_ellipsoid<double, 2>(points).body.center()));
  EXPECT_LT((fit.center() - ellipsect::Vec<double, 2>(3, 1)).norm(), 0.02);
  EXPECT_NEAR(fit.radii().maxCoeff(), 2, 0.02);
  EXPECT_NEAR(fit.radii().minCoeff(), 0.5, 0.02);

  const Outcome m = run_cli({"enclose", (scenes / "meshes" / "tetrahedron.stl").string()}, dir);
  ASSERT_EQ(m.code, 0) << describe(m);
  EXPECT_EQ(nlohmann::json::parse(m.out).at("bodies").at(0).at("radii").size(), 3u);

  // inscribe: the library's largest ellipse in the points' hull, inside every face of it.
  const Outcome in = run_cli({"inscribe", points_file.string()}, dir);
  ASSERT_EQ(in.code, 0) << describe(in);
  EXPECT_NE(in.err.find("inscribe: optimal"), std::string::npos) << in.err;
  const auto inside = read_body(in.out);
  const auto faces = ellipsect::hull_half_spaces<double, 2>(points);
  EXPECT_EQ(inside.center(), (ellipsect::inscribed_ellipsoid<double, 2>(faces).body.center()));
  for (const auto& h : faces) {
    // The body's support along the face's normal, from the stored numbers: |B n| + n.(c - p).
    R s = 0, support = 0;
    for (int k = 0; k < 2; ++k) {
      R y = 0;
      for (int i = 0; i < 2; ++i) y += R(inside.axes()(i, k)) * R(h.normal()[i]);
      support += y * y * R(inside.radii()[k]) * R(inside.radii()[k]);
      s += R(h.normal()[k]) * (R(inside.center()[k]) - R(h.point()[k]));
    }
    EXPECT_LE(sqrt(support) + s, 0);
  }
  const Outcome tet = run_cli({"inscribe", (scenes / "meshes" / "tetrahedron.stl").string()}, dir);
  ASSERT_EQ(tet.code, 0) << describe(tet);
  EXPECT_NE(tet.err.find("inside every one of the 4 faces"), std::string::npos) << tet.err;
}

// Bad points files exit with 2 and name the file, the line and the column; bad options with 1.
TEST(CliGeometry, BadPointsAreNamed) {
  const auto dir = work_dir();
  write_file(dir / "no_header.csv", "1,2\n3,4\n");
  write_file(dir / "bad_number.csv", "x,y\n0,0\n1,oops\n");
  write_file(dir / "few.csv", "x,y,z\n0,0,0\n1,0,0\n");
  write_file(dir / "line.csv", "x,y\n0,0\n1,1\n2,2\n3,3\n4,4\n5,5\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"enclose", (dir / "no_header.csv").string()}, "no_header.csv:1: header"},
      {{"enclose", (dir / "bad_number.csv").string()}, "bad_number.csv:3: y: expected a finite number"},
      {{"fit", (dir / "bad_number.csv").string()}, "bad_number.csv:3: y"},
      {{"enclose", (dir / "few.csv").string()}, "few.csv: points: must hold at least 4"},
      {{"enclose", (dir / "line.csv").string()}, "line"},
      {{"fit", (dir / "line.csv").string()}, "points"},
      {{"inscribe", (dir / "line.csv").string()}, "line.csv: points: are collinear"},
      {{"inscribe", (dir / "few.csv").string()}, "few.csv: points: must hold at least 4"},
  };
  for (const auto& [args, message] : cases) {
    const Outcome r = run_cli(args, dir);
    EXPECT_EQ(r.code, 2) << describe(r);
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
  const Outcome gap = run_cli({"enclose", (scenes / "edge_points.csv").string(), "--volume-gap", "0"}, dir);
  EXPECT_EQ(gap.code, 1) << describe(gap);
  EXPECT_NE(gap.err.find("volume_gap"), std::string::npos) << gap.err;
  for (const auto& [args, field] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"inscribe", "--max-inscribed-iterations", "0"}, "max_inscribed_iterations"},
           {{"fit", "--fit-tolerance", "1"}, "fit_tolerance"},
           {{"enclose", "--max-enclosing-iterations", "-1"}, "max_enclosing_iterations"}}) {
    std::vector<std::string> full = args;
    full.push_back((scenes / "edge_points.csv").string());
    const Outcome r = run_cli(full, dir);
    EXPECT_EQ(r.code, 1) << describe(r);
    EXPECT_NE(r.err.find(field), std::string::npos) << r.err;
  }
  const Outcome missing = run_cli({"fit", (dir / "absent.csv").string()}, dir);
  EXPECT_EQ(missing.code, 3) << describe(missing);
}

}  // namespace
