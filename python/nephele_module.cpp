// The Python module `nephele` (pybind11): scenes from a preset, a TOML file or a dict, rendered
// on the Vulkan device into NumPy arrays.
//
//   import nephele
//   image = nephele.render(preset="default", width=320, height=200)   # (200, 320, 4) float32
//   layers = nephele.render(scene={"clouds": {"coverage": 0.8}}, layers=True)
//   nephele.presets(); nephele.scene_toml(preset="mountains")
//
// Bad input raises nephele.InputError with nephele's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "nephele/error.h"
#include "nephele/cloud_query.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"

namespace py = pybind11;

namespace {

// One renderer for the module's life: its device, tables and noise are made once.
nephele::Renderer& renderer() {
  static std::unique_ptr<nephele::Renderer> shared = std::make_unique<nephele::Renderer>();
  return *shared;
}

// A Python value as the TOML literal text set_scene_value takes.
std::string toml_literal(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return std::to_string(value.cast<long long>());
  if (py::isinstance<py::float_>(value)) {
    const double v = value.cast<double>();
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream text;
    text.precision(17);
    text << v;
    std::string s = text.str();
    if (s.find_first_of(".eE") == std::string::npos) s += ".0";
    return s;
  }
  if (py::isinstance<py::str>(value)) {
    std::string out = "\"";
    for (char c : value.cast<std::string>()) {
      if (c == '"' || c == '\\') out += '\\';
      out += c;
    }
    return out + "\"";
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::isinstance<py::array>(value)) {
    std::string out = "[";
    bool first = true;
    for (const py::handle item : py::iter(value)) {
      out += (first ? "" : ", ") + toml_literal(key, item);
      first = false;
    }
    return out + "]";
  }
  throw nephele::InputError(key + ": a " + std::string(py::str(value.get_type().attr("__name__"))) +
                            " cannot be a scene value (numbers, booleans, strings and lists of them can)");
}

// Applies a (possibly nested) dict of scene keys: {"clouds": {"coverage": 0.5}} or
// {"clouds.coverage": 0.5}.
void apply(nephele::Scene& scene, const py::dict& values, const std::string& prefix) {
  for (const auto& [k, v] : values) {
    const std::string key = prefix + std::string(py::str(k));
    if (py::isinstance<py::dict>(v)) apply(scene, v.cast<py::dict>(), key + ".");
    else nephele::set_scene_value(scene, key, toml_literal(key, v));
  }
}

nephele::Scene make_scene(const std::string& preset, const py::object& scene_dict, const py::object& toml,
                          const py::object& width, const py::object& height) {
  nephele::Scene scene = toml.is_none() ? nephele::load_preset(preset)
                                        : nephele::load_scene_file(toml.cast<std::string>());
  if (!scene_dict.is_none()) apply(scene, scene_dict.cast<py::dict>(), "");
  if (!width.is_none()) nephele::set_scene_value(scene, "output.width", toml_literal("width", width));
  if (!height.is_none()) nephele::set_scene_value(scene, "output.height", toml_literal("height", height));
  nephele::validate_scene(scene);
  return scene;
}

// Points as an (n, 3) float array of ENU metres; InputError naming `name` otherwise.
std::vector<glm::vec3> points(const py::object& value, const char* name) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || !(a.ndim() == 2 && a.shape(1) == 3) && !(a.ndim() == 1 && a.shape(0) == 3))
    throw nephele::InputError(std::string(name) + ": an (n, 3) array of ENU positions (m) is needed");
  const size_t n = a.ndim() == 1 ? 1 : size_t(a.shape(0));
  std::vector<glm::vec3> out(n);
  const double* v = a.data();
  for (size_t i = 0; i < n; ++i) out[i] = glm::vec3(float(v[3 * i]), float(v[3 * i + 1]), float(v[3 * i + 2]));
  return out;
}

// An image as a (height, width, channels) float32 array (a copy).
py::array_t<float> to_array(const nephele::Image& image, int channels = 4) {
  py::array_t<float> out({image.height, image.width, channels});
  auto view = out.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < channels; ++c) view(y, x, c) = image.at(x, y)[c];
  return out;
}

}  // namespace

