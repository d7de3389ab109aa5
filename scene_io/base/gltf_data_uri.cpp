#include "scene_io/base/gltf_data_uri.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace tessera {
namespace {

constexpr char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

std::string shown(char c) {
  return std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c)
                                                      : fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
}

// %XX escapes decoded; nullopt (and `problem`) for a '%' not followed by two hex digits.
std::optional<std::string> percent_decoded(const std::string& data, std::string& problem) {
  std::string out;
  out.reserve(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (data[i] != '%') {
      out += data[i];
      continue;
    }
    const int hi = i + 2 < data.size() ? hex_value(data[i + 1]) : -1;
    const int lo = i + 2 < data.size() ? hex_value(data[i + 2]) : -1;
    if (hi < 0 || lo < 0) {
      problem = fmt::format("with a '%' that is not followed by two hexadecimal digits (character {} of its data)", i);
      return std::nullopt;
    }
    out += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return out;
}

std::optional<std::vector<std::uint8_t>> base64_decoded(std::string text, std::string& problem) {
  std::size_t end = text.size();
  while (end > 0 && text.size() - end < 2 && text[end - 1] == '=') --end;
  std::vector<std::uint8_t> out;
  out.reserve(end / 4 * 3 + 2);
  std::uint32_t group = 0;
  int bits = 0;
  for (std::size_t i = 0; i < end; ++i) {
    const int v = base64_value(text[i]);
    if (v < 0) {
      problem = fmt::format("that is not valid base64 (character {} of its data is '{}')", i, shown(text[i]));
      return std::nullopt;
    }
    group = (group << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>(group >> bits));
      group &= (1u << bits) - 1;
    }
  }
  if (end % 4 == 1) {
    problem = fmt::format("that is not valid base64 (its {} characters of data leave 6 bits over)", end);
    return std::nullopt;
  }
  return out;
}

}  // namespace

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

std::string data_uri_media_type(const std::string& uri) {
  if (!is_data_uri(uri)) return "";
  std::string type = uri.substr(5, std::min(uri.find(';'), uri.find(',')) - 5);
  for (char& c : type) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));  // RFC 2045
  return type;
}

std::optional<DataUri> decode_data_uri(const std::string& uri, std::string& problem) {
  const std::size_t comma = uri.find(',');
  if (!is_data_uri(uri) || comma == std::string::npos) {
    problem = "without the ',' that ends its header (data:[media type][;base64],data)";
    return std::nullopt;
  }
  const std::string header = uri.substr(5, comma - 5);
  const bool base64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
  DataUri out;
  out.media_type = data_uri_media_type(uri);
  // Between the media type and ";base64", only attribute=value parameters.
  const std::size_t params_end = base64 ? header.size() - 7 : header.size();
  for (std::size_t at = header.find(';'); at < params_end;) {
    const std::size_t next = std::min(header.find(';', at + 1), params_end);
    const std::string parameter = header.substr(at + 1, next - at - 1);
    if (parameter.find('=') == std::string::npos || parameter.front() == '=') {
      problem = fmt::format("whose header has a parameter '{}' that is not attribute=value", parameter.substr(0, 40));
      return std::nullopt;
    }
    at = next;
  }
  std::optional<std::string> data = percent_decoded(uri.substr(comma + 1), problem);
  if (!data) return std::nullopt;
  if (!base64) {
    out.bytes.assign(data->begin(), data->end());
    return out;
  }
  std::optional<std::vector<std::uint8_t>> bytes = base64_decoded(std::move(*data), problem);
  if (!bytes) return std::nullopt;
  out.bytes = std::move(*bytes);
  return out;
}

std::string encode_data_uri(const std::string& media_type, const std::vector<std::uint8_t>& bytes) {
  std::string out = "data:" + media_type + ";base64,";
  out.reserve(out.size() + (bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = static_cast<std::uint32_t>(bytes[i]) << 16 |
                            (i + 1 < bytes.size() ? static_cast<std::uint32_t>(bytes[i + 1]) << 8 : 0u) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0u);
    out += kBase64[n >> 18 & 63];
    out += kBase64[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kBase64[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kBase64[n & 63] : '=';
  }
  return out;
}

}  // namespace tessera
