# Finds every third-party dependency from Debian 12 packages (see debian-packages.txt)
# and exposes each as an imported target. Nothing is downloaded.

# Embree 3.13: the BVH and ray queries (libembree-dev). Target: embree
find_package(embree 3.13 REQUIRED)

# oneTBB 2021: parallel_for over image tiles (libtbb-dev). Target: TBB::tbb
find_package(TBB REQUIRED)

find_package(PkgConfig REQUIRED)

# OpenEXR 3.1 + Imath: HDR frame output with custom header attributes (libopenexr-dev).
# Trap: find_package(OpenEXR) loads Debian's Imath config, whose ImathTargets.cmake also
# imports Imath::PyImath_Python3_11 and so prints a "references the file libPyImath... but
# this file does not exist" message on every configure unless python3-imath is installed.
# OpenEXR.pc (which requires Imath.pc) names the same headers and libraries without the
# Python bindings, so use pkg-config. Target: tessera::openexr
pkg_check_modules(OPENEXR REQUIRED IMPORTED_TARGET OpenEXR>=3)
add_library(tessera::openexr ALIAS PkgConfig::OPENEXR)

# OpenImageIO 2.4: PNG/JPEG/PPM output, HDR/EXR environment-map input, and the heat map's
# colour map (ImageBufAlgo::color_map). Trap: Debian's OpenImageIOTargets.cmake names
# /usr/include/opencv4, which does not exist unless OpenCV's headers are installed, and CMake
# then refuses the target. pkg-config's OpenImageIO.pc is correct, so use it instead of
# find_package(OpenImageIO).
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
add_library(tessera::oiio ALIAS PkgConfig::OIIO)

# Cairo 1.16: the charts tessera draws (the heat map and the scaling plot), anti-aliased with
# FreeType text, as PNG or SVG (libcairo2-dev). Target: tessera::cairo
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo>=1.16 cairo-svg)
add_library(tessera::cairo ALIAS PkgConfig::CAIRO)

# MPI (openmpi-bin, libopenmpi-dev): distributed rendering across ranks (renderer/parallel/mpi_ranks.cpp).
# Optional: without it tessera builds and runs as one process (renderer/parallel/mpi_ranks_absent.cpp).
# The C API from C++ (the project has no C language enabled); the deprecated C++ bindings skipped.
set(MPI_CXX_SKIP_MPICXX ON)
find_package(MPI COMPONENTS CXX)
option(TESSERA_MPI "Distributed rendering with MPI (mpirun -np N tessera render ...)" ${MPI_CXX_FOUND})

# OpenColorIO (libopencolorio-dev): the preview's view transform, built in or from a
# studio's config (imageio/display_transform.cpp). Its pkg-config file, like OpenEXR's.
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO>=2.1)
add_library(tessera::ocio ALIAS PkgConfig::OCIO)

# tinygltf 2.7: glTF 2.0 JSON/GLB parsing (libtinygltf-dev). Debian ships it as a shared
# library with stb_image and nlohmann-json built in. Target: TinyGLTF::TinyGLTF
find_package(TinyGLTF REQUIRED)

# Draco 1.5: decodes KHR_draco_mesh_compression primitives (libdraco-dev; scene_io/decode/gltf_draco.cpp).
# Target: draco::draco
find_package(draco REQUIRED CONFIG)
# libdraco.so exports a tinygltf of its own (its glTF reader's, of another version): a program
# that links both must name libtinygltf.so first, or tinygltf's calls bind to Draco's copy and
# its classes differ. Draco as tinygltf's dependency puts it after tinygltf on every link line.
set_property(TARGET TinyGLTF::TinyGLTF APPEND PROPERTY INTERFACE_LINK_LIBRARIES draco::draco)

# meshoptimizer 0.18: decodes EXT_meshopt_compression buffer views and their filters
# (libmeshoptimizer-dev; scene_io/decode/gltf_meshopt.cpp). Target: meshoptimizer::meshoptimizer
find_package(meshoptimizer REQUIRED CONFIG)

# libwebp 1.2: decodes EXT_texture_webp images (libwebp-dev; scene_io/decode/gltf_images.cpp). It ships
# no CMake config, so pkg-config. Target: tessera::webp
pkg_check_modules(WEBP REQUIRED IMPORTED_TARGET libwebp)
add_library(tessera::webp ALIAS PkgConfig::WEBP)

# libjpeg-turbo 2.1's TurboJPEG API: decodes glTF's JPEG images (libturbojpeg0-dev;
# scene_io/decode/gltf_jpeg.cpp), several times faster than tinygltf's stb_image. Target: tessera::turbojpeg
pkg_check_modules(TURBOJPEG REQUIRED IMPORTED_TARGET libturbojpeg>=2.1)
add_library(tessera::turbojpeg ALIAS PkgConfig::TURBOJPEG)

# glm: vector and matrix math (libglm-dev), header only. Target: glm::glm
find_package(glm REQUIRED)

# Eigen 3.4: the small dense least-squares solves of the denoiser (libeigen3-dev), header
# only. Target: Eigen3::Eigen
find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# CLI11: command-line parsing with subcommands and --help (libcli11-dev).
find_package(CLI11 REQUIRED)

# fmt: message and table formatting (libfmt-dev).
find_package(fmt REQUIRED)

# nlohmann-json: every JSON document tessera reads or writes (nlohmann-json3-dev), header only.
find_package(nlohmann_json REQUIRED)

if(TESSERA_PYTHON)
  # The Python module: pybind11 (pybind11-dev) over CPython's headers (python3-dev); numpy
  # arrays in and out (python3-numpy), pytest for its tests (python3-pytest).
  # Debian's Python 3, whose numpy and pytest the packages install, even when another python3
  # comes first on PATH.
  if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the module is built for")
  endif()
  set(PYBIND11_FINDPYTHON ON)
  find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
  find_package(pybind11 REQUIRED CONFIG)
endif()

if(TESSERA_BUILD_TESTS)
  # GoogleTest via CTest (libgtest-dev).
  find_package(GTest REQUIRED)
endif()
