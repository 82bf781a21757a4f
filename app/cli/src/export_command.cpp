// ffdkit-cli export: a scene as binary glTF 2.0 (the deformed mesh at a frame, the animation as
// morph targets, or as a skin on the lattices' control points).
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "console.h"
#include "frames.h"
#include "shape_guard.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/exporters/scene_animation.h"

namespace ffdkit::cli {

namespace {

namespace fs = std::filesystem;

int runExport(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  if (args.positional().size() != 1) throw UsageError("expected one SCENE, got " + std::to_string(args.positional().size()));
  const auto output = args.value("output");
  if (!output) throw UsageError("missing -o OUT.glb");
  exporters::GltfExportOptions options;
  const int contents = int(args.value("frame").has_value()) + int(args.flag("morph")) + int(args.flag("skin"));
  if (contents > 1) throw UsageError("choose one of --frame, --morph, --skin");
  if (args.flag("morph")) options.content = exporters::GltfContent::Morph;
  if (args.flag("skin")) options.content = exporters::GltfContent::Skin;
  if (options.content != exporters::GltfContent::Skin &&
      (args.value("joints") || args.value("tolerance") || args.flag("no-raise") || args.flag("allow-folding")))
    throw UsageError("--joints, --tolerance, --no-raise and --allow-folding go with --skin");
  if (const auto joints = args.value("joints")) {
    if (*joints != "4" && *joints != "8") throw UsageError("--joints takes 4 or 8, got '" + *joints + "'");
    options.joints = std::stoi(*joints);
    options.raiseJoints = false;  // asked for a k: keep it
  }
  if (args.flag("no-raise")) options.raiseJoints = false;
  if (const auto tolerance = args.value("tolerance")) {
    options.tolerance = parseNumber(*tolerance, "--tolerance");
    if (options.tolerance < 0.0) throw UsageError("--tolerance must be >= 0, got " + *tolerance);
  }
  options.normals = !args.flag("no-normals");

  const std::vector<VariationSetting> settings = parseSettings(args.values("set"));
  const ReadSettings read = readSettings(args);
  console.begin("read", "reading " + args.positional()[0]);
  scenes::Scene scene = readSceneFile(args.positional()[0], read);
  console.end();
  exporters::AnimationSource animation = exporters::sceneAnimation(scene);
  if (options.content == exporters::GltfContent::Frame) {
    // The scene as saved, or its animation at --frame; then --set on top (as deform does).
    if (const auto frame = args.value("frame")) scenes::applyAnimationFrame(scene, parseFrame(*frame, scene.animation()));
    animation = {};
  }
  // Morph / skin: --set gives widgets that are not keyed their values for the whole animation.
  applySettings(scene.widgets, settings);

  // A skin carries the lattices' motion to every renderer: refuse one that folds space over
  // itself (the certified bound of checkFolding) at any key unless asked.
  if (options.content == exporters::GltfContent::Skin) {
    const std::vector<std::string> findings = skinFoldFindings(scene, animation);
    if (!findings.empty() && !args.flag("allow-folding")) {
      std::string message = "export --skin: the deformation folds space over itself:";
      for (const auto& f : findings) message += "\n  " + f;
      throw std::runtime_error(message + "\n(--allow-folding exports it anyway)");
    }
    for (const auto& f : findings) console.warn(f);
  }

  console.begin("export", "exporting " + *output);
  const exporters::GltfExportReport report = exporters::exportGltf(scene, animation, fs::path(*output), options);
  console.end();
  const std::string content(exporters::gltfContentName(report.content));
  console.say(format("wrote %s: %s, %d objects, %lld vertices, %lld triangles, %llu bytes", output->c_str(),
                     content.c_str(), report.objects, static_cast<long long>(report.vertices),
                     static_cast<long long>(report.triangles), static_cast<unsigned long long>(report.bytes)));
  if (report.content == exporters::GltfContent::Morph)
    console.say(format("morph targets: %d per mesh, %s weights; largest error at a key %.3g (float32 rounding)",
                       report.morphTargets, report.interpolation.c_str(), report.maxError));
  if (report.content == exporters::GltfContent::Skin) {
    console.say(format("skin: %d joints (the static joint and the control points), %d per vertex, joint scale %g, "
                       "%s translations at %zu sampled times",
                       report.joints, report.k, report.jointScale, report.interpolation.c_str(), report.samples.size()));
    console.say("time        error(k=4)  error(k=8)  all weights  (scene units; scene size " +
                format("%.4g", report.sceneSize) + ")");
    for (const auto& sample : report.samples)
      console.say(format("%-10.4g  %-10.3g  %-10.3g  %-10.3g", sample.time, sample.error4, sample.error8, sample.linearError));
    console.say(format("largest error with k = %d: %.3g (tolerance %g)", report.k, report.maxError, options.tolerance));
  }
  if (report.content == exporters::GltfContent::Frame)
    console.say(format("largest error: %.3g (float32 rounding)", report.maxError));
  console.printTimings();
  return 0;
}

}  // namespace

Command exportCommand() {
  return {"export",
          "write a scene as binary glTF 2.0 (.glb): a deformed frame, morph targets or a skin",
          "ffdkit-cli export SCENE -o OUT.glb [--frame F | --morph | --skin [--joints 4|8] [--tolerance E] [--allow-folding]]",
          "--frame F: the deformed meshes at frame F of the scene's animation (in its frame range;\n"
          "without any of the three: the scene as saved); --set values apply after it. With --morph /\n"
          "--skin, --set holds for the whole animation and keyed widgets take their keys.\n"
          "--morph: the undeformed meshes with one morph target per key; an animation drives their\n"
          "weights (STEP when every key is constant, else LINEAR): exact at the keys to float32.\n"
          "--skin: the undeformed meshes skinned to the lattices' control points (translation-only\n"
          "joints), each vertex keeping its 4 (or 8) largest FFD weights. The position error this\n"
          "causes is measured against ffdkit's own deformation at every key and frame and printed;\n"
          "above --tolerance (default 0.001, scene units) 4 joints become 8, and if 8 still exceed it\n"
          "nothing is written (exit 1, the message gives the errors). --joints fixes k. See docs/export.md.\n"
          "A skin whose lattices fold space over themselves at a key (the certified det J bound of\n"
          "info) is refused (exit 1, the message names the lattice, key and cells) unless --allow-folding.\n"
          "The file is written atomically: nothing is left behind when anything fails.\n",
          withReadOptions({{"output", 'o', "OUT.glb", "the .glb to write"},
           {"frame", '\0', "F", "export the deformed meshes at frame F of the scene's animation"},
           {"morph", '\0', "", "export the animation as morph targets"},
           {"skin", '\0', "", "export the animation as a skin on the lattices' control points"},
           {"joints", '\0', "K", "with --skin: joints per vertex, 4 or 8 (default 4, raised to 8 if needed)"},
           {"tolerance", '\0', "E", "with --skin: largest position error allowed (default 0.001)"},
           {"no-raise", '\0', "", "with --skin: refuse rather than raise 4 joints to 8"},
           {"allow-folding", '\0', "", "with --skin: export even when a lattice folds space over itself at a key"},
           {"no-normals", '\0', "", "write no NORMAL attributes"},
           setOption(), quietOption(), progressOption(), timingsOption()}),
          runExport};
}

}  // namespace ffdkit::cli
