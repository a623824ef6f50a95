#include "mb_kinematics/io/sdf_model.h"

#include <dlfcn.h>

#include <stdexcept>

#include "mb_kinematics/io/sdformat_reader.h"
#include "mb_kinematics/io/text_file.h"

namespace mbk {
namespace {

// The reader library's file beside this library's own (devel or install space).
std::string reader_path() {
  Dl_info info;
  if (!dladdr(reinterpret_cast<void*>(&load_sdf_file), &info) || !info.dli_fname)
    return kSdformatReaderLibrary;
  const std::string self = info.dli_fname;
  const std::size_t slash = self.rfind('/');
  return slash == std::string::npos ? kSdformatReaderLibrary
                                    : self.substr(0, slash + 1) + kSdformatReaderLibrary;
}

SdformatReadFunction open_reader() {
  const std::string path = reader_path();
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const std::string why = dlerror();
    if (why.find("libsdformat") != std::string::npos)
      throw std::runtime_error(
          "SDFormat models need sdformat's library libsdformat12.so.12 (Debian package "
          "libsdformat12-12, which libsdformat-dev installs): " +
          why);
    throw std::runtime_error(
        "SDFormat models need " + path +
        ", built when sdformat's headers are installed (Debian and Ubuntu package "
        "libsdformat-dev; install it and rebuild): " +
        why);
  }
  auto read = reinterpret_cast<SdformatReadFunction>(dlsym(handle, kSdformatReadSymbol));
  if (!read) throw std::runtime_error(path + " lacks " + kSdformatReadSymbol);
  return read;
}

SdformatReadFunction reader() {
  static const SdformatReadFunction read = open_reader();
  return read;
}

Model load(const std::string& path_or_text, bool text, const std::string& source) {
  SdformatReadFunction read = reader();
  Model model;
  std::string error;
  if (!read(path_or_text, text, source, model, error)) throw std::invalid_argument(error);
  return model;
}

}  // namespace

bool is_sdf_text(const std::string& xml) { return xml_root_is(xml, "sdf"); }

Model load_sdf_file(const std::string& path) {
  read_text_file(path, "SDFormat file");  // the project's message for a file that cannot be read
  return load(path, false, path);
}

Model load_sdf_string(const std::string& xml, const std::string& source) {
  return load(xml, true, source);
}

}  // namespace mbk
