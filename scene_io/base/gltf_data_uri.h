// RFC 2397 data URIs, as glTF buffers and images may give their bytes:
// data:[<media type>][;<parameter>...][;base64],<data>. The data is percent-encoded bytes, or
// base64 (which may itself hold percent escapes). tinygltf decodes only plain base64 of a few
// media types, so gltf_prepare.cpp hands it every other readable data URI re-encoded that way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tessera {

struct DataUri {
  std::string media_type;  // "application/octet-stream"; empty when the URI gives none
  std::vector<std::uint8_t> bytes;
};

// True when `uri` starts with "data:".
bool is_data_uri(const std::string& uri);

// The media type of data URI `uri`, lower case (RFC 2045); empty when it gives none. Reads
// only the header, so it costs nothing for a large URI.
std::string data_uri_media_type(const std::string& uri);

// The URI decoded, or nullopt with `problem` set to what is wrong, worded to follow
// "buffer 0 has a data URI " ("that is not valid base64 (character 4 of its data is '!')").
std::optional<DataUri> decode_data_uri(const std::string& uri, std::string& problem);

// data:<media type>;base64,<bytes in base64>
std::string encode_data_uri(const std::string& media_type, const std::vector<std::uint8_t>& bytes);

}  // namespace tessera
