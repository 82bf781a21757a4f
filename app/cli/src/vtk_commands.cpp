// ffdkit-cli render and plot, and the .vtp and legacy .vtk writer, in a build with VTK: the
// commands' options live here, their work in the VTK module (modules.h), loaded when one of them
// runs, so that ffdkit-cli starts without VTK.
#include "commands.h"
#include "ffdkit/meshio/vtk_writer.h"
#include "module_loader.h"

namespace ffdkit::cli {

namespace {

int runRender(const Args& args) { return vtkModule("render").render(args); }

int runPlot(const Args& args) { return vtkModule("plot").plot(args); }

}  // namespace

Command renderCommand() {
  return {"render",
          "render a scene to PNG off screen",
          "ffdkit-cli render SCENE OUTPUT.png [--frame T] [--size WxH] [--camera PRESET] [--set NAME=VALUE]...\n"
          "       ffdkit-cli render SCENE --frames A:B -o out_%04d.png [options]",
          "Draws the scene's objects at their deformed points and its lattices, as the app shows\n"
          "them, into an off-screen window (needs an X display; use xvfb-run on a server).\n"
          "Camera presets: scene (the scene's own camera), front (from -y), side (from +x),\n"
          "top (from +z), iso (from (1,-1,1)); presets frame the deformed objects.\n"
          "Animation (docs/animation.md): --frame T renders the scene at frame T; --frames A:B renders\n"
          "every frame from A to B into -o PATTERN, whose one %0Nd becomes the frame number\n"
          "(out_%04d.png -> out_0007.png). Frames must lie in the scene's frame range. --set values\n"
          "are applied after the animation at every frame.\n",
          withReadOptions({{"size", '\0', "WxH", "image size in pixels (1024x768)"},
           {"output", 'o', "PATH", "the PNG (instead of OUTPUT.png), or with --frames a pattern with one %0Nd"},
           {"frame", '\0', "T", "render the animation at frame T (the scene's frame range)"},
           {"frames", '\0', "A:B", "render frames A..B into -o PATTERN (one PNG per frame)"},
           {"camera", '\0', "PRESET", "scene, front, top, side or iso (scene)"},
           setOption(), quietOption(), progressOption(), timingsOption()}),
          runRender};
}

Command plotCommand() {
  return {"plot",
          "plot curvature (and torsion) against arc length of a generated curve to PNG",
          "ffdkit-cli plot SCENE --object NAME -o PLOT.png [options]\n"
          "       ffdkit-cli plot --generator NAME PARAMETERS.json -o PLOT.png [options]",
          "The curve comes from a generated object of a scene (its generator, parameters and\n"
          "density) or from a generator name and a JSON object of its parameters (as written in\n"
          "a scene file's \"parameters\"). Curvature is orange; torsion, for space curves, blue.\n"
          "ffdkit-cli info --generators lists the curve generators. Needs an X display (xvfb-run).\n",
          withReadOptions({{"object", '\0', "NAME", "the generated curve object of SCENE"},
           {"generator", 'g', "NAME", "a curve generator of the registry"},
           {"output", 'o', "PLOT.png", "the PNG to write"},
           {"density", '\0', "D", "sampling relative to the generator's default, (0, 64] (the object's, or 1)"},
           {"size", '\0', "WxH", "image size in pixels (900x520)"},
           {"title", '\0', "TEXT", "chart title (the object or generator name)"},
           quietOption(), progressOption(), timingsOption()}),
          runPlot};
}

}  // namespace ffdkit::cli

namespace ffdkit::meshio {

// meshio's hook (ffdkit/meshio/vtk_writer.h): this definition replaces meshio's at link time, so
// VTK's writers are loaded with the module when a command writes .vtp or .vtk.
std::string vtkPolyDataBytes(const MeshData& mesh, bool xml) {
  std::string (*write)(const MeshData&, bool) = nullptr;
  try {
    write = cli::vtkModule(xml ? "writing a .vtp file" : "writing a legacy .vtk file").polyDataBytes;
  } catch (const cli::ModuleLoadError& e) {
    throw MeshIoError(e.what());
  }
  return write(mesh, xml);
}

}  // namespace ffdkit::meshio
