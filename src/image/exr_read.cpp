// nephele — reading a multi-layer EXR's channels and header attributes (nephele/image.h), for
// the film output's tests and tools.
#include <ImfAttribute.h>
#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfStringAttribute.h>

#include <charconv>
#include <string>
#include <vector>

#include "nephele/error.h"
#include "nephele/image.h"

namespace nephele {

namespace {

std::string shortest(float value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError("image '" + path + "': " + what);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> read_exr_attributes(const std::string& path) {
  std::vector<std::pair<std::string, std::string>> out;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    for (auto it = header.begin(); it != header.end(); ++it) {
      const Imf::Attribute& a = it.attribute();
      std::string value;
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a)) {
        value = s->value();
      } else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a)) {
        value = shortest(f->value());
      } else if (const auto* m = dynamic_cast<const Imf::M44fAttribute*>(&a)) {
        for (int r = 0; r < 4; ++r)
          for (int c = 0; c < 4; ++c) value += (value.empty() ? "" : " ") + shortest(m->value()[r][c]);
      } else {
        value = std::string("(") + a.typeName() + ")";
      }
      out.emplace_back(it.name(), value);
    }
  } catch (const std::exception& e) {
    fail(path, std::string("cannot read the EXR header: ") + e.what());
  }
  return out;
}

Image read_exr_channel(const std::string& path, const std::string& channel) {
  try {
    Imf::InputFile file(path.c_str());
    if (!file.header().channels().findChannel(channel))
      fail(path, "has no channel \"" + channel + "\"");
    const Imath::Box2i window = file.header().dataWindow();
    const int w = window.max.x - window.min.x + 1;
    const int h = window.max.y - window.min.y + 1;
    std::vector<float> values(size_t(w) * size_t(h));
    char* origin = reinterpret_cast<char*>(values.data() - window.min.x -
                                           ptrdiff_t(window.min.y) * w);
    Imf::FrameBuffer frame;
    frame.insert(channel, Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * size_t(w)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    Image image(w, h);
    for (size_t i = 0; i < values.size(); ++i)
      image.pixels[i] = glm::vec4(values[i], values[i], values[i], 1.0f);
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, std::string("cannot read channel \"") + channel + "\": " + e.what());
  }
}

}  // namespace nephele
