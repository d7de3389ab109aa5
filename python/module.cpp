// tessera._native (and _native_x86_64_v3): what the Python package (python/tessera/__init__.py) is built on. A session
// renders in memory (app/session/frame_session.h) on a thread of its own while the calling
// thread, without the GIL, waits; every 50 ms it takes the GIL back to report progress and to
// let Python see a Ctrl-C, which cancels the render (tiles under way finish) and raises
// KeyboardInterrupt. EXR files are read and written through imageio, as the program does.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "app/isa_dispatch.h"
#include "app/session/frame_session.h"
#include "imageio/exr_header.h"
#include "imageio/frame_layers.h"
#include "imageio/image_input.h"
#include "imageio/image_output.h"
#include "renderer/util/isa.h"
#include "scene_io/base/load_error.h"

namespace py = pybind11;

namespace tessera {
namespace {

// The package's exceptions; created with the module.
PyObject* error_type = nullptr;  // tessera.Error
PyObject* usage_error_type = nullptr;  // tessera.UsageError: also a ValueError
PyObject* scene_error_type = nullptr;  // tessera.SceneLoadError: also a ValueError
PyObject* file_error_type = nullptr;  // tessera.FileError: also an OSError

void translate_exception(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const UsageError& e) {
    PyErr_SetString(usage_error_type, e.what());
  } catch (const SceneLoadError& e) {
    PyErr_SetString(scene_error_type, e.what());
  } catch (const OutputError& e) {
    PyErr_SetString(file_error_type, e.what());
  } catch (const ImageInputError& e) {
    PyErr_SetString(file_error_type, e.what());
  } catch (const std::invalid_argument& e) {  // an unreadable environment map, a bad layer
    PyErr_SetString(usage_error_type, e.what());
  }
}

py::dict layers_dict(const std::vector<ImageLayer>& layers, int width, int height) {
  py::dict out;
  for (const ImageLayer& layer : layers) {
    const auto channels = static_cast<py::ssize_t>(layer.channels.size());
    py::array_t<float> a({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width), channels});
    std::memcpy(a.mutable_data(), layer.pixels.data(), layer.pixels.size() * sizeof(float));
    out[py::str(layer.name)] = a;
  }
  return out;
}

// Floats come back as numpy.float32 and doubles as Python floats, so a header read and written
// again keeps each attribute's type; matrices as 4x4 float32 arrays, [i][j] as OpenEXR's M44f.
py::object attribute_value(const HeaderAttribute& a) {
  if (const auto* s = std::get_if<std::string>(&a.value)) return py::str(*s);
  if (const auto* i = std::get_if<int>(&a.value)) return py::int_(*i);
  if (const auto* d = std::get_if<double>(&a.value)) return py::float_(*d);
  py::module_ numpy = py::module_::import("numpy");
  if (const auto* f = std::get_if<float>(&a.value)) return numpy.attr("float32")(*f);
  const glm::mat4& m = std::get<glm::mat4>(a.value);
  py::array_t<float> out({4, 4});
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out.mutable_at(i, j) = m[i][j];
  return std::move(out);
}

py::dict metadata_dict(const std::vector<HeaderAttribute>& attributes) {
  py::dict out;
  for (const HeaderAttribute& a : attributes) out[py::str(a.name)] = attribute_value(a);
  return out;
}

HeaderAttribute attribute_from(const std::string& name, py::handle value) {
  py::module_ numpy = py::module_::import("numpy");
  if (py::isinstance<py::str>(value)) return {name, value.cast<std::string>()};
  if (py::isinstance(value, numpy.attr("float32"))) return {name, value.cast<float>()};
  if (py::isinstance<py::float_>(value) || py::isinstance(value, numpy.attr("floating"))) return {name, value.cast<double>()};
  if (py::isinstance<py::int_>(value) || py::isinstance(value, numpy.attr("integer"))) {
    const long long v = value.cast<long long>();
    if (v < INT32_MIN || v > INT32_MAX) throw UsageError("metadata '" + name + "': an integer beyond 32 bits");
    return {name, static_cast<int>(v)};
  }
  const auto m = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!m || m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4)
    throw UsageError("metadata '" + name + "': " + py::str(py::type::of(value)).cast<std::string>() +
                     " is none of str, int, float, numpy.float32 and a 4x4 matrix");
  glm::mat4 out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i][j] = m.at(i, j);
  return {name, out};
}

// The layers of a dict, each H x W x C (or H x W: one channel), all of one size.
std::vector<ImageLayer> layers_from_dict(const py::dict& layers, int& width, int& height) {
  std::vector<ImageLayer> out;
  width = height = -1;
  for (const auto& [key, value] : layers) {
    const std::string name = py::str(key);
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a || (a.ndim() != 2 && a.ndim() != 3))
      throw UsageError("layer '" + name + "': expected an array of height x width x channels");
    const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
    const int channels = a.ndim() == 3 ? static_cast<int>(a.shape(2)) : 1;
    if (width >= 0 && (w != width || h != height))
      throw UsageError(fmt::format("layer '{}' is {}x{}, the others {}x{} (width x height)", name, w, h, width, height));
    if (w == 0 || h == 0) throw UsageError("layer '" + name + "' has no pixels");
    width = w, height = h;
    std::vector<float> pixels(a.data(), a.data() + a.size());
    out.push_back({name, layer_channel_names(name, channels), std::move(pixels)});
  }
  if (out.empty()) throw UsageError("no layers to write");
  return out;
}

