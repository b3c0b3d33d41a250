// The Python module `nephele` (pybind11): scenes from a preset, a TOML file or a dict, rendered
// on the Vulkan device into NumPy arrays.
//
//   import nephele
//   image = nephele.render(preset="default", width=320, height=200)   # (200, 320, 4) float32
//   layers = nephele.render(scene={"clouds": {"coverage": 0.8}}, layers=True)
//   image, stats = nephele.render(preset="sunset", stats=True)         # stats["ev100"], ...
//   png = nephele.display(image, ev100=stats["ev100"], tonemap=stats["tonemap"])  # uint8 RGBA
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

#include "nephele/cloud_query.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/image.h"
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

// A (height, width, 3 or 4) array of linear radiance as an Image (alpha 1 when missing).
nephele::Image from_array(const py::object& value) {
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) || a.shape(0) < 1 ||
      a.shape(1) < 1) {
    std::string shape = "not an array of numbers";
    if (a) {
      shape = "shape (";
      for (py::ssize_t i = 0; i < a.ndim(); ++i)
        shape += (i ? ", " : "") + std::to_string(a.shape(i));
      shape += a.ndim() == 1 ? ",)" : ")";
    }
    throw nephele::InputError(
        "image: " + shape +
        "; a (height, width, 3 or 4) array of linear cd/m^2 is needed (render's image)");
  }
  const int height = int(a.shape(0)), width = int(a.shape(1)), channels = int(a.shape(2));
  nephele::Image image(width, height);
  auto view = a.unchecked<3>();
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at(x, y) = glm::vec4(view(y, x, 0), view(y, x, 1), view(y, x, 2),
                                 channels == 4 ? view(y, x, 3) : 1.0f);
  return image;
}

