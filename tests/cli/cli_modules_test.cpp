// The heavy shared libraries come in only with the work that needs them (loadable_module.hpp):
// RDKit with the first molecule read through it, Open MPI under mpirun, cairo with the first PNG.
// A process that reads a PQR file or prints its version maps none of them.
#include "program_run.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"

#include <gtest/gtest.h>
#include <link.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;

/// The file names of the shared objects mapped into this process.
std::vector<std::string> loaded_objects() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) {
        if (info->dlpi_name != nullptr && *info->dlpi_name != '\0') {
          static_cast<std::vector<std::string>*>(out)->push_back(
              fs::path(info->dlpi_name).filename().string());
        }
        return 0;
      },
      &names);
  return names;
}

bool is_loaded(const std::string& prefix) {
  for (const std::string& name : loaded_objects()) {
    if (name.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

fs::path scratch(const std::string& name) {
  const fs::path folder =
      fs::temp_directory_path() / ("surfcomp_modules_test_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  return folder / name;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// A glycine residue in PQR (charge and radius columns) and ethanol as a mol block.
const char* kGlycinePqr =
    "ATOM      1  N   GLY A   1       7.179   3.473  -5.160  0.2943 1.8240\n"
    "ATOM      2  CA  GLY A   1       6.122   4.429  -5.466 -0.0100 1.9080\n"
    "ATOM      3  C   GLY A   1       4.810   3.747  -5.402  0.6163 1.9080\n"
    "ATOM      4  O   GLY A   1       4.814   2.506  -5.096 -0.5722 1.6612\n"
    "END\n";

const char* kEthanolSdf =
    "ethanol\n     surfcomp\n\n"
    "  3  2  0  0  0  0  0  0  0  0999 V2000\n"
    "   -0.8883    0.1670   -0.0273 C   0  0  0  0  0  0  0  0  0  0  0  0\n"
    "    0.4658   -0.5116   -0.0368 C   0  0  0  0  0  0  0  0  0  0  0  0\n"
    "    1.4311    0.3229    0.5867 O   0  0  0  0  0  0  0  0  0  0  0  0\n"
    "  1  2  1  0\n  2  3  1  0\nM  END\n$$$$\n";

TEST(LoadableModules, RdkitComesInWithTheFirstMoleculeReadThroughIt) {
  ASSERT_FALSE(is_loaded("libRDKit")) << "the test program itself maps RDKit";
  const fs::path pqr = scratch("glycine.pqr");
  write(pqr, kGlycinePqr);
  const surfcomp::Molecule glycine = surfcomp::io::read_molecule(pqr);
  EXPECT_EQ(glycine.atoms.size(), 4U);
  EXPECT_FALSE(is_loaded("libRDKit")) << "reading a PQR file of standard residues needs no RDKit";
  EXPECT_FALSE(is_loaded("libsurfcomp_rdkit"));

  const fs::path sdf = scratch("ethanol.sdf");
  write(sdf, kEthanolSdf);
  const surfcomp::Molecule ethanol = surfcomp::io::read_molecule(sdf);
  EXPECT_EQ(ethanol.atoms.size(), 3U);
  EXPECT_TRUE(is_loaded("libsurfcomp_rdkit.so"));
  EXPECT_TRUE(is_loaded("libRDKitGraphMol"));
  fs::remove_all(pqr.parent_path());
}

TEST(LoadableModules, TheModuleThrowsCoreErrorsTheCallerCatches) {
  const fs::path sdf = scratch("truncated.sdf");
  write(sdf, std::string(kEthanolSdf).substr(0, 120));
  EXPECT_THROW(surfcomp::io::read_molecule(sdf), surfcomp::FormatError);
  fs::remove_all(sdf.parent_path());
}

TEST(LoadableModules, VersionMapsNeitherRdkitNorMpiNorCairo) {
  // LD_DEBUG=files: the dynamic loader names every object it opens.
  const surfcomp::test::ProgramRun run =
      surfcomp::test::run_program("--version", {{}, "LD_DEBUG=files "});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("surfcomp "), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("file=libtbb"), std::string::npos)
      << "LD_DEBUG printed no library loads: " << run.err;
  for (const char* heavy : {"file=libRDKit", "file=libmpi", "file=libcairo", "file=libhwy"})
    EXPECT_EQ(run.err.find(heavy), std::string::npos) << heavy << " in\n" << run.err;
}

TEST(LoadableModules, AMissingModuleIsOneLineAndNoOutput) {
  const fs::path sdf = scratch("ethanol.sdf");
  write(sdf, kEthanolSdf);
  const fs::path empty = scratch("no-modules");
  fs::create_directories(empty);
  const fs::path out = scratch("ethanol.ply");
  const surfcomp::test::ProgramRun run =
      surfcomp::test::run_program("surf-build " + sdf.string() + " -o " + out.string(),
                                  {{}, "SURFCOMP_MODULE_DIR=" + empty.string() + " "});
  EXPECT_EQ(run.status, 1) << run.err;
  EXPECT_NE(run.err.find("libsurfcomp_rdkit.so: not found in " + empty.string()), std::string::npos)
      << run.err;
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(sdf.parent_path());
}

}  // namespace