// Renders on a worker thread; the caller's thread reports progress and watches for Ctrl-C.
SessionFrame render_watched(FrameSession& session, const std::vector<std::string>& arguments, py::object progress) {
  RenderMonitor monitor;
  std::optional<SessionFrame> frame;
  double seconds = 0.0;  // the session's own time: what Python's share is measured against
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::thread worker([&] {
    try {
      const auto start = std::chrono::steady_clock::now();
      frame = session.render(arguments, &monitor);
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    done = true;
    finished.notify_all();
  });
  std::optional<py::error_already_set> python_error;  // Ctrl-C, or the progress callback's own
  for (;;) {
    bool over;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(mutex);
      over = finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
    }
    if (over) break;
    if (python_error) continue;  // cancelled: wait for the worker
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) progress(monitor.samples_done.load(), monitor.samples_total.load());
    } catch (py::error_already_set& e) {
      python_error = std::move(e);
      monitor.cancel = true;
    }
  }
  worker.join();
  if (python_error) throw std::move(*python_error);
  if (failure) std::rethrow_exception(failure);
  if (!progress.is_none()) progress(monitor.samples_done.load(), monitor.samples_total.load());
  frame->session_seconds = seconds;
  return std::move(*frame);
}

py::tuple render(FrameSession& session, const std::vector<std::string>& arguments, py::object progress) {
  SessionFrame frame = render_watched(session, arguments, std::move(progress));
  const std::vector<ImageLayer> layers = frame_layers(frame.image);
  std::vector<HeaderAttribute> header = frame_header_attributes(frame.write.metadata, frame.image.samples_per_pixel);
  header.erase(std::remove_if(header.begin(), header.end(),
                              [](const HeaderAttribute& a) { return a.name == "capDate" || a.name == "utcOffset"; }),
               header.end());  // when it was written, not rendered
  py::dict stats;
  stats["seconds"] = frame.stats.seconds;
  stats["load_seconds"] = frame.load_seconds;
  stats["build_seconds"] = frame.build_seconds;
  stats["updated"] = frame.updated;
  stats["session_seconds"] = frame.session_seconds;
  stats["samples"] = frame.stats.camera_samples;
  stats["rays"] = frame.stats.rays;
  stats["threads"] = frame.stats.threads;
  return py::make_tuple(layers_dict(layers, frame.image.width, frame.image.height), metadata_dict(header),
                        frame.warnings, stats);
}

py::tuple read_exr(const std::string& path) {
  ExrChannels exr;
  {
    py::gil_scoped_release release;
    exr = read_exr_channels(path);
  }
  return py::make_tuple(layers_dict(channel_layers(exr), exr.width, exr.height), metadata_dict(exr.attributes));
}

void write_exr(const std::string& path, const py::dict& layers, const py::dict& metadata, bool half) {
  int width = 0, height = 0;
  const std::vector<ImageLayer> image_layers = layers_from_dict(layers, width, height);
  ImageWriteParams params;
  params.half = half;
  params.render_metadata = false;
  for (const auto& [key, value] : metadata) params.attributes.push_back(attribute_from(py::str(key), value));
  check_output_path(path);
  py::gil_scoped_release release;
  FrameImage image = frame_from_exr(layers_to_channels(image_layers, width, height));
  write_image(path, image, params);
}

PyObject* new_exception(py::module_& m, const char* name, PyObject* bases, const char* doc) {
  PyObject* type = PyErr_NewExceptionWithDoc((std::string("tessera.") + name).c_str(), doc, bases, nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

}  // namespace
}  // namespace tessera

// _native, or _native_x86_64_v3 for the AVX2/FMA build (python/CMakeLists.txt).
PYBIND11_MODULE(TESSERA_PYTHON_MODULE, m) {
  using namespace tessera;
  m.doc() = "tessera's native part: see the tessera package.";
  error_type = new_exception(m, "Error", PyExc_Exception, "Any error tessera reports.");
  usage_error_type = new_exception(m, "UsageError", py::make_tuple(py::handle(error_type), py::handle(PyExc_ValueError)).release().ptr(),
                                   "A bad option or value: the message is the command line's.");
  scene_error_type = new_exception(m, "SceneLoadError", py::make_tuple(py::handle(error_type), py::handle(PyExc_ValueError)).release().ptr(),
                                   "The scene file cannot be read, or is not glTF tessera can render.");
  file_error_type = new_exception(m, "FileError", py::make_tuple(py::handle(error_type), py::handle(PyExc_OSError)).release().ptr(),
                                  "An image file cannot be read or written.");
  // Local to this module: the generic and the AVX2/FMA module are both loaded (the first
  // tells whether the CPU runs the second), each with its own copy of tessera's types.
  py::register_local_exception_translator(&translate_exception);

  py::class_<FrameSession>(m, "Session", py::module_local())
      .def(py::init([](const std::string& path) {
             py::gil_scoped_release release;
             return std::make_unique<FrameSession>(path);
           }),
           py::arg("path"))
      .def_property_readonly("path", &FrameSession::path)
      .def("render", &render, py::arg("arguments"), py::arg("progress") = py::none());
  m.def("read_exr", &read_exr, py::arg("path"));
  m.def("write_exr", &write_exr, py::arg("path"), py::arg("layers"), py::arg("metadata"), py::arg("half") = false);
  m.def("version", [] { return tessera_version(); });
  m.def("isa", [] { return std::string(compiled_isa()); });
  m.def("cpu_runs_x86_64_v3", &cpu_runs_x86_64_v3);
}