// A frame's statistics as the CLI's --stats-json writes them (nephele::frame_stats_json, no
// "image"; "dims" of a voxel cloud a tuple), with the exposure the CLI's PNG has: "ev100" (the
// scene's, or metered as the CLI meters a still), its linear "exposure", the scene's "tonemap"
// and the frame's "metered_luminance".
py::dict stats_dict(const nephele::FrameStats& stats, double ev100, nephele::ToneMap tonemap) {
  py::dict d = py::module_::import("json").attr("loads")(nephele::frame_stats_json(stats, ev100));
  d["metered_luminance"] = stats.metered_luminance;
  d["exposure"] = nephele::exposure_from_ev100(ev100);
  d["tonemap"] = std::string(nephele::to_string(tonemap));
  if (d.contains("voxel_clouds"))
    for (py::handle cloud : d["voxel_clouds"]) cloud["dims"] = py::tuple(cloud["dims"]);
  return d;
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
      "scene_parameters",
      [] {
        py::list list;
        for (const nephele::SceneParameter& p : nephele::scene_parameters()) {
          py::dict d;
          d["key"] = p.key;
          d["unit"] = p.unit;
          d["allowed"] = p.allowed.empty() ? py::object(py::str(p.allowed_values))
                                           : py::object(py::cast(p.allowed));
          d["min"] = std::isnan(p.min) ? py::object(py::none()) : py::object(py::float_(p.min));
          d["max"] = std::isnan(p.max) ? py::object(py::none()) : py::object(py::float_(p.max));
          d["min_open"] = p.min_open;
          d["max_open"] = p.max_open;
          d["off"] = p.off ? py::object(py::float_(*p.off)) : py::object(py::none());
          d["default"] = p.default_value;
          d["meaning"] = p.meaning;
          list.append(d);
        }
        return list;
      },
      "Every scene key as a dict: key, unit, allowed (the range as text, or the list of names), "
      "min, max (None when any value goes), min_open, max_open, off (a value outside the range "
      "that is allowed too), default (TOML text, without a preset) and meaning; the same table "
      "validation and docs/scene-reference.md use.");
  m.def(
      "scene_toml",
      [](const std::string& preset, const py::object& scene, const py::object& toml) {
        return nephele::scene_to_toml(make_scene(preset, scene, toml, py::none(), py::none()));
      },
      py::arg("preset") = "default", py::arg("scene") = py::none(), py::arg("toml") = py::none(),
      "The resolved scene as TOML: a preset or a TOML file, with a dict of keys over it.");
  m.def(
      "render",
      [](const std::string& preset, const py::object& scene_dict, const py::object& toml,
         const py::object& width, const py::object& height, bool layers, bool stats) -> py::object {
        const nephele::Scene scene = make_scene(preset, scene_dict, toml, width, height);
        py::object out;
        nephele::Frame frame;
        if (!layers) {
          {
            py::gil_scoped_release release;
            frame = renderer().render(scene);
          }
          out = to_array(frame.color);
        } else {
          nephele::FilmLayers film;
          {
            py::gil_scoped_release release;
            film = renderer().render_layers(scene);
          }
          py::dict dict;
          dict["image"] = to_array(film.frame.color);
          dict["sky"] = to_array(film.sky);
          dict["clouds"] = to_array(film.clouds);
          dict["clouds_depth_m"] = to_array(film.clouds_depth_m, 1);
          out = std::move(dict);
          frame = std::move(film.frame);
        }
        if (!stats) return out;
        // The EV100 of the CLI's still: the scene's, or its auto exposure's meter.
        const double ev100 = nephele::frame_ev100(scene.output, frame.color, nullptr, 0.0);
        return py::make_tuple(out, stats_dict(frame.stats, ev100, scene.output.tonemap));
      },
      py::arg("preset") = "default", py::arg("scene") = py::none(), py::arg("toml") = py::none(),
      py::arg("width") = py::none(), py::arg("height") = py::none(), py::arg("layers") = false,
      py::arg("stats") = false,
      "Renders a still: linear HDR radiance (cd/m^2) as a (height, width, 4) float32 array, or "
      "with "
      "layers=True a dict of the image and its film layers (sky, clouds premultiplied, "
      "clouds_depth_m). With stats=True, a tuple (that, stats): the frame's statistics as the "
      "CLI's "
      "--stats-json has them (ev100: the exposure of the CLI's PNG, the scene's or its auto "
      "exposure's; "
      "exposure, tonemap, sky_cover_fraction and sky_cover_oktas, cloud_cover_fraction, "
      "mean_luminance, "
      "sun_elevation_deg, passes_ms, ...).");
  m.def(
      "display",
      [](const py::object& image_value, const py::object& ev100_value, const std::string& tonemap) {
        const auto op = nephele::parse_tonemap(tonemap);
        if (!op)
          throw nephele::InputError("tonemap \"" + tonemap +
                                    "\": unknown (allowed: aces, agx, uncharted2, reinhard, none)");
        double ev100 = 0.0;
        if (!ev100_value.is_none()) {
          // A number (numpy's too), not a bool or a string, within the scene's output.ev100 range.
          bool number =
              !py::isinstance<py::bool_>(ev100_value) && !py::isinstance<py::str>(ev100_value);
          if (number) {
            try {
              ev100 = py::float_(ev100_value).cast<double>();
            } catch (const py::error_already_set&) {
              number = false;
            }
          }
          if (!number || !(ev100 >= -20.0 && ev100 <= 30.0))
            throw nephele::InputError(
                "ev100 = " + std::string(py::repr(ev100_value)) +
                ": must be a number in [-20, 30], or None to meter the image");
        }
        const nephele::Image image = from_array(image_value);
        std::vector<unsigned char> rgba;
        {
          py::gil_scoped_release release;
          // As write_image writes a PNG: exposed, tone-mapped, sRGB; without an EV100 metered as
          // write_image meters (the default auto exposure).
          const float exposure = ev100_value.is_none()
                                     ? nephele::still_exposure(nephele::OutputParams{}, image)
                                     : float(nephele::exposure_from_ev100(ev100));
          rgba = nephele::tonemap_srgb8(image, exposure, *op);
        }
        py::array_t<unsigned char> out({image.height, image.width, 4});
        std::copy(rgba.begin(), rgba.end(), out.mutable_data());
        return out;
      },
      py::arg("image"), py::arg("ev100") = py::none(), py::arg("tonemap") = "aces",
      "The 8-bit sRGB image the CLI writes to PNG for linear radiance `image` ((height, width, 3 "
      "or 4), "
      "cd/m^2, as render returns it): exposed at `ev100` (None: metered as an auto exposure with "
      "the "
      "default limits meters it), tone-mapped by `tonemap` (aces, agx, uncharted2, reinhard, "
      "none), "
      "sRGB-encoded by nephele's own code; a (height, width, 4) uint8 RGBA array, alpha 255. "
      "For the CLI's PNG of a scene: display(image, ev100=stats['ev100'], "
      "tonemap=stats['tonemap']) "
      "with render(..., stats=True).");
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
