#include "surfcomp/core/loadable_module.hpp"

#include "surfcomp/core/error.hpp"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cstdlib>
#include <system_error>

namespace surfcomp {
namespace {

/// The program, or the shared object (the Python extension) that holds this code.
std::filesystem::path holding_object() {
  static const char anchor = 0;
  Dl_info info{};
  void* map = nullptr;
  if (dladdr1(&anchor, &info, &map, RTLD_DL_LINKMAP) != 0 && map != nullptr) {
    // The program's own entry has an empty name; a shared object's is the path it was loaded by.
    const char* name = static_cast<const link_map*>(map)->l_name;
    if (name != nullptr && *name != '\0') {
      std::error_code error;
      std::filesystem::path path = std::filesystem::absolute(name, error);
      if (!error) return path;
    }
  }
  std::error_code error;
  return std::filesystem::read_symlink("/proc/self/exe", error);
}

}  // namespace

std::vector<std::filesystem::path> module_folders() {
  if (const char* set = std::getenv("SURFCOMP_MODULE_DIR"); set != nullptr && *set != '\0')
    return {std::filesystem::path(set)};
  std::vector<std::filesystem::path> folders;
  const std::filesystem::path object = holding_object();
  if (!object.empty())
    folders.push_back((object.parent_path() / SURFCOMP_MODULE_RELATIVE_DIR).lexically_normal());
  for (const char* folder : {SURFCOMP_MODULE_BUILD_DIR, SURFCOMP_MODULE_INSTALL_DIR}) {
    const std::filesystem::path path = std::filesystem::path(folder).lexically_normal();
    if (std::find(folders.begin(), folders.end(), path) == folders.end()) folders.push_back(path);
  }
  return folders;
}

const void* module_symbol(const std::string& file_name, const std::string& symbol) {
  const std::vector<std::filesystem::path> folders = module_folders();
  std::string tried;
  for (const std::filesystem::path& folder : folders) {
    const std::filesystem::path path = folder / file_name;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
      tried += (tried.empty() ? "" : ", ") + folder.string();
      continue;
    }
    // RTLD_LOCAL: the module's symbols and its libraries' stay out of the global scope, where
    // every later lookup of the program would search them.
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (module == nullptr) throw FileError(path.string(), std::string("cannot load: ") + dlerror());
    dlerror();
    const void* address = dlsym(module, symbol.c_str());
    if (address == nullptr) {
      const char* reason = dlerror();
      throw FileError(path.string(),
                      "lacks " + symbol + (reason != nullptr ? ": " + std::string(reason) : ""));
    }
    return address;
  }
  throw FileError(
      file_name, "not found in " + tried + "; set SURFCOMP_MODULE_DIR to the folder that holds it");
}

}  // namespace surfcomp
