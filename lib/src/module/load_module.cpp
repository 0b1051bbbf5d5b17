#include "rodlab/module.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>
#include <vector>

namespace rodlab {

namespace fs = std::filesystem;

namespace {

/// Where to look for the module the build put at `built`, in order and without repeats.
std::vector<fs::path> candidates(const fs::path& built) {
  std::vector<fs::path> paths;
  auto add = [&](const fs::path& p) {
    for (const auto& q : paths)
      if (q == p) return;
    paths.push_back(p);
  };
  const fs::path name = built.filename();
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&load_module), &self) != 0 && self.dli_fname &&
      fs::path(self.dli_fname).is_absolute()) {
    const fs::path object(self.dli_fname);
    if (std::error_code e; !fs::equivalent(object, "/proc/self/exe", e))
      add(object.parent_path() / name);  // a shared object holds this code: the Python module
  }
  std::error_code error;
  if (const fs::path program = fs::read_symlink("/proc/self/exe", error); !error)
    add(program.parent_path().parent_path() / "lib" / name);
  add(built);
  return paths;
}

}  // namespace

const void* load_module(const std::string& built, const char* symbol, std::string& why) {
  why.clear();
  for (const fs::path& path : candidates(built)) {
    if (void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL)) {
      if (auto* table = reinterpret_cast<const void* (*)()>(::dlsym(handle, symbol)))
        return table();
      why += (why.empty() ? "" : "; ") + path.string() + " has no " + symbol;
      continue;
    }
    const char* error = ::dlerror();
    why += (why.empty() ? "" : "; ") + (error ? std::string(error) : path.string());
  }
  return nullptr;
}

}  // namespace rodlab
