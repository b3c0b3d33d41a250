// nephele — OBJ meshes checked before tinyobjloader reads them: it reads "nan", "inf", "0x10"
// and words as 0 and a missing coordinate as 0, which would deform a mesh without a word.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace nephele {

// The largest OBJ file read (voxelized clouds, terrain meshes): tinyobjloader holds several
// times the text in memory.
constexpr uint64_t kMaxObjBytes = uint64_t(64) << 20;

// The first line whose numbers are not what OBJ allows, as "line 3 ('v 1 1 nan'): 'nan' is not
// a finite decimal number"; "" when every `v`, `vn` and `vt` line holds decimal numbers (at
// least 3, 3 and 1 of them) and every `f` corner integer indices.
std::string obj_number_problem(std::string_view text);

// The file's text, or InputError `where` + why not: missing, not a regular file, over
// kMaxObjBytes, or with numbers obj_number_problem refuses.
std::string read_obj_text(const std::string& path, const std::string& where);

// tinyobjloader's error text (lines each ending in a newline) as part of a one-line message: its
// lines joined by "; ", shortened; `fallback` when it is empty.
std::string obj_error_for_message(const std::string& error, const std::string& fallback);

}  // namespace nephele
