// libFuzzer harness: the OBJ reader (read_obj of a scratch .obj file).
#include "fuzz_input.hpp"
#include "fuzz_mesh.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static surfcomp::fuzz::ScratchFile file(".obj");
  try {
    surfcomp::fuzz::check_surface(surfcomp::mesh::io::read_obj(file.write(data, size)));
  } catch (const surfcomp::Error&) {
  }
  return 0;
}
