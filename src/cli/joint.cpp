// adjoin joint SCENE [--set K=V]... [--unset K]... [--contact N|all] [--tol LENGTH] [--out DIR] [--quiet]
//
// The minimum seismic joint (study/seismic_joint.hpp): the smallest clear gap at rest with
// which the scene's floors never touch (a two-block scene's model.gap0, a building scene's
// contact N's gap, or with --contact all one uniform gap of every pair and each pair's own),
// by bisection over runs and directly from one run without contact; the codes' SRSS and
// absolute-sum rules beside it. Prints the result and writes DIR/joint.json
// (default out/<scene name>/).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/study/seismic_joint.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/run_watch.hpp"
#include "command.hpp"
#include "progress.hpp"

namespace adjoin::cli {
namespace {

using nlohmann::ordered_json;

struct JointArgs {
  std::string scene, out;
  std::vector<std::string> overrides, unsets;
  std::string contact = "1";  // a pair's number, or "all"
  double tol = 0.0;
  bool tol_given = false, quiet = false, allow_long = false;
};

std::string shortest(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

constexpr const char* kSrssRule =
    "ASCE 7-16 12.12.3 (adjacent structures on the same property): delta_MT = sqrt(delta_M1^2 + delta_M2^2)";

std::string joint_json(const SeismicJoint& j) {
  ordered_json notes = ordered_json::array();
  for (const auto& n : j.notes) notes.push_back(n);
  ordered_json pairs = ordered_json::array();
  for (const PairJoint& p : j.pairs)
    pairs.push_back({{"contact", p.contact},
                     {"floors", {p.floor_a, p.floor_b}},
                     {"s_max", p.s_max},
                     {"t", p.t_critical},
                     {"peak_a", p.peak_a},
                     {"peak_b", p.peak_b},
                     {"srss", p.srss},
                     {"abs_sum", p.abs_sum}});
  ordered_json out{
      {"scene", j.scene},
      {"units", j.length_unit == "m" ? "SI" : "dimensionless"},
      {"gap_key", j.gap_key},
      {"contact", j.contact},
      {"floors", {j.floor_a, j.floor_b}},
      {"joint", j.joint},
      {"tolerance", j.tol},
      {"bisection",
       {{"joint", j.joint}, {"touching_below", j.joint_low}, {"runs", j.runs}, {"bracket", {0.0, j.bracket_top}},
        {"widenings", j.widenings}}},
      {"direct", {{"s_max", j.s_max}, {"difference", j.difference}, {"agree", j.agree}}},
      {"critical_approach", {{"t", j.t_critical}, {"floors", {j.floor_a, j.floor_b}}}},
      {"code_rules",
       {{"peak_a", {{"floor", j.floor_a}, {"max_abs", j.peak_a}, {"t", j.t_peak_a}}},
        {"peak_b", {{"floor", j.floor_b}, {"max_abs", j.peak_b}, {"t", j.t_peak_b}}},
        {"srss", j.srss},
        {"srss_rule", kSrssRule},
        {"abs_sum", j.abs_sum},
        {"abs_sum_rule", "the absolute sum delta_M1 + delta_M2 (the conservative rule)"}}},
      {"every_pair", j.every_pair},
      {"pairs", pairs},
      {"wall_seconds", j.wall_seconds},
      {"notes", notes}};
  return out.dump(2) + "\n";
}

void print(const SeismicJoint& j) {
  const char* u = j.length_unit.c_str();
  const char* tu = j.time_unit.c_str();
  const std::string pair = j.building ? "contact " + std::to_string(j.contact) + ", floors A" + std::to_string(j.floor_a) +
                                            "-B" + std::to_string(j.floor_b)
                                      : std::string("blocks 1-2");
  if (j.every_pair)
    std::printf("minimum uniform seismic joint of %s (%s, every pair; critical: %s): %.6g %s\n", j.scene.c_str(),
                j.gap_key.c_str(), pair.c_str(), j.joint, u);
  else
    std::printf("minimum seismic joint of %s (%s, %s): %.6g %s\n", j.scene.c_str(), j.gap_key.c_str(), pair.c_str(), j.joint, u);
  std::printf("  bisection over runs: %.8g %s (%zu runs, bracket [0, %.6g]%s, tolerance %.3g %s; %.8g %s touches)\n",
              j.joint, u, j.runs, j.bracket_top, j.widenings ? " after widening" : "", j.tol, u, j.joint_low, u);
  std::printf("  direct, one run without contact: s_max = %.8g %s; bisection - direct = %.3g %s (%s)\n", j.s_max, u,
              j.difference, u, j.agree ? "agree within the tolerance" : "DISAGREE: the response depends on the gap");
  std::printf("  critical approach: t = %.6g %s, floors A%d-B%d\n", j.t_critical, tu, j.floor_a, j.floor_b);
  std::printf("  codes' rules from the floors' own peaks |x_A%d| = %.6g %s (t = %.4g), |x_B%d| = %.6g %s (t = %.4g):\n",
              j.floor_a, j.peak_a, u, j.t_peak_a, j.floor_b, j.peak_b, u, j.t_peak_b);
  std::printf("    SRSS (ASCE 7-16 12.12.3, same property) %.6g %s (%+.1f %%), absolute sum %.6g %s (%+.1f %%) against s_max\n",
              j.srss, u, j.s_max > 0.0 ? 100.0 * (j.srss / j.s_max - 1.0) : 0.0, j.abs_sum, u,
              j.s_max > 0.0 ? 100.0 * (j.abs_sum / j.s_max - 1.0) : 0.0);
  if (j.every_pair)
    for (const PairJoint& p : j.pairs)
      std::printf("  contact %d, floors A%d-B%d: its own joint s_max = %.8g %s (t = %.6g %s); SRSS %.6g %s, absolute sum %.6g %s\n",
                  p.contact, p.floor_a, p.floor_b, p.s_max, u, p.t_critical, tu, p.srss, u, p.abs_sum, u);
  for (const auto& n : j.notes) std::printf("  note: %s\n", n.c_str());
  std::printf("  %.3g s for all runs\n", j.wall_seconds);
}

std::filesystem::path output_folder(const JointArgs& args, const std::string& scene_name) {
  return args.out.empty() ? std::filesystem::path("out") / scene_name : std::filesystem::path(args.out);
}

int joint_command(const JointArgs& args) {
  SeismicJointOptions options;
  if (args.tol_given) {
    if (!(args.tol > 0.0) || !std::isfinite(args.tol))
      throw InputError("--tol " + shortest(args.tol) + ": expected a positive length (the bisection's tolerance, in "
                       "the scene's length unit: m for building and SI scenes)");
    options.tol = args.tol;
  }
  const bool every_pair = args.contact == "all";
  std::size_t used = 0;
  int number = 0;
  try {
    if (!every_pair) number = std::stoi(args.contact, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (!every_pair && (used != args.contact.size() || number < 1))
    throw InputError("--contact " + args.contact + ": expected a contact pair's number 1, 2, ... or \"all\" (every pair at one gap)");
  options.contact = every_pair ? 0 : number;

  SeismicJoint j;
  std::string name;
  if (is_building_scene(args.scene)) {
    BuildingScene scene = load_building_scene(args.scene, args.overrides, args.unsets);
    for (const auto& warning : scene.warnings) std::cerr << "warning: " << warning << "\n";
    check_memory(scene);
    const std::size_t n = scene.structure.contacts.size();
    if (n == 0)
      throw InputError(args.scene + ": no contact pair: adjoin joint needs a [[contact]] with floors = [i, j] (its gap "
                       "is the joint; --contact N chooses among several)");
    if (static_cast<std::size_t>(options.contact) > n)
      throw InputError("--contact " + args.contact + ": the scene has " + std::to_string(n) + " contact pair" +
                       (n == 1 ? "" : "s") + " (expected 1.." + std::to_string(n) + " or all)");
    name = scene.name;
    check_output_folder(output_folder(args, name));  // before the runs, not after them
    RunWatch watch(watch_options(args.quiet, args.allow_long));
    scene.watch = &watch;
    j = seismic_joint(scene, options);
  } else {
    const Scene scene = load_scene(args.scene, args.overrides, args.unsets);
    for (const auto& warning : scene.warnings) std::cerr << "warning: " << warning << "\n";
    if (options.contact != 1)
      throw InputError("--contact " + args.contact +
                       ": a two-block scene has one contact pair, the blocks' (its gap is model.gap0; expected 1)");
    name = scene.name;
    check_output_folder(output_folder(args, name));
    j = seismic_joint(scene, options);
  }

  FileSet files(output_folder(args, name), {"joint.json"});
  files.open("joint.json") << joint_json(j);
  const auto path = files.commit().front();
  if (!args.quiet) {
    print(j);
    std::printf("wrote %s\n", path.string().c_str());
  }
  return 0;
}

const Registration registration(48, "joint", "Minimum seismic joint: the smallest gap with which the floors never touch (bisection over runs, and directly from one run)",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<JointArgs>();
  sub->add_option("scene", args->scene, "Scene file (TOML)")->required();
  sub->add_option("--set", args->overrides, "Override a scene key by dotted path, e.g. --set solver.scheme=implicit")
      ->allow_extra_args(false);
  sub->add_option("--unset", args->unsets, "Remove a scene key or section before the --set overrides")
      ->allow_extra_args(false);
  sub->add_option("--contact", args->contact,
                                  "Building scenes: the contact pair whose gap is the joint (default 1), or all: every "
                                  "pair at one uniform gap, and each pair's own joint");
  auto* tol = sub->add_option("--tol", args->tol,
                              "Bisection tolerance in the scene's length unit (m; default 1e-6 of s_max)");
  sub->add_option("--out", args->out, "Output folder for joint.json (default out/<scene name>/)");
  sub->add_flag("--quiet,-q", args->quiet, "Print nothing on success");
  sub->add_flag("--allow-long", args->allow_long,
                "Building scenes: run even when a run is estimated at more than 2 hours (refused otherwise)");
  return [args, tol]() {
    args->tol_given = tol->count() > 0;
    return joint_command(*args);
  };
});

}  // namespace
}  // namespace adjoin::cli
