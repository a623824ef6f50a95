// MuJoCo's C library, opened when an MJCF file is first read (dlopen), so that mbk, the node and
// the Python module start without it and a missing library is one error naming its package.
// Built with MuJoCo's headers (Debian: libmujoco-dev); without them every call throws.
#pragma once

#include <string>

struct mjModel_;
struct mjVFS_;

namespace mbk {

// The functions of libmujoco the MJCF loader calls, with MuJoCo's signatures.
struct MujocoLibrary {
  mjModel_* (*load_xml)(const char* filename, const mjVFS_* vfs, char* error, int error_size);
  void (*delete_model)(mjModel_* model);
  void (*default_vfs)(mjVFS_* vfs);
  int (*make_empty_file_vfs)(mjVFS_* vfs, const char* filename, int filesize);
  int (*find_file_vfs)(const mjVFS_* vfs, const char* filename);
  void (*delete_vfs)(mjVFS_* vfs);
};

// libmujoco of the version of the headers it was built with, opened once. Throws
// std::runtime_error naming the Debian package when it cannot be opened or has another version.
const MujocoLibrary& mujoco_library();

// The library's file name the build expects, e.g. "libmujoco.so.2.2.2" ("" without headers).
std::string mujoco_library_name();

}  // namespace mbk
