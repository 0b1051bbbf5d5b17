#pragma once
// Modules: shared objects that rodlab loads with dlopen only when a run needs them, so that no
// other process maps their libraries at start-up (every shared object a program links is opened,
// mapped and relocated before main; docs/performance.md "Process start-up"). Each module exports
// one C function returning its table of calls (validation/studies/mpi_module.hpp,
// solvers/control/ceres_module.hpp).
#include <string>

namespace rodlab {

/// Loads the module whose file the build put at `built` and returns what its exported C function
/// `symbol` returns (its table of calls). The file is looked for, by its name, beside the object
/// holding this code when that is a shared object (the Python module), in the lib/ directory
/// beside the running program's bin/ (the build tree's layout), and at `built`. RTLD_GLOBAL, so
/// that a library the module opens in turn (OpenMPI's components) sees its symbols. Returns
/// nullptr, with what was tried and why each failed in `why`, when none loads.
const void* load_module(const std::string& built, const char* symbol, std::string& why);

/// The same, typed: `Api` is the module's table.
template <class Api>
const Api* load_module_api(const std::string& built, const char* symbol, std::string& why) {
  return static_cast<const Api*>(load_module(built, symbol, why));
}

}  // namespace rodlab
