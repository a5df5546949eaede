// surfcomp's loadable modules: the parts that need a heavy shared library that most runs never
// use (Open MPI for `mpirun surfcomp screen`, cairo for the PNG images of patch-map) are shared
// objects loaded when first needed, so that the program does not map and initialise those
// libraries at every start (docs/decisions.md#loadable-modules).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp {

/// The folders searched for a module, in order. When the environment variable
/// SURFCOMP_MODULE_DIR is set and not empty, that folder alone. Otherwise: the modules' folder
/// relative to the program or shared object that holds this code, as installed (bin/surfcomp
/// finds lib/surfcomp/) and in the build tree, which has the same layout; the build tree's
/// modules folder; the modules folder of the configured install prefix.
std::vector<std::filesystem::path> module_folders();

/// The address of the exported symbol `symbol` of the module `file_name` (a file name such as
/// "libsurfcomp_png.so"), loaded from the first folder of module_folders() that holds the file.
/// The module stays loaded; a second call finds it loaded. Throws FileError naming the file and
/// the folders tried when none holds it, and with the system loader's reason when the file does
/// not load or lacks the symbol.
const void* module_symbol(const std::string& file_name, const std::string& symbol);

}  // namespace surfcomp
