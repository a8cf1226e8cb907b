// The mesh readers (then TriangleMesh::validate, as scenes do) and ParaView
// presets (JSON text, and files: JSON or XML).
#include "harness.h"

#include "penumbra/io/mesh_reader.h"
#include "penumbra/io/paraview_preset.h"

namespace penumbra::fuzz {
namespace {

std::string_view as_text(Input input) { return {reinterpret_cast<const char*>(input.data()), input.size()}; }

}  // namespace

void fuzz_obj(Input input) { read_mesh(write_input("input.obj", input)).validate("input.obj"); }

void fuzz_ply(Input input) { read_mesh(write_input("input.ply", input)).validate("input.ply"); }

void fuzz_preset(Input input) {
  const std::string_view text = as_text(input);
  if (!text.empty() && text.front() == '<') {
    const auto path = write_input("input.xml", input);
    (void)paraview_preset_names(path);
    (void)read_paraview_preset(path);
    return;
  }
  (void)parse_paraview_preset(text);
  (void)paraview_preset_names(write_input("input.json", input));
}

}  // namespace penumbra::fuzz
