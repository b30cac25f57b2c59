// rosmill primitive NAME -o FILE.stl [--ascii]: writes a test primitive of "Tool Path Generation for CNC Milling based
// on STL Files" (Eng. & Tech. Journal 33(A) 2, 2015).
#include <cstdio>
#include <memory>

#include "command.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"

namespace rosmill::core::cli {
namespace {

struct PrimitiveArgs {
  std::string name;
  std::string output;
  bool ascii = false;
};

CommandRegistration registration([](CLI::App& app) {
  auto args = std::make_shared<PrimitiveArgs>();
  auto* cmd = app.add_subcommand(
      "primitive", "write a test primitive of the STL slicing paper (cube, cylinder, dome, cone, cavity) as STL");
  cmd->add_option("NAME", args->name, "cube | cylinder | dome | cone | cavity")
      ->required()
      ->check(CLI::IsMember(primitive_names()));
  cmd->add_option("-o,--output", args->output, "STL file to write")->required();
  cmd->add_flag("--ascii", args->ascii, "write ASCII STL (default binary)");
  cmd->callback([args] {
    const Mesh mesh = make_primitive(args->name);
    write_stl(args->output, mesh, args->ascii);
    std::printf("%s: %zu triangles -> %s\n", args->name.c_str(), mesh.face_count(), args->output.c_str());
  });
});

}  // namespace
}  // namespace rosmill::core::cli
