// libFuzzer harness: the MOL2 reader (read_molecule of a .mol2 file).
#include "fuzz_molecule.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  surfcomp::fuzz::fuzz_molecule_reader(data, size, ".mol2", false);
  return 0;
}
