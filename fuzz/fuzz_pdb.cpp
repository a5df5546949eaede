// libFuzzer harness: the PDB reader (read_molecule of a .pdb file).
#include "fuzz_molecule.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  surfcomp::fuzz::fuzz_molecule_reader(data, size, ".pdb", true);
  return 0;
}
