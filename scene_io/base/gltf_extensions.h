// Which glTF extensions tessera reads, and what it does with each one a file names.
#pragma once

#include <string>
#include <vector>

namespace tessera {

enum class ExtensionSupport {
  Supported,  // implemented
  Fallback,   // not decoded; the file's fallback (e.g. a PNG beside a KTX2 image) is used
  Ignored,    // not implemented: refused when required, else ignored
};

struct ExtensionStatus {
  ExtensionSupport support;
  std::string why;  // for Fallback and Ignored: one short clause
};

ExtensionStatus gltf_extension_status(const std::string& name);

// "supported", "used as a fallback: ...", "ignored: ..." (for `tessera info`).
std::string describe_extension_status(const std::string& name);

// Extensions tessera accepts in extensionsRequired (Supported and Fallback ones).
const std::vector<std::string>& supported_gltf_extensions();
bool is_supported_gltf_extension(const std::string& name);

}  // namespace tessera
