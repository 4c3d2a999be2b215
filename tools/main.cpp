// The `ellipsect` command-line program: scenes in, answers and pictures out.
//   ellipsect check SCENE    relation, first contact and distance of every pair (JSON or CSV)
//   ellipsect render SCENE   an SVG or PNG picture of the scene at one time
//   ellipsect bench SCENE    queries per second on the scene's pairs
//   ellipsect enclose FILE   the minimum-volume ellipse or ellipsoid of points or a mesh, as a scene
//   ellipsect inscribe FILE  the maximum-volume ellipse or ellipsoid in their convex hull, as a scene
//   ellipsect fit FILE       their least-squares ellipse or ellipsoid, as a scene
// docs/cli.md documents the commands, docs/scene-format.md the scene files.
#include "commands.hpp"
#include "common.hpp"

#include <ellipsect/geometry.hpp>
#include <ellipsect/version.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <string>

namespace {

using namespace ellipsect::cli;

void add_common(CLI::App& cmd, Common& c, std::vector<double>& window, std::string& progress) {
  cmd.add_option("SCENE", c.scene, "Scene file: JSON (.json) or CSV (.csv); see docs/scene-format.md")
      ->required()
      ->type_name("FILE");
  cmd.add_option("--pairs", c.pairs_file,
                 "CSV file of pairs to check (columns a,b: body ids); for JSON scenes and bodies CSVs")
      ->type_name("FILE");
  cmd.add_option("--window", window, "Time window T0 T1 for first contact (T1 may be inf); overrides the scene's")
      ->expected(2)
      ->type_name("T0 T1");
  cmd.add_option("-j,--threads", c.threads, "Worker threads (default 0: all cores)")->check(CLI::NonNegativeNumber);
  cmd.add_option("--progress", progress, "Progress bar on stderr: auto (when stderr is a terminal), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->default_str("auto");
}

// The queries' Options from --tolerance and one option per cap, named as its field with
// dashes (--max-contact-iterations, ...; absent: the defaults); a value Options rejects is a
// usage error naming the option.
struct OptionValues {
  std::optional<double> tolerance;
  std::optional<std::int64_t> max_contact_iterations, max_distance_iterations, max_contact_function_iterations,
      max_slide_rounds, max_motion_steps, max_slabs;
};

// --max-...: the cap of Options' member `cap`, what it caps in `what`.
template <class Cap>
void add_cap(CLI::App& cmd, std::optional<std::int64_t>& value, Cap ellipsect::Options::*cap, const char* what) {
  std::string option = "--" + std::string(Cap::field);
  std::replace(option.begin(), option.end(), '_', '-');
  cmd.add_option(option, value,
                 std::string("Cap on ") + what + ", in [1, " + std::to_string(Cap::max) + "] (default " +
                     std::to_string(ellipsect::Options{}.*cap) + ")")
      ->type_name("N");
}

void add_query_options(CLI::App& cmd, OptionValues& v) {
  using ellipsect::Options;
  cmd.add_option("--tolerance", v.tolerance,
                 "Relative tangency band of the queries, in [1e-14, 1e-9], or 0 for exact relations (default 1e-12; docs/method.md)")
      ->type_name("X");
  add_cap(cmd, v.max_contact_iterations, &Options::max_contact_iterations,
          "Newton's iterations on the contact time under linear motion; reaching it is did_not_converge");
  add_cap(cmd, v.max_distance_iterations, &Options::max_distance_iterations,
          "the evaluations of each distance descent; reaching it is did_not_converge");
  add_cap(cmd, v.max_contact_function_iterations, &Options::max_contact_function_iterations,
          "the Perram-Wertheim maximization's iterations; reaching it is did_not_converge");
  add_cap(cmd, v.max_slide_rounds, &Options::max_slide_rounds, "the rounds of collide-and-slide");
  add_cap(cmd, v.max_motion_steps, &Options::max_motion_steps,
          "the advancement steps of first contact under rigid motion; reaching it is did_not_converge");
  add_cap(cmd, v.max_slabs, &Options::max_slabs, "the slabs of the earliest-contact search in a periodic box");
}

ellipsect::Options finish_query_options(const OptionValues& v) {
  ellipsect::Options o;
  try {
    if (v.tolerance) o.tolerance = *v.tolerance;
    if (v.max_contact_iterations) o.max_contact_iterations = *v.max_contact_iterations;
    if (v.max_distance_iterations) o.max_distance_iterations = *v.max_distance_iterations;
    if (v.max_contact_function_iterations) o.max_contact_function_iterations = *v.max_contact_function_iterations;
    if (v.max_slide_rounds) o.max_slide_rounds = *v.max_slide_rounds;
    if (v.max_motion_steps) o.max_motion_steps = *v.max_motion_steps;
    if (v.max_slabs) o.max_slabs = *v.max_slabs;
  } catch (const ellipsect::InputError& e) {
    // what() is "ellipsect: <field>: <detail>"; the option is the field with dashes.
    std::string option = "--" + e.field();
    std::replace(option.begin(), option.end(), '_', '-');
    throw UsageError(option + std::string(e.what()).substr(std::string("ellipsect: ").size() + e.field().size()));
  }
  return o;
}

void finish_common(Common& c, const std::vector<double>& window, const std::string& progress) {
  if (!window.empty()) {
    if (window.size() != 2 || std::isnan(window[0]) || !std::isfinite(window[0]) || std::isnan(window[1]) ||
        window[1] < window[0])
      throw UsageError("--window: expected T0 T1 with T0 finite and T1 >= T0 (T1 may be inf)");
    c.window = Window{window[0], window[1]};
  }
  c.progress = parse_progress_mode(progress);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ellipsect " + std::string(ellipsect::version) +
               ": exact collision queries between ellipses and ellipsoids, on scene files."};
  app.name("ellipsect");
  app.set_version_flag("--version", std::string("ellipsect ") + ellipsect::version);
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  ellipsect check examples/scenes/swept_2d.json\n"
      "  ellipsect render examples/scenes/swept_2d.json -o swept_2d.svg\n"
      "  ellipsect bench examples/scenes/bodies_10k.csv\n"
      "Run 'ellipsect COMMAND --help' for a command's options.\n"
      "Exit codes: 0 ok, 1 bad command line, 2 bad input, 3 I/O error, 4 internal error.");