PYBIND11_MODULE(nephele, m) {
  m.doc() = "nephele: skies and volumetric clouds rendered with Vulkan (lavapipe where there is no GPU)";
  static py::exception<nephele::InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const nephele::InputError& e) {
      input_error(e.what());
    }
  });

  m.def("presets", &nephele::preset_names, "The built-in scenes' names.");
  m.def(
      "scene_toml",
      [](const std::string& preset, const py::object& scene, const py::object& toml) {
        return nephele::scene_to_toml(make_scene(preset, scene, toml, py::none(), py::none()));
      },
      py::arg("preset") = "default", py::arg("scene") = py::none(), py::arg("toml") = py::none(),
      "The resolved scene as TOML: a preset or a TOML file, with a dict of keys over it.");
  m.def(
      "render",
      [](const std::string& preset, const py::object& scene_dict, const py::object& toml, const py::object& width,
         const py::object& height, bool layers) -> py::object {
        const nephele::Scene scene = make_scene(preset, scene_dict, toml, width, height);
        if (!layers) {
          nephele::Frame frame;
          {
            py::gil_scoped_release release;
            frame = renderer().render(scene);
          }
          return to_array(frame.color);
        }
        nephele::FilmLayers film;
        {
          py::gil_scoped_release release;
          film = renderer().render_layers(scene);
        }
        py::dict out;
        out["image"] = to_array(film.frame.color);
        out["sky"] = to_array(film.sky);
        out["clouds"] = to_array(film.clouds);
        out["clouds_depth_m"] = to_array(film.clouds_depth_m, 1);
        return std::move(out);
      },
      py::arg("preset") = "default", py::arg("scene") = py::none(), py::arg("toml") = py::none(),
      py::arg("width") = py::none(), py::arg("height") = py::none(), py::arg("layers") = false,
      "Renders a still: linear HDR radiance (cd/m^2) as a (height, width, 4) float32 array, or with "
      "layers=True a dict of the image and its film layers (sky, clouds premultiplied, "
      "clouds_depth_m).");
  m.def(
      "cloud_density",
      [](const py::object& positions, const std::string& preset, const py::object& scene_dict, const py::object& toml,
         const py::object& time_s) {
        const nephele::Scene scene = make_scene(preset, scene_dict, toml, py::none(), py::none());
        const std::vector<glm::vec3> p = points(positions, "positions");
        const float t = time_s.is_none() ? scene.time_s : time_s.cast<float>();
        py::array_t<float> out(py::ssize_t(p.size()));
        auto view = out.mutable_unchecked<1>();
        {
          py::gil_scoped_release release;
          const nephele::CloudQuery query = renderer().cloud_query(scene);
          for (size_t i = 0; i < p.size(); ++i) view(py::ssize_t(i)) = query.density(p[i], t);
        }
        return out;
      },
      py::arg("positions"), py::arg("preset") = "default", py::arg("scene") = py::none(), py::arg("toml") = py::none(),
      py::arg("time_s") = py::none(),
      "The clouds' density field (dimensionless; sigma_t = density x clouds.extinction_per_m) at ENU "
      "positions (an (n, 3) array, m), at time_s (the scene's time when None), computed on the CPU by the "
      "shaders' own density function.");
  m.def(
      "optical_depth",
      [](const py::object& from, const py::object& to, const std::string& preset, const py::object& scene_dict,
         const py::object& toml, const py::object& time_s, float step_m) {
        const nephele::Scene scene = make_scene(preset, scene_dict, toml, py::none(), py::none());
        const std::vector<glm::vec3> a = points(from, "from"), b = points(to, "to");
        if (a.size() != b.size())
          throw nephele::InputError("from and to: " + std::to_string(a.size()) + " and " + std::to_string(b.size()) +
                                    " positions; as many of each are needed");
        const float t = time_s.is_none() ? scene.time_s : time_s.cast<float>();
        py::array_t<float> out(py::ssize_t(a.size()));
        auto view = out.mutable_unchecked<1>();
        {
          py::gil_scoped_release release;
          const nephele::CloudQuery query = renderer().cloud_query(scene);
          for (size_t i = 0; i < a.size(); ++i) view(py::ssize_t(i)) = query.optical_depth(a[i], b[i], t, step_m);
        }
        return out;
      },
      py::arg("from"), py::arg("to"), py::arg("preset") = "default", py::arg("scene") = py::none(),
      py::arg("toml") = py::none(), py::arg("time_s") = py::none(), py::arg("step_m") = 10.0f,
      "The clouds' optical depth along segments from `from` to `to` (ENU, (n, 3) arrays, m): exp(-depth) is "
      "the direct light's transmittance through the clouds.");
}
