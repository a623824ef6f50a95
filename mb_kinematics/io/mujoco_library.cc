#include "mb_kinematics/io/mujoco_library.h"

#include <dlfcn.h>

#include <stdexcept>

#if __has_include(<mujoco/mujoco.h>)
#include <mujoco/mujoco.h>
#define MBK_HAVE_MUJOCO_HEADERS 1
#endif

namespace mbk {

#ifdef MBK_HAVE_MUJOCO_HEADERS
namespace {

constexpr int kVersion = mjVERSION_HEADER;  // e.g. 222 for 2.2.2

std::string version_text(int version) {
  return std::to_string(version / 100) + "." + std::to_string(version / 10 % 10) + "." +
         std::to_string(version % 10);
}

std::string missing(const std::string& what) {
  return "MJCF models need MuJoCo " + version_text(kVersion) + "'s library " +
         mujoco_library_name() + " (Debian package libmujoco" + version_text(kVersion) +
         ", which libmujoco-dev installs): " + what;
}

template <typename F>
void bind(void* handle, const char* symbol, F& function) {
  function = reinterpret_cast<F>(dlsym(handle, symbol));
  if (!function) throw std::runtime_error(missing(std::string("it lacks ") + symbol));
}

MujocoLibrary open_library() {
  void* handle = dlopen(mujoco_library_name().c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error(missing(dlerror()));
  int (*version)() = nullptr;
  bind(handle, "mj_version", version);
  if (version() != kVersion)  // mjModel's layout changes between versions
    throw std::runtime_error(missing("it reports version " + version_text(version())));
  MujocoLibrary library;
  bind(handle, "mj_loadXML", library.load_xml);
  bind(handle, "mj_deleteModel", library.delete_model);
  bind(handle, "mj_defaultVFS", library.default_vfs);
  bind(handle, "mj_makeEmptyFileVFS", library.make_empty_file_vfs);
  bind(handle, "mj_findFileVFS", library.find_file_vfs);
  bind(handle, "mj_deleteVFS", library.delete_vfs);
  return library;  // the handle stays open for the process
}

}  // namespace

const MujocoLibrary& mujoco_library() {
  static const MujocoLibrary library = open_library();  // a failure is retried at the next call
  return library;
}

std::string mujoco_library_name() { return "libmujoco.so." + version_text(kVersion); }

#else

const MujocoLibrary& mujoco_library() {
  throw std::runtime_error(
      "MJCF models need MuJoCo: this mb_kinematics was built without its headers (Debian and "
      "Ubuntu package libmujoco-dev); install it and rebuild");
}

std::string mujoco_library_name() { return ""; }

#endif

}  // namespace mbk
