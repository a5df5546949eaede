// libFuzzer harness: the OFF reader (read_off of a scratch .off file).
#include "fuzz_input.hpp"
#include "fuzz_mesh.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/off.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static surfcomp::fuzz::ScratchFile file(".off");
  try {
    surfcomp::fuzz::check_surface(surfcomp::mesh::io::read_off(file.write(data, size)));
  } catch (const surfcomp::Error&) {
  }
  return 0;
}
