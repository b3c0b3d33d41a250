// nephele — OBJ text checked before tinyobjloader reads it.
#include "io/obj_text.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "nephele/error.h"

namespace nephele {
namespace {

bool is_decimal(const std::string& token) {
  if (token.empty() || token.find_first_not_of("0123456789+-.eE") != std::string::npos)
    return false;
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && std::isfinite(value) &&
         std::fabs(value) <= 3.4e38;  // a float, as the loader keeps it
}

bool is_index(const std::string& part) {
  size_t digits = part.size() > 0 && part[0] == '-' ? 1 : 0;
  if (digits == part.size()) return false;
  return part.find_first_not_of("0123456789", digits) == std::string::npos && part.size() < 11;
}

// A face corner: v, v/vt, v//vn or v/vt/vn.
bool is_corner(const std::string& token) {
  std::vector<std::string> parts(1);
  for (char c : token) {
    if (c == '/')
      parts.emplace_back();
    else
      parts.back().push_back(c);
  }
  if (parts.size() > 3 || !is_index(parts[0])) return false;
  for (size_t i = 1; i < parts.size(); ++i)
    if (!parts[i].empty() ? !is_index(parts[i]) : !(i == 1 && parts.size() == 3)) return false;
  return true;
}

}  // namespace

std::string obj_number_problem(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    const std::string content = line.substr(0, line.find('#'));
    std::istringstream words(content);
    std::string kind, token;
    words >> kind;
    const bool vertex = kind == "v" || kind == "vn" || kind == "vt";
    if (!vertex && kind != "f") continue;
    const auto problem = [&](const std::string& why) {
      return "line " + std::to_string(number) + " ('" + shorten_for_message(line) + "'): " + why;
    };
    size_t count = 0;
    while (words >> token) {
      ++count;
      if (vertex && !is_decimal(token))
        return problem("'" + shorten_for_message(token) + "' is not a finite decimal number");
      if (!vertex && !is_corner(token))
        return problem("'" + shorten_for_message(token) +
                       "' is not a face corner (v, v/vt, v//vn or v/vt/vn, integers)");
    }
    const size_t needed = kind == "vt" ? 1 : 3;
    if (count < needed)
      return problem(std::to_string(count) + (count == 1 ? " number" : " numbers") + " (" + kind +
                     " needs at least " + std::to_string(needed) + ")");
  }
  return "";
}

std::string read_obj_text(const std::string& path, const std::string& where) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    throw InputError(where + "does not exist (an OBJ mesh file is required)");
  if (!fs::is_regular_file(status))
    throw InputError(where + "is not a regular file (an OBJ mesh file is required)");
  const uint64_t bytes = fs::file_size(path, ec);
  if (ec || bytes > kMaxObjBytes)
    throw InputError(where + "is " + std::to_string(bytes >> 20) + " MiB (OBJ meshes of at most " +
                     std::to_string(kMaxObjBytes >> 20) + " MiB are read)");
  std::ifstream in(path, std::ios::binary);
  std::string text(bytes, '\0');
  if (!in.read(text.data(), std::streamsize(bytes)))
    throw InputError(where + "cannot be read (an OBJ mesh file is required)");
  if (const std::string problem = obj_number_problem(text); !problem.empty())
    throw InputError(where + problem);
  return text;
}

std::string obj_error_for_message(const std::string& error, const std::string& fallback) {
  std::string joined;
  std::istringstream lines(error);
  for (std::string line; std::getline(lines, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) joined += (joined.empty() ? "" : "; ") + line;
  }
  return shorten_for_message(joined.empty() ? fallback : joined);
}

}  // namespace nephele
