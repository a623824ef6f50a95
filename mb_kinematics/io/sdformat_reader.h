// The interface of the SDFormat reader library (libmbk_sdformat.so, linked with libsdformat12),
// which io/sdf_model.cc opens when the first SDFormat model is read: mbk_io itself does not need
// sdformat to load.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

constexpr const char* kSdformatReaderLibrary = "libmbk_sdformat.so";
constexpr const char* kSdformatReadSymbol = "mbk_read_sdformat";

// Reads a file (text = false) or an SDFormat text into `model` (finalized); false with a one-line
// `error` ("<source>: <what>", control characters escaped) for a model sdformat refuses or that
// does not map.
using SdformatReadFunction = bool (*)(const std::string& path_or_text, bool text,
                                      const std::string& source, Model& model, std::string& error);

}  // namespace mbk
