#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/core/json_output.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/scene/scene_generator.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"

namespace boxpile::cli {
namespace {

// The size flags of `boxpile scene`, each bound to its SceneSizes member.
struct SizeFlag {
  const char* name;
  const char* help;
};
constexpr SizeFlag kSizeFlags[] = {
    {"base", "pyramid: cubes in the bottom row (default 5)"},
    {"width", "wall: bricks per row (default 6)"},
    {"height", "wall: rows (default 4); tower: cubes (default 10)"},
    {"nx", "grid: cubes along x (default 5)"},
    {"ny", "grid: cubes along y (default 5)"},
    {"layers", "grid: layers (default 1)"},
    {"count", "heap: cubes (default 20); dominoes: dominoes (default 10)"},
    {"gap", "m between neighbours (pyramid, wall: 0; grid: --size; heap: 0.05 --size)"},
    {"seed", "heap: the seed of the random orientations and places (default 1)"},
};

int* count_of(SceneSizes& s, std::string_view flag) {
  if (flag == "base") return &s.base;
  if (flag == "width") return &s.width;
  if (flag == "height") return &s.height;
  if (flag == "nx") return &s.nx;
  if (flag == "ny") return &s.ny;
  if (flag == "layers") return &s.layers;
  if (flag == "count") return &s.count;
  return nullptr;
}

}  // namespace

void add_scene_command(CLI::App& app, SceneOptions& options) {
  std::string kinds;
  for (const SceneKind& k : scene_kinds()) kinds += "\n  " + std::string(k.name) + ": " + std::string(k.description);
  CLI::App* cmd = app.add_subcommand("scene", "Write a scene file of boxes in a usual arrangement (docs/scene-format.md): "
                                              "pyramid, wall, tower, grid, heap or dominoes");
  std::vector<std::string> names;
  for (const SceneKind& k : scene_kinds()) names.emplace_back(k.name);
  cmd->add_option("kind", options.kind, "What to build:" + kinds)->required()->check(CLI::IsMember(names));
  for (const SizeFlag& f : kSizeFlags) {
    const std::string flag = std::string("--") + f.name;
    if (int* n = count_of(options.sizes, f.name)) {
      cmd->add_option(flag, *n, f.help)->check(CLI::Range(1, 1'000'000));
    } else if (std::string_view(f.name) == "gap") {
      cmd->add_option(flag, options.sizes.gap, f.help)->check(CLI::Range(0.0, 2000.0));
    } else {
      cmd->add_option(flag, options.sizes.seed, f.help);
    }
  }
  cmd->add_option("--size", options.sizes.size, "m: a cube's edge, a brick's height, a domino's height, in [0.01, 200]")
      ->capture_default_str();
  cmd->add_option("--mass", options.sizes.mass, "kg of each box")->capture_default_str();
  cmd->add_option("--out", options.out, "Write the scene to this file (atomically); without it, to stdout");
  cmd->footer("The scene is checked by the scene loader before it is written (no two boxes overlap).");
  options.command = cmd;
}

int run_scene_command(const SceneOptions& options) {
  // A size the kind does not take is refused, not ignored.
  for (const SceneKind& k : scene_kinds()) {
    if (k.name != options.kind) continue;
    for (const SizeFlag& f : kSizeFlags) {
      const std::string flag = std::string("--") + f.name;
      if (options.command->count(flag) == 0) continue;
      if (std::find(k.sizes.begin(), k.sizes.end(), f.name) != k.sizes.end()) continue;
      std::string takes;
      for (std::string_view s : k.sizes) takes += (takes.empty() ? "--" : ", --") + std::string(s);
      throw UsageError(flag + ": " + options.kind + " does not take it (it takes " + takes + ", --size, --mass)");
    }
  }
  std::optional<OutputFile> out;
  if (options.out) out.emplace(*options.out, std::vector<std::filesystem::path>{});
  nlohmann::json scene;
  try {
    scene = generate_scene(options.kind, options.sizes);
  } catch (const SceneGeneratorError& e) {
    throw UsageError(e.what());
  }
  const std::string text = scene.dump(1);
  // What is written loads: the loader's checks (overlaps, ranges) are the judge.
  const Scene loaded = parse_checked_scene(text, options.out.value_or("<stdout>"));
  if (out) {
    write_json_file(scene, *out);
    std::cerr << "boxpile scene: " << loaded.name << ", " << loaded.bodies.size() << " boxes\nscene: "
              << std::filesystem::absolute(out->target()).lexically_normal().string() << '\n';
  } else {
    std::cout << text << '\n';
  }
  return kExitOk;
}

}  // namespace boxpile::cli