  CheckOptions check;
  RenderOptions render;
  BenchOptions bench;
  std::vector<double> check_window, render_window, bench_window;
  OptionValues check_options;
  std::string check_progress = "auto", render_progress = "auto", bench_progress = "auto";

  CLI::App* c = app.add_subcommand(
      "check", "Relation (and, with velocities, first contact; on request, signed distance) of every pair");
  add_common(*c, check.common, check_window, check_progress);
  c->add_option("-o,--output", check.output, "Output file (default: stdout); written whole or not at all")
      ->type_name("FILE");
  c->add_option("-f,--format", check.format, "Output format: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->default_str("json");
  c->add_option("--query", check.queries,
                "Comma-separated answers per pair: relation, contact, distance (the signed distance: minus the "
                "penetration depth when overlapping); default: relation, and contact when the scene has velocities")
      ->delimiter(',')
      ->type_name("LIST");
  c->add_option("--report", check.report,
                "Without listed pairs: all (every pair), candidates (only pairs the broad phase keeps; the others are "
                "separated), auto (all up to 1000 bodies, else candidates)")
      ->check(CLI::IsMember({"auto", "all", "candidates"}))
      ->default_str("auto");
  c->add_flag("--no-broad-phase", [&](std::int64_t) { check.broad_phase = false; },
              "Evaluate every pair exactly, without the bounding-box broad phase (implies --report all)");
  c->add_flag("--stats", check.stats, "Print the pair count, time and throughput to stderr");
  add_query_options(*c, check_options);
  c->footer(
      "Examples:\n"
      "  ellipsect check examples/scenes/swept_2d.json\n"
      "  ellipsect check examples/scenes/bodies_10k.csv --format csv -o overlaps.csv\n"
      "  ellipsect check examples/scenes/swept_3d.json --query relation,distance\n"
      "  ellipsect check pairs.csv --window 0 10 -o results.json --stats\n"
      "  ellipsect check examples/scenes/swept_2d.json --tolerance 1e-9 --max-contact-iterations 128");

  CLI::App* r = app.add_subcommand("render", "Draw the scene at one time as SVG (or PNG through rsvg-convert)");
  add_common(*r, render.common, render_window, render_progress);
  r->add_option("-o,--output", render.output, "Output picture: .svg, or .png (needs rsvg-convert)")
      ->required()
      ->type_name("FILE");
  r->add_option("-t,--time", render.time, "Time to draw (default: the first contact, else the window start)")
      ->type_name("T");
  r->add_option("--plane", render.plane, "3D scenes: projection plane xy, yz or xz")
      ->check(CLI::IsMember({"xy", "yz", "xz"}))
      ->default_str("xy");
  r->add_option("--width", render.width, "Width of the plot area in pixels")
      ->check(CLI::Range(100, 20000))
      ->default_str("800");
  r->add_option("--row", render.row, "Pairs CSV: the data row to draw (default 1)")->check(CLI::PositiveNumber);
  r->footer(
      "Examples:\n"
      "  ellipsect render examples/scenes/swept_2d.json -o swept_2d.svg\n"
      "  ellipsect render examples/scenes/swept_3d.json --plane xz -o swept_3d.png\n"
      "  ellipsect render examples/scenes/swept_2d.json --time 1.5 -o at_1.5.svg");

  CLI::App* b = app.add_subcommand("bench", "Time the queries on the scene's pairs; prints queries per second");
  add_common(*b, bench.common, bench_window, bench_progress);
  b->add_option("--query", bench.queries,
                "Comma-separated queries to time: overlap, classify, contact, distance (signed_distance, as check "
                "computes it); default: overlap, classify, and contact when the scene has velocities")
      ->delimiter(',')
      ->type_name("LIST");
  b->add_option("--min-time", bench.min_time, "Seconds to run each query (at least one pass over the pairs)")
      ->default_str("0.5");
  b->add_option("--limit", bench.limit, "At most this many pairs (pairs CSVs are loaded into memory)")
      ->default_str("100000");
  b->add_option("-f,--format", bench.format, "Output format: text or json")
      ->check(CLI::IsMember({"text", "json"}))
      ->default_str("text");
  b->add_option("-o,--output", bench.output, "Output file (default: stdout)")->type_name("FILE");
  b->footer(
      "Examples:\n"
      "  ellipsect bench examples/scenes/swept_3d.json\n"
      "  ellipsect bench examples/scenes/bodies_10k.csv --query overlap -j 1 --min-time 2");

  // enclose, inscribe and fit: points or a mesh in, a one-body scene out.
  GeometryOptions enclose, inscribe, fit;
  enclose.id = "enclosing";
  enclose.max_iterations = ellipsect::EnclosingOptions{}.max_enclosing_iterations;
  inscribe.id = "inscribed";
  inscribe.max_iterations = ellipsect::InscribedOptions{}.max_inscribed_iterations;
  fit.id = "fit";
  fit.max_iterations = ellipsect::FitOptions{}.max_fit_iterations;
  const auto add_geometry = [](CLI::App& cmd, GeometryOptions& g) {
    cmd.add_option("FILE", g.input, "Points: a CSV with a header naming columns x, y (and z); or a mesh: .obj, .stl")
        ->required()
        ->type_name("FILE");
    cmd.add_option("-o,--output", g.output, "Output scene (JSON; default: stdout); written whole or not at all")
        ->type_name("FILE");
    cmd.add_option("--id", g.id, "The body's id in the scene")->default_str(g.id);
  };
  CLI::App* en = app.add_subcommand(
      "enclose", "The minimum-volume ellipse or ellipsoid holding every point (certified), as a one-body scene");
  add_geometry(*en, enclose);
  en->add_option("--volume-gap", enclose.volume_gap,
                 "The volume gap to reach, vol <= (1 + gap) min, in [1e-12, 1] (default 1e-9)")
      ->type_name("X");
  en->add_option("--max-enclosing-iterations", enclose.max_iterations,
                 "Cap on the weight updates, in [1, 10000000] (default 1000000); reaching it is did_not_converge")
      ->type_name("N");
  en->footer(
      "Examples:\n"
      "  ellipsect enclose examples/scenes/edge_points.csv -o hull.json\n"
      "  ellipsect enclose examples/scenes/meshes/hill.obj --volume-gap 1e-6 -o hill_hull.json\n"
      "  ellipsect check hull.json");
  CLI::App* in = app.add_subcommand(
      "inscribe", "The maximum-volume ellipse or ellipsoid inside the points' convex hull (certified), as a one-body scene");
  add_geometry(*in, inscribe);
  in->add_option("--volume-gap", inscribe.volume_gap,
                 "The volume gap to reach, max <= (1 + gap) vol, in [1e-12, 1] (default 1e-9)")
      ->type_name("X");
  in->add_option("--max-inscribed-iterations", inscribe.max_iterations,
                 "Cap on the Newton steps, in [1, 1000000] (default 10000); reaching it is did_not_converge")
      ->type_name("N");
  in->footer(
      "Examples:\n"
      "  ellipsect inscribe examples/scenes/edge_points.csv -o inside.json\n"
      "  ellipsect inscribe examples/scenes/meshes/hill.obj -o hill_inside.json");
  CLI::App* fi = app.add_subcommand("fit", "The least-squares ellipse or ellipsoid of the points (orthogonal distances), as a one-body scene");
  add_geometry(*fi, fit);
  fi->add_option("--fit-tolerance", fit.fit_tolerance, "The stationarity to reach, in [1e-15, 1e-3] (default 1e-8)")
      ->type_name("X");
  fi->add_option("--max-fit-iterations", fit.max_iterations,
                 "Cap on the Levenberg-Marquardt steps, in [1, 100000] (default 200); reaching it is did_not_converge")
      ->type_name("N");
  fi->footer(
      "Examples:\n"
      "  ellipsect fit examples/scenes/edge_points.csv -o ellipse.json\n"
      "  ellipsect fit scan.csv --fit-tolerance 1e-10");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? exit_ok : exit_usage;
  }

  try {
    if (c->parsed()) {
      finish_common(check.common, check_window, check_progress);
      check.options = finish_query_options(check_options);
      return run_check(check);
    }
    if (r->parsed()) {
      finish_common(render.common, render_window, render_progress);
      return run_render(render);
    }
    if (en->parsed()) return run_enclose(enclose);
    if (in->parsed()) return run_inscribe(inscribe);
    if (fi->parsed()) return run_fit(fit);
    finish_common(bench.common, bench_window, bench_progress);
    return run_bench(bench);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "ellipsect: error: %s\nRun with --help for more information.\n", e.what());
    return exit_usage;
  } catch (const BadInput& e) {
    std::fprintf(stderr, "ellipsect: error: %s\n", e.what());
    return exit_bad_input;
  } catch (const IoError& e) {
    std::fprintf(stderr, "ellipsect: error: %s\n", e.what());
    return exit_io;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "ellipsect: error: out of memory\n");
    return exit_internal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ellipsect: internal error: %s\n", e.what());
    return exit_internal;
  }
}
