// Reading what tessera wrote, for the tests: the RGB pixels and header attributes of an EXR.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace tessera::test {

std::vector<float> exr_rgb(const std::string& path);  // the data window's R, G, B interleaved, top row first
// The data and display windows, each as {min x, min y, max x, max y} (inclusive).
struct ExrWindows {
  std::array<int, 4> data, display;
};
ExrWindows exr_windows(const std::string& path);
int exr_int(const std::string& path, const char* attribute);
std::string exr_string(const std::string& path, const char* attribute);
float exr_float(const std::string& path, const char* attribute);
std::vector<float> exr_m44f(const std::string& path, const char* attribute);  // 16 values, row by row

}  // namespace tessera::test
