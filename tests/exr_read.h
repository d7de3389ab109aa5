// Reading what tessera wrote, for the tests: the RGB pixels and header attributes of an EXR.
#pragma once

#include <string>
#include <vector>

namespace tessera::test {

std::vector<float> exr_rgb(const std::string& path);  // interleaved R, G, B, top row first
int exr_int(const std::string& path, const char* attribute);
float exr_float(const std::string& path, const char* attribute);
std::vector<float> exr_m44f(const std::string& path, const char* attribute);  // 16 values, row by row

}  // namespace tessera::test
