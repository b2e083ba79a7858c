// Loading the PETSc module (petsc_plugin.hpp) on first use, and what depends on it.
#include "petsc_plugin.hpp"

#include <dlfcn.h>

#include <filesystem>

#include "perinom/core/error.hpp"
#include "perinom/solvers/petsc.hpp"

namespace perinom {
namespace {

std::string& pending_options() {
  static std::string options;
  return options;
}

struct Module {
  const detail::PetscPlugin* plugin = nullptr;
  std::string why;  ///< why it is absent
};

/// libperinom_petsc.so from the folder this library was loaded from (build or install tree).
const Module& module() {
  static const Module m = [] {
    Module out;
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&petsc_available), &info) || !info.dli_fname) {
      out.why = "the folder of libperinom is unknown";
      return out;
    }
    const std::filesystem::path path = std::filesystem::path(info.dli_fname).parent_path() / "libperinom_petsc.so";
    if (!std::filesystem::exists(path)) {
      out.why = "this perinom was built without PETSc (install petsc-dev and rebuild)";
      return out;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      out.why = std::string("its PETSc module did not load: ") + dlerror();
      return out;
    }
    const auto entry = reinterpret_cast<const detail::PetscPlugin* (*)()>(dlsym(handle, "perinom_petsc_plugin"));
    if (!entry) out.why = path.string() + " has no entry point";
    else out.plugin = entry();
    return out;
  }();
  return m;
}

bool& loaded() {
  static bool flag = false;
  return flag;
}

}  // namespace

namespace detail {
const PetscPlugin& petsc_plugin(const std::string& what) {
  const Module& m = module();
  loaded() = true;
  if (!m.plugin) throw InputError(what + " needs PETSc, and " + m.why);
  return *m.plugin;
}
}  // namespace detail

bool petsc_available() {
  loaded() = true;
  return module().plugin != nullptr;
}

void set_petsc_options(const std::string& options) {
  detail::petsc_plugin("--petsc-options");
  pending_options() = options;
}

void finalize_petsc() {
  if (loaded() && module().plugin) module().plugin->finalize();
}

namespace detail {
SolveReport solve_newton_petsc(TangentModel& model, const Loading& loading, const NewtonOptions& options,
                               std::vector<double>& u, Progress* progress) {
  const PetscPlugin& p = petsc_plugin("solver.linear_solver: " + options.linear_solver);
  return p.solve_newton(model, loading, options, u, progress, pending_options());
}
}  // namespace detail

}  // namespace perinom
