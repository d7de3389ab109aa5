# Finds every third-party dependency from Debian 12 packages (see debian-packages.txt)
# and exposes each as an imported target. Nothing is downloaded.

# Embree 3.13: the BVH and ray queries (libembree-dev). Target: embree
find_package(embree 3.13 REQUIRED)

# oneTBB 2021: parallel_for over image tiles (libtbb-dev). Target: TBB::tbb
find_package(TBB REQUIRED)

# OpenEXR 3.1 + Imath: HDR frame output with custom header attributes (libopenexr-dev).
find_package(OpenEXR 3 REQUIRED)

# OpenImageIO 2.4: PNG/JPEG/PPM output and HDR/EXR environment-map input.
# Trap: Debian's OpenImageIOTargets.cmake names /usr/include/opencv4, which does not exist
# unless OpenCV's headers are installed, and CMake then refuses the target. pkg-config's
# OpenImageIO.pc is correct, so use it instead of find_package(OpenImageIO).
find_package(PkgConfig REQUIRED)
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
add_library(tessera::oiio ALIAS PkgConfig::OIIO)

# tinygltf 2.7: glTF 2.0 JSON/GLB parsing (libtinygltf-dev). Debian ships it as a shared
# library with stb_image and nlohmann-json built in. Target: TinyGLTF::TinyGLTF
find_package(TinyGLTF REQUIRED)

# Draco 1.5: decodes KHR_draco_mesh_compression primitives (libdraco-dev; scene_io/gltf_draco.cpp).
# Target: draco::draco
find_package(draco REQUIRED CONFIG)

# meshoptimizer 0.18: decodes EXT_meshopt_compression buffer views and their filters
# (libmeshoptimizer-dev; scene_io/gltf_meshopt.cpp). Target: meshoptimizer::meshoptimizer
find_package(meshoptimizer REQUIRED CONFIG)

# libwebp 1.2: decodes EXT_texture_webp images (libwebp-dev; scene_io/gltf_images.cpp). It ships
# no CMake config, so pkg-config. Target: tessera::webp
pkg_check_modules(WEBP REQUIRED IMPORTED_TARGET libwebp)
add_library(tessera::webp ALIAS PkgConfig::WEBP)

# glm: vector and matrix math (libglm-dev), header only. Target: glm::glm
find_package(glm REQUIRED)

# Eigen 3.4: the small dense least-squares solves of the denoiser (libeigen3-dev), header
# only. Target: Eigen3::Eigen
find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# CLI11: command-line parsing with subcommands and --help (libcli11-dev).
find_package(CLI11 REQUIRED)

# fmt: message and table formatting (libfmt-dev).
find_package(fmt REQUIRED)

# nlohmann-json: JSON output for stats (nlohmann-json3-dev), header only.
find_package(nlohmann_json REQUIRED)

if(TESSERA_BUILD_TESTS)
  # GoogleTest via CTest (libgtest-dev).
  find_package(GTest REQUIRED)
endif()
