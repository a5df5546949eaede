// libFuzzer harness: the MSMS reader (read_msms of a scratch X.vert / X.face pair). The input is
// the .vert content, a NUL byte, then the .face content (no NUL: an empty .face).
#include "fuzz_input.hpp"
#include "fuzz_mesh.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/msms.hpp"

#include <algorithm>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static surfcomp::fuzz::ScratchFile vert(".vert");
  static surfcomp::fuzz::ScratchFile face(".face");
  const std::uint8_t* end = data + size;
  const std::uint8_t* split = std::find(data, end, std::uint8_t{0});
  vert.write(data, static_cast<std::size_t>(split - data));
  face.write(split == end ? end : split + 1,
             split == end ? 0 : static_cast<std::size_t>(end - split - 1));
  try {
    surfcomp::fuzz::check_surface(surfcomp::mesh::io::read_msms(vert.path()));
  } catch (const surfcomp::Error&) {
  }
  return 0;
}
