// libFuzzer harness: the PLY reader, ascii and binary (read_ply from a stream; the seeds hold
// both encodings).
#include "fuzz_mesh.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    surfcomp::fuzz::check_surface(surfcomp::mesh::io::read_ply(in, "fuzz.ply"));
  } catch (const surfcomp::Error&) {
  }
  return 0;
}
